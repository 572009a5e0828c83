"""Idles and attention: a character who is not acting breathes, shifts its weight and looks around.

The story time line fills the gaps between a character's actions by holding its last pose
(services/orchestrator/timeline.py); a held pose reads as a frozen mannequin. ``enliven`` layers a
small, seeded, deterministic motion over the idle frames of a composed motion: breathing (chest
and shoulders), a weight shift from foot to foot every few seconds while standing (hips sway and
the pelvis tilts, both feet stay planted by a two-bone leg solve), a slow torso sway while seated,
micro drift of the arms, and a gaze that turns the head (and, for far turns, the chest) toward
whatever deserves attention: who acts or walks nearby, the object the next action uses.

The layer is zero at the edges of every idle stretch and eases in over ``RAMP_S``, so it never
touches an action's frames and never pops. While a prop is in hand the shoulders and arms keep their
pose and the rest of the layer moves both hands as one, carrying the prop's track along (``in_hand``); a
prop the character put down does not stop the layer. Lives in the domain library because it works on
the assembled time line the orchestrator builds, after the motion service has made every piece. Over 400 lines because it keeps the
layer, the stretches it covers, attention and blinks together: they share one timing and seeding rule.
"""

from __future__ import annotations

import hashlib
import zlib
from collections.abc import Sequence

import msgspec
import numpy as np

from proto.motion_data import Motion, Segment
from wana.arrays import from_wire, to_wire
from wana.domain import quat
from wana.domain.actions import get_clip
from wana.domain.skeleton import JOINT_INDEX, REST_OFFSETS, forward_kinematics
from wana.domain.units import FPS

RAMP_S = 0.4  # seconds over which the layer eases in (and out) at the edges of an idle stretch
BREATH_PERIOD_S = (3.4, 4.4)  # range of one breath's period, seconds (seeded per character)
BREATH_DEG = 0.8  # chest extension per breath, degrees, per spine joint (three of them)
SHOULDER_DEG = 1.8  # shoulders rise on the in-breath, degrees
SHIFT_EVERY_S = (3.0, 5.5)  # seconds between weight shifts (seeded)
SHIFT_S = 1.1  # seconds a weight shift takes
SHIFT_M = 0.022  # metres the hips travel sideways toward the loaded foot
PELVIS_DEG = 3.0  # pelvis roll toward the loaded side (contrapposto), degrees
GAZE_YAW_MAX = np.radians(70.0)  # radians the head turns at most (beyond: the chest helps)
GAZE_PITCH_MAX = np.radians(30.0)
MICRO_DEG = 1.0  # degrees: radius of the head's steady micro-motion (what keeps a busy body from freezing)
GAZE_OMEGA = 9.0  # rad/s, natural frequency of the critically damped gaze follow (about 0.35 s to settle)
IDLE_ACTIONS = frozenset({"hold", "wait", "idle"})  # segment actions that are idle stretches


def seed_of(name: str, salt: int = 0) -> int:
    """A stable seed from a character's name (the same story gives the same idles)."""
    return zlib.crc32(f"{name}:{salt}".encode()) & 0x7FFFFFFF


def idle_weight(
    frames: int, spans: Sequence[tuple[int, int]], held: Sequence[tuple[int, int]] = ()
) -> np.ndarray:
    """(T,) layer weight: 1 inside idle spans, eased to 0 over RAMP_S at each edge, 0 elsewhere.

    Args:
        frames: T.
        spans: [start, end) frame ranges of idle stretches.
        held: [start, end) frame ranges where a prop is held (weight 0 there, eased).
    """
    w = np.zeros(frames)
    ramp = max(1, int(round(RAMP_S * FPS)))
    for a, b in spans:
        a, b = max(0, a), min(frames, b)
        if b - a < 3:
            continue
        k = np.arange(a, b)
        edge = np.minimum(k - a + 1, b - k) / ramp  # 0 just outside the stretch, 1 RAMP_S inside
        u = np.clip(edge, 0.0, 1.0)
        w[a:b] = np.maximum(w[a:b], u * u * (3 - 2 * u))
    for a, b in held:
        w[max(0, a - ramp) : min(frames, b + ramp)] = 0.0
    return w


