"""Per-frame body tests over a whole motion: inside furniture, inside another body, too fast, popping.

Each test returns, per frame, whether it fails and what is worst there, so that the story checks can cut the
frames of each sentence out of one pass over the motion (the editor runs this on every edit).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wana.domain.skeleton import JOINT_INDEX, JOINT_NAMES
from wana.fidelity.bodies import Body
from wana.fidelity.world import World, point_box_distance

PENETRATION_M = 0.03  # a body part may sink this far into furniture or another body (soft contact)
HIPS_MAX_MS = 6.0  # metres per second between two frames
HANDS_MAX_MS = 10.0
POP_M = 0.10  # metres: a joint jumping this far (relative to the hips) in one frame at an action boundary
POP_RATIO = 3.0  # ... and this many times more than it moves on the frames around the boundary


@dataclass(frozen=True)
class FrameFailures:
    """Which frames fail one test, and what is worst on each failing frame.

    Attributes:
        failing: (T,) bool.
        amount: (T,) metres (depth inside, or speed in m/s for continuity) of the worst part, 0 where fine.
        what: (T,) object id or other character at fault ("" where fine).
        joint: (T,) index of the worst joint (-1 where fine).
    """

    failing: np.ndarray
    amount: np.ndarray
    what: np.ndarray
    joint: np.ndarray

    @classmethod
    def none(cls, frames: int) -> FrameFailures:
        return cls(
            np.zeros(frames, bool),
            np.zeros(frames),
            np.full(frames, "", object),
            np.full(frames, -1, np.int64),
        )


def penetration(body: Body, world: World, exempt: dict[str, np.ndarray]) -> FrameFailures:
    """Frames where a body part is more than PENETRATION_M inside a piece of furniture.

    Args:
        body: the character.
        world: the room.
        exempt: object id -> (T, P) bool: the body spheres and frames whose touching it is the stated contact
            (the whole body on the chair being sat on, the arms on the desk under the laptop being typed on).
    """
    out = FrameFailures.none(body.frames)
    frame_box = body.bounds  # (T, 2, 3)
    r = body.radii[None, :, None]
    for placed, boxes, outer in world.solids:
        frames = np.nonzero(np.all((frame_box[:, 0] <= outer[1]) & (frame_box[:, 1] >= outer[0]), axis=1))[0]
        if not len(frames):
            continue
        pts = body.points[frames]
        near = np.zeros((body.frames, len(body.radii)), bool)
        near[frames] = np.all((pts >= outer[0] - r) & (pts <= outer[1] + r), axis=2)  # (T, P)
        allowed = exempt.get(placed.id)
        if allowed is not None:
            near &= ~allowed
        if not near.any():
            continue
        t_idx, p_idx = np.nonzero(near)
        centres = body.points[t_idx, p_idx]
        reach = float(body.radii.max())
        lo, hi = centres.min(axis=0) - reach, centres.max(axis=0) + reach
        boxes = boxes[
            np.all((boxes[:, 0] <= hi) & (boxes[:, 1] >= lo), axis=1)
        ]  # only boxes a sphere can reach
        if not len(boxes):
            continue
        depth = body.radii[p_idx] - point_box_distance(centres, boxes).min(axis=1)
        deep = depth > PENETRATION_M
        if not deep.any():
            continue
        t_idx, p_idx, depth = t_idx[deep], p_idx[deep], depth[deep]
        # keep the deepest part per frame
        order = np.lexsort((-depth, t_idx))
        t_idx, p_idx, depth = t_idx[order], p_idx[order], depth[order]
        first = np.r_[True, t_idx[1:] != t_idx[:-1]]
        t_idx, p_idx, depth = t_idx[first], p_idx[first], depth[first]
        worse = depth > out.amount[t_idx]
        t_idx, p_idx, depth = t_idx[worse], p_idx[worse], depth[worse]
        out.failing[t_idx] = True
        out.amount[t_idx] = depth
        out.what[t_idx] = placed.id
        out.joint[t_idx] = body.point_joint[p_idx]
    return out


def overlap(a: Body, b: Body, allowed: np.ndarray | None = None) -> tuple[FrameFailures, FrameFailures]:
    """Frames where two characters' bodies interpenetrate by more than PENETRATION_M (one result per side).

    Args:
        a, b: the two characters (compared on the frames both have).
        allowed: (T,) frames where they touch on purpose (a hug, a handshake), not tested.
    """
    frames = min(a.frames, b.frames)
    fa, fb = FrameFailures.none(a.frames), FrameFailures.none(b.frames)
    ba, bb = a.bounds[:frames], b.bounds[:frames]
    test = np.all((ba[:, 0] < bb[:, 1] - PENETRATION_M) & (bb[:, 0] < ba[:, 1] - PENETRATION_M), axis=1)
    if allowed is not None:
        test &= ~allowed[:frames]
    t = np.nonzero(test)[0]
    if not len(t):
        return fa, fb
    pa, pb = a.points[t].astype(np.float32), b.points[t].astype(np.float32)  # (n, P, 3)
    sq = (
        (pa * pa).sum(-1)[:, :, None]
        + (pb * pb).sum(-1)[:, None, :]
        - 2.0 * np.einsum("npc,nqc->npq", pa, pb)
    )
    depth = a.radii[None, :, None] + b.radii[None, None, :] - np.sqrt(np.maximum(sq, 0.0))  # (n, P, Q)
    flat = depth.reshape(len(t), -1)
    worst = flat.argmax(axis=1)
    amount = flat[np.arange(len(t)), worst]
    bad = amount > PENETRATION_M
    i, j = np.unravel_index(worst[bad], depth.shape[1:])
    for out, other, joint in ((fa, b.name, a.point_joint[i]), (fb, a.name, b.point_joint[j])):
        out.failing[t[bad]] = True
        out.amount[t[bad]] = amount[bad]
        out.what[t[bad]] = other
        out.joint[t[bad]] = joint
    return fa, fb


def speeds(body: Body, fps: int) -> FrameFailures:
    """Frames reached too fast: the hips over HIPS_MAX_MS or a hand over HANDS_MAX_MS since the frame before."""
    out = FrameFailures.none(body.frames)
    if body.frames < 2:
        return out
    limits = {"Hips": HIPS_MAX_MS, "LeftHand": HANDS_MAX_MS, "RightHand": HANDS_MAX_MS}
    for name, limit in limits.items():
        v = np.linalg.norm(np.diff(body.joint(name), axis=0), axis=1) * fps  # (T-1,) m/s into frame t+1
        bad = np.nonzero((v > limit) & (v > out.amount[1:]))[0] + 1
        out.failing[bad] = True
        out.amount[bad] = v[bad - 1]
        out.joint[bad] = JOINT_INDEX[name]
        out.what[bad] = "speed"
    return out


def pops(body: Body, boundaries: list[int]) -> FrameFailures:
    """Action boundaries where the pose jumps: a joint moves (relative to the hips) POP_M in one frame and
    POP_RATIO times more than on the frames around it."""
    out = FrameFailures.none(body.frames)
    rel = body.joints - body.joints[:, :1]
    step = np.zeros((body.frames, len(JOINT_NAMES)))
    step[1:] = np.linalg.norm(np.diff(rel, axis=0), axis=2)  # (T, J): how far each joint moved into frame t
    for b in boundaries:
        if not 0 < b < body.frames:
            continue
        around = [f for f in (b - 2, b - 1, b + 1, b + 2) if 0 < f < body.frames]
        usual = step[around].mean(axis=0) if around else np.zeros(len(JOINT_NAMES))
        jump = step[b]
        bad = (jump > POP_M) & (jump > POP_RATIO * usual)
        if bad.any():
            j = int(np.argmax(np.where(bad, jump, 0.0)))
            out.failing[b] = True
            out.amount[b] = float(jump[j])
            out.joint[b] = j
            out.what[b] = "pop"
    return out


__all__ = ["FrameFailures", "overlap", "penetration", "pops", "speeds"]
