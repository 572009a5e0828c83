"""Handing an object over, solved on both bodies: "John gives the cup to Anna".

The giver's plan (services.motion.planning) walks up to the receiver, holds the object out to the point
between the two and lets go of it there (its prop track ends at the hand-off frame). Each character's
motion is synthesised alone, so here, once the story is on one time line, the receiver's arm reaches that
point at that frame (two-bone IK on the receiver's own skeleton, faded in before and out after, so nothing
pops) and the object goes on in the receiver's hand: a prop track from the hand-off until the receiver's
own next track of it (its later actions hold it: the orchestrator's end state says so) or the story's end.
Over the first frames the object turns from how the giver held it to how the receiver holds it, with its
grip point on the receiver's hand in every frame.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import msgspec
import numpy as np

from proto.motion import PairedAction
from proto.motion_data import Motion, PropTrack
from wana.arrays import from_wire, to_wire
from wana.domain import quat
from wana.domain.skeleton import JOINT_INDEX, forward_kinematics

HANDOVER_CLIP = "present"  # the clip that closes a hand-over (PairedAction.action)
REACH_FRAMES = 18  # frames the receiver's arm takes to come up to the hand-off point (and to settle after)
TURN_FRAMES = 12  # frames over which the object turns from the giver's grip to the receiver's
TOWARDS_M = 0.04  # metres the receiver's hand stays short of the giver's, towards the receiver
REACH_MAX = 1.6  # metres between the two hips beyond which the receiver's arm is not pulled over


def _offsets(name: str) -> np.ndarray:
    from services.motion.pairs import offsets_of

    return offsets_of(name)


def _rest_rotation(joint: str) -> np.ndarray:
    from services.motion.synthesis import _hand_at_rest

    return _hand_at_rest(joint)


def _released(giver: Motion, action_index: int) -> PropTrack | None:
    """The giver's prop track that ends during its hand-over action (the let-go), None when it holds none."""
    segs = [s for s in giver.segments if s.action_index == action_index]
    if not segs:
        return None
    lo, hi = min(s.start_frame for s in segs), max(s.end_frame for s in segs)
    ending = [t for t in giver.props if lo < t.end_frame < hi]
    return max(ending, key=lambda t: t.end_frame, default=None)


def _receive(
    receiver: Motion, gave: PropTrack, rotations: np.ndarray, root: np.ndarray
) -> tuple[np.ndarray, PropTrack]:
    """The receiver's rotations with its arm at the hand-off and the object's track in its hand."""
    from services.motion.pairs import profile, two_bone

    frames = len(root)
    at = gave.end_frame  # the first frame the giver no longer holds it
    origin = from_wire(gave.position).astype(np.float64)[-1]
    turn = from_wire(gave.rotation).astype(np.float64)[-1]
    grip = np.asarray(gave.grip, np.float64)
    point = origin + quat.rotate(turn, grip)  # the giver's grip point at the let-go, world
    offsets = _offsets(receiver.character)
    away = root[min(at, frames - 1), [0, 2]] - point[[0, 2]]
    reach = np.linalg.norm(away)
    if reach <= REACH_MAX:
        goal = point.copy()
        goal[[0, 2]] += away / max(reach, 1e-9) * TOWARDS_M
        weight = profile(frames, at - REACH_FRAMES, at - 1, at + 1, at + REACH_FRAMES)
        target = np.broadcast_to(goal, (frames, 3))
        rotations = two_bone(rotations, root, offsets, gave.joint, target, weight)
    later = [t.start_frame for t in receiver.props if t.object_id == gave.object_id and t.start_frame >= at]
    end = max(at + 1, min([*later, frames]))
    pos, grot = forward_kinematics(rotations[at:end], root[at:end], offsets)
    j = JOINT_INDEX[gave.joint]
    held = quat.normalize(
        quat.mul(grot[:, j], np.broadcast_to(quat.inv(_rest_rotation(gave.joint)), (end - at, 4)))
    )
    n = min(len(held), TURN_FRAMES)
    w = np.linspace(0.0, 1.0, n)
    held[:n] = quat.slerp(np.broadcast_to(turn, (n, 4)), held[:n], w * w * (3 - 2 * w))
    held = quat.normalize(held)
    track_origin = pos[:, j] - quat.rotate(held, np.broadcast_to(grip, (end - at, 3)))
    track = PropTrack(
        object_id=gave.object_id,
        joint=gave.joint,
        start_frame=at,
        end_frame=end,
        grip=gave.grip,
        position=to_wire(track_origin.astype(np.float32)),
        rotation=to_wire(held.astype(np.float32)),
    )
    return rotations, track


def hand_over(
    motions: Mapping[str, Motion], pairs: Sequence[PairedAction]
) -> tuple[dict[str, Motion], list[str]]:
    """Every hand-over of the story passed from the giver's hand to the receiver's (see the module docstring).

    Args:
        motions: name -> the character's whole motion on the story's time line.
        pairs: the story's paired actions; those of HANDOVER_CLIP with a partner are hand-overs.

    Returns:
        the motions (receivers replaced) and diagnostics.
    """
    out = dict(motions)
    notes: list[str] = []
    for pair in pairs:
        if pair.action != HANDOVER_CLIP or not pair.partner:
            continue
        giver, receiver = out.get(pair.actor), out.get(pair.partner)
        if giver is None or receiver is None:
            continue
        gave = _released(giver, pair.action_index)
        if gave is None:
            notes.append(f"{pair.actor} has nothing in the hand to give {pair.partner}")
            continue
        rotations = from_wire(receiver.rotations).astype(np.float64)
        root = from_wire(receiver.root_position).astype(np.float64)
        if gave.end_frame >= len(root):
            continue
        rotations, track = _receive(receiver, gave, rotations, root)
        out[pair.partner] = msgspec.structs.replace(
            receiver,
            rotations=to_wire(quat.normalize(rotations).astype(np.float32)),
            props=sorted([*receiver.props, track], key=lambda t: t.start_frame),
        )
    return out, notes


__all__ = ["HANDOVER_CLIP", "hand_over"]
