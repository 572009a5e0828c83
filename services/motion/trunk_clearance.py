"""Trunk clearance: a trunk bent over a table straightens up until the chest and the head are out of it.

An action's upper body comes from its clip, and a reach to a target leans the spine forward on top of it
(synthesis: ``lean_needed``, up to 40 degrees seated, after the hips slid forward on the seat). Neither looks
at what is in front: writing in a notebook at a school desk, eating from a bowl on the dining table, the head
goes down into the desk top and the chest into the table's edge. Here, after a segment is synthesised, the
trunk's capsule spheres (chest, neck, head, as the story checks sample them: wana.fidelity.bodies) are tested
against the room's furniture (wana.fidelity.solids); on the frames where one is visibly inside, the spine and
the neck turn back toward upright (never past it: an upright trunk is left as it is) by the smallest angle
that takes the deepest sphere out, spread over neighbouring frames as the arm clearance spreads its turns.
The hands that were on a contact point are brought back onto it by IK afterwards (as far as the arms reach:
a person sitting up writes with a longer arm, not with the nose in the book).

The object sat or lain on (the stated contact) is not in the way, nor is the held prop.
"""

from __future__ import annotations

import numpy as np

from proto.scene import PlacedObject
from services.motion.clearance import deepest, seated_on, spread_turns
from services.motion.ik import global_transforms, two_bone_ik
from wana.domain import quat
from wana.domain.skeleton import JOINT_INDEX, PARENTS
from wana.fidelity.bodies import ALONG, BONE_RADII, HEAD_CENTRE, HEAD_RADIUS

ROUNDS = 6  # straighten, spread, test again
BENT = ("Spine", "Spine1", "Spine2", "Neck")  # the joints the straightening is shared over
TESTED = ("Spine1", "Spine2", "Neck", "Head")  # the bones (by child joint) whose spheres are tested
MAX_TURN = np.radians(20.0)  # radians the trunk straightens by at most in one round
MIN_TURN = np.radians(0.5)  # radians: smaller corrections are not worth a round
IK_EASE = 12  # frames over which a hand eases back onto its contact point (0.4 s, as synthesis eases it)
UP = np.array([0.0, 1.0, 0.0])


def _layout() -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(P,) parent joint, child joint, share along the bone and radius of each tested trunk sphere (the head's
    centre sphere is added apart: it sits off the bone)."""
    parent, child, share, radii = [], [], [], []
    for name in TESTED:
        j = JOINT_INDEX[name]
        for t in (*ALONG, 1.0):
            parent.append(int(PARENTS[j]))
            child.append(j)
            share.append(t)
            radii.append(BONE_RADII[name])
    return np.array(parent), np.array(child), np.array(share), np.array(radii)


_PARENT, _CHILD, _SHARE, _RADII = _layout()


def trunk_spheres(pos: np.ndarray, grot: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(T, P, 3) centres of the chest, neck and head spheres and their (P,) radii, from FK positions and
    global rotations."""
    a, b = pos[:, _PARENT], pos[:, _CHILD]
    centres = a + _SHARE[None, :, None] * (b - a)
    head = JOINT_INDEX["Head"]
    centre = pos[:, head] + quat.rotate(quat.normalize(grot[:, head]), np.array(HEAD_CENTRE))
    return np.concatenate([centres, centre[:, None]], axis=1), np.r_[_RADII, HEAD_RADIUS]


def _tilt(pos: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(T,) radians the trunk (Spine -> Head) leans from upright and (T, 3) the unit axis that turns it back."""
    trunk = pos[:, JOINT_INDEX["Head"]] - pos[:, JOINT_INDEX["Spine"]]
    length = np.maximum(np.linalg.norm(trunk, axis=1), 1e-9)
    tilt = np.arccos(np.clip(trunk[:, 1] / length, -1.0, 1.0))
    axis = np.cross(trunk, UP)
    size = np.linalg.norm(axis, axis=1, keepdims=True)
    return tilt, np.where(size > 1e-9, axis / np.maximum(size, 1e-9), 0.0)


def straighten(
    rotations: np.ndarray,
    root: np.ndarray,
    offsets: np.ndarray,
    solids: list[tuple[PlacedObject, np.ndarray, float]],
) -> tuple[np.ndarray, bool]:
    """Turn the spine and the neck back toward upright where the chest or the head is inside furniture.

    Args:
        rotations: (T, J, 4) local joint rotations of a piece.
        root: (T, 3) world hips positions, metres.
        offsets: (J, 3) the character's rest offsets (the skeleton the checks and the renderer play).
        solids: the room's furniture (services.motion.clearance.furniture); what the character sits or
            lies on is left out frame by frame.

    Returns:
        (T, J, 4) rotations, and whether any frame changed.
    """
    rot = np.array(rotations, dtype=np.float64, copy=True)
    t = len(rot)
    if not solids or t == 0:
        return rot, False
    root = np.asarray(root, dtype=np.float64)
    skip = seated_on(root, solids)
    changed = False
    for _ in range(ROUNDS):
        pos, grot = global_transforms(rot, root, offsets)
        centres, radii = trunk_spheres(pos, grot)
        excess, worst, owner = deepest(centres, radii, solids, skip)
        tilt, axis = _tilt(pos)
        fix = (owner >= 0) & (excess > 0) & (tilt > MIN_TURN)
        if not fix.any():
            break
        f = np.nonzero(fix)[0]
        lever = np.linalg.norm(centres[f, worst[f]] - pos[f, JOINT_INDEX["Spine"]], axis=1)
        angle = np.minimum(np.minimum(excess[f] / np.maximum(lever, 0.1) * 1.2, MAX_TURN), tilt[f])
        turn = np.zeros((t, 3))
        turn[f] = axis[f] * angle[:, None]
        spread = spread_turns(turn, np.zeros(t, bool))
        size = np.linalg.norm(spread, axis=1)
        # never past upright: the spread may carry a frame's turn onto a neighbour that leans less
        size = np.minimum(size, tilt)
        moving = size > MIN_TURN / 4.0
        if not moving.any():
            break
        ax = spread[moving] / np.maximum(np.linalg.norm(spread[moving], axis=1, keepdims=True), 1e-12)
        share = quat.from_axis_angle(ax, size[moving] / len(BENT))
        for name in BENT:  # the same world turn at each joint: the later joints' parents turn with it
            j = JOINT_INDEX[name]
            parent = grot[moving, PARENTS[j]]
            local = quat.mul(quat.mul(quat.inv(parent), share), parent)
            rot[moving, j] = quat.normalize(quat.mul(local, rot[moving, j]))
        changed = True
    return rot, changed


def hands_back(
    rotations: np.ndarray, root: np.ndarray, contact_frames: dict[str, tuple[np.ndarray, np.ndarray]]
) -> np.ndarray:
    """(T, J, 4) rotations with each hand that had a contact point reaching for it again (two-bone IK on its
    contact frames, eased in and out over IK_EASE frames)."""
    rot = rotations
    t = len(rot)
    for joint, (frames, target) in contact_frames.items():
        if "Hand" not in joint:
            continue
        frames = np.asarray(frames, int)
        frames = frames[(frames >= 0) & (frames < t)]
        if not len(frames):
            continue
        dist = np.min(np.abs(np.arange(t)[:, None] - frames[None, :]), axis=1)
        weight = np.clip(1.0 - dist / IK_EASE, 0.0, 1.0)
        tgt = np.broadcast_to(np.asarray(target, dtype=np.float64), (t, 3))
        rot = two_bone_ik(rot, root, joint, tgt, weight)
    return rot


__all__ = ["hands_back", "straighten", "trunk_spheres"]
