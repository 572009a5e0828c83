"""Arm clearance: a free arm swings clear of the furniture it would pass through.

The gait's arm swing, an action clip's free hand and the arm of a character who turns beside a cabinet are
played as authored, whatever stands at the elbow: the left hand of a walker passing a filing cabinet, the
fingers of a one-handed action in the counter beside it. Here, after a segment is synthesised, the arm's
capsule spheres (forearm, hand, fingers, as the story checks sample them: wana.fidelity.bodies) are tested
against the solids of the scene's furniture (wana.fidelity.solids); on the frames where one is visibly inside,
the whole arm turns about the shoulder by the smallest rotation that takes its deepest sphere out along the
solid's outward direction. The corrections are spread over neighbouring frames (held at their peak, then
eased) so that the arm does not jump, and a hand at a contact point (IK'd onto the object) is left where it is.
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np

from proto.scene import PlacedObject, Scene
from services.motion.clearance import deepest, furniture, seated_on, spread_turns
from services.motion.ik import global_transforms
from services.motion.planning import resting_on
from services.motion.synthesis import MotionPiece, held_prop
from services.motion.trunk_clearance import hands_back, straighten
from wana.domain import quat
from wana.domain.skeleton import JOINT_INDEX, PARENTS
from wana.fidelity.bodies import ALONG, BONE_RADII
from wana.fidelity.solids import depth_inside

ROUNDS = 5  # correct, spread, test again: a turn out of one object can graze another
STEP_M = 0.01  # metres: the finite difference that finds a solid's outward direction
MAX_TURN = np.radians(35.0)  # radians: an arm is never turned further than this in one round
BONES = (("ForeArm", "Hand"), ("Hand", "HandMiddle1"))  # per side: the bones whose spheres are tested
SHOULDER = "Arm"  # the joint the arm turns about


@functools.lru_cache(maxsize=2)
def _layout(side: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(P,) parent joint, child joint and share along the bone of each tested sphere, and (P,) radii."""
    parent, child, share, radii = [], [], [], []
    for a, b in BONES:
        for t in (*ALONG, 1.0):
            parent.append(JOINT_INDEX[side + a])
            child.append(JOINT_INDEX[side + b])
            share.append(t)
            radii.append(BONE_RADII[side + b])
    return np.array(parent), np.array(child), np.array([share, radii])


def _spheres(pos: np.ndarray, side: str) -> tuple[np.ndarray, np.ndarray]:
    """(T, P, 3) sphere centres of one arm and their (P,) radii."""
    parent, child, sr = _layout(side)
    share, radii = sr
    return pos[:, parent] + share[None, :, None] * (pos[:, child] - pos[:, parent]), radii