def _smooth_noise(rng: np.random.Generator, t: np.ndarray, periods: Sequence[float]) -> np.ndarray:
    """(T,) a smooth, zero-mean wobble in [-1, 1]: a sum of sines with seeded phases."""
    out = np.zeros_like(t)
    for p in periods:
        out += np.sin(2 * np.pi * t / (p * rng.uniform(0.85, 1.15)) + rng.uniform(0, 2 * np.pi))
    return out / len(periods)


def weight_shift(rng: np.random.Generator, t: np.ndarray) -> np.ndarray:
    """(T,) which foot carries the weight, in [-1, 1] (+1: the left), changing every few seconds."""
    side = np.zeros_like(t)
    when, s = rng.uniform(0.3, 1.5), 1.0 if rng.random() < 0.5 else -1.0
    prev = 0.0
    end = float(t[-1]) if len(t) else 0.0
    while when < end:
        u = np.clip((t - when) / SHIFT_S, 0.0, 1.0)
        u = u * u * (3 - 2 * u)
        side = np.where(t >= when, prev + (s - prev) * u, side)
        prev, s = s, -np.sign(s) * rng.uniform(0.6, 1.0)
        when += rng.uniform(*SHIFT_EVERY_S)
    return side


def _posture(rot: np.ndarray, pos: np.ndarray) -> np.ndarray:
    """(T,) 0 standing, 1 seated / crouched (thighs far from vertical), 2 lying (trunk far from upright)."""
    thigh = pos[:, JOINT_INDEX["LeftLeg"]] - pos[:, JOINT_INDEX["LeftUpLeg"]]
    trunk = pos[:, JOINT_INDEX["Neck"]] - pos[:, JOINT_INDEX["Hips"]]
    thigh_down = -thigh[:, 1] / np.maximum(np.linalg.norm(thigh, axis=1), 1e-9)
    trunk_up = trunk[:, 1] / np.maximum(np.linalg.norm(trunk, axis=1), 1e-9)
    out = np.where(thigh_down > np.cos(np.radians(35.0)), 0, 1)
    return np.where(trunk_up < np.cos(np.radians(55.0)), 2, out)


def _post(rot: np.ndarray, joint: str, axis: tuple[float, float, float], deg: np.ndarray) -> None:
    """Rotate a joint about one of its local axes by deg (T,) degrees, in place."""
    j = JOINT_INDEX[joint]
    rot[:, j] = quat.mul(rot[:, j], quat.from_axis_angle(np.asarray(axis, float), np.radians(deg)))


