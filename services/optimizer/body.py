"""The character's body as volumes: joint positions by forward kinematics, capsules around bones.

Each bone is a capsule (segment between two joints, a radius); a capsule is represented by
spheres spaced at most its radius apart along the segment, so that a box test against spheres is a
clamp and a norm, fully vectorised over frames, spheres and boxes. Forward kinematics here is a
numpy rotation-matrix chain (same result as ``wana.domain.skeleton.forward_kinematics``, several times
faster, which matters when every annealing proposal needs the body of a whole motion).
"""

from __future__ import annotations

import hashlib
from collections import OrderedDict
from dataclasses import dataclass

import numpy as np

from proto.motion_data import Motion
from wana.arrays import from_wire
from wana.domain.skeleton import JOINT_INDEX, JOINT_NAMES, N_JOINTS, PARENTS, REST_OFFSETS

# (from joint, to joint, radius in metres) for a 1.75 m character. "HeadTop" is the head joint
# extended by one neck length, so the skull gets a capsule of its own.
BONES: tuple[tuple[str, str, float], ...] = (
    ("Hips", "Spine", 0.12),
    ("Spine", "Spine1", 0.12),
    ("Spine1", "Spine2", 0.12),
    ("Spine2", "Neck", 0.11),
    ("Neck", "Head", 0.05),
    ("Head", "HeadTop", 0.095),
    ("LeftShoulder", "LeftArm", 0.06),
    ("LeftArm", "LeftForeArm", 0.05),
    ("LeftForeArm", "LeftHand", 0.04),
    ("LeftHand", "LeftHandMiddle1", 0.035),
    ("RightShoulder", "RightArm", 0.06),
    ("RightArm", "RightForeArm", 0.05),
    ("RightForeArm", "RightHand", 0.04),
    ("RightHand", "RightHandMiddle1", 0.035),
    ("LeftUpLeg", "LeftLeg", 0.07),
    ("LeftLeg", "LeftFoot", 0.05),
    ("LeftFoot", "LeftToeBase", 0.04),
    ("RightUpLeg", "RightLeg", 0.07),
    ("RightLeg", "RightFoot", 0.05),
    ("RightFoot", "RightToeBase", 0.04),
)

# Body parts, each named by the end joints of its bones; the broad phase bounds each part per frame.
PARTS: tuple[tuple[str, tuple[str, ...]], ...] = (
    ("torso", ("Spine", "Spine1", "Spine2", "Neck")),
    ("head", ("Head", "HeadTop")),
    ("left_arm", ("LeftArm", "LeftForeArm", "LeftHand", "LeftHandMiddle1")),
    ("right_arm", ("RightArm", "RightForeArm", "RightHand", "RightHandMiddle1")),
    ("left_leg", ("LeftLeg", "LeftFoot", "LeftToeBase")),
    ("right_leg", ("RightLeg", "RightFoot", "RightToeBase")),
)


def quat_to_matrix(q: np.ndarray) -> np.ndarray:
    """(..., 4) unit quaternions (x, y, z, w) -> (..., 3, 3) rotation matrices."""
    q = q / np.maximum(np.linalg.norm(q, axis=-1, keepdims=True), 1e-12)
    x, y, z, w = np.moveaxis(q, -1, 0)
    xx, yy, zz = x * x, y * y, z * z
    xy, xz, yz, wx, wy, wz = x * y, x * z, y * z, w * x, w * y, w * z
    m = np.stack(
        [
            1 - 2 * (yy + zz),
            2 * (xy - wz),
            2 * (xz + wy),
            2 * (xy + wz),
            1 - 2 * (xx + zz),
            2 * (yz - wx),
            2 * (xz - wy),
            2 * (yz + wx),
            1 - 2 * (xx + yy),
        ],
        axis=-1,
    )
    return m.reshape(*q.shape[:-1], 3, 3)