def _outward(placed: PlacedObject, points: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """(n, 3) unit directions in which each point leaves the object fastest (finite differences of depth)."""
    grad = np.zeros_like(points)
    for axis in range(3):
        step = np.zeros(3)
        step[axis] = STEP_M
        grad[:, axis] = depth_inside(placed, points + step, radii) - depth_inside(
            placed, points - step, radii
        )
    out = -grad
    norm = np.linalg.norm(out, axis=1, keepdims=True)
    flat = norm[:, 0] < 1e-9
    out[flat] = (0.0, 1.0, 0.0)  # deep in a solid with no slope: up, out of a top
    norm[flat] = 1.0
    return out / norm


def clear_arms(
    rotations: np.ndarray,
    root: np.ndarray,
    offsets: np.ndarray,
    solids: list[tuple[PlacedObject, np.ndarray, float]],
    keep: dict[str, np.ndarray] | None = None,
    worked: dict[str, frozenset[str]] | None = None,
) -> np.ndarray:
    """Turn each arm about its shoulder out of the furniture it goes into.

    Args:
        rotations: (T, J, 4) local joint rotations of a piece.
        root: (T, 3) world hips positions, metres.
        offsets: (J, 3) the character's rest offsets (the skeleton the checks and the renderer play).
        solids: the room's furniture (``furniture``).
        keep: side ("Left", "Right") -> (T,) bool: frames whose hand is at a contact point and stays there.
        worked: side -> ids of the objects that side's hand works at (the bench under the nail hammered):
            not in its way.

    Returns:
        (T, J, 4) rotations with the arms' shoulder joints turned where they were inside furniture.
    """
    keep = keep or {}
    worked = worked or {}
    rot = np.array(rotations, dtype=np.float64, copy=True)
    t = len(rot)
    if not solids or t == 0:
        return rot
    seat = seated_on(np.asarray(root, dtype=np.float64), solids)
    skips = {
        side: seat | np.array([o.id in worked.get(side, frozenset()) for o, _, _ in solids], bool)[None, :]
        for side in ("Left", "Right")
    }
    for _ in range(ROUNDS):
        pos, grot = global_transforms(rot, root, offsets)
        changed = False
        for side in ("Left", "Right"):
            centres, radii = _spheres(pos, side)
            excess, worst, owner = deepest(centres, radii, solids, skips[side])
            fix = (owner >= 0) & (excess > 0)
            held = keep.get(side)
            if held is not None:
                fix &= ~held[:t]
            if not fix.any():
                continue
            turn = np.zeros((t, 3))
            shoulder = pos[:, JOINT_INDEX[side + SHOULDER]]
            elbow = pos[:, JOINT_INDEX[side + "ForeArm"]]
            for k in np.unique(owner[fix]):
                f = np.nonzero(fix & (owner == k))[0]
                p = centres[f, worst[f]]
                out = _outward(solids[k][0], p, radii[worst[f]])
                # a thin part (a chair's back, a table top) pierced through has no good side: out on the
                # elbow's, as the arm came in, so that neighbouring frames do not push it through either way
                back = np.sum(out * (elbow[f] - p), axis=1) < 0
                out[back] *= -1.0
                arm = p - shoulder[f]
                moved = arm + out * excess[f, None]
                axis = np.cross(arm, moved)
                sin = np.linalg.norm(axis, axis=1)
                angle = np.minimum(np.arctan2(sin, np.sum(arm * moved, axis=1)), MAX_TURN)
                ok = sin > 1e-9
                turn[f[ok]] = axis[ok] / sin[ok, None] * angle[ok, None]
            spread = spread_turns(turn, held[:t] if held is not None else np.zeros(t, bool))
            angle = np.linalg.norm(spread, axis=1)
            moving = angle > 1e-6
            if not moving.any():
                continue
            j = JOINT_INDEX[side + SHOULDER]
            parent = grot[moving, PARENTS[j]]
            world_turn = quat.from_axis_angle(spread[moving] / angle[moving, None], angle[moving])
            local_turn = quat.mul(quat.mul(quat.inv(parent), world_turn), parent)
            rot[moving, j] = quat.normalize(quat.mul(local_turn, rot[moving, j]))
            changed = True
        if not changed:
            break
    return rot


def clear_piece(piece: MotionPiece, scene: Scene, offsets: np.ndarray) -> MotionPiece:
    """The piece with its trunk straightened out of the furniture it bends into (trunk_clearance), then its
    free arms turned out of the room's furniture; a hand on its contact point keeps its
    frames, the object sat or lain on (the stated contact) and the held prop are not in the way, nor is what a
    working hand (the one on the object, the one with the tool) works at and what that rests on."""
    seg = piece.segment
    solids = furniture(scene, frozenset({seg.prop} if seg.prop else ()))
    by_id = {o.id: o for o in scene.objects}
    target = by_id.get(seg.target_id)
    at = frozenset() if target is None else resting_on(scene, target.support or target.id) | {target.id}
    working = {_side_of(j) for j in piece.contact_frames if "Hand" in j}
    if seg.prop:
        working.add(_side_of(seg.prop_joint))
    t = len(piece.rotations)
    keep: dict[str, np.ndarray] = {}
    for joint, (frames, _) in piece.contact_frames.items():
        side = _side_of(joint)
        if side and "Hand" in joint:
            mask = keep.setdefault(side, np.zeros(t, bool))
            mask[np.asarray(frames, int)[(np.asarray(frames, int) >= 0) & (np.asarray(frames, int) < t)]] = (
                True
            )
    worked = {side: at for side in working if side}
    rot, straightened = straighten(piece.rotations, piece.root, offsets, solids)
    if straightened:  # the hands on their contact points again, from the straightened shoulders
        rot = hands_back(rot, piece.root, piece.contact_frames)
    rot = clear_arms(rot, piece.root, offsets, solids, keep, worked)
    cleared = dataclasses.replace(piece, rotations=quat.normalize(rot))
    if seg.prop:  # the prop goes on in the hand where the hand now is
        cleared.props = [held_prop(cleared)]
    return cleared


def _side_of(joint: str) -> str:
    return "Left" if joint.startswith("Left") else "Right" if joint.startswith("Right") else ""
