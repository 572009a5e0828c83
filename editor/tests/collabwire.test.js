import assert from "node:assert/strict";
import { test } from "node:test";
import { ChangeSet, Text } from "@codemirror/state";
import { fromWire, toWire } from "../src/collabwire.js";
import { applyChanges } from "../src/textdiff.js";

test("a CodeMirror change set becomes the gateway's code-point changes and back", () => {
  const base = "Anna 🙂 walks. Ben sits.";
  const doc = Text.of([base]);
  // insert after the emoji (UTF-16 offset 7 = code point 6) and replace "Ben" (UTF-16 15..18)
  const changes = ChangeSet.of(
    [
      { from: 7, insert: "!" },
      { from: 15, to: 18, insert: "Tom" },
    ],
    base.length,
  );
  const wire = toWire(changes, base);
  assert.deepEqual(wire, [
    { start: 6, end: 6, text: "!" },
    { start: 14, end: 17, text: "Tom" },
  ]);
  assert.equal(applyChanges(base, wire), changes.apply(doc).toString());
  assert.equal(fromWire(wire, base).apply(doc).toString(), "Anna 🙂! walks. Tom sits.");
});

test("text without astral characters keeps its offsets", () => {
  const base = "Eve walks.";
  const wire = [{ start: 0, end: 3, text: "Tom" }];
  assert.deepEqual(toWire(fromWire(wire, base), base), wire);
});
