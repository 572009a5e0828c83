"""Segment-wise synthesis: a MotionPlan -> proto.motion_data.Motion.

Each planned segment is synthesised from the end state of the previous one only
(`synthesise_segment(plan, k, start_state) -> (MotionPiece, end_state)`), so the orchestrator can
recompute from segment k on and stop as soon as an end state comes out unchanged. Every piece
starts and ends exactly in its posture's rest pose at its start / end state (`join_rest`: the first and
last JOIN frames blend from / into it), so pieces synthesised apart join without a pose pop wherever the
orchestrator puts them on the time line, and holds between them hold that pose. Upper body from
the action, lower body from locomotion or the posture; IK brings contact joints to the object's
contact points; foot locking removes sliding.
"""

from __future__ import annotations

import dataclasses
import functools
from dataclasses import asdict, dataclass, field

import msgspec
import numpy as np

from proto.motion_data import Motion, PropTrack, Segment
from services.motion.blend import fade_from, layer, upper_body_mask
from services.motion.gait_style import NEUTRAL as NEUTRAL_GAIT
from services.motion.gait_style import gait_style
from services.motion.ik import joint_globals, lean_needed, lean_spine, lock_feet, trunk_tilt, two_bone_ik
from services.motion.locomotion import lock_walk, locomote
from services.motion.style import apply_style, resample_fps, style_of, within_body_limits
from wana.arrays import to_wire
from wana.domain import quat
from wana.domain.actions import JOIN_FRAMES, ActionClip, get_clip, neutral_rotations
from wana.domain.skeleton import JOINT_INDEX, JOINT_NAMES, N_JOINTS, REST_OFFSETS
from wana.domain.units import FPS

FADE = 6  # frames of cross-fade at the start of each piece
JOIN = (
    JOIN_FRAMES  # frames over which a piece blends from its start state's rest pose and into its end state's
)
POSTURE_AFTER = {
    "sit": "sit",
    "lie_down": "lie",
    "sleep": "lie",
    "sit_on_floor": "sit_floor",
    "stand": "stand",
}
POSTURE_CLIP = {"sit": "sit", "lie": "lie_down", "sit_floor": "sit_on_floor"}
SEATED_MAX_LEAN = np.radians(40.0)  # radians of spine pitch a seated character leans toward a hand target
SCOOT_MAX = 0.15  # metres the hips may slide forward on a seat to bring the hands to a far target
FULL_REACH = 0.97  # share of the arm's reach a hand contact may use (nearly straight arm: pressing, wiping)
COMFORT_REACH = 0.85  # the same for typing and playing: elbows bent ~110 degrees
STAND_MAX_LEAN = np.radians(30.0)  # radians of trunk lean a standing reach may use before ...
CROUCH_MAX = 0.45  # ... the knees bend: metres the hips may drop (feet planted) to reach a low target
BEND_DOWN = ("pick_up", "put_down")  # clips that bend down to the floor with the feet planted
ARM_PREFIXES = tuple(
    side + part for side in ("Left", "Right") for part in ("Shoulder", "Arm", "ForeArm", "Hand")
)
HAND_JOINTS = ("LeftHand", "RightHand", "LeftHandMiddle1", "RightHandMiddle1")
# Getting up from a seat ends clear of the seat's front edge (the plan gives that spot as the stand's Hips
# target, services.motion.planning.seat_approach): the body rises and moves forward to it from RISE_FROM_S into
# the clip on; a target farther than RISE_MAX_M (a resumed plan's stale spot) is not moved to.
RISE_FROM_S = 0.3
RISE_MAX_M = 0.6


@dataclass(frozen=True)
class SegmentState:
    """Where a character is between segments (hashable; floats rounded to mm / mrad)."""

    x: float = 0.0
    z: float = 0.0
    yaw: float = 0.0
    posture: str = "stand"
    phase: float = 0.0
    hips_dy: float = 0.0  # metres the hips sit above (+) or below the posture's rest height (a seat's height)

    def rounded(self) -> SegmentState:
        return SegmentState(
            round(float(self.x), 3),
            round(float(self.z), 3),
            round(float(np.arctan2(np.sin(self.yaw), np.cos(self.yaw))), 3),
            self.posture,
            round(float(self.phase), 3),
            round(float(self.hips_dy), 3),
        )

    def to_dict(self) -> dict:
        return asdict(self)


