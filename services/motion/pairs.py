"""Two-person interactions solved on both bodies: hug, handshake, high five, holding hands, a hand on the
shoulder, a kiss on the cheek, a push.

Each character's motion is synthesised alone, so an actor's hug clip closes its arms round the air where the
partner stands, and the partner stands passive. This pass runs once the story is on one time line (both
motions on the same frames): over the actor's clip it turns the partner to face the actor, leans both in
when the clip needs it (a hug), gives the partner its answer (the actor's own arm pose, as the text does not
say otherwise: a hug is returned, a handshake has two hands, a high five two palms), and then solves both
arms together with two-bone IK towards shared contact points: the two hands of a handshake meet at the point
between them, the arms of a hug reach the other's back. IK runs on each character's own skeleton (the rest
offsets the renderer and the story checks use), so the hands meet on screen, not on the reference skeleton.
At the clip's contact frames (its interaction window) the contact joints are at their targets; outside them
the correction fades out, so nothing pops.

Over 400 lines because the pieces of one solve (the table of paired actions, the IK on a character's own
skeleton, turning, leaning, the answer pose, aligning a pair's two clips and the guards) only make sense
together and are used nowhere else.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import lru_cache

import msgspec
import numpy as np

from proto.motion import PairContact, PairedAction
from proto.motion_data import Motion, Segment
from wana.arrays import from_wire, to_wire
from wana.domain import quat
from wana.domain.actions import get_clip
from wana.domain.skeleton import JOINT_INDEX, JOINT_NAMES, forward_kinematics

# Body sphere radii (metres) of the joints a hand may rest on: as the story checks' capsules
# (wana.fidelity.bodies.BONE_RADII), so a hand put on the surface touches it there too.
SURFACE_M = {"Spine1": 0.11, "Spine2": 0.12, "LeftArm": 0.045, "RightArm": 0.045}
OUTSIDE_M = 0.005  # a hand rests this far outside the surface it touches
ANSWER_FRAMES = 15  # frames at least that the partner's answering hand takes to reach the contact
RAMP_FRAMES = 12  # frames the partner's turn and answer fade in before the actor's clip and out after it
TWIST_MAX = 0.8  # radians a seated body's chest turns towards the other at most (its hips stay on the seat)
SPINE = ("Spine", "Spine1", "Spine2")
TURN_MIN = 0.12  # radians: a partner this far off facing the actor is turned towards them
MEET_MARGIN = 0.9  # share of the partner's reach a bending actor's hand comes within (the point between them)
REACH_SHARE = 0.93  # a meeting point is kept within this share of each arm's straight reach
HANDS_MAX_MS = 9.0  # m/s: a fit that moves a hand faster than this is dropped (the story checks allow 10)
BUSY_HIPS_M = 0.1  # metres the partner's hips rise or drop during the clip that mean it sits down or gets up
SEATED_HIPS_M = 0.75  # metres: hips lower than this are seated
# radians the actor may bend down to reach the other's shoulder or back (a seated partner's, from behind)
LEAN_STEPS = (0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7)
REACH_MAX = 1.6  # metres between the two hips beyond which no contact is attempted (nobody walked up)
ARM_JOINTS = tuple(
    n for n in JOINT_NAMES if n.startswith(("LeftShoulder", "LeftArm", "LeftForeArm", "LeftHand"))
)
CHAINS = {  # end joint -> (upper, middle)
    "LeftHand": ("LeftArm", "LeftForeArm"),
    "RightHand": ("RightArm", "RightForeArm"),
    "LeftHandMiddle1": ("LeftArm", "LeftForeArm"),
    "RightHandMiddle1": ("RightArm", "RightForeArm"),
}


@dataclass(frozen=True)
class Touch:
    """A hand on the other's body: ``joint`` goes to the surface of the other's ``on`` sphere, on the side
    ``towards`` points in the other's facing frame (x: their left, y: up, z: their front)."""

    joint: str
    on: str
    towards: tuple[float, float, float]


