// A character drawn as a bone-capsule figure driven by local joint rotations (x, y, z, w) per frame.

import * as THREE from "three";

const PALETTE = [0xf2a541, 0x4fc3f7, 0xe57373, 0x81c784, 0xba68c8, 0xffd54f];

/** Decode base64 of little-endian float32 bytes (a Float32Array, from a binary frame, as it is). */
export function decodeF32(b64) {
  if (typeof b64 !== "string") return b64;
  const bin = atob(b64);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  return new Float32Array(bytes.buffer);
}

function radiusFor(name) {
  if (/Spine|Hips/.test(name)) return 0.09;
  if (/Neck/.test(name)) return 0.05;
  if (/UpLeg/.test(name)) return 0.075;
  if (/Leg/.test(name)) return 0.06;
  if (/Foot|Toe/.test(name)) return 0.04;
  if (/Arm/.test(name) && !/Fore/.test(name)) return 0.05;
  if (/Shoulder/.test(name)) return 0.05;
  return 0.04;
}

export class CharacterFigure {
  /** @param {object} data one entry of the animation message's `characters`; @param {number} index */
  constructor(data, index) {
    this.name = data.name;
    this.frames = data.frames;
    this.jointCount = data.joints.length;
    this.root = decodeF32(data.root_position); // (T, 3)
    this.rotations = decodeF32(data.rotations); // (T, J, 4)
    this.present = data.present ? decodeF32(data.present) : null; // (T,) 1 on stage, 0 off stage
    this.segments = data.segments;
    this.group = new THREE.Group();
    this.group.name = `character:${data.name}`;
    this.group.userData = { kind: "character", name: data.name };
    const offsets = decodeF32(data.offsets); // (J, 3)
    const material = new THREE.MeshStandardMaterial({ color: PALETTE[index % PALETTE.length], roughness: 0.6 });
    this.joints = data.joints.map((name, j) => {
      const joint = new THREE.Object3D();
      joint.name = name;
      joint.position.set(offsets[3 * j], offsets[3 * j + 1], offsets[3 * j + 2]);
      return joint;
    });
    data.parents.forEach((p, j) => {
      if (p < 0) this.group.add(this.joints[j]);
      else this.joints[p].add(this.joints[j]);
      if (p < 0) return;
      // A capsule from the parent's origin to this joint, carried by the parent.
      const bone = new THREE.Vector3(offsets[3 * j], offsets[3 * j + 1], offsets[3 * j + 2]);
      const length = bone.length();
      if (length < 1e-4) return;
      const r = radiusFor(data.joints[p]);
      const capsule = new THREE.Mesh(new THREE.CapsuleGeometry(r, Math.max(length - r, 0.01), 4, 8), material);
      capsule.position.copy(bone).multiplyScalar(0.5);
      capsule.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), bone.clone().normalize());
      capsule.castShadow = true;
      this.joints[p].add(capsule);
    });
    const head = data.joints.indexOf("Head");
    if (head >= 0) {
      const skull = new THREE.Mesh(new THREE.SphereGeometry(0.11, 16, 12), material);
      skull.position.set(0, 0.1, 0.01);
      skull.castShadow = true;
      this.joints[head].add(skull);
      const nose = new THREE.Mesh(new THREE.ConeGeometry(0.025, 0.06, 8), material);
      nose.position.set(0, 0.1, 0.12);
      nose.rotation.x = Math.PI / 2;
      this.joints[head].add(nose);
    }
    this.setFrame(0);
  }

  /** Pose the figure at frame f (clamped). */
  setFrame(f) {
    if (this.frames === 0) return;
    const t = Math.max(0, Math.min(this.frames - 1, f));
    this.group.visible = !this.present || this.present[t] > 0.5; // off stage: not drawn
    const J = this.jointCount;
    for (let j = 0; j < J; j++) {
      const k = (t * J + j) * 4;
      this.joints[j].quaternion.set(this.rotations[k], this.rotations[k + 1], this.rotations[k + 2], this.rotations[k + 3]);
    }
    // The root joint (Hips) sits at the world root position.
    const rootIndex = this.joints.findIndex((joint) => joint.parent === this.group);
    this.joints[rootIndex].position.set(this.root[3 * t], this.root[3 * t + 1], this.root[3 * t + 2]);
  }

  /** World position of the hips now. */
  position() {
    return this.joints[0].getWorldPosition(new THREE.Vector3());
  }

  /** Ids of sentences whose segment plays at frame f. */
  activeSentences(f) {
    return this.segments.filter((s) => f >= s.start_frame && f < s.end_frame && s.sentence_id).map((s) => s.sentence_id);
  }

  dispose() {
    this.group.traverse((o) => o.geometry?.dispose());
  }
}