def joint_positions(
    rotations: np.ndarray, root_position: np.ndarray, offsets: np.ndarray | None = None
) -> np.ndarray:
    """Global joint positions by forward kinematics.

    Args:
        rotations: (T, J, 4) local quaternions (x, y, z, w), canonical joint order.
        root_position: (T, 3) world Hips position, metres.
        offsets: (J, 3) rest offsets; defaults to the reference skeleton's.

    Returns:
        (T, J, 3) world joint positions, metres.
    """
    rotations = np.asarray(rotations, dtype=np.float64)
    root_position = np.asarray(root_position, dtype=np.float64)
    if rotations.ndim != 3 or rotations.shape[1:] != (N_JOINTS, 4):
        raise ValueError(f"rotations must be (T, {N_JOINTS}, 4), got {rotations.shape}")
    if root_position.shape != (rotations.shape[0], 3):
        raise ValueError(f"root_position must be ({rotations.shape[0]}, 3), got {root_position.shape}")
    offsets = REST_OFFSETS if offsets is None else np.asarray(offsets, dtype=np.float64)
    local = quat_to_matrix(rotations)  # (T, J, 3, 3)
    glob = np.empty_like(local)
    pos = np.empty((rotations.shape[0], N_JOINTS, 3))
    for j in range(N_JOINTS):
        p = PARENTS[j]
        if p < 0:
            glob[:, j] = local[:, j]
            pos[:, j] = root_position
        else:
            glob[:, j] = glob[:, p] @ local[:, j]
            pos[:, j] = pos[:, p] + glob[:, p] @ offsets[j]
    return pos


_FK_CACHE: OrderedDict[bytes, np.ndarray] = OrderedDict()
_FK_CACHE_SIZE = 256


_ROT_DIGESTS: OrderedDict[int, tuple[bytes, bytes]] = OrderedDict()


def _rotations_digest(data: bytes) -> bytes:
    """Digest of a rotations buffer, memoised by identity (proposals share their rotations bytes)."""
    hit = _ROT_DIGESTS.get(id(data))
    if hit is not None and hit[0] is data:
        return hit[1]
    digest = hashlib.blake2b(data, digest_size=16).digest()
    _ROT_DIGESTS[id(data)] = (data, digest)  # holding data keeps the id unique
    if len(_ROT_DIGESTS) > 64:
        _ROT_DIGESTS.popitem(last=False)
    return digest


def _motion_key(motion: Motion) -> bytes:
    h = hashlib.blake2b(digest_size=16)
    h.update(_rotations_digest(motion.rotations.data))
    h.update(motion.root_position.data)
    h.update(repr((motion.rotations.shape, motion.rotations.dtype, motion.root_position.dtype)).encode())
    return h.digest()


# id(positions) -> (positions, base positions, per-frame shift (T, 3)) for motions that are another
# motion translated frame by frame, so that per-motion work can be derived from the base's.
_SHIFTED: OrderedDict[int, tuple[np.ndarray, np.ndarray, np.ndarray]] = OrderedDict()


def remember_joint_positions(
    motion: Motion, positions: np.ndarray, base: np.ndarray | None = None, shift: np.ndarray | None = None
) -> np.ndarray:
    """Seed the cache with positions (T, J, 3) known without FK (a motion only translated, say).

    Args:
        motion: the motion the positions belong to.
        positions: its joint positions.
        base: the joint positions it was translated from, if so.
        shift: (T, 3) the per-frame translation from ``base``.

    Returns:
        the cached (read-only) positions.
    """
    positions = np.asarray(positions, dtype=np.float64)
    positions.setflags(write=False)
    if base is not None and shift is not None:
        _SHIFTED[id(positions)] = (positions, base, np.asarray(shift, dtype=np.float64))
        if len(_SHIFTED) > _FK_CACHE_SIZE:
            _SHIFTED.popitem(last=False)
    _FK_CACHE[_motion_key(motion)] = positions
    return positions