@dataclass(frozen=True)
class PairSpec:
    """How one paired action is solved.

    Attributes:
        actor: the actor's hands on the partner's body.
        partner: the partner's hands on the actor's body (its answer), () when it stays passive.
        meet: (actor joint, partner joint) pairs that meet at the point between them (a handshake).
        answer: "same" (the partner copies the actor's arm pose), "mirror" (left and right swapped: holding
            hands, the actor's right in the partner's left), or "" (no answer).
        lean: radians both lean towards each other during the clip (a hug).
    """

    actor: tuple[Touch, ...] = ()
    partner: tuple[Touch, ...] = ()
    meet: tuple[tuple[str, str], ...] = ()
    answer: str = ""
    lean: float = 0.0


BACK = (
    0.66  # share of a hug's hand direction that is "back" (the rest: the flank; the fingers reach the back)
)
PAIRS: dict[str, PairSpec] = {
    "hug": PairSpec(
        actor=(
            Touch("LeftHand", "Spine2", (-0.75, 0.0, -BACK)),
            Touch("RightHand", "Spine2", (0.75, 0.0, -BACK)),
        ),
        partner=(
            Touch("LeftHand", "Spine1", (-0.75, 0.0, -BACK)),
            Touch("RightHand", "Spine1", (0.75, 0.0, -BACK)),
        ),
        answer="same",
        lean=0.22,
    ),
    "shake_hands": PairSpec(meet=(("RightHand", "RightHand"),), answer="same"),
    "high_five": PairSpec(meet=(("RightHandMiddle1", "RightHandMiddle1"),), answer="same"),
    "hold_hands": PairSpec(meet=(("RightHand", "LeftHand"),), answer="mirror"),
    "comfort": PairSpec(actor=(Touch("RightHand", "LeftArm", (0.3, 1.0, 0.0)),)),
    "kiss_cheek": PairSpec(actor=(Touch("RightHand", "LeftArm", (0.7, 0.7, 0.0)),), lean=0.08),
    "push_person": PairSpec(
        actor=(
            Touch("LeftHand", "Spine2", (-0.35, 0.0, 0.94)),
            Touch("RightHand", "Spine2", (0.35, 0.0, 0.94)),
        )
    ),
}


@lru_cache(maxsize=32)
def offsets_of(name: str) -> np.ndarray:
    """(J, 3) rest offsets of the character who plays ``name`` (the renderer's pick; an unknown name gets a
    built-in character chosen by the sum of its letters, as wana.fidelity.bodies does)."""
    from wana.assets.characters import character_for

    return np.asarray(character_for(name).offsets, dtype=np.float64)


def _smooth(u: np.ndarray) -> np.ndarray:
    u = np.clip(u, 0.0, 1.0)
    return u * u * (3 - 2 * u)


def profile(frames: int, start: int, full: int, until: int, end: int) -> np.ndarray:
    """(frames,) weights: 0 before ``start``, rising to 1 at ``full``, 1 until ``until``, 0 again at ``end``."""
    f = np.arange(frames, dtype=np.float64)
    up = _smooth((f - start) / max(full - start, 1)) if full > start else (f >= start).astype(float)
    down = 1.0 - _smooth((f - until) / max(end - until, 1)) if end > until else (f < until).astype(float)
    return np.minimum(up, down)


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.maximum(np.linalg.norm(v, axis=-1, keepdims=True), 1e-9)