@dataclass(frozen=True)
class PlannedSegment:
    """One step of a character's plan.

    kind: "locomotion" (waypoints, speed, face_yaw), "action" (a library clip, optional contact
    targets: joint -> world (x, y, z)), or "wait".
    """

    index: int
    kind: str
    action: str
    duration_s: float = 0.0  # 0 = natural length
    waypoints: tuple[tuple[float, float], ...] = ()
    speed: float = 1.4
    face_yaw: float | None = None
    targets: tuple[tuple[str, tuple[float, float, float]], ...] = ()
    target_id: str = ""
    sentence_id: str = ""
    action_index: int = -1  # index of the ActionNode this segment serves
    prop: str = ""  # id of a small object held during the clip's contact window ("" = none)
    prop_joint: str = "RightHand"  # the joint holding it
    prop_grip: tuple[float, float, float] = (0.0, 0.0, 0.0)  # its grip point, object frame, metres
    prop_yaw: float = 0.0  # its yaw as placed (radians): the orientation it is picked up in
    mood: tuple[float, float] = (
        0.0,
        0.0,
    )  # valence, arousal in [-1, 1]: the style it is played in (style.py)
    manner: str = ""  # a locomotion's manner word ("tiredly"): its arm swing and posture
    upright: bool = (
        False  # the clip's arms alone on the standing pose (upright_clip): a pick-up at shelf height
    )
    prop_span: str = "window"  # held over: "window" (the clip's contact window), "grasp" (from the grasp
    # on: picked up here), "whole" (the whole piece: held from before), "release" (until it is put down)


@dataclass(frozen=True)
class MotionPlan:
    character: str
    start: tuple[float, float, float]  # x, z, yaw
    segments: tuple[PlannedSegment, ...] = ()
    diagnostics: tuple[str, ...] = ()

    def start_state(self) -> SegmentState:
        return SegmentState(*self.start).rounded()


@dataclass
class MotionPiece:
    """Frames of one segment: root (T, 3), rotations (T, J, 4), contacts (T, 2), plus contact targets per frame."""

    root: np.ndarray
    rotations: np.ndarray
    contacts: np.ndarray
    segment: PlannedSegment
    contact_frames: dict[str, tuple[np.ndarray, np.ndarray]] = field(
        default_factory=dict
    )  # joint -> (frames, target)
    props: list[PropTrack] = field(default_factory=list)  # frames relative to the piece


@functools.lru_cache(maxsize=8)
def posture_pose(posture: str) -> tuple[np.ndarray, np.ndarray]:
    """(J, 4) rotations and (3,) root offset (character frame) of a posture's rest pose."""
    if posture in POSTURE_CLIP:
        clip = get_clip(POSTURE_CLIP[posture])
        rot, root, _ = clip.sample()
        return rot[-1], root[-1]
    return neutral_rotations(), np.zeros(3)


@functools.lru_cache(maxsize=16)
def upright_clip(name: str) -> ActionClip:
    """A clip's arms alone, played on the standing pose: its trunk bend, knee dip and root travel left out. A
    pick-up of papers on top of a filing cabinet reaches with the arm and keeps the pick-up's timing, instead
    of bending down into the cabinet under them."""
    clip = get_clip(name)
    keys = tuple(
        dataclasses.replace(
            k, rotations={j: q for j, q in k.rotations.items() if j.startswith(ARM_PREFIXES)}, root=(0.0, 0.0, 0.0),
            root_yaw=0.0,
        )
        for k in clip.keyframes
    )  # fmt: skip
    return dataclasses.replace(clip, name=f"{name}_upright", body_parts=("upper_body",), keyframes=keys)


def clip_of(seg: PlannedSegment) -> ActionClip:
    """The library clip a segment plays (its upright variant when the segment asks for it)."""
    return upright_clip(seg.action) if seg.upright else get_clip(seg.action)


