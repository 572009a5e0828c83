"""The canonical motion on a user's rig: world-space bone rotations copied, feet kept on the floor.

Each mapped joint takes the canonical joint's world rotation, composed with the rotation that turns the
user's rest bone onto the canonical rest bone (so an A-pose or a rig facing -Z works as a T-pose facing +Z
would). Canonical joints the rig lacks cost nothing (world rotations do not accumulate through them);
joints the map does not name (twists, fingers) keep their rest local rotation and follow their parents.

The root height is scaled by the ratio of hip heights, then each frame is shifted so that the lower foot
stands as high over the floor as the canonical one does: the user's feet plant where the canonical feet
plant, whatever its leg length. The path over the floor is the canonical one (the scene's targets stay
where they are).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from wana.cast.glb_rig import CastRig, topological
from wana.domain.skeleton import JOINT_INDEX, JOINT_NAMES, PARENTS, forward_kinematics

# the bone each canonical joint aims along: its child in the chain
_AIM: dict[str, str] = {
    JOINT_NAMES[c]: JOINT_NAMES[p]
    for c, p in ((int(PARENTS[j]), j) for j in range(len(JOINT_NAMES)) if PARENTS[j] >= 0)
    if JOINT_NAMES[p] not in ("LeftShoulder", "RightShoulder", "LeftUpLeg", "RightUpLeg")
}
_FEET = ("LeftFoot", "RightFoot")


@dataclass
class CastPose:
    """The user's joints over all frames, in the skin's joint order.

    Attributes:
        rotation: (T, J, 4) local rotations (x, y, z, w).
        hips_translation: (T, 3) the Hips joint's local translation (in its parent's space).
        hips: index of the Hips joint.
        world: (T, J, 3) world joint positions, metres.
    """

    rotation: np.ndarray
    hips_translation: np.ndarray
    hips: int
    world: np.ndarray


def _rot(m: np.ndarray) -> Rotation:
    """The rotation of a 4x4 (or stack) with scale."""
    r = m[..., :3, :3]
    return Rotation.from_matrix(r / np.linalg.norm(r, axis=-2, keepdims=True))


def _align(a: np.ndarray, b: np.ndarray) -> Rotation:
    """The shortest rotation taking direction a onto b."""
    a, b = a / np.linalg.norm(a), b / np.linalg.norm(b)
    axis = np.cross(a, b)
    s, c = np.linalg.norm(axis), float(np.dot(a, b))
    if s < 1e-9:
        if c > 0:
            return Rotation.identity()
        perp = np.cross(a, [1.0, 0.0, 0.0] if abs(a[0]) < 0.9 else [0.0, 1.0, 0.0])
        return Rotation.from_rotvec(np.pi * perp / np.linalg.norm(perp))
    return Rotation.from_rotvec(axis / s * np.arctan2(s, c))


def retarget(
    rig: CastRig,
    joints: dict[str, int],
    rotations: np.ndarray,
    root: np.ndarray,
    offsets: np.ndarray,
    foot_height: float,
) -> CastPose:
    """The canonical motion on the user's rig.

    Args:
        rig: the user's character.
        joints: canonical joint -> rig joint index (``map_joints``).
        rotations: (T, 24, 4) canonical local rotations.
        root: (T, 3) canonical Hips world positions.
        offsets: (24, 3) rest offsets of the canonical character the motion was made for.
        foot_height: that character's ankle height over the floor at rest, metres.
    """
    t = rotations.shape[0]
    _, g_canon = forward_kinematics(rotations, root, offsets)
    p_canon, _ = forward_kinematics(rotations, root, offsets)
    rest = rig.rest_world()
    p_rest = rest[:, :3, 3]
    r_rest = _rot(rest)
    left = p_rest[joints["LeftUpLeg"]] - p_rest[joints["RightUpLeg"]]
    facing = Rotation.from_rotvec([0.0, -np.arctan2(-left[2], left[0]), 0.0])  # the rig's left onto +X
    canon_rest, _ = forward_kinematics(
        np.tile([0.0, 0.0, 0.0, 1.0], (1, len(JOINT_NAMES), 1)), offsets[:1], offsets
    )
    # world rotation of each mapped joint = canonical world rotation * (rest correction * rest rotation)
    target: dict[int, Rotation] = {}
    for name, j in joints.items():
        fix = facing
        aim = _AIM.get(name)
        if name != "Hips" and aim in joints:
            d_user = facing.apply(p_rest[joints[aim]] - p_rest[j])
            d_canon = canon_rest[0, JOINT_INDEX[aim]] - canon_rest[0, JOINT_INDEX[name]]
            if np.linalg.norm(d_user) > 1e-6 and np.linalg.norm(d_canon) > 1e-6:
                fix = _align(d_user, d_canon) * facing
        target[j] = fix * r_rest[j]
    n = rig.n_joints
    local_rest = Rotation.from_quat(rig.rotation)
    out = np.zeros((t, n, 4))
    world_rot: list[Rotation | None] = [None] * n
    base_rot = _rot(rig.base)
    for j in topological(rig.parents):
        p = int(rig.parents[j])
        parent = base_rot if p < 0 else world_rot[p]
        assert parent is not None
        if j in target:
            name = next(k for k, v in joints.items() if v == j)
            world = Rotation.from_quat(g_canon[:, JOINT_INDEX[name]]) * target[j]
            local = parent.inv() * world if p < 0 else parent.inv() * world
        else:
            local = Rotation.from_quat(np.tile(local_rest[j].as_quat(), (t, 1)))
            world = parent * local
        world_rot[j] = world
        out[:, j] = local.as_quat()
    hips = joints["Hips"]
    # the Hips' parent space is fixed (the joints above the Hips, if any, are never mapped)
    local_m = rig.local_matrices()
    parent_m = rig.base.copy()
    chain = []
    p = int(rig.parents[hips])
    while p >= 0:
        chain.append(p)
        p = int(rig.parents[p])
    for q in reversed(chain):
        parent_m = parent_m @ local_m[q]
    floor = rig.floor()
    user_foot = min(p_rest[joints[f], 1] for f in _FEET) - floor
    scale = (p_rest[hips, 1] - floor) / max(offsets[0, 1], 1e-6)
    hips_world = np.column_stack([root[:, 0], root[:, 1] * scale, root[:, 2]])
    world = _positions(rig, out, hips, hips_world, parent_m)
    canon_clear = np.minimum(p_canon[:, JOINT_INDEX["LeftFoot"], 1], p_canon[:, JOINT_INDEX["RightFoot"], 1])
    user_clear = np.minimum(world[:, joints["LeftFoot"], 1], world[:, joints["RightFoot"], 1])
    shift = (canon_clear - foot_height) - (user_clear - user_foot)
    hips_world[:, 1] += shift
    world[..., 1] += shift[:, None]
    inv_parent = np.linalg.inv(parent_m)
    hips_local = hips_world @ inv_parent[:3, :3].T + inv_parent[:3, 3]
    return CastPose(rotation=out, hips_translation=hips_local, hips=hips, world=world)


def _positions(
    rig: CastRig, rotation: np.ndarray, hips: int, hips_world: np.ndarray, parent_m: np.ndarray
) -> np.ndarray:
    """(T, J, 3) world joint positions with the Hips placed at ``hips_world``."""
    t = rotation.shape[0]
    n = rig.n_joints
    mats = np.zeros((t, n, 4, 4))
    local = np.zeros((t, n, 4, 4))
    local[:, :, :3, :3] = (
        Rotation.from_quat(rotation.reshape(-1, 4)).as_matrix().reshape(t, n, 3, 3)
        * rig.scale[None, :, None, :]
    )
    local[:, :, :3, 3] = rig.translation[None]
    local[:, :, 3, 3] = 1.0
    inv_parent = np.linalg.inv(parent_m)
    local[:, hips, :3, 3] = hips_world @ inv_parent[:3, :3].T + inv_parent[:3, 3]
    for j in topological(rig.parents):
        p = int(rig.parents[j])
        mats[:, j] = (rig.base[None] if p < 0 else mats[:, p]) @ local[:, j]
    return mats[:, :, :3, 3]
