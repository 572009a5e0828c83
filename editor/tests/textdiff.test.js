// Unit tests of the text diff and rebase the editor relies on: `npm test` (node's built-in runner).
import assert from "node:assert/strict";
import { test } from "node:test";

import { applyChanges, cpLength, cpToUtf16, diff, mapOffset, rebase, utf16ToCp } from "../src/textdiff.js";

test("diff finds the one changed range in code points", () => {
  assert.equal(diff("Eve walks.", "Eve walks."), null);
  assert.deepEqual(diff("Eve walks.", "Eve runs."), { start: 4, end: 8, text: "run" });
  assert.deepEqual(diff("", "A desk$."), { start: 0, end: 0, text: "A desk$." });
  assert.deepEqual(diff("Eve walks.", "Eve."), { start: 3, end: 9, text: "" });
});

test("offsets count code points, not UTF-16 units", () => {
  const text = "😀 Eve walks.";
  assert.equal(cpLength(text), 12);
  assert.deepEqual(diff(text, "😀 Tom walks."), { start: 2, end: 5, text: "Tom" });
  assert.equal(cpToUtf16(text, 2), 3);
  assert.equal(utf16ToCp(text, 3), 2);
});

test("applying a diff reproduces the new text", () => {
  const before = "In the office there is a desk$. Eve walks to the desk.";
  const after = "In the office there is a red desk$. Eve runs to the desk.";
  assert.equal(applyChanges(before, [diff(before, after)]), after);
  assert.equal(applyChanges("abcdef", [{ start: 4, end: 5, text: "E" }, { start: 0, end: 1, text: "A" }]), "AbcdEf");
});

test("offsets after a change move with it", () => {
  const change = { start: 4, end: 9, text: "runs" };
  assert.equal(mapOffset(2, change), 2);
  assert.equal(mapOffset(10, change), 9);
  assert.equal(mapOffset(6, change), 8);
});

test("a local edit after a remote one is shifted onto the server text", () => {
  const base = "Eve walks. Tom sits.";
  const server = "Ann walks. Tom sits."; // remote: Eve -> Ann
  const local = "Eve walks. Tom waves."; // mine: sits -> waves
  const { text, local: moved } = rebase(base, local, server);
  assert.equal(text, "Ann walks. Tom waves.");
  assert.equal(applyChanges(server, [moved]), text);
});

test("a local edit before a remote one keeps its offsets", () => {
  const base = "Eve walks. Tom sits.";
  const { text } = rebase(base, "Eve runs. Tom sits.", "Eve walks. Tom stands up.");
  assert.equal(text, "Eve runs. Tom stands up.");
});

test("when both touch the same characters the server wins", () => {
  const base = "Eve walks.";
  assert.deepEqual(rebase(base, "Eve runs.", "Eve jumps."), { text: "Eve jumps.", local: null });
  assert.deepEqual(rebase(base, base, "Eve jumps."), { text: "Eve jumps.", local: null });
  assert.equal(rebase(base, "Eve runs.", base).text, "Eve runs.");
});
