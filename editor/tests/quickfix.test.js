import assert from "node:assert/strict";
import { test } from "node:test";
import { missingObject, suggestedWords } from "../src/quickfix.js";

test("the words a diagnostic suggests are read from its message", () => {
  assert.deepEqual(suggestedWords("'sitts' is not an action in the motion library; did you mean 'sit'?"), ["sit"]);
  assert.deepEqual(suggestedWords("'chiar' is not in the object catalog; did you mean 'chair' or 'chain'?"), ["chair", "chain"]);
  assert.deepEqual(suggestedWords("sentence has no verb"), []);
});

test("a missing object is named from the message", () => {
  assert.equal(missingObject("Eve sits on the armchair but there is no armchair in the scene"), "armchair");
  assert.equal(missingObject("the animation does not show this: Eve is not at the door"), null);
});