def _angle(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.arccos(np.clip(np.einsum("...i,...i->...", _unit(a), _unit(b)), -1.0, 1.0))


def two_bone(
    rotations: np.ndarray,
    root: np.ndarray,
    offsets: np.ndarray,
    end: str,
    target: np.ndarray,
    weight: np.ndarray,
) -> np.ndarray:
    """Bring ``end`` (a hand or its middle finger) to ``target`` on a skeleton with its own rest offsets.

    The analytic two-bone solution (after D. Holden, as services.motion.ik) from world joint positions, so
    any rest offsets work; two passes, then a slerp by ``weight``.

    Args:
        rotations: (T, J, 4) local rotations (not modified).
        root: (T, 3) hips positions.
        offsets: (J, 3) the character's rest offsets.
        end: a key of CHAINS.
        target: (T, 3) world targets.
        weight: (T,) in [0, 1].

    Returns:
        new (T, J, 4) local rotations.
    """
    out = rotations.copy()
    idx = np.flatnonzero(weight > 1e-6)
    if not len(idx):
        return out
    ua, mb = (JOINT_INDEX[n] for n in CHAINS[end])
    ec = JOINT_INDEX[end]
    sub = rotations[idx].copy()
    tgt = target[idx]
    for _ in range(2):
        pos, grot = forward_kinematics(sub, root[idx], offsets)
        a, b, c = pos[:, ua], pos[:, mb], pos[:, ec]
        g_a, g_b = grot[:, ua], grot[:, mb]
        lab, lcb = np.linalg.norm(b - a, axis=1), np.linalg.norm(c - b, axis=1)
        lat = np.clip(np.linalg.norm(tgt - a, axis=1), 0.01, lab + lcb - 1e-3)
        ac_ab_0, ba_bc_0, ac_at_0 = _angle(c - a, b - a), _angle(a - b, c - b), _angle(c - a, tgt - a)
        ac_ab_1 = np.arccos(np.clip((lcb**2 - lab**2 - lat**2) / (-2 * lab * lat), -1, 1))
        ba_bc_1 = np.arccos(np.clip((lat**2 - lab**2 - lcb**2) / (-2 * lab * lcb), -1, 1))
        axis0 = quat.cross(c - a, b - a)
        straight = np.linalg.norm(axis0, axis=1) < 1e-6
        if straight.any():  # a straight arm bends its elbow down
            axis0[straight] = quat.cross(c - a, np.broadcast_to([0.0, -1.0, 0.0], (len(idx), 3)))[straight]
        axis0 = _unit(axis0)
        axis1 = quat.cross(c - a, tgt - a)
        n1 = np.linalg.norm(axis1, axis=1, keepdims=True)
        axis1 = np.where(n1 > 1e-9, axis1 / np.maximum(n1, 1e-9), axis0)
        ga_inv, gb_inv = quat.inv(g_a), quat.inv(g_b)
        r0 = quat.from_axis_angle(quat.rotate(ga_inv, axis0), ac_ab_1 - ac_ab_0)
        r1 = quat.from_axis_angle(quat.rotate(gb_inv, axis0), ba_bc_1 - ba_bc_0)
        r2 = quat.from_axis_angle(quat.rotate(ga_inv, axis1), ac_at_0)
        sub[:, ua] = quat.normalize(quat.mul(sub[:, ua], quat.mul(r0, r2)))
        sub[:, mb] = quat.normalize(quat.mul(sub[:, mb], r1))
    w = weight[idx]
    out[idx, ua] = quat.slerp(rotations[idx, ua], sub[:, ua], w)
    out[idx, mb] = quat.slerp(rotations[idx, mb], sub[:, mb], w)
    return out


def _facing(rotations: np.ndarray) -> np.ndarray:
    """(T,) heading of the hips, radians about +Y (0 faces +Z)."""
    return quat.yaw_of(rotations[:, 0])


def _wrap(a: np.ndarray) -> np.ndarray:
    return (a + math.pi) % (2 * math.pi) - math.pi


def turn_towards(
    rotations: np.ndarray, root: np.ndarray, other: np.ndarray, weight: np.ndarray
) -> np.ndarray:
    """Hips turned (about +Y, by ``weight``) to face ``other`` (T, 3) where they are off by more than TURN_MIN."""
    d = other[:, [0, 2]] - root[:, [0, 2]]
    want = np.arctan2(d[:, 0], d[:, 1])
    err = _wrap(want - _facing(rotations))
    err = np.where(np.abs(err) > TURN_MIN, err, 0.0)
    # one correction over the whole interaction (the mean where it is in force), so the turn does not wobble
    w = weight > 1e-6
    if not w.any():
        return rotations
    delta = float(np.angle(np.exp(1j * err[w]).mean()))
    out = rotations.copy()
    out[:, 0] = quat.normalize(quat.mul(quat.yaw(delta * weight), rotations[:, 0]))
    return out


def twist_towards(
    rotations: np.ndarray, root: np.ndarray, other: np.ndarray, weight: np.ndarray
) -> np.ndarray:
    """A seated body's chest turned (about its spine, by ``weight``) towards ``other`` (T, 3), by at most
    TWIST_MAX radians shared over the three spine joints: the hips stay square to the seat, the shoulders face
    the one who comes to shake hands (a hand reaching back over the shoulder instead: duo-meeting_room-07)."""
    d = other[:, [0, 2]] - root[:, [0, 2]]
    err = _wrap(np.arctan2(d[:, 0], d[:, 1]) - _facing(rotations))
    w = weight > 1e-6
    if not w.any():
        return rotations
    delta = float(np.clip(np.angle(np.exp(1j * err[w]).mean()), -TWIST_MAX, TWIST_MAX))
    out = rotations.copy()
    turn = quat.yaw(delta / len(SPINE) * weight)
    for joint in SPINE:
        j = JOINT_INDEX[joint]
        out[:, j] = quat.normalize(quat.mul(turn, rotations[:, j]))
    return out


def lean_in(rotations: np.ndarray, pitch: float, weight: np.ndarray) -> np.ndarray:
    """The spine leant forward by ``pitch`` radians (in the hips' frame), by ``weight``."""
    if pitch == 0.0:
        return rotations
    out = rotations.copy()
    spine = JOINT_INDEX["Spine"]
    bend = quat.from_axis_angle(np.array([1.0, 0.0, 0.0]), pitch * weight)
    out[:, spine] = quat.normalize(quat.mul(bend, rotations[:, spine]))
    return out


def _mirror(q: np.ndarray) -> np.ndarray:
    """A local rotation reflected across the body's mid plane (x -> -x): left and right swapped."""
    return q * np.array([1.0, -1.0, -1.0, 1.0])


def answer_pose(rotations: np.ndarray, actor: np.ndarray, how: str, weight: np.ndarray) -> np.ndarray:
    """The partner's arms blended (by ``weight``) towards the actor's arm pose: "same" side or "mirror"ed."""
    if not how:
        return rotations
    out = rotations.copy()
    for name in ARM_JOINTS:
        for side, other in (("Left", "Right"), ("Right", "Left")):
            mine = JOINT_INDEX[name.replace("Left", side)]
            theirs = JOINT_INDEX[name.replace("Left", other if how == "mirror" else side)]
            src = _mirror(actor[:, theirs]) if how == "mirror" else actor[:, theirs]
            out[:, mine] = quat.slerp(rotations[:, mine], src, weight)
    return out


def surface_point(pos: np.ndarray, grot: np.ndarray, touch: Touch) -> np.ndarray:
    """(T, 3) world point on the surface of ``touch.on``'s sphere, on the side ``touch.towards`` points to in
    the chest's facing frame (a seated body's chest turned to the actor has its back turned too: with the
    hips' heading a hug's hands went to mom's flank, group-living_room-03 s12)."""
    heading = quat.yaw_of(grot[:, JOINT_INDEX["Spine2"]])
    d = np.asarray(touch.towards, float)
    d = d / np.linalg.norm(d)
    turned = quat.rotate(quat.yaw(heading), np.broadcast_to(d, (len(heading), 3)))
    return pos[:, JOINT_INDEX[touch.on]] + turned * (SURFACE_M[touch.on] + OUTSIDE_M)


@dataclass
class _Side:
    """One character's frames of an interaction, being edited."""

    name: str
    rotations: np.ndarray  # (W, J, 4)
    root: np.ndarray  # (W, 3)
    offsets: np.ndarray

    def fk(self) -> tuple[np.ndarray, np.ndarray]:
        return forward_kinematics(self.rotations, self.root, self.offsets)


def _window(seg: Segment, clip_name: str) -> tuple[int, int]:
    """The clip's contact frames (its interaction window) on the story's frames, as the story checks take them."""
    clip = get_clip(clip_name)
    length = seg.end_frame - seg.start_frame
    window = clip.interaction.window if clip.interaction is not None else (0.0, 0.0)
    if clip.looping or clip.duration_s <= 0 or window[1] <= window[0]:
        return seg.start_frame, seg.end_frame
    a = seg.start_frame + round(window[0] / clip.duration_s * length)
    b = seg.start_frame + round(window[1] / clip.duration_s * length)
    return a, max(b, a + 1)


def _present(motion: Motion) -> np.ndarray:
    frames = int(motion.root_position.shape[0])
    if motion.present is None:
        return np.ones(frames, bool)
    on = from_wire(motion.present).astype(bool).reshape(-1)
    return (
        np.pad(on, (0, max(0, frames - len(on))), mode="edge")[:frames] if len(on) else np.ones(frames, bool)
    )


def _partner(pair: PairedAction, motions: Mapping[str, Motion], at: int) -> str:
    """The named partner, else the nearest other character on stage at frame ``at``."""
    if pair.partner and pair.partner in motions and pair.partner != pair.actor:
        return pair.partner
    me = from_wire(motions[pair.actor].root_position)
    best, best_d = "", math.inf
    for name, motion in motions.items():
        if name == pair.actor:
            continue
        root = from_wire(motion.root_position)
        if at >= len(root) or at >= len(me) or not _present(motion)[at]:
            continue
        d = float(np.linalg.norm(root[at, [0, 2]] - me[at, [0, 2]]))
        if d < best_d:
            best, best_d = name, d
    return best


def _segment(motion: Motion, pair: PairedAction) -> Segment | None:
    for seg in motion.segments:
        if seg.action_index == pair.action_index and seg.action == pair.action:
            return seg
    return None


def _together(theirs: Segment, mine: Segment) -> bool:
    """True when the partner's segment is its half of the same action as ``mine``: of the same sentence (the one
    who walks up from far away starts its clip after the other's has ended), else overlapping in time."""
    if theirs.sentence_id and mine.sentence_id:
        return theirs.sentence_id == mine.sentence_id
    return theirs.start_frame < mine.end_frame and theirs.end_frame > mine.start_frame


def align_mutual(motions: Mapping[str, Motion], pairs: Sequence[PairedAction]) -> dict[str, Motion]:
    """Two characters doing one action together ("They hug") start their clips on the same frame.

    Each clip starts once its own character has got there: the one who walks up to the other starts late,
    the one who waits plays its clip into the air. The earlier clip is held back (its character keeps the
    pose it had) to start with the later one; the wait is taken back from that character's next hold.
    """
    from services.motion.giveway import Track, take_back

    out = dict(motions)
    seen: set[tuple[str, str, int]] = set()
    for pair in pairs:
        motion = out.get(pair.actor)
        seg = _segment(motion, pair) if motion is not None else None
        if seg is None or not pair.partner or pair.partner not in out:
            continue
        theirs = [s for s in out[pair.partner].segments if s.action == pair.action and _together(s, seg)]
        if not theirs or (pair.partner, pair.actor, theirs[0].start_frame) in seen:
            continue
        other = theirs[0]
        seen.add((pair.actor, pair.partner, seg.start_frame))
        shift = seg.start_frame - other.start_frame
        if shift == 0:
            continue
        early, at = (pair.partner, other.start_frame) if shift > 0 else (pair.actor, seg.start_frame)
        track = Track.of(out[early])
        length = track.frames
        track.insert(at, abs(shift), before=True)
        take_back(track, at + abs(shift) + (other.end_frame - other.start_frame), abs(shift))
        if track.frames > length:  # no hold to give the wait back: the end is cut (it only holds a pose)
            track.remove(length, track.frames - length)
        elif track.frames < length:
            track.pad(length)
        out[early] = track.to_motion()
    return out


def solve_pairs(
    motions: Mapping[str, Motion], pairs: Sequence[PairedAction]
) -> tuple[dict[str, Motion], list[PairContact], list[str]]:
    """Every paired action's two bodies solved together (see the module docstring).

    Args:
        motions: name -> the character's whole motion on the story's time line.
        pairs: the paired actions, in story order (each with the partner's answer delay, PairedAction.delay_s).

    Returns:
        the motions (the changed ones replaced), the contact gaps reached per pair, and diagnostics.
    """
    motions = align_mutual(motions, pairs)
    arrays = {
        n: (from_wire(m.rotations).astype(np.float64), from_wire(m.root_position).astype(np.float64))
        for n, m in motions.items()
    }
    changed: set[str] = set()
    contacts: list[PairContact] = []
    notes: list[str] = []
    done: set[tuple[str, str, int]] = set()  # (partner, actor, window start) already solved as a meet
    leaned: set[tuple[frozenset[str], int]] = (
        set()
    )  # (the two, window start) already leant towards each other
    for pair in pairs:
        spec = PAIRS.get(pair.action)
        motion = motions.get(pair.actor)
        if spec is None or motion is None:
            continue
        seg = _segment(motion, pair)
        if seg is None or seg.end_frame <= seg.start_frame:
            continue
        w0, w1 = _window(seg, pair.action)
        partner = _partner(pair, motions, (w0 + w1) // 2)
        if not partner:
            notes.append(f"nobody for {pair.actor} to {pair.action.replace('_', ' ')}")
            continue
        if (pair.actor, partner, w0) in done:
            continue
        rot_a, root_a = arrays[pair.actor]
        rot_b, root_b = arrays[partner]
        frames = min(len(rot_a), len(rot_b))
        pad = RAMP_FRAMES + ANSWER_FRAMES  # the turn's ramp, or a short clip's hands easing in before it
        lo, hi = max(0, seg.start_frame - pad), min(frames, seg.end_frame + pad)
        if w0 >= frames or hi <= lo:
            continue
        apart = float(np.linalg.norm(root_a[w0, [0, 2]] - root_b[w0, [0, 2]]))
        if apart > REACH_MAX or not (_present(motion)[w0] and _present(motions[partner])[w0]):
            notes.append(
                f"{partner} is {apart:.1f} m from {pair.actor}: too far to {pair.action.replace('_', ' ')}"
            )
            continue
        mutual = _mutual(motions[partner], pair, partner, w0, w1)
        # A partner sitting down or standing up meanwhile is busy: it neither turns nor answers (its arm
        # pulled to a shared point while its body drops would whip), the actor reaches for it as it is.
        busy = float(np.ptp(root_b[seg.start_frame : seg.end_frame, 1])) > BUSY_HIPS_M
        a = _Side(pair.actor, rot_a[lo:hi].copy(), root_a[lo:hi], offsets_of(pair.actor))
        b = _Side(partner, rot_b[lo:hi].copy(), root_b[lo:hi], offsets_of(partner))
        n = hi - lo
        s0, e0, c0, c1 = seg.start_frame - lo, seg.end_frame - lo, w0 - lo, w1 - lo
        # the answer waits its delay, but never so long that the hand must cross to the contact in a few
        # frames (a seated partner's hand rising from the lap 0.75 m in 3 frames whipped at 12 m/s, and the
        # speed guard then dropped the whole answer: duo-meeting_room-07 s12); a short clip's answer starts
        # before the actor's clip does, up to the ramp before it
        answer = max(min(s0 + int(round(pair.delay_s * motion.fps)), c0 - ANSWER_FRAMES), 0)
        held = profile(n, s0 - RAMP_FRAMES, s0, e0, e0 + RAMP_FRAMES)  # turning: the whole clip
        # the hands: full at the contact frames, eased in and out over ANSWER_FRAMES at least (a clip in contact
        # from its first frame to its last, holding hands, stepped the hand 0.5 m in one frame: gump s11); they
        # let go before the clip ends, as the story checks let the two touch only during it
        start = max(min(s0, c0 - ANSWER_FRAMES), 0)
        until = c1 if e0 - c1 >= ANSWER_FRAMES else max(c0 + 1, e0 - ANSWER_FRAMES)
        end = min(max(e0, until + ANSWER_FRAMES), n)
        reach_a = profile(n, start, c0, until, end)
        reach_b = profile(n, answer, c0, until, end)
        # a seated body's legs would swing into the other or the table: its chest turns instead
        if root_a[w0, 1] >= SEATED_HIPS_M:
            a.rotations = turn_towards(a.rotations, a.root, b.root, held)
        else:
            a.rotations = twist_towards(a.rotations, a.root, b.root, held)
        if root_b[w0, 1] >= SEATED_HIPS_M and not busy:
            b.rotations = turn_towards(b.rotations, b.root, a.root, held)
        elif not busy and (spec.meet or spec.partner):  # one who answers; a hand put on the shoulder is not
            b.rotations = twist_towards(b.rotations, b.root, a.root, held)
        together = (frozenset((pair.actor, partner)), w0)
        if together not in leaned:  # "They hug": both lean in once, in the first of the two passes
            a.rotations = lean_in(a.rotations, spec.lean, reach_a)  # upright again by the clip's end
            if not busy:
                b.rotations = lean_in(b.rotations, spec.lean, reach_b)
            leaned.add(together)
        if not mutual and not busy:
            b.rotations = answer_pose(b.rotations, a.rotations, spec.answer, reach_b)
        pos_b, grot_b = b.fk()
        goals_a = [(t.joint, surface_point(pos_b, grot_b, t)) for t in spec.actor]
        # a shoulder out of the standing arm's reach (the partner sits): the actor bends down to it; so for a
        # seated partner's hand, till the two arms' reaches overlap (duo-office-01 s6 missed by 6 cm)
        bend_to = list(goals_a)
        if root_b[w0, 1] < SEATED_HIPS_M:
            pos_a, _ = a.fk()
            bend_to += [(ja, _reachable(pos_b, jb, pos_a, ja, busy)) for ja, jb in spec.meet]
        a.rotations = lean_in(a.rotations, _reach_lean(a, bend_to, c0, c1), reach_a)
        pos_a, grot_a = a.fk()
        goals_b = [] if mutual or busy else [(t.joint, surface_point(pos_a, grot_a, t)) for t in spec.partner]
        for ja, jb in spec.meet:
            if busy:
                goals_a.append((ja, pos_b[:, JOINT_INDEX[jb]]))
                continue
            mid = (pos_a[:, JOINT_INDEX[ja]] + pos_b[:, JOINT_INDEX[jb]]) / 2
            mid = _within_reach(mid, _shoulder_reach(pos_a, ja), _shoulder_reach(pos_b, jb))
            goals_a.append((ja, mid))
            goals_b.append((jb, mid))
        for joint, goal in goals_a:
            a.rotations = two_bone(a.rotations, a.root, a.offsets, joint, goal, reach_a)
        for joint, goal in goals_b:
            b.rotations = two_bone(b.rotations, b.root, b.offsets, joint, goal, reach_b)
        gap = _gap(a, b, goals_a, goals_b, c0, until)
        contacts.append(
            PairContact(
                actor=pair.actor, partner=partner, action=pair.action, start_frame=w0, end_frame=w1, gap_m=gap
            )
        )
        for side, rot in ((a, rot_a), (b, rot_b)):
            if (
                _fastest_hand(side) > HANDS_MAX_MS
                and _fastest_hand(_Side(side.name, rot[lo:hi], side.root, side.offsets)) <= HANDS_MAX_MS
            ):
                side.rotations = rot[
                    lo:hi
                ].copy()  # the fit would whip a hand: this side keeps its own motion
        rot_a[lo:hi], rot_b[lo:hi] = a.rotations, b.rotations
        changed |= {pair.actor, partner}
        if spec.meet:
            done.add((partner, pair.actor, w0))
    out = dict(motions)
    for name in changed:
        rot = arrays[name][0]
        out[name] = msgspec.structs.replace(
            motions[name], rotations=to_wire(quat.normalize(rot).astype(np.float32))
        )
    return out, contacts, notes


def _fastest_hand(side: _Side, fps: int = 30) -> float:
    """m/s: the fastest either hand moves between two frames."""
    pos, _ = side.fk()
    hands = pos[:, [JOINT_INDEX["LeftHand"], JOINT_INDEX["RightHand"]]]
    return float(np.linalg.norm(np.diff(hands, axis=0), axis=2).max() * fps) if len(hands) > 1 else 0.0


def _shoulder_reach(pos: np.ndarray, end: str) -> tuple[np.ndarray, np.ndarray]:
    """(T, 3) the upper joint of the arm that ends in ``end``, and (T,) how far the straight arm reaches."""
    ua, mb = (JOINT_INDEX[n] for n in CHAINS[end])
    ec = JOINT_INDEX[end]
    reach = np.linalg.norm(pos[:, mb] - pos[:, ua], axis=1) + np.linalg.norm(pos[:, ec] - pos[:, mb], axis=1)
    return pos[:, ua], reach


def _reachable(pos_b: np.ndarray, jb: str, pos_a: np.ndarray, ja: str, busy: bool) -> np.ndarray:
    """(T, 3) where the actor's ``ja`` must get to for the two hands to meet: the partner's ``jb`` itself when
    it is busy (it does not answer), else the point of the partner's reach nearest the actor's shoulder."""
    if busy:
        return pos_b[:, JOINT_INDEX[jb]]
    shoulder_b, reach_b = _shoulder_reach(pos_b, jb)
    shoulder_a, _ = _shoulder_reach(pos_a, ja)
    return shoulder_b + _unit(shoulder_a - shoulder_b) * (reach_b * REACH_SHARE * MEET_MARGIN)[:, None]


def _within_reach(
    goal: np.ndarray, *arms: tuple[np.ndarray, np.ndarray], share: float = REACH_SHARE
) -> np.ndarray:
    """The meeting point (T, 3) pulled in until each arm reaches it with its elbow a little bent (a raised
    high five meets lower than both hands were held, rather than missing)."""
    goal = goal.copy()
    for _ in range(4):
        for shoulder, reach in arms:
            d = goal - shoulder
            n = np.linalg.norm(d, axis=1, keepdims=True)
            limit = reach[:, None] * share
            goal = np.where(n > limit, shoulder + d / np.maximum(n, 1e-9) * limit, goal)
    return goal


def _reach_lean(side: _Side, goals: list[tuple[str, np.ndarray]], c0: int, c1: int) -> float:
    """Radians more the spine leans forward so that every goal is within REACH_SHARE of its arm's reach
    at the contact frames (the smallest of LEAN_STEPS that does it, the largest when none does); 0 when
    the goals are within reach as the character stands."""
    if not goals or c1 <= c0:
        return 0.0
    frames = slice(c0, c1)

    def short(rotations: np.ndarray) -> float:
        pos, _ = forward_kinematics(rotations[frames], side.root[frames], side.offsets)
        worst = -math.inf
        for joint, goal in goals:
            shoulder, reach = _shoulder_reach(pos, joint)
            worst = max(
                worst, float((np.linalg.norm(goal[frames] - shoulder, axis=1) - reach * REACH_SHARE).max())
            )
        return worst

    if short(side.rotations) <= 0.0:
        return 0.0
    ones = np.ones(len(side.rotations))
    for pitch in LEAN_STEPS:
        if short(lean_in(side.rotations, pitch, ones)) <= 0.0:
            return pitch
    return LEAN_STEPS[-1]


def _mutual(theirs: Motion, pair: PairedAction, partner: str, w0: int, w1: int) -> bool:
    """True when the partner does the same touching action over these frames itself ("They hug")."""
    del partner
    return any(
        seg.action == pair.action and seg.start_frame < w1 and seg.end_frame > w0 for seg in theirs.segments
    )


def _gap(
    a: _Side,
    b: _Side,
    goals_a: list[tuple[str, np.ndarray]],
    goals_b: list[tuple[str, np.ndarray]],
    c0: int,
    c1: int,
) -> float:
    """The largest distance (metres) from a contact joint to its target at the contact frames."""
    worst = 0.0
    for side, goals in ((a, goals_a), (b, goals_b)):
        if not goals:
            continue
        pos, _ = forward_kinematics(side.rotations[c0:c1], side.root[c0:c1], side.offsets)
        for joint, goal in goals:
            d = np.linalg.norm(pos[:, JOINT_INDEX[joint]] - goal[c0:c1], axis=1)
            worst = max(worst, float(d.max()) if len(d) else 0.0)
    return round(worst, 4)


__all__ = ["PAIRS", "PairSpec", "Touch", "offsets_of", "profile", "solve_pairs", "two_bone"]