def _gaze_angles(
    rot: np.ndarray, pos: np.ndarray, grot: np.ndarray, points: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """(T,) yaw and pitch (radians, pitch > 0 down) the head must turn by to face points (T, 3); 0 where NaN."""
    head = pos[:, JOINT_INDEX["Head"]]
    chest = grot[:, JOINT_INDEX["Spine2"]]
    d = quat.rotate(quat.inv(chest), np.nan_to_num(points - head))  # in the chest's frame
    cur = quat.rotate(
        quat.mul(rot[:, JOINT_INDEX["Neck"]], rot[:, JOINT_INDEX["Head"]]), np.array([0.0, 0.0, 1.0])
    )
    want_yaw = np.arctan2(d[:, 0], d[:, 2])
    want_pitch = np.arctan2(-d[:, 1], np.hypot(d[:, 0], d[:, 2]))
    cur_yaw = np.arctan2(cur[:, 0], cur[:, 2])
    cur_pitch = np.arctan2(-cur[:, 1], np.hypot(cur[:, 0], cur[:, 2]))
    ok = np.isfinite(points).all(axis=1) & (np.linalg.norm(d, axis=1) > 0.3) & (d[:, 2] > -0.2)
    yaw = np.where(ok, np.angle(np.exp(1j * (want_yaw - cur_yaw))), 0.0)
    pitch = np.where(ok, want_pitch - cur_pitch, 0.0)
    return np.clip(yaw, -GAZE_YAW_MAX, GAZE_YAW_MAX), np.clip(pitch, -GAZE_PITCH_MAX, GAZE_PITCH_MAX)


def _follow(x: np.ndarray, omega: float = GAZE_OMEGA) -> np.ndarray:
    """(T,) x followed by a critically damped spring (the head's quick, eased turn toward a new target)."""
    dt = 1.0 / FPS
    y, v = (x[0] if len(x) else 0.0), 0.0
    out = np.empty_like(x)
    for i, target in enumerate(x):
        a = omega * omega * (target - y) - 2 * omega * v
        v += a * dt
        y += v * dt
        out[i] = y
    return out


def _plant_leg(
    rot: np.ndarray, root: np.ndarray, side: str, ankle: np.ndarray, foot_global: np.ndarray
) -> None:
    """Bend one leg (in place) so its ankle reaches ankle (T, 3) from the moved hips; the foot keeps foot_global."""
    up, knee, foot = JOINT_INDEX[f"{side}UpLeg"], JOINT_INDEX[f"{side}Leg"], JOINT_INDEX[f"{side}Foot"]
    pos, grot = forward_kinematics(rot, root)
    l1 = float(np.linalg.norm(REST_OFFSETS[knee]))
    l2 = float(np.linalg.norm(REST_OFFSETS[foot]))
    hip, k0 = pos[:, up], pos[:, knee]
    d = ankle - hip
    dist = np.clip(np.linalg.norm(d, axis=1), 1e-6, l1 + l2 - 1e-4)
    u = d / np.linalg.norm(d, axis=1, keepdims=True)
    hint = k0 - hip - np.sum((k0 - hip) * u, axis=1, keepdims=True) * u  # keep the knee's current plane
    fwd = quat.rotate(grot[:, 0], np.array([0.0, 0.0, 1.0]))
    hint = np.where(np.linalg.norm(hint, axis=1, keepdims=True) < 1e-4, fwd, hint)
    n = hint - np.sum(hint * u, axis=1, keepdims=True) * u
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-9)
    a = (l1 * l1 - l2 * l2 + dist * dist) / (2 * dist)
    h = np.sqrt(np.maximum(l1 * l1 - a * a, 0.0))
    knee_goal = hip + a[:, None] * u + h[:, None] * n
    ankle_goal = hip + dist[:, None] * u
    r1 = quat.between(k0 - hip, knee_goal - hip)
    g_up = quat.mul(r1, grot[:, up])
    rot[:, up] = quat.mul(quat.inv(grot[:, 0]), g_up)
    shin_now = quat.rotate(r1, pos[:, foot] - k0)
    r2 = quat.between(shin_now, ankle_goal - knee_goal)
    g_knee = quat.mul(r2, quat.mul(r1, grot[:, knee]))
    rot[:, knee] = quat.mul(quat.inv(g_up), g_knee)
    rot[:, foot] = quat.mul(quat.inv(g_knee), foot_global)


