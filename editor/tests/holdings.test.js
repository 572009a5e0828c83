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

test("a binary patch of a version this page does not hold is missing: the page resumes", () => {
  const h = new Holdings();
  const patch = {
    name: "Eve", hash: "e2", patch: "e1", frames: 1, ops: [[1, 0, 0]], scale: 32767, has_present: false,
    _blobs: [new Int16Array(0), new Uint32Array(0), new Uint8Array(0)],
  };
  const { message, missing } = h.resolve(animation(2, [patch]));
  assert.equal(message, null);
  assert.deepEqual(missing, ["e1"]);
});

test("a full binary entry, then a patch of it, rebuild the frames from the held one", () => {
  const h = new Holdings();
  const full = {
    name: "Eve", hash: "e1", frames: 2, joints: ["Hips"], parents: [-1], offsets: "AAAAAAAAAAAAAAAA",
    ops: [[2, -1, 1]], scale: 32767, has_present: false,
    _blobs: [Int16Array.from([0, 0, 0, 32767, 100, 0, 0, 32767]), new Uint32Array(6), new Uint8Array([1, 1])],
  };
  const first = h.resolve(animation(1, [full])).message.characters[0];
  assert.equal(first.rotations[3], 1);
  const patch = {
    name: "Eve", hash: "e2", patch: "e1", frames: 3, ops: [[1, 1, 0], [2, 0, 1]], scale: 32767, has_present: false,
    _blobs: [Int16Array.from([5, 0, 0, 0, 0, 0, 0, 0]), new Uint32Array(6), new Uint8Array(2)],
  };
  const second = h.resolve(animation(2, [patch])).message.characters[0];
  assert.deepEqual(Array.from(second._q.rot), [100, 0, 0, 32767, 5, 0, 0, 32767, 100, 0, 0, 32767]);
  assert.deepEqual(second.joints, ["Hips"]); // kept from the held entry
  assert.equal(second.present, null);
});
