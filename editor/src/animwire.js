// Binary animation frames from the gateway (services/gateway/animwire.py), and rebuilding a character's
// frames from a patch against the version this page holds.
//
// Frame: "WAN2" | zlib( u32 header length | header JSON | padding to 8 | blobs ). Each character entry
// carries `ops`: [n, src, residual] runs that rebuild its frames in order from the held frames src.. (src
// -1: zeros), adding the next n residual rows when residual is 1 (wrapping integer sums). Rotations travel
// as int16 (x `scale`), root positions as the bits of float32, presence as uint8. Each blob is filtered
// ("delta-planes"): row deltas, stored column by column, byte plane by byte plane (undone in `unfilter`).
// A large JSON message comes as "WJZ1" | zlib(its text) (`decodeMessage`).

const DTYPES = { i16: Int16Array, u32: Uint32Array, u8: Uint8Array };

async function inflate(bytes) {
  const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("deflate"));
  return new Response(stream).arrayBuffer();
}

function magicOf(buffer) {
  return String.fromCharCode(...new Uint8Array(buffer, 0, 4));
}

/** A blob of `shape` from its filtered bytes: byte b of column c, row r at b*C*R + c*R + r; rows summed. */
export function unfilter(bytes, Type, shape) {
  const rows = shape[0] ?? 0;
  const cols = shape.slice(1).reduce((a, b) => a * b, 1);
  const size = Type.BYTES_PER_ELEMENT;
  const out = new Type(rows * cols);
  const plane = rows * cols;
  for (let c = 0; c < cols; c++) {
    let acc = 0;
    for (let r = 0; r < rows; r++) {
      const at = c * rows + r;
      let v = bytes[at];
      if (size > 1) v |= bytes[plane + at] << 8;
      if (size > 2) v |= (bytes[2 * plane + at] << 16) | (bytes[3 * plane + at] << 24);
      acc = size === 4 ? (acc + v) >>> 0 : acc + v;
      out[r * cols + c] = acc; // the typed array wraps the sum to its width
      acc = out[r * cols + c];
    }
  }
  return out;
}

/**
 * Decode one binary message: an animation frame (each entry's blobs attached as `_blobs`), or a
 * compressed JSON message.
 */
export async function decodeMessage(buffer) {
  if (magicOf(buffer) === "WJZ1") return JSON.parse(new TextDecoder().decode(await inflate(buffer.slice(4))));
  return decodeFrame(buffer);
}

/** Decode one binary animation frame into its message; each entry's blobs are attached as `_blobs`. */
export async function decodeFrame(buffer) {
  if (magicOf(buffer) !== "WAN2") throw new Error("not a wana binary animation frame");
  const body = await inflate(buffer.slice(4));
  const length = new DataView(body).getUint32(0, true);
  const msg = JSON.parse(new TextDecoder().decode(new Uint8Array(body, 4, length)));
  const start = 4 + length + ((8 - ((4 + length) % 8)) % 8);
  const blobs = msg.blobs.map(([offset, nbytes, dtype, shape]) =>
    unfilter(new Uint8Array(body, start + offset, nbytes), DTYPES[dtype], shape),
  );
  for (const c of msg.characters) if (c.ops) c._blobs = blobs.slice(c.blob_base, c.blob_base + 3);
  delete msg.blobs;
  return msg;
}

/**
 * The full character entry an entry with `ops` stands for.
 * @param {object} entry a character entry of a decoded frame (full, or a patch of `held`)
 * @param {object|null} held the held entry the patch names (with its `_q` frames), null for a full entry
 */
export function rebuild(entry, held) {
  const [resRot, resRoot, resPres] = entry._blobs;
  const base = entry.patch ? held._q : null;
  const width = base ? base.width : resRot.length / Math.max(resPres.length, 1);
  const frames = entry.frames;
  const rot = new Int16Array(frames * width);
  const root = new Uint32Array(frames * 3);
  const pres = new Uint8Array(frames);
  let at = 0;
  let k = 0;
  for (const [n, src, add] of entry.ops) {
    if (src >= 0 && base) {
      rot.set(base.rot.subarray(src * width, (src + n) * width), at * width);
      root.set(base.root.subarray(src * 3, (src + n) * 3), at * 3);
      pres.set(base.pres.subarray(src, src + n), at);
    }
    if (add) {
      for (let i = 0; i < n * width; i++) rot[at * width + i] += resRot[k * width + i];
      for (let i = 0; i < n * 3; i++) root[at * 3 + i] += resRoot[k * 3 + i];
      for (let i = 0; i < n; i++) pres[at + i] += resPres[k + i];
      k += n;
    }
    at += n;
  }
  const rotations = new Float32Array(rot.length);
  for (let i = 0; i < rot.length; i++) rotations[i] = rot[i] / entry.scale;
  const { _blobs, ops, patch, blob_base, ...meta } = entry;
  const kept = held ? { joints: held.joints, parents: held.parents, offsets: held.offsets } : {};
  return {
    ...kept,
    ...meta,
    rotations,
    root_position: new Float32Array(root.buffer),
    present: entry.has_present ? Float32Array.from(pres) : null,
    _q: { rot, root, pres, width },
  };
}
