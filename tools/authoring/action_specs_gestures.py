"""Gestures authored as curves, with the principles of animation (issue 23).

A gesture keyed as a few whole poses with ease in/out between each stops dead at every key and moves
every joint in lockstep: a mannequin. Here each joint follows its own smooth curve (a clamped cubic
spline through a few values, or a damped oscillation) sampled to one key per frame, so that

- anticipation: a small move the other way first (the arm dips and pulls back before it rises);
- follow-through and overlapping action: the joint that drives leads and the ones it carries lag
  (upper arm -> forearm -> hand; neck -> head), and they overshoot and settle;
- arcs: limbs move by directions interpolated on the sphere, so hands travel on arcs;
- ease in / out: the curves start, stop and turn with zero speed and never overshoot their points;
- secondary motion: the head tilts, the chest turns and the free arm sways with the gesture;
- moving holds: a held pose keeps drifting a little, it never freezes.

The wave is at shoulder height with the forearm swinging; pointing turns the body toward where it
points; nodding and head shakes are damped; the shrug lifts the shoulders; laughing bounces them.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
from scipy.interpolate import CubicHermiteSpline, PchipInterpolator

from tools.authoring.author_actions import Spec
from wana.domain import quat
from wana.domain.posing import Pose, arm, merge, neutral
from wana.domain.units import FPS

N = neutral()
REST_UPPER = (0.12, -1.0, 0.0)  # neutral upper-arm direction (posing.neutral)
REST_FORE = (0.08, -1.0, 0.18)


def curve(points: Sequence[tuple[float, float]]) -> Callable[[float], float]:
    """A smooth curve through (t, value) points that never overshoots them (monotone cubic, PCHIP slopes):
    zero speed at both ends and at every turning point, so each extreme eases in and out."""
    ts, vs = zip(*points, strict=True)
    t_arr, v_arr = np.asarray(ts, float), np.asarray(vs, float)
    slopes = PchipInterpolator(t_arr, v_arr).derivative()(t_arr)
    slopes[0] = slopes[-1] = 0.0
    spline = CubicHermiteSpline(t_arr, v_arr, slopes)
    lo, hi = ts[0], ts[-1]
    return lambda t: float(spline(min(max(t, lo), hi)))


def lerp_dir(a: Sequence[float], b: Sequence[float], u: float) -> tuple[float, float, float]:
    """Direction between unit-normalised a and b by u on the great circle (u outside [0, 1] extrapolates)."""
    va = np.asarray(a, float) / np.linalg.norm(a)
    vb = np.asarray(b, float) / np.linalg.norm(b)
    q = quat.slerp(quat.identity(), quat.between(va, vb), u)
    v = quat.rotate(q, va)
    return float(v[0]), float(v[1]), float(v[2])


def arc_dir(
    a: Sequence[float], via: Sequence[float], b: Sequence[float], u: float
) -> tuple[float, float, float]:
    """Direction from a (u = 0) through via (u = 0.5) to b (u = 1): an arc that avoids the body."""
    if u <= 0.5:
        return lerp_dir(a, via, 2.0 * u)
    return lerp_dir(via, b, 2.0 * u - 1.0)


FORE_FRONT = (0.3, 0.05, 0.95)  # the forearm held out in front: the way from hanging to raised


def turn(pitch: float = 0.0, yaw: float = 0.0, roll: float = 0.0) -> np.ndarray:
    """A local rotation from degrees (pitch > 0 bends forward / looks down, yaw > 0 turns left)."""
    return quat.from_euler("YXZ", np.array([yaw, pitch, roll]))


def trunk(pitch: float = 0.0, yaw: float = 0.0, roll: float = 0.0) -> Pose:
    """Spine joints sharing a bend, the upper ones a little more (the chest carries the gesture)."""
    w = (0.25, 0.35, 0.4)
    return {
        j: turn(pitch * k, yaw * k, roll * k) for j, k in zip(("Spine", "Spine1", "Spine2"), w, strict=True)
    }


def neck_head(
    pitch_neck: float, pitch_head: float, yaw_neck: float = 0.0, yaw_head: float = 0.0, roll: float = 0.0
) -> Pose:
    return {"Neck": turn(pitch_neck, yaw_neck, roll * 0.4), "Head": turn(pitch_head, yaw_head, roll * 0.6)}


def shoulders(left: float = 0.0, right: float = 0.0) -> Pose:
    """Shoulder lifts in degrees (> 0 up)."""
    return {
        "LeftShoulder": quat.from_euler("XYZ", np.array([0.0, 0.0, left])),
        "RightShoulder": quat.from_euler("XYZ", np.array([0.0, 0.0, -right])),
    }


def frames(duration: float, pose_at: Callable[[float], Pose]) -> list[tuple]:
    """One key per frame from a pose function of time (the first key neutral, the last back at neutral)."""
    n = int(round(duration * FPS))
    keys: list[tuple] = [(0.0, N, "linear")]
    for i in range(1, n + 1):
        t = i / FPS
        keys.append((round(t, 4), merge(N, pose_at(t)) if i < n else N, "linear"))
    return keys


def _bump(t: float, a: float, b: float) -> float:
    """0 outside [a, b], a smooth sine bump peaking at 1 in the middle."""
    if t <= a or t >= b:
        return 0.0
    return float(np.sin(np.pi * (t - a) / (b - a)) ** 2)


def _ramp(t: float, a: float, b: float) -> float:
    u = min(max((t - a) / (b - a), 0.0), 1.0)
    return u * u * (3 - 2 * u)


def wave_pose(
    side: str, raise_at: Callable[[float], float], t: float, period: float, start: float, end: float
) -> Pose:
    """The waving arm at shoulder height, the forearm swinging from the elbow, the hand trailing it."""
    r = raise_at(t)
    r_fore = raise_at(t - 0.06)  # the forearm follows the upper arm up and down (overlap)
    dip = _bump(t, 0.0, 0.3)  # anticipation: the elbow drops and pulls back before the rise
    env = _ramp(t, start, start + 0.25) * (1.0 - _ramp(t, end - 0.3, end))
    phase = 2 * np.pi * (t - start) / period
    upper = lerp_dir(REST_UPPER, (0.85, 0.2, 0.45), r)
    upper = (
        upper[0] - 0.12 * dip + 0.05 * env * np.sin(phase + 0.7),
        upper[1] - 0.05 * dip,
        upper[2] - 0.25 * dip,
    )
    fore = arc_dir(REST_FORE, FORE_FRONT, (0.05, 1.0, 0.2), r_fore)
    fore = (fore[0] + env * (0.08 + 0.42 * np.sin(phase)), fore[1], fore[2])
    hand = (0.0, 28.0 * env * np.sin(phase - 0.9), -10.0 * r)  # trails the forearm side to side
    lift = 7.0 * r - 3.0 * dip
    s = 1.0 if side == "L" else -1.0  # the body leans away from a raised left arm, toward the right
    free = "R" if side == "L" else "L"
    sway = 0.04 * env * np.sin(phase * 0.5)
    return merge(
        arm(side, upper, fore, hand),
        arm(free, (0.14 + 0.04 * r + sway, -1.0, 0.03), (0.1 + sway, -1.0, 0.22 + 0.05 * r)),
        shoulders(left=lift if side == "L" else 0.0, right=lift if side == "R" else 0.0),
        trunk(pitch=-3.0 * r, yaw=s * 5.0 * r, roll=-s * 3.0 * r + s * 1.0 * env * np.sin(phase + np.pi)),
        neck_head(-1.5 * r, -3.0 * r, roll=s * 7.0 * r + s * 1.5 * env * np.sin(phase - 1.5)),
    )


def wave(side: str = "R", cycles: int = 3, period: float = 0.52) -> list[tuple]:
    start = 0.6
    end = start + cycles * period + 0.12
    duration = end + 0.6
    raise_at = curve(
        [
            (0.0, 0.0),
            (0.12, -0.05),
            (0.65, 1.08),
            (0.8, 1.0),
            (end, 0.98),
            (end + 0.45, -0.03),
            (duration, 0.0),
        ]
    )
    return frames(duration, lambda t: wave_pose(side, raise_at, t, period, start, end))


def wave_both(cycles: int = 3, period: float = 0.6) -> list[tuple]:
    """Both arms wave overhead-wide (signalling), mirrored, the body bouncing with the swings."""
    start = 0.65
    end = start + cycles * period + 0.1
    duration = end + 0.65
    raise_at = curve(
        [
            (0.0, 0.0),
            (0.15, -0.06),
            (0.7, 1.06),
            (0.85, 1.0),
            (end, 0.97),
            (end + 0.5, -0.03),
            (duration, 0.0),
        ]
    )

    def pose(t: float) -> Pose:
        r, rf = raise_at(t), raise_at(t - 0.07)
        env = _ramp(t, start, start + 0.3) * (1.0 - _ramp(t, end - 0.3, end))
        phase = 2 * np.pi * (t - start) / period
        upper = lerp_dir(REST_UPPER, (0.6, 0.75, 0.2), r)
        fore = arc_dir(REST_FORE, FORE_FRONT, (0.0, 1.0, 0.1), rf)
        out: Pose = {}
        for side, s in (("L", 1.0), ("R", -1.0)):
            f = (fore[0] + 0.5 * env * np.sin(phase), fore[1], fore[2])
            u = (upper[0] + 0.05 * env * np.sin(phase + 0.7), upper[1], upper[2])
            out.update(arm(side, u, f, (0.0, 0.0, 25.0 * env * np.sin(phase - 0.9) * s)))
        return merge(
            out,
            shoulders(6.0 * r, 6.0 * r),
            trunk(pitch=-4.0 * r + 1.5 * env * np.sin(2 * phase)),
            neck_head(-2.0 * r, -4.0 * r),
        )

    return frames(duration, pose)


def point(
    side: str,
    aim: tuple[float, float, float],
    body_yaw: float,
    head_yaw: float,
    head_pitch: float = 0.0,
    body_pitch: float = 0.0,
    duration: float = 2.3,
) -> list[tuple]:
    """Point along aim (arm-frame direction): the eyes go first, the arm pulls back, then thrusts out past
    the aim and settles, the chest turns with it; a moving hold with a bent elbow; the forearm trails home."""
    aim_v = np.asarray(aim, float) / np.linalg.norm(aim)
    upper_aim = lerp_dir(aim_v, (aim_v[0], aim_v[1] - 0.35, aim_v[2]), 1.0)  # elbow a little below the line
    fore_aim = lerp_dir(aim_v, (aim_v[0], aim_v[1] + 0.12, aim_v[2]), 1.0)
    hold_end = duration - 0.6
    reach = curve([(0.0, 0.0), (0.2, 0.0), (0.68, 1.07), (0.85, 1.0), (hold_end, 0.96), (duration, 0.0)])
    look = curve([(0.0, 0.0), (0.3, 1.0), (hold_end, 1.0), (duration - 0.15, 0.0), (duration, 0.0)])
    body = curve([(0.0, 0.0), (0.2, -0.15), (0.7, 1.05), (0.9, 1.0), (hold_end + 0.05, 1.0), (duration, 0.0)])

    def pose(t: float) -> Pose:
        r, rf, b, lk = reach(t), reach(t - 0.07), body(t), look(t)
        drift = 0.02 * np.sin(2 * np.pi * t / 1.3) * min(r, 1.0)
        pull = _bump(t, 0.0, 0.45)  # anticipation: the elbow draws back and bends before the thrust
        upper = lerp_dir(lerp_dir(REST_UPPER, upper_aim, max(r, 0.0)), (0.2, -0.9, -0.35), 0.6 * pull)
        fore = lerp_dir(lerp_dir(REST_FORE, fore_aim, max(rf, 0.0)), (0.15, -0.35, 0.9), 0.6 * pull)
        upper = (upper[0], upper[1] + drift, upper[2])
        s = 1.0 if side == "L" else -1.0
        free = "R" if side == "L" else "L"
        return merge(
            arm(side, upper, fore, (0.0, 0.0, 5.0 * r)),
            arm(free, (0.14 + 0.05 * b, -1.0, -0.02 * b), (0.1, -1.0, 0.25)),
            trunk(pitch=body_pitch * b, yaw=body_yaw * b, roll=-s * 2.0 * b),
            neck_head(0.4 * head_pitch * lk, 0.6 * head_pitch * lk, 0.4 * head_yaw * lk, 0.6 * head_yaw * lk),
        )

    return frames(duration, pose)


def nod(duration: float = 1.5) -> list[tuple]:
    """Yes: a small lift of the chin, then two nods, the second smaller; the head lags the neck."""
    p = curve([(0.0, 0.0), (0.12, -4.0), (0.36, 16.0), (0.6, 1.0), (0.84, 11.0), (1.1, 1.5), (duration, 0.0)])

    def pose(t: float) -> Pose:
        return merge(
            neck_head(0.45 * p(t), 0.55 * p(t - 0.06)),
            trunk(pitch=0.15 * p(t + 0.03)),
            shoulders(0.8 * _bump(t, 0.2, 0.6), 0.8 * _bump(t, 0.2, 0.6)),
        )

    return frames(duration, pose)


def shake_head(duration: float = 1.7) -> list[tuple]:
    """No: damped side-to-side turns, the head trailing the neck and rolling with the turn."""
    y = curve(
        [
            (0.0, 0.0),
            (0.14, 4.0),
            (0.38, -22.0),
            (0.65, 20.0),
            (0.92, -15.0),
            (1.2, 8.0),
            (1.45, -2.0),
            (duration, 0.0),
        ]
    )

    def pose(t: float) -> Pose:
        return merge(
            neck_head(
                2.0 * _bump(t, 0.1, 1.5),
                3.0 * _bump(t, 0.1, 1.5),
                0.45 * y(t),
                0.55 * y(t - 0.05),
                roll=0.15 * y(t - 0.08),
            ),
            trunk(yaw=0.1 * y(t + 0.03)),
        )

    return frames(duration, pose)


def shrug(duration: float = 1.8) -> list[tuple]:
    """The shoulders rise fast past their mark, hold while sinking a little, and drop below rest before
    settling; elbows bend and the palms turn up a beat later; the head tilts."""
    s = curve(
        [
            (0.0, 0.0),
            (0.12, -0.12),
            (0.42, 1.07),
            (0.55, 1.0),
            (1.1, 0.9),
            (1.42, -0.1),
            (1.6, 0.02),
            (duration, 0.0),
        ]
    )

    def pose(t: float) -> Pose:
        u, ua = s(t), s(t - 0.06)
        upper = lerp_dir(REST_UPPER, (0.3, -0.8, 0.3), ua)
        fore = lerp_dir(REST_FORE, (0.55, -0.1, 0.8), s(t - 0.1))
        return merge(
            arm("L", upper, fore, (0.0, 0.0, 70.0 * max(ua, 0.0))),
            arm("R", upper, fore, (0.0, 0.0, 70.0 * max(ua, 0.0))),
            shoulders(16.0 * u, 16.0 * u),
            trunk(pitch=-3.0 * ua),
            neck_head(-2.0 * u, -3.0 * s(t - 0.08), roll=9.0 * s(t - 0.1)),
        )

    return frames(duration, pose)


def laugh(duration: float = 2.6) -> list[tuple]:
    """The head goes back, then the laugh doubles the body over while the shoulders bounce, fading."""
    env = curve([(0.0, 0.0), (0.25, 1.0), (1.6, 0.8), (2.2, 0.15), (duration, 0.0)])
    lean = curve([(0.0, 0.0), (0.12, 2.0), (0.45, -8.0), (1.3, 9.0), (2.0, 5.0), (duration, 0.0)])
    hands = curve([(0.0, 0.0), (0.5, 0.0), (1.0, 1.0), (1.9, 1.0), (duration, 0.0)])

    def pose(t: float) -> Pose:
        e = env(t)
        bounce = e * abs(np.sin(2 * np.pi * t / 0.64))  # about three pulses a second, shoulders up on each
        h = hands(t)
        upper = lerp_dir(REST_UPPER, (0.25, -0.9, 0.4), h)
        fore = lerp_dir(REST_FORE, (-0.55, 0.05, 0.85), hands(t - 0.08))
        return merge(
            arm("L", (upper[0] + 0.03 * bounce, upper[1], upper[2]), fore),
            arm("R", (upper[0] + 0.03 * bounce, upper[1], upper[2]), fore),
            shoulders(9.0 * bounce, 9.0 * bounce),
            trunk(pitch=lean(t) + 2.5 * bounce),
            neck_head(0.6 * lean(t - 0.05) - 6.0 * e, 0.8 * lean(t - 0.1) - 10.0 * e + 3.0 * bounce),
        )

    return frames(duration, pose)


def specs() -> list[Spec]:
    return [
        Spec(
            "wave",
            ["greet", "gesture", "social"],
            ["wave at", "wave hello", "greet", "say hello", "say goodbye", "hail", "wave goodbye"],
            wave("R"),
        ),
        Spec("wave_left_hand", ["greet", "gesture"], ["wave with the left hand"], wave("L")),
        Spec(
            "wave_hands",
            ["greet", "gesture", "happy", "social"],
            ["wave both hands", "wave both arms", "signal", "flag down"],
            wave_both(),
        ),
        Spec(
            "point",
            ["gesture", "social"],
            ["point at", "point to", "indicate", "show"],
            point("R", (0.25, 0.1, 1.0), body_yaw=-14.0, head_yaw=-8.0, body_pitch=4.0),
        ),
        Spec(
            "point_left",
            ["gesture"],
            ["point to the left"],
            point("L", (1.0, 0.1, 0.35), body_yaw=28.0, head_yaw=40.0),
        ),
        Spec(
            "point_right",
            ["gesture"],
            ["point to the right"],
            point("R", (1.0, 0.1, 0.35), body_yaw=-28.0, head_yaw=-40.0),
        ),
        Spec(
            "point_up",
            ["gesture"],
            ["point upward", "point at the sky"],
            point("R", (0.3, 0.95, 0.35), body_yaw=-6.0, head_yaw=-5.0, head_pitch=-28.0, body_pitch=-6.0),
        ),
        Spec(
            "point_down",
            ["gesture"],
            ["point at the floor", "point downward"],
            point("R", (0.2, -0.6, 0.9), body_yaw=-8.0, head_yaw=-5.0, head_pitch=28.0, body_pitch=10.0),
        ),
        Spec(
            "nod",
            ["gesture", "agree", "head"],
            ["agree", "nod yes", "nod the head", "say yes", "accept"],
            nod(),
            body_parts=["head"],
        ),
        Spec(
            "shake_head",
            ["gesture", "disagree", "head"],
            ["say no", "refuse", "disagree", "deny", "decline"],
            shake_head(),
            body_parts=["head"],
        ),
        Spec("shrug", ["gesture", "doubt"], ["shrug shoulders", "not know"], shrug()),
        Spec("laugh", ["happy", "emotion"], ["giggle", "chuckle", "smile", "be amused"], laugh()),
    ]
