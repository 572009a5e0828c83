// Unit tests of how the editor fills `unchanged` entries of animation messages: `npm test`.
import assert from "node:assert/strict";
import { test } from "node:test";

import { Holdings } from "../src/holdings.js";

const eve = { name: "Eve", hash: "e1", frames: 3, rotations: "AAAA" };
const tom = { name: "Tom", hash: "t1", frames: 4, rotations: "BBBB" };
const desk = { id: "desk", hash: "d1", category: "desk" };

function animation(version, characters, objects = []) {
  return { type: "animation", version, characters, objects };
}

test("a full message is kept as it is and its entries are held by hash", () => {
  const h = new Holdings();
  const { message, missing, unchanged } = h.resolve(animation(1, [eve, tom], [desk]));
  assert.deepEqual(message.characters, [eve, tom]);
  assert.deepEqual(missing, []);
  assert.deepEqual(unchanged, []);
  assert.deepEqual([...h.characters.keys()], ["e1", "t1"]);
  assert.deepEqual([...h.objects.keys()], ["d1"]);
});

test("unchanged stubs are filled from the previous message and changed entries replace the old ones", () => {
  const h = new Holdings();
  h.resolve(animation(1, [eve, tom], [desk]));
  const eve2 = { ...eve, hash: "e2", frames: 5 };
  const { message, unchanged } = h.resolve(
    animation(2, [eve2, { name: "Tom", hash: "t1", unchanged: true }], [{ id: "desk", hash: "d1", unchanged: true }]),
  );
  assert.deepEqual(message.characters, [eve2, tom]);
  assert.deepEqual(message.objects, [desk]);
  assert.deepEqual(unchanged, ["Tom"]);
  assert.deepEqual([...h.characters.keys()].sort(), ["e2", "t1"]);
});

test("only the last message is held: a stub of an older entry is reported missing and everything is forgotten", () => {
  const h = new Holdings();
  h.resolve(animation(1, [eve]));
  h.resolve(animation(2, [{ ...eve, hash: "e2" }]));
  const { message, missing } = h.resolve(animation(3, [{ name: "Eve", hash: "e1", unchanged: true }]));
  assert.equal(message, null);
  assert.deepEqual(missing, ["e1"]);
  assert.equal(h.characters.size, 0);
});
