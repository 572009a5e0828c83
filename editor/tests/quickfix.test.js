import assert from "node:assert/strict";
import { test } from "node:test";
import { inflectLike, missingObject, suggestedWords, unknownWord } from "../src/quickfix.js";

test("the words a diagnostic suggests are read from its message", () => {
  assert.deepEqual(suggestedWords("'sitts' is not an action in the motion library; did you mean 'sit'?"), ["sit"]);
  assert.deepEqual(suggestedWords("'chiar' is not in the object catalog; did you mean 'chair' or 'chain'?"), ["chair", "chain"]);
  assert.deepEqual(suggestedWords("sentence has no verb"), []);
});

test("a missing object is named from the message", () => {
  assert.equal(missingObject("Eve sits on the armchair but there is no armchair in the scene"), "armchair");
  assert.equal(missingObject("the animation does not show this: Eve is not at the door"), null);
});

test("an action suggestion keeps the writer's third person", () => {
  const msg = "'sitts' is not an action in the motion library; did you mean 'sit'?";
  assert.equal(inflectLike("sit", "sitts", msg), "sits");
  assert.equal(inflectLike("carry", "carrys", "'carrys' is not an action"), "carries");
  assert.equal(inflectLike("chair", "chiars", "'chiars' is not in the object catalog"), "chair");
});

test("the unknown word is the one the message quotes", () => {
  assert.equal(unknownWord("unknown action word: 'sitts' is not an action in the motion library; did you mean 'sit'?"), "sitts");
  assert.equal(unknownWord("sentence has no verb"), "");
});