def shifted_from(positions: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """(base positions, per-frame shift (T, 3)) when ``positions`` was remembered as a translated motion."""
    hit = _SHIFTED.get(id(positions))
    if hit is None or hit[0] is not positions:
        return None
    return hit[1], hit[2]
    if len(_FK_CACHE) > _FK_CACHE_SIZE:
        _FK_CACHE.popitem(last=False)


def motion_joint_positions(motion: Motion) -> np.ndarray:
    """(T, J, 3) world joint positions of a Motion, cached by the motion's array bytes.

    Annealing proposals that do not change a motion (the object moved was not one it depends on)
    then cost a hash instead of a forward-kinematics pass.
    """
    if motion.joint_names and tuple(motion.joint_names) != JOINT_NAMES:
        raise ValueError(
            "motion joints are not in the canonical skeleton order (wana.domain.skeleton.JOINT_NAMES)"
        )
    if motion.rotations.shape[:1] != motion.root_position.shape[:1]:
        raise ValueError(
            f"motion has {motion.rotations.shape[:1]} rotation frames but "
            f"{motion.root_position.shape[:1]} root frames"
        )
    key = _motion_key(motion)
    hit = _FK_CACHE.get(key)
    if hit is not None:
        _FK_CACHE.move_to_end(key)
        return hit
    pos = joint_positions(from_wire(motion.rotations), from_wire(motion.root_position))
    pos.setflags(write=False)
    _FK_CACHE[key] = pos
    if len(_FK_CACHE) > _FK_CACHE_SIZE:
        _FK_CACHE.popitem(last=False)
    return pos


@dataclass(frozen=True)
class BodySpheres:
    """Sphere sampling of the bone capsules.

    Attributes:
        a: (S,) index of the segment's first joint (into the extended joint list: canonical + HeadTop).
        b: (S,) index of its second joint.
        t: (S,) position along the segment in [0, 1].
        radius: (S,) sphere radius, metres.
        bone: (S,) index into BONES.
        part: (S,) body part (see PARTS), the unit of the collision broad phase.
    """

    a: np.ndarray
    b: np.ndarray
    t: np.ndarray
    radius: np.ndarray
    bone: np.ndarray
    part: np.ndarray

    def centres(self, positions: np.ndarray) -> np.ndarray:
        """(..., J, 3) joint positions -> (..., S, 3) sphere centres."""
        ext = extend_head(positions)
        t = self.t[:, None]
        return ext[..., self.a, :] * (1.0 - t) + ext[..., self.b, :] * t


def extend_head(positions: np.ndarray) -> np.ndarray:
    """(..., J, 3) -> (..., J + 1, 3): the canonical joints plus HeadTop."""
    head = positions[..., JOINT_INDEX["Head"], :]
    neck = positions[..., JOINT_INDEX["Neck"], :]
    top = head + (head - neck) * 1.3
    return np.concatenate([positions, top[..., None, :]], axis=-2)


def body_spheres(height: float = 1.75, spacing: float = 1.0) -> BodySpheres:
    """Spheres covering the bone capsules of a character of ``height`` metres.

    Args:
        height: character height, metres.
        spacing: distance between consecutive spheres of a bone, in sphere radii (1 keeps the capsule's
            surface within ~13 % of a radius; 2 is a coarser body for ranking proposals).
    """
    k = height / 1.75
    names = {n: i for i, n in enumerate((*JOINT_NAMES, "HeadTop"))}
    rest = extend_head(_rest_positions()[None])[0] * k
    a, b, t, r, bone = [], [], [], [], []
    for bi, (ja, jb, radius) in enumerate(BONES):
        length = float(np.linalg.norm(rest[names[jb]] - rest[names[ja]]))
        n = max(2, int(np.ceil(length / (radius * k * spacing))) + 1)
        a += [names[ja]] * n
        b += [names[jb]] * n
        t += list(np.linspace(0.0, 1.0, n))
        r += [radius * k] * n
        bone += [bi] * n
    bone_arr = np.array(bone)
    part = np.array(
        [next(i for i, (_, bones) in enumerate(PARTS) if BONES[bi][1] in bones) for bi in bone_arr]
    )
    return BodySpheres(np.array(a), np.array(b), np.array(t), np.array(r), bone_arr, part)


def _rest_positions() -> np.ndarray:
    pos = np.zeros((N_JOINTS, 3))
    for j in range(N_JOINTS):
        p = PARENTS[j]
        pos[j] = REST_OFFSETS[j] if p < 0 else pos[p] + REST_OFFSETS[j]
    return pos