def enliven(
    rot: np.ndarray,
    root: np.ndarray,
    weight: np.ndarray,
    seed: int,
    gaze: np.ndarray | None = None,
    head_weight: np.ndarray | None = None,
    arms: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """The idle layer over a composed motion.

    Args:
        rot: (T, J, 4) local rotations (root yawed), as Motion.rotations.
        root: (T, 3) world hips, metres.
        weight: (T,) in [0, 1], how much of the layer each frame gets (``idle_weight``).
        seed: the character's seed (``seed_of``): breathing rate, shift times, drift phases.
        gaze: (T, 3) world points to look at, NaN where nothing calls for attention (eyes ahead).
        head_weight: (T,) in [0, 1], the gaze alone (head and neck) where the body is busy (typing);
            default: ``weight``.
        arms: (T,) in [0, 1], how much of the layer the shoulders and arms get (0 while a prop is in hand:
            the rest moves both hands as one, so a prop held in one or both hands stays in them); default 1.

    Returns:
        rotations (T, J, 4) and hips (T, 3) with the layer applied; frames with weight 0 are unchanged.
    """
    rot0 = np.asarray(rot, dtype=np.float64)
    root0 = np.asarray(root, dtype=np.float64)
    rot, root = rot0.copy(), root0.copy()
    w = np.clip(np.asarray(weight, dtype=np.float64), 0.0, 1.0)
    hw = w if head_weight is None else np.maximum(w, np.clip(head_weight, 0.0, 1.0))
    g = None if gaze is None else np.asarray(gaze, dtype=np.float64)
    aw = w if arms is None else w * np.clip(np.asarray(arms, dtype=np.float64), 0.0, 1.0)
    # Each stretch the layer covers has its own clock, starting at 0: an edit that moves a stretch in time,
    # or lengthens it, leaves its frames as they were, so the editor is sent only what the edit changed.
    for a, b in _runs(hw > 0):
        rot[a:b], root[a:b] = _enliven_run(
            rot0[a:b], root0[a:b], w[a:b], hw[a:b], seed, None if g is None else g[a:b], aw[a:b]
        )
    return rot, root


def _enliven_run(
    rot0: np.ndarray,
    root0: np.ndarray,
    w: np.ndarray,
    hw: np.ndarray,
    seed: int,
    gaze: np.ndarray | None,
    aw: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """``enliven`` over one stretch of frames, its clock starting at 0 (the weight shifts draw from their own
    generator: how many there are depends on the stretch's length, and the other draws must not)."""
    rot, root = rot0.copy(), root0.copy()
    t_count = len(rot)
    if t_count < 2:
        return rot, root
    rng = np.random.default_rng(seed)
    t = np.arange(t_count) / FPS
    pos, grot = forward_kinematics(rot, root)
    posture = _posture(rot, pos)
    standing = (posture == 0).astype(float)
    lying = (posture == 2).astype(float)

    period = rng.uniform(*BREATH_PERIOD_S)
    breath = np.sin(2 * np.pi * t / period + rng.uniform(0, 2 * np.pi))  # +1: lungs full
    breath_amp = w * (1.0 - 0.5 * lying)
    for j in ("Spine", "Spine1", "Spine2"):
        _post(rot, j, (1, 0, 0), -BREATH_DEG * breath * breath_amp)  # extend (chest up) on the in-breath
    _post(rot, "Neck", (1, 0, 0), 2.0 * BREATH_DEG * breath * breath_amp)  # keep the eyes level
    _post(rot, "LeftShoulder", (0, 0, 1), SHOULDER_DEG * breath * aw)
    _post(rot, "RightShoulder", (0, 0, 1), -SHOULDER_DEG * breath * aw)

    # Seated and standing: the torso drifts a little; the arms hang and sway with it.
    sway = _smooth_noise(rng, t, (6.3, 9.1))
    twist = _smooth_noise(rng, t, (7.7, 11.3))
    for j in ("Spine1", "Spine2"):
        _post(rot, j, (0, 0, 1), 1.2 * sway * w * (1 - lying))
        _post(rot, j, (0, 1, 0), 1.5 * twist * w * (1 - lying))
    for side, s in (("Left", 1.0), ("Right", -1.0)):
        _post(rot, f"{side}Arm", (0, 0, 1), s * 1.5 * _smooth_noise(rng, t, (3.1, 4.9)) * aw * (1 - lying))
        _post(
            rot, f"{side}ForeArm", (0, 1, 0), s * 3.0 * _smooth_noise(rng, t, (2.3, 3.7)) * aw * (1 - lying)
        )

    # Standing: the weight goes from foot to foot; the pelvis rises on the loaded side, the chest counters.
    shift = weight_shift(np.random.default_rng(seed + 1), t) * w * standing
    if np.any(shift != 0):
        ankles = pos[:, [JOINT_INDEX["LeftFoot"], JOINT_INDEX["RightFoot"]]]
        feet = grot[:, [JOINT_INDEX["LeftFoot"], JOINT_INDEX["RightFoot"]]]
        left = quat.rotate(grot[:, 0], np.array([1.0, 0.0, 0.0]))
        left[:, 1] = 0.0
        left /= np.maximum(np.linalg.norm(left, axis=1, keepdims=True), 1e-9)
        root += (SHIFT_M * shift)[:, None] * left
        root[:, 1] -= 0.006 * np.abs(shift)  # both knees soften a little through the shift
        _post(rot, "Hips", (0, 0, 1), PELVIS_DEG * shift)
        _post(rot, "Spine", (0, 0, 1), -0.6 * PELVIS_DEG * shift)
        _post(rot, "Spine1", (0, 0, 1), -0.4 * PELVIS_DEG * shift)
        _plant_leg(rot, root, "Left", ankles[:, 0], feet[:, 0])
        _plant_leg(rot, root, "Right", ankles[:, 1], feet[:, 1])

    # Gaze: toward what calls for attention, else a slow wander; far turns bring the chest along.
    pos2, grot2 = forward_kinematics(rot, root)
    if gaze is not None:
        yaw, pitch = _gaze_angles(rot, pos2, grot2, gaze)
    else:
        yaw, pitch = np.zeros(t_count), np.zeros(t_count)
    wander = np.radians(6.0) * _smooth_noise(rng, t, (5.3, 8.9))
    # Small quick adjustments on top (the eyes re-aim and the head follows): never quite still.
    # A small circle (yaw and pitch in quadrature) turns the head at a steady speed whatever the rest does.
    circle = 2 * np.pi * t / rng.uniform(1.4, 1.8) + rng.uniform(0, 2 * np.pi)
    jitter_yaw = np.radians(MICRO_DEG) * np.sin(circle)
    jitter_pitch = np.radians(MICRO_DEG) * np.cos(circle)
    looking = np.abs(yaw) > 1e-6
    yaw = (_follow(np.where(looking, yaw, wander)) + 0.3 * wander * looking + jitter_yaw) * hw * (1 - lying)
    pitch = (
        _follow(np.where(looking, pitch, np.radians(2.0) * _smooth_noise(rng, t, (4.7, 7.1)))) + jitter_pitch
    ) * hw
    chest = np.sign(yaw) * np.maximum(np.abs(yaw) - np.radians(35.0), 0.0) * 0.5 * w
    _post(rot, "Spine2", (0, 1, 0), np.degrees(chest))
    head_yaw = np.degrees(yaw - chest)
    for j, share in (("Neck", 0.4), ("Head", 0.6)):
        _post(rot, j, (0, 1, 0), share * head_yaw)
        _post(rot, j, (1, 0, 0), share * np.degrees(pitch))
    out = quat.normalize(rot)
    keep = hw <= 0  # untouched frames stay bit for bit what they were
    out[keep], root[keep] = rot0[keep], root0[keep]
    return out, root


BLINK_EVERY_S = (2.0, 5.5)  # seconds between blinks (seeded)
BLINK_FRAMES = 5  # frames a blink takes: close, closed, open


def blinks(frames: int, seed: int) -> np.ndarray:
    """(T,) eyes_closed weight in [0, 1]: a blink every few seconds, now and then a double blink."""
    rng = np.random.default_rng(seed + 1)
    out = np.zeros(frames)
    shape = np.array([0.5, 1.0, 1.0, 0.6, 0.2])
    f = int(rng.uniform(0.5, 2.0) * FPS)
    while f < frames:
        n = min(BLINK_FRAMES, frames - f)
        out[f : f + n] = np.maximum(out[f : f + n], shape[:n])
        f += int(rng.uniform(*BLINK_EVERY_S) * FPS) if rng.random() > 0.15 else BLINK_FRAMES + 3
    return out


def with_blinks(face: np.ndarray, names: Sequence[str], seed: int) -> np.ndarray:
    """(T, E) face weights with blinks on their "eyes_closed" column (unchanged when the rig has none)."""
    if "eyes_closed" not in names or len(face) == 0:
        return face
    out = np.array(face, dtype=np.float32, copy=True)
    k = list(names).index("eyes_closed")
    out[:, k] = np.maximum(out[:, k], blinks(len(out), seed).astype(np.float32))
    return out


STILL_DEG = 0.05  # degrees: a frame whose joints all turn less than this from the last one is still
STILL_MIN_S = 0.3  # seconds of stillness inside a segment that count as an idle stretch
CALM_CONTACTS = frozenset({"seat", "bed"})  # interactions whose contact the layer cannot break (hips)


def still_frames(rot: np.ndarray) -> np.ndarray:
    """(T,) True where no joint's local rotation changed by more than STILL_DEG since the frame before."""
    r = np.asarray(rot, dtype=np.float64)
    still = np.zeros(len(r), bool)
    if len(r) > 1:
        dot = np.clip(np.abs(np.sum(r[1:] * r[:-1], axis=-1)), 0.0, 1.0)
        still[1:] = np.degrees(2 * np.arccos(dot)).max(axis=1) < STILL_DEG
    return still


def _runs(mask: np.ndarray) -> list[tuple[int, int]]:
    idx = np.flatnonzero(mask)
    if not len(idx):
        return []
    breaks = np.flatnonzero(np.diff(idx) > 1)
    return [
        (int(a), int(b) + 1)
        for a, b in zip(np.r_[idx[0], idx[breaks + 1]], np.r_[idx[breaks], idx[-1]], strict=True)
    ]


def _calm(action: str) -> bool:
    """True when a segment's clip touches nothing the layer could pull a hand or foot away from."""
    try:
        clip = get_clip(action)
    except KeyError:
        return action in IDLE_ACTIONS or action == "walk"
    return clip.interaction is None or clip.interaction.object in CALM_CONTACTS


def _head_free(action: str) -> bool:
    """True when a segment leaves the head to the gaze: no walk, no clip that moves the head, touches a person
    or brings something held to the face."""
    try:
        clip = get_clip(action)
    except KeyError:
        return action in IDLE_ACTIONS
    touches_person = clip.interaction is not None and clip.interaction.object in ("person", "handheld")
    moves_head = "head" in clip.body_parts or "head" in clip.tags or "look" in clip.tags
    return not (touches_person or moves_head or "locomotion" in clip.tags or clip.drives_lower_body)


def idle_spans(
    segments: Sequence[Segment], frames: int, rot: np.ndarray | None = None
) -> list[tuple[int, int]]:
    """[start, end) frames of a motion's idle stretches.

    Holds and waits, frames no segment covers, and (given the rotations) every still run of at least
    STILL_MIN_S inside a segment whose clip holds no hand contact (the end of a sit, a held gesture).
    """
    mask = np.zeros(frames, bool)
    covered = np.zeros(frames, bool)
    still = still_frames(rot) if rot is not None else np.zeros(frames, bool)
    least = int(STILL_MIN_S * FPS)
    for s in segments:
        a, b = max(0, s.start_frame), min(frames, s.end_frame)
        covered[a:b] = True
        if s.action in IDLE_ACTIONS:
            mask[a:b] = True
        elif rot is not None and _calm(s.action):
            for ra, rb in _runs(still[a:b]):
                if rb - ra >= least:
                    mask[a + ra : a + rb] = True
    mask |= ~covered
    return _runs(mask)


HEAD_ABOVE_HIPS_M = 0.62  # metres from the hips to the eyes of a standing character (where others look)
LOOK_AHEAD_S = 1.2  # seconds before an action that the character looks at what it will use
NOTICE_M = 7.0  # metres within which another character's acting draws the eyes


def attention(
    name: str,
    motions: dict[str, Motion],
    upcoming: dict[int, tuple[float, float, float] | str] | None = None,
) -> np.ndarray:
    """(T, 3) world points one character looks at while idle; NaN where nothing calls for attention.

    Who acts or walks draws the eyes (the one who started most recently wins, within NOTICE_M); for the
    last LOOK_AHEAD_S before one of the character's own actions, what that action uses: ``upcoming`` maps
    an action index to a world point (an object) or the name of a character.
    """
    own = motions[name]
    root = from_wire(own.root_position).astype(np.float64)
    frames = len(root)
    out = np.full((frames, 3), np.nan)
    since = np.full(frames, -1)  # start frame of the action now drawing the eyes
    for other, m in motions.items():
        if other == name:
            continue
        o_root = from_wire(m.root_position).astype(np.float64)[:frames]
        present = from_wire(m.present)[:frames] > 0 if m.present is not None else np.ones(len(o_root), bool)
        head = o_root + np.array([0.0, HEAD_ABOVE_HIPS_M * 0.9, 0.0])
        for s in m.segments:
            if s.action in IDLE_ACTIONS:
                continue
            a, b = max(0, s.start_frame), min(frames, s.end_frame, len(o_root))
            if b <= a:
                continue
            k = np.arange(a, b)
            near = np.linalg.norm((o_root[a:b] - root[a:b])[:, [0, 2]], axis=1) < NOTICE_M
            take = near & present[a:b] & (since[a:b] <= s.start_frame)
            out[k[take]] = head[k[take]]
            since[k[take]] = s.start_frame
    ahead = int(LOOK_AHEAD_S * FPS)
    for s in own.segments:
        goal = (upcoming or {}).get(s.action_index) if s.action not in IDLE_ACTIONS else None
        if goal is None:
            continue
        a, b = max(0, s.start_frame - ahead), min(frames, s.start_frame)
        if b <= a:
            continue
        if isinstance(goal, str):
            if goal not in motions:
                continue
            g_root = from_wire(motions[goal].root_position).astype(np.float64)
            out[a:b] = g_root[np.minimum(np.arange(a, b), len(g_root) - 1)] + [0, HEAD_ABOVE_HIPS_M * 0.9, 0]
        else:
            out[a:b] = goal
    return out


def enliven_motion(
    motion: Motion,
    gaze: np.ndarray | None = None,
    seed: int | None = None,
    touching: Sequence[tuple[int, int]] = (),
) -> Motion:
    """A composed Motion with the idle layer over its idle stretches (``enliven``); props' frames untouched.

    ``touching``: [start, end) frames where the character's hands were solved onto another character (a
    handshake, a hug, a hand on the shoulder, services/motion/pairs.py): there the layer leaves the body and
    arms as solved (eased in and out like a held prop), so breathing and weight shifts do not pull the
    meeting hands apart; the gaze still plays.

    The layer is laid window by window (each run of frames it touches, ``_windows``), each in its own time
    and seed, so a window is a function of its own frames only: an edit that shifts the time line
    leaves every window it does not touch as it was, and those come from a cache (``_WINDOWS``) instead of
    being laid again. What a story edit costs is then the windows near the edit, not the whole story.
    """
    root = from_wire(motion.root_position)  # as sent (float32): hashed per window as it is, widened there
    rot = from_wire(motion.rotations)
    frames = len(root)
    held = in_hand(motion, rot, root)
    weight = idle_weight(frames, idle_spans(motion.segments, frames, rot))
    if touching:
        weight = weight * _arms_free(frames, touching)
    arms = _arms_free(frames, [*held, *touching])
    head = idle_weight(
        frames, [(s.start_frame, s.end_frame) for s in motion.segments if _head_free(s.action)]
    )
    if not np.any(np.maximum(weight, head) > 0):
        return motion
    seed = seed_of(motion.character) if seed is None else seed
    out_rot, out_root = rot.astype(np.float32), root.astype(np.float32)
    for a, b in _windows(np.maximum(weight, head) > 0):
        look = None if gaze is None else np.asarray(gaze, dtype=np.float64)[a:b]
        out_rot[a:b], out_root[a:b] = _window(
            rot[a:b], root[a:b], weight[a:b], seed, look, head[a:b], arms[a:b]
        )
    props = _props_in_hand(motion, rot, root, out_rot, out_root) if held else motion.props
    return msgspec.structs.replace(
        motion, root_position=to_wire(out_root), rotations=to_wire(out_rot), props=props
    )


def _arms_free(frames: int, held: Sequence[tuple[int, int]]) -> np.ndarray:
    """(T,) 0 where a prop is in hand, eased back to 1 over RAMP_S either side."""
    ramp = max(1, int(round(RAMP_S * FPS)))
    k = np.arange(frames)
    out = np.ones(frames)
    for a, b in held:
        gap = np.maximum(np.maximum(a - k, k - (b - 1)), 0) / ramp  # 0 inside, 1 a ramp away
        u = np.clip(gap, 0.0, 1.0)
        out = np.minimum(out, u * u * (3 - 2 * u))
    return out


def _props_in_hand(
    motion: Motion, rot: np.ndarray, root: np.ndarray, new_rot: np.ndarray, new_root: np.ndarray
) -> list:
    """Prop tracks carried along where the layer moved their joint while the prop is in hand."""
    pos0, g0 = forward_kinematics(np.asarray(rot, np.float64), np.asarray(root, np.float64))
    pos1, g1 = forward_kinematics(np.asarray(new_rot, np.float64), np.asarray(new_root, np.float64))
    out = []
    for p in motion.props:
        joint = JOINT_INDEX.get(p.joint)
        a, b = max(0, p.start_frame), min(len(rot), p.end_frame)
        at = from_wire(p.position).astype(np.float64)
        if joint is None or b <= a or len(at) < b - p.start_frame:
            out.append(p)
            continue
        q = from_wire(p.rotation).astype(np.float64)
        k = slice(a - p.start_frame, b - p.start_frame)
        grip = at[k] + quat.rotate(q[k], np.asarray(p.grip, float))
        near = np.linalg.norm(grip - pos0[a:b, joint], axis=1) < IN_HAND_M
        turn = quat.mul(g1[a:b, joint], quat.inv(g0[a:b, joint]))
        moved_at = pos1[a:b, joint] + quat.rotate(turn, at[k] - pos0[a:b, joint])
        at[k] = np.where(near[:, None], moved_at, at[k])
        q[k] = np.where(near[:, None], quat.normalize(quat.mul(turn, q[k])), q[k])
        out.append(
            msgspec.structs.replace(
                p, position=to_wire(at.astype(np.float32)), rotation=to_wire(q.astype(np.float32))
            )
        )
    return out


IN_HAND_M = 0.05  # metres from the holding joint to a prop's grip point within which the prop is in hand


def in_hand(motion: Motion, rot: np.ndarray, root: np.ndarray) -> list[tuple[int, int]]:
    """[start, end) frames in which a prop track's grip point is on its joint: the prop is in the hand.

    A track also covers a prop the character set down (services/orchestrator: it stays where it was put,
    a still track until someone takes it): those frames are not held, and the layer may move the hand.
    """
    frames = len(rot)
    mask = np.zeros(frames, bool)
    if not motion.props:
        return []
    pos, _ = forward_kinematics(np.asarray(rot, np.float64), np.asarray(root, np.float64))
    for p in motion.props:
        a, b = max(0, p.start_frame), min(frames, p.end_frame)
        if b <= a:
            continue
        joint = JOINT_INDEX.get(p.joint)
        if joint is None:
            mask[a:b] = True
            continue
        at = from_wire(p.position).astype(np.float64)[: b - a]
        grip = at + quat.rotate(from_wire(p.rotation).astype(np.float64)[: b - a], np.asarray(p.grip, float))
        mask[a : a + len(at)] |= np.linalg.norm(grip - pos[a : a + len(at), joint], axis=1) < IN_HAND_M
    return _runs(mask)


WINDOW_GAP = 2  # frames: touched runs closer than this are laid as one window
_WINDOWS: dict[bytes, tuple[np.ndarray, np.ndarray]] = {}  # content digest -> laid window (float32)
_WINDOW_BYTES = [0]
WINDOW_CACHE_BYTES = 96 * 2**20  # the cache is emptied when it holds more than this


def _windows(touched: np.ndarray) -> list[tuple[int, int]]:
    """[start, end) runs of touched frames, runs closer than WINDOW_GAP merged."""
    runs = _runs(touched)
    out: list[tuple[int, int]] = []
    for a, b in runs:
        if out and a - out[-1][1] < WINDOW_GAP:
            out[-1] = (out[-1][0], b)
        else:
            out.append((a, b))
    return out


def _window(
    rot: np.ndarray,
    root: np.ndarray,
    weight: np.ndarray,
    seed: int,
    gaze: np.ndarray | None,
    head: np.ndarray,
    arms: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """``enliven`` over one window in its own time (t = 0 at its first frame), seeded by the character's
    seed and the window's length (windows of one character differ; the same window is laid the same
    wherever the story puts it), from the cache when these exact frames were laid before."""
    parts = [rot, root, weight, head, arms] + ([] if gaze is None else [gaze])
    digest = hashlib.blake2b(f"{seed}:{len(rot)}:{gaze is None}".encode(), digest_size=16)
    for part in parts:
        digest.update(np.ascontiguousarray(part).tobytes())
    key = digest.digest()
    hit = _WINDOWS.get(key)
    if hit is not None:
        return hit
    own_seed = (seed + 7919 * len(rot)) & 0x7FFFFFFF
    r, p = enliven(rot.astype(np.float64), root.astype(np.float64), weight, own_seed, gaze, head, arms)
    laid = (r.astype(np.float32), p.astype(np.float32))
    if _WINDOW_BYTES[0] > WINDOW_CACHE_BYTES:
        _WINDOWS.clear()
        _WINDOW_BYTES[0] = 0
    _WINDOWS[key] = laid
    _WINDOW_BYTES[0] += laid[0].nbytes + laid[1].nbytes
    return laid
