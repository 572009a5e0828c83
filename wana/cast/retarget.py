"""The canonical motion on a user's rig: world-space bone rotations copied, feet kept on the floor.

Each mapped joint takes the canonical joint's world rotation, composed with the rotation that turns the
user's rest bone onto the canonical rest bone (so an A-pose or a rig facing -Z works as a T-pose facing +Z
would). Canonical joints the rig lacks cost nothing (world rotations do not accumulate through them);
joints the map does not name (twists, fingers) keep their rest local rotation and follow their parents.

The root height is scaled by the ratio of hip heights, then each frame is shifted so that the lower foot
stands as high over the floor as the canonical one does. The path over the floor is the canonical one (the
scene's targets stay where they are), so each leg is then bent by two-bone IK on its own lengths to put the
ankle over the canonical ankle, at the height just found: the feet plant where the canonical feet plant and
do not slide; where a short leg cannot reach the canonical step the hips are lowered until it can.
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
    world_target = {
        j: Rotation.from_quat(g_canon[:, JOINT_INDEX[name]]) * target[j] for name, j in joints.items()
    }
    out = _locals(rig, world_target, t)
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
    legs = {}
    drop = np.zeros(t)
    for side in ("Left", "Right"):  # each foot where the canonical foot is over the floor, at its own height
        a, b, c = (joints[f"{side}{k}"] for k in ("UpLeg", "Leg", "Foot"))
        goal = p_canon[:, JOINT_INDEX[f"{side}Foot"]].copy()
        goal[:, 1] = world[:, c, 1]
        reach = np.linalg.norm(world[0, b] - world[0, a]) + np.linalg.norm(world[0, c] - world[0, b])
        flat = np.linalg.norm(goal[:, [0, 2]] - world[:, a][:, [0, 2]], axis=1)
        highest = goal[:, 1] + np.sqrt(np.maximum((reach * 0.995) ** 2 - flat**2, 0.0))
        drop = np.maximum(drop, world[:, a, 1] - highest)  # a leg too short for the step lowers the hips
        legs[side] = (a, b, c, goal)
    hips_world[:, 1] -= drop
    world[..., 1] -= drop[:, None]
    for a, b, c, goal in legs.values():
        thigh, shin = _two_bone(world[:, a], world[:, b], world[:, c], goal)
        world_target[a] = thigh * _world_of(rig, out, a)
        world_target[b] = shin * thigh * _world_of(rig, out, b)
    out = _locals(rig, world_target, t)
    world = _positions(rig, out, hips, hips_world, parent_m)
    inv_parent = np.linalg.inv(parent_m)
    hips_local = hips_world @ inv_parent[:3, :3].T + inv_parent[:3, 3]
    return CastPose(rotation=out, hips_translation=hips_local, hips=hips, world=world)


def _locals(rig: CastRig, world_target: dict[int, Rotation], t: int) -> np.ndarray:
    """(T, J, 4) local rotations: the targets' world rotations, the other joints at their rest locals."""
    n = rig.n_joints
    local_rest = Rotation.from_quat(rig.rotation)
    out = np.zeros((t, n, 4))
    world_rot: list[Rotation | None] = [None] * n
    base_rot = _rot(rig.base)
    for j in topological(rig.parents):
        p = int(rig.parents[j])
        parent = base_rot if p < 0 else world_rot[p]
        assert parent is not None
        if j in world_target:
            world = world_target[j]
            local = parent.inv() * world
        else:
            local = Rotation.from_quat(np.tile(local_rest[j].as_quat(), (t, 1)))
            world = parent * local
        world_rot[j] = world
        out[:, j] = local.as_quat()
    return out


def _world_of(rig: CastRig, local: np.ndarray, joint: int) -> Rotation:
    """(T,) world rotations of one joint from the local rotations."""
    chain = [joint]
    while rig.parents[chain[-1]] >= 0:
        chain.append(int(rig.parents[chain[-1]]))
    world = _rot(rig.base) * Rotation.from_quat(local[:, chain[-1]])
    for j in reversed(chain[:-1]):
        world = world * Rotation.from_quat(local[:, j])
    return world


def _two_bone(a: np.ndarray, b: np.ndarray, c: np.ndarray, goal: np.ndarray) -> tuple[Rotation, Rotation]:
    """World-space corrections (T,) of the upper and lower bone that put the end c on the goal, keeping the
    knee's bend plane; a goal out of reach is pulled in over the floor (the height is what plants)."""
    l1 = np.linalg.norm(b - a, axis=1)
    l2 = np.linalg.norm(c - b, axis=1)
    reach = (l1 + l2) * (1.0 - 1e-5)
    d = goal - a
    dy = np.clip(d[:, 1], -reach, reach)
    flat = np.linalg.norm(d[:, [0, 2]], axis=1)
    room = np.sqrt(np.maximum(reach**2 - dy**2, 0.0))
    pull = np.where(flat > room, room / np.maximum(flat, 1e-9), 1.0)
    d[:, 0] *= pull
    d[:, 2] *= pull
    dist = np.clip(np.linalg.norm(d, axis=1), np.abs(l1 - l2) + 1e-6, reach)
    u = d / np.maximum(np.linalg.norm(d, axis=1, keepdims=True), 1e-9)
    bend = (b - a) - np.sum((b - a) * u, axis=1, keepdims=True) * u
    forward = np.cross(u, np.array([1.0, 0.0, 0.0]))  # a straight leg bends its knee forward
    bend = np.where(np.linalg.norm(bend, axis=1, keepdims=True) > 1e-6, bend, forward)
    bend /= np.maximum(np.linalg.norm(bend, axis=1, keepdims=True), 1e-9)
    along = (l1**2 - l2**2 + dist**2) / (2 * dist)
    knee = a + u * along[:, None] + bend * np.sqrt(np.maximum(l1**2 - along**2, 0.0))[:, None]
    thigh = _align_many(b - a, knee - a)
    c_moved = knee + thigh.apply(c - b)
    shin = _align_many(c_moved - knee, a + u * dist[:, None] - knee)
    return thigh, shin


def _align_many(x: np.ndarray, y: np.ndarray) -> Rotation:
    """(T,) shortest rotations taking each x onto y."""
    x = x / np.maximum(np.linalg.norm(x, axis=1, keepdims=True), 1e-12)
    y = y / np.maximum(np.linalg.norm(y, axis=1, keepdims=True), 1e-12)
    axis = np.cross(x, y)
    s = np.linalg.norm(axis, axis=1)
    angle = np.arctan2(s, np.sum(x * y, axis=1))
    rotvec = np.where(s[:, None] > 1e-12, axis / np.maximum(s, 1e-12)[:, None] * angle[:, None], 0.0)
    return Rotation.from_rotvec(rotvec)


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
