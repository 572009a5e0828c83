// The director's camera as the render service exports it in scene.glb: an animated perspective camera
// node keyed on every frame (translation, rotation; yfov per frame in the node's extras). Reading it here,
// not re-planning it, is what makes the preview frame the story as the MP4 does. No three.js import, so
// node --test can check it against the exporter's own file.

const GLB_MAGIC = 0x46546c67;

/** Split a GLB (ArrayBuffer) into its JSON document and binary chunk. */
export function readGlb(buffer) {
  const view = new DataView(buffer);
  if (view.getUint32(0, true) !== GLB_MAGIC) throw new Error("not a GLB file");
  const jsonLength = view.getUint32(12, true);
  const json = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 20, jsonLength)));
  const binStart = 20 + jsonLength + 8;
  const binLength = view.getUint32(20 + jsonLength, true);
  return { json, bin: buffer.slice(binStart, binStart + binLength) };
}

function floats(doc, bin, index) {
  const acc = doc.accessors[index];
  const bv = doc.bufferViews[acc.bufferView];
  const width = { SCALAR: 1, VEC3: 3, VEC4: 4 }[acc.type];
  return new Float32Array(bin, (bv.byteOffset || 0) + (acc.byteOffset || 0), acc.count * width);
}

/** The camera of a scene.glb, or null when it has none: {frames, translation, rotation, yfov, aspect}. */
export function directorCamera(buffer) {
  const { json, bin } = readGlb(buffer);
  const index = (json.nodes || []).findIndex((n) => n.camera !== undefined && n.name === "camera");
  if (index < 0) return null;
  const node = json.nodes[index];
  const animation = (json.animations || [])[0];
  const channel = (path) => animation?.channels.find((c) => c.target.node === index && c.target.path === path);
  const t = channel("translation");
  const r = channel("rotation");
  if (!t || !r) return null;
  const translation = floats(json, bin, animation.samplers[t.sampler].output);
  const rotation = floats(json, bin, animation.samplers[r.sampler].output);
  const perspective = json.cameras[node.camera].perspective;
  const yfov = node.extras?.yfov_per_frame || [];
  return { frames: translation.length / 3, translation, rotation, yfov, defaultYfov: perspective.yfov, aspect: perspective.aspectRatio };
}

/** Position, quaternion (x, y, z, w) and vertical field of view in degrees at frame f (held past the end). */
export function cameraAt(cam, f) {
  const i = Math.max(0, Math.min(cam.frames - 1, Math.round(f)));
  const yfov = cam.yfov.length ? cam.yfov[Math.min(i, cam.yfov.length - 1)] : cam.defaultYfov;
  return {
    position: Array.from(cam.translation.slice(3 * i, 3 * i + 3)),
    quaternion: Array.from(cam.rotation.slice(4 * i, 4 * i + 4)),
    fovDeg: (yfov * 180) / Math.PI,
  };
}