def _to_world(
    state: SegmentState, offsets: np.ndarray, yaw_track: np.ndarray, hips_dy: np.ndarray | float | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Character-frame root offsets (T, 3) -> world hips (T, 3); heading (T,).

    hips_dy: (T,) or scalar metres added to the hips height (default: the state's seat height when
    not standing).
    """
    heading = state.yaw + yaw_track
    q = quat.yaw(np.full(len(offsets), state.yaw))
    world = quat.rotate(q, offsets)
    world[:, 0] += state.x
    world[:, 2] += state.z
    world[:, 1] += REST_OFFSETS[0, 1] + (_seat_dy(state) if hips_dy is None else hips_dy)
    return world, heading


def _seat_dy(state: SegmentState) -> float:
    return state.hips_dy if state.posture != "stand" else 0.0


def _clip_contacts(rot: np.ndarray, root: np.ndarray) -> np.ndarray:
    out = np.zeros((len(rot), 2), np.uint8)
    for k, name in enumerate(("LeftFoot", "RightFoot")):
        f, _ = joint_globals(rot, root, JOINT_INDEX[name])
        v = np.zeros(len(f))
        v[1:] = np.linalg.norm(np.diff(f[:, [0, 2]], axis=0), axis=1)
        out[:, k] = ((f[:, 1] < 0.09) & (v < 0.01)).astype(np.uint8)
    return out


def _action_piece(seg: PlannedSegment, state: SegmentState) -> tuple[MotionPiece, SegmentState]:
    clip: ActionClip = clip_of(seg)
    dur = (
        seg.duration_s
        if seg.duration_s > 0
        else (max(clip.duration_s, 3.0) if clip.looping else clip.duration_s)
    )
    style = within_body_limits(style_of(*seg.mood), clip)
    plain = clip.interaction is None  # contact clips keep their timing (windows are in clip time)
    if plain and style.tempo != 1.0:
        rate = resample_fps(FPS, style)
        rot, offs, yaw_track = clip.sample(
            rate, dur * FPS / rate if seg.duration_s > 0 or clip.looping else dur
        )
        dur = len(rot) / FPS
    else:
        rot, offs, yaw_track = clip.sample(FPS, dur)
    t = len(rot)
    posture = state.posture
    new_posture = POSTURE_AFTER.get(clip.name, posture)
    if clip.drives_lower_body:
        dy: np.ndarray | float = _seat_dy(state)
        if dy and new_posture == "stand":  # getting up from a seat of another height: fade it out
            dy = dy * (1.0 - _smooth(np.linspace(0.0, 1.0, t)))
        root, heading = _to_world(state, offs, yaw_track, dy)
    else:
        base_rot, base_off = posture_pose(posture)
        base = np.repeat(base_rot[None], t, 0)
        rot = layer(base, rot, upper_body_mask())
        root, heading = _to_world(state, np.repeat(base_off[None], t, 0), np.zeros(t))
    rot = apply_style(rot, posture_pose(posture)[0], style, amplitude=plain)
    rot[:, 0] = quat.mul(quat.yaw(heading), rot[:, 0])
    start_rot, start_off = posture_pose(posture)
    start_pose = start_rot.copy()
    start_pose[0] = quat.mul(quat.yaw(state.yaw), start_pose[0])
    rot = fade_from(start_pose, rot, FADE if clip.name not in POSTURE_AFTER else 0)
    contact_frames: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    targets = dict(seg.targets)
    seat_shift = np.zeros(3)  # where the hips end up relative to the clip's own ending (metres, world)
    if "Hips" in targets and clip.interaction:  # move the root so the hips land on the seat / bed point
        w0, w1 = clip.interaction.window
        frames = np.arange(t)
        ramp = _smooth(np.clip((frames / FPS - (w0 - 0.6)) / 0.6, 0, 1))
        hit = min(int(w0 * FPS), t - 1)
        delta = np.asarray(targets["Hips"]) - root[hit]
        root = root + ramp[:, None] * delta
        seat_shift = ramp[-1] * delta
        inside = frames[(frames >= int(w0 * FPS)) & (frames < max(int(w1 * FPS), int(w0 * FPS) + 1))]
        contact_frames["Hips"] = (inside, np.asarray(targets["Hips"]))
    stand_feet = not clip.drives_lower_body or seg.action in POSTURE_AFTER
    contacts = np.ones((t, 2), np.uint8) if stand_feet else _clip_contacts(rot, root)
    stand_lean = None  # standing at a low target: bend the knees first, the trunk at most STAND_MAX_LEAN
    bends_down = clip.name in BEND_DOWN  # its own dip is not enough for a grip on the floor: crouch on it
    if (
        posture == "stand"
        and clip.interaction
        and (bends_down or (not clip.drives_lower_body and stand_feet))
    ):
        low = {j: p for j, p in targets.items() if j in HAND_JOINTS}
        if low and clip.interaction.object != "person":
            root, stand_lean = _crouch_to_reach(rot, root, low, _contact_weight(clip, t, dur), clip)
    rot = lock_feet(rot, root, contacts)  # feet stay planted: a lowered root bends the knees
    if (
        clip.interaction
        and clip.interaction.object != "person"
        and (clip.interaction.object not in ("handheld", "tool") or targets)
    ):
        w0, w1 = clip.interaction.window
        frames = np.arange(t)
        if clip.looping:
            w0, w1 = 0.0, dur
        tt = frames / FPS
        weight = np.clip(np.minimum((tt - (w0 - 0.4)) / 0.4, ((w1 + 0.4) - tt) / 0.4), 0, 1)
        # Keys and instruments are worked with bent elbows: lean in until the hands are at a comfortable reach.
        slack = COMFORT_REACH if clip.interaction.object in ("keyboard", "instrument") else FULL_REACH
        hands = {
            j: p
            for j, p in targets.items()
            if j in ("LeftHand", "RightHand", "LeftHandMiddle1", "RightHandMiddle1")
        }
        max_lean = np.radians(80.0) if stand_lean is None else stand_lean
        if posture in ("sit", "sit_floor") and not clip.drives_lower_body and hands:
            # Seated, the trunk leans at most SEATED_MAX_LEAN; past that the hips slide forward on the seat.
            max_lean = SEATED_MAX_LEAN
            root = _scoot_to_reach(rot, root, heading, hands, weight, slack)
        if hands:  # one lean for both hands: the one the farther hand needs
            needs = [
                lean_needed(rot, root, j, np.asarray(p, dtype=np.float64), weight, max_lean, slack)
                for j, p in hands.items()
            ]
            rot = lean_spine(
                rot, max_lean if None in needs else max(n for n in needs if n is not None), weight
            )
        for joint, target in hands.items():
            tgt = np.broadcast_to(np.asarray(target, dtype=np.float64), (t, 3))
            rot = two_bone_ik(rot, root, joint, tgt, weight)
            inside = frames[weight >= 0.999]
            contact_frames[joint] = (inside, np.asarray(target))
    end_off = offs[-1] if clip.drives_lower_body else np.zeros(3)
    end_yaw = state.yaw + float(yaw_track[-1])
    hips_dy = 0.0 if new_posture == "stand" else state.hips_dy
    if clip.drives_lower_body and new_posture == "stand" and clip.name not in POSTURE_AFTER:
        # Travel built into the clip (a step, a jump forward) moves the character.
        moved = quat.rotate(quat.yaw(np.array(state.yaw)), np.array([end_off[0], 0.0, end_off[2]]))
        end = SegmentState(state.x + moved[0], state.z + moved[2], end_yaw, new_posture, state.phase)
    elif "Hips" in targets and clip.interaction:
        # Seated (lying) where the hips landed, wherever the approach walk stopped: the next pieces put the
        # posture's hips there, at the seat's height; getting up ends SEAT_BACK in front of the seat.
        end = SegmentState(
            state.x + seat_shift[0],
            state.z + seat_shift[2],
            end_yaw,
            new_posture,
            state.phase,
            state.hips_dy * (1.0 - ramp[-1]) + seat_shift[1],
        )
    else:
        end = SegmentState(state.x, state.z, end_yaw, new_posture, state.phase, hips_dy)
    rise = _rise_shift(clip, posture, targets, state)
    if rise is not None:  # getting up onto the spot in front of the seat
        root = root + rise_path(rise, state.yaw, t, dur)
        end = SegmentState(state.x + rise[0], state.z + rise[2], end_yaw, new_posture, state.phase, hips_dy)
    return MotionPiece(root, quat.normalize(rot), contacts, seg, contact_frames), end.rounded()


def rise_path(rise: np.ndarray, yaw: float, frames: int, dur: float) -> np.ndarray:
    """(frames, 3) world metres the hips are moved by on each frame of a stand-up that ends ``rise`` away.

    The part of ``rise`` back from the seat's facing (``yaw``) comes first, the rest (sideways) after it: one
    gets up beside a chair tucked in at a desk by pushing back out from under it, then stepping aside; moved
    on one ramp, the knees under the desk swept sideways through its end (solo-office-01 s11, a foot 6 cm in).
    A rise with no part back (onto the spot in front) is one ramp from RISE_FROM_S to the clip's end.
    """
    u = np.clip((np.arange(frames) / FPS - RISE_FROM_S) / max(dur - RISE_FROM_S, 1.0 / FPS), 0, 1)
    fwd = np.array([np.sin(yaw), 0.0, np.cos(yaw)])
    back = min(float(rise @ fwd), 0.0) * fwd
    aside = rise - back
    if not np.any(back) or not np.any(aside):
        return _smooth(u)[:, None] * rise
    share = float(np.linalg.norm(back) / (np.linalg.norm(back) + np.linalg.norm(aside)))
    first = _smooth(np.clip(u / max(share, 1e-6), 0, 1))
    second = _smooth(np.clip((u - share) / max(1.0 - share, 1e-6), 0, 1))
    return first[:, None] * back + second[:, None] * aside


def _rise_shift(
    clip: ActionClip, posture: str, targets: dict[str, tuple[float, float, float]], state: SegmentState
) -> np.ndarray | None:
    """(3,) world metres a stand-up from a seat moves forward to its Hips target (xz), None when it stays."""
    if clip.name != "stand" or posture == "stand" or clip.interaction or "Hips" not in targets:
        return None
    goal = np.asarray(targets["Hips"], dtype=np.float64)
    shift = np.array([goal[0] - state.x, 0.0, goal[2] - state.z])
    size = float(np.linalg.norm(shift))
    return shift if 1e-3 < size <= RISE_MAX_M else None


def _contact_weight(clip: ActionClip, t: int, dur: float) -> np.ndarray:
    """(T,) how much the contact holds per frame: the clip's window, eased in and out over 0.4 s."""
    assert clip.interaction is not None
    w0, w1 = (0.0, dur) if clip.looping else clip.interaction.window
    tt = np.arange(t) / FPS
    return np.clip(np.minimum((tt - (w0 - 0.4)) / 0.4, ((w1 + 0.4) - tt) / 0.4), 0, 1)


def _crouch_to_reach(
    rot: np.ndarray,
    root: np.ndarray,
    hands: dict[str, tuple[float, float, float]],
    weight: np.ndarray,
    clip: ActionClip,
) -> tuple[np.ndarray, float | None]:
    """Root (T, 3) lowered (at most CROUCH_MAX, eased in by weight) just far enough that the spine lean
    bringing every hand target within reach leaves the trunk (hips -> neck, the clip's own bend included:
    a wiping clip already bends ~15 degrees) within STAND_MAX_LEAN of upright, and that lean. When no
    crouch is enough, the crouch whose lean tilts the trunk least and None (the trunk then leans as far
    as it must)."""
    assert clip.interaction is not None
    slack = COMFORT_REACH if clip.interaction.object in ("keyboard", "instrument") else FULL_REACH
    best, best_tilt = root, np.inf
    for drop in np.linspace(0.0, CROUCH_MAX, 10):
        lowered = root.copy()
        lowered[:, 1] -= weight * drop
        needs = [
            lean_needed(rot, lowered, j, np.asarray(p, dtype=np.float64), weight, np.radians(80.0), slack)
            for j, p in hands.items()
        ]
        if None in needs:
            continue
        lean = max(n for n in needs if n is not None)
        tilt = trunk_tilt(lean_spine(rot, lean, weight), lowered, weight)
        if tilt <= STAND_MAX_LEAN:
            return lowered, lean
        if tilt < best_tilt:
            best, best_tilt = lowered, tilt
    return best, None


def _scoot_to_reach(
    rot: np.ndarray,
    root: np.ndarray,
    heading: np.ndarray,
    hands: dict[str, tuple[float, float, float]],
    weight: np.ndarray,
    slack: float,
) -> np.ndarray:
    """Root (T, 3) slid forward (at most SCOOT_MAX, eased in by weight) just far enough that a lean of
    SEATED_MAX_LEAN brings every hand target within slack * reach; the farthest slide when none is."""
    fwd = np.stack([np.sin(heading), np.zeros(len(heading)), np.cos(heading)], -1)  # (T, 3)
    moved = root
    for scoot in np.linspace(0.0, SCOOT_MAX, 6):
        moved = root + (weight * scoot)[:, None] * fwd
        if all(
            lean_needed(rot, moved, j, np.asarray(p, dtype=np.float64), weight, SEATED_MAX_LEAN, slack)
            is not None
            for j, p in hands.items()
        ):
            return moved
    return moved


def _locomotion_piece(seg: PlannedSegment, state: SegmentState) -> tuple[MotionPiece, SegmentState]:
    pieces: list[MotionPiece] = []
    wps = np.asarray(seg.waypoints, dtype=np.float64).reshape(-1, 2) if seg.waypoints else np.zeros((0, 2))
    if state.posture != "stand":  # get up first, onto where the walk begins (in front of the seat)
        rise = (("Hips", (float(wps[0, 0]), 0.0, float(wps[0, 1]))),) if len(wps) else ()
        up, state = _action_piece(
            PlannedSegment(index=seg.index, kind="action", action="stand", targets=rise), state
        )
        pieces.append(up)
    wps = (
        np.concatenate([[[state.x, state.z]], wps])
        if len(wps) == 0 or np.linalg.norm(wps[0] - [state.x, state.z]) > 1e-3
        else wps
    )
    loco = locomote(wps, seg.speed, state.yaw, seg.face_yaw, state.phase, manner=seg.manner)
    rot = loco.rotations
    if gait_style(seg.manner) == NEUTRAL_GAIT:  # a manner the gait has no walk for: the mood's style
        rot = apply_style(rot, _standing_pose(state.yaw), style_of(*seg.mood))
    rot = fade_from(_standing_pose(state.yaw), rot, FADE)
    rot = lock_walk(rot, loco.root_position, loco.contacts)
    piece = MotionPiece(loco.root_position, rot, loco.contacts, seg)
    # The character comes to rest at the goal, so the next walk starts from a standing pose at phase 0: the end
    # state depends on where the walk ends, not on how it got there (edits to the manner stop early).
    end = SegmentState(
        float(loco.root_position[-1, 0]),
        float(loco.root_position[-1, 2]),
        float(loco.heading[-1]),
        "stand",
        0.0,
    ).rounded()
    if pieces:
        piece = MotionPiece(
            np.concatenate([pieces[0].root, piece.root]),
            np.concatenate([pieces[0].rotations, piece.rotations]),
            np.concatenate([pieces[0].contacts, piece.contacts]),
            seg,
        )
    return piece, end


def _smooth(u: np.ndarray) -> np.ndarray:
    """Smoothstep of u in [0, 1]."""
    return u * u * (3 - 2 * u)


def _standing_pose(yaw: float) -> np.ndarray:
    p = neutral_rotations().copy()
    p[0] = quat.mul(quat.yaw(np.array(yaw)), p[0])
    return p


def rest_frame(state: SegmentState) -> tuple[np.ndarray, np.ndarray]:
    """(J, 4) rotations (root yawed) and (3,) world hips of the rest pose of a state's posture."""
    base_rot, base_off = posture_pose(state.posture)
    rot = base_rot.copy()
    rot[0] = quat.mul(quat.yaw(np.array(state.yaw)), rot[0])
    root, _ = _to_world(state, base_off[None], np.zeros(1))
    return rot, root[0]


def join_rest(piece: MotionPiece, start: SegmentState, end: SegmentState, frames: int = JOIN) -> MotionPiece:
    """The piece with its first frame exactly the start state's rest pose and its last the end state's,
    blended over ``frames`` frames at each end (smoothstep, rotations slerped, hips lerped).

    Every piece is synthesised from its start state alone (so the orchestrator can recompute from any
    segment on); ending where the next piece starts is what makes the boundary invisible: the piece
    after, or a hold on the time line, starts from exactly this pose.
    """
    t = len(piece.root)
    n = min(frames, t // 2)
    if n < 2:
        return piece
    rot = np.array(piece.rotations, dtype=np.float64, copy=True)
    root = np.array(piece.root, dtype=np.float64, copy=True)
    u = _smooth(np.arange(n) / (n - 1))  # 0 at the boundary frame, 1 inside the piece
    for (pose, hips), idx, w in (
        (rest_frame(start), np.arange(n), u),
        (rest_frame(end), np.arange(t - n, t), u[::-1]),
    ):
        ww = np.repeat(w[:, None], N_JOINTS, 1)
        rot[idx] = quat.slerp(np.broadcast_to(pose, (n, N_JOINTS, 4)), rot[idx], ww)
        root[idx] = hips + (root[idx] - hips) * w[:, None]
    # The blended frames leave the contact: a looping contact (typing) holds from the first to the last
    # frame the join leaves alone.
    held = {
        j: (frames[(frames >= n) & (frames < t - n)], target)
        for j, (frames, target) in piece.contact_frames.items()
    }
    return MotionPiece(root, quat.normalize(rot), piece.contacts, piece.segment, held, piece.props)


def synthesise_segment(
    plan: MotionPlan, k: int, start_state: SegmentState
) -> tuple[MotionPiece, SegmentState]:
    """Synthesise segment k of a plan from the end state of segment k-1 (or plan.start_state())."""
    piece, end = _synthesise_segment(plan, k, start_state)
    piece = join_rest(piece, start_state, end)
    if piece.segment.prop:
        piece.props = [held_prop(piece)]
    return piece, end


PROP_TURN_S = 0.4  # seconds over which a prop turns from how it lay to how the hand holds it (and back)


@functools.lru_cache(maxsize=8)
def _hand_at_rest(joint: str) -> np.ndarray:
    """(4,) the joint's world rotation in the standing rest pose, facing +Z."""
    _, grot = joint_globals(neutral_rotations()[None], np.zeros((1, 3)), JOINT_INDEX[joint])
    return np.asarray(grot[0], dtype=np.float64)


def _held_frames(seg: PlannedSegment, t: int) -> tuple[int, int]:
    """[a, b) frames of a piece during which its segment's prop is in the hand."""
    if seg.prop_span == "whole":
        return 0, t
    try:
        clip = clip_of(seg)
    except KeyError:
        return 0, t
    w0, w1 = clip.interaction.window if clip.interaction else (0.0, clip.duration_s)
    if clip.looping:
        w0, w1 = 0.0, t / FPS
    if seg.prop_span == "grasp":  # from the moment the hand reaches it to the end: it stays in the hand
        return int(np.clip(round(w0 * FPS), 0, t - 1)), t
    if seg.prop_span == "release":  # until the hand has set it down
        return 0, int(np.clip(round((w0 + w1) / 2 * FPS), 1, t))
    a = int(np.clip(round(w0 * FPS), JOIN, max(JOIN, t - JOIN - 1)))
    b = int(np.clip(round(w1 * FPS), a + 1, max(a + 1, t - JOIN)))
    return a, b


def holding_after(seg: PlannedSegment) -> str:
    """The id of the prop still in the hand after a segment ("" when the hands are empty)."""
    return seg.prop if seg.prop and seg.prop_span in ("grasp", "whole") else ""


def held_prop(piece: MotionPiece) -> PropTrack:
    """The prop of a piece's segment held by its joint over the frames its span names.

    The prop sits in the hand the same way in every piece (upright and facing forward when the arm hangs at
    rest), so a prop held across several segments moves on continuously from one to the next; where it is
    picked up (put down) it turns from (to) the orientation it lay in over PROP_TURN_S, and its grip point
    is on the joint in every held frame.
    """
    seg = piece.segment
    t = len(piece.root)
    a, b = _held_frames(seg, t)
    pos, grot = joint_globals(piece.rotations[a:b], piece.root[a:b], JOINT_INDEX[seg.prop_joint])
    rest = quat.inv(_hand_at_rest(seg.prop_joint))  # the object in the hand's frame
    rot = quat.normalize(quat.mul(grot, np.broadcast_to(rest, grot.shape)))
    lying = np.broadcast_to(quat.yaw(np.array(seg.prop_yaw)), rot.shape)
    n = min(len(rot), max(1, int(PROP_TURN_S * FPS)))
    if seg.prop_span in ("grasp", "window"):
        w = _smooth(np.linspace(0.0, 1.0, n))
        rot[:n] = quat.slerp(lying[:n], rot[:n], w)
    if seg.prop_span in ("release", "window"):
        w = _smooth(np.linspace(1.0, 0.0, n))
        rot[len(rot) - n :] = quat.slerp(lying[:n], rot[len(rot) - n :], w)
    rot = quat.normalize(rot)
    origin = pos - quat.rotate(rot, np.broadcast_to(np.asarray(seg.prop_grip, float), pos.shape))
    return PropTrack(
        object_id=seg.prop,
        joint=seg.prop_joint,
        start_frame=a,
        end_frame=b,
        grip=tuple(float(v) for v in seg.prop_grip),  # type: ignore[arg-type]
        position=to_wire(origin.astype(np.float32)),
        rotation=to_wire(rot.astype(np.float32)),
    )


def _synthesise_segment(
    plan: MotionPlan, k: int, start_state: SegmentState
) -> tuple[MotionPiece, SegmentState]:
    seg = plan.segments[k]
    if seg.kind == "locomotion":
        return _locomotion_piece(seg, start_state)
    if seg.kind == "wait":
        base_rot, base_off = posture_pose(start_state.posture)
        t = max(1, int(round(seg.duration_s * FPS)))
        rot = np.repeat(base_rot[None], t, 0)
        rot[:, 0] = quat.mul(quat.yaw(np.full(t, start_state.yaw)), rot[:, 0])
        if seg.action == "sleep" and start_state.posture == "sit":
            _doze(rot)
        root, _ = _to_world(start_state, np.repeat(base_off[None], t, 0), np.zeros(t))
        return MotionPiece(root, rot, np.ones((t, 2), np.uint8), seg), start_state
    return _action_piece(seg, start_state)


DOZE_PITCH = (("Neck", 18.0), ("Head", 16.0))  # degrees a head dozing off in a chair sinks forward


def _doze(rot: np.ndarray) -> None:
    """Falling asleep sitting up: the head sinks towards the chest over the first second, then stays."""
    u = np.clip(np.arange(len(rot)) / float(FPS), 0.0, 1.0)
    ease = u * u * (3.0 - 2.0 * u)
    for joint, degrees in DOZE_PITCH:
        nod = quat.from_euler("ZYX", np.stack([np.zeros_like(u), np.zeros_like(u), degrees * ease], -1))
        rot[:, JOINT_INDEX[joint]] = quat.mul(rot[:, JOINT_INDEX[joint]], nod)


def synthesise(plan: MotionPlan) -> tuple[Motion, list[MotionPiece], list[SegmentState]]:
    """All segments in order; returns the Motion, the pieces and the end state of each segment."""
    state = plan.start_state()
    pieces, states = [], []
    for k in range(len(plan.segments)):
        piece, state = synthesise_segment(plan, k, state)
        pieces.append(piece)
        states.append(state)
    return assemble(plan.character, pieces, plan.start_state()), pieces, states


def assemble(character: str, pieces: list[MotionPiece], start: SegmentState | None = None) -> Motion:
    """Concatenate pieces into a proto Motion (float32 arrays, segments with frame ranges)."""
    props: list[PropTrack] = []
    if not pieces:
        s = start or SegmentState()
        rot = _standing_pose(s.yaw)[None]
        root = np.array([[s.x, REST_OFFSETS[0, 1], s.z]])
        contacts = np.ones((1, 2), np.uint8)
        segments: list[Segment] = []
    else:
        rot = np.concatenate([p.rotations for p in pieces])
        root = np.concatenate([p.root for p in pieces])
        contacts = np.concatenate([p.contacts for p in pieces])
        segments, f = [], 0
        for p in pieces:
            n = len(p.root)
            props += [
                msgspec.structs.replace(h, start_frame=h.start_frame + f, end_frame=h.end_frame + f)
                for h in p.props
            ]
            segments.append(
                Segment(
                    index=p.segment.index,
                    action=p.segment.action,
                    start_frame=f,
                    end_frame=f + n,
                    sentence_id=p.segment.sentence_id,
                    action_index=p.segment.action_index,
                )
            )
            f += n
    return Motion(
        character=character,
        fps=FPS,
        joint_names=list(JOINT_NAMES),
        root_position=to_wire(root.astype(np.float32)),
        rotations=to_wire(rot.astype(np.float32)),
        foot_contact=to_wire(contacts.astype(np.uint8)),
        segments=segments,
        props=props,
    )


assert N_JOINTS == len(JOINT_NAMES)
