"""How a manner word changes a walk: speed (and with it stride and cadence), arm swing, trunk and head.

The locomotion network picks cadence and stride from the speed it is asked for (captured people lengthen
their stride as they speed up), so a manner's speed factor changes the stride too; arm swing and posture
are laid over the network's poses afterwards: each arm's rotation is split into its slow part (a one-cycle
moving average) and the swing about it, and the swing is scaled; the chest leans and the head pitches by a
fixed angle. Only the upper body is touched, so the planted feet stay where the network put them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from wana.domain import quat
from wana.domain.skeleton import JOINT_INDEX


@dataclass(frozen=True)
class GaitStyle:
    """speed: factor on the commanded speed; arm_swing: factor on the arms' swing about their mean;
    trunk_deg: chest lean forward (+) or back (-); head_deg: head down (+) or up (-)."""

    speed: float = 1.0
    arm_swing: float = 1.0
    trunk_deg: float = 0.0
    head_deg: float = 0.0


NEUTRAL = GaitStyle()
_SLOW = GaitStyle(speed=0.6, arm_swing=0.7, head_deg=4.0)
_BRISK = GaitStyle(speed=1.3, arm_swing=1.4, trunk_deg=3.0)
_QUICK = GaitStyle(speed=1.5, arm_swing=1.3, trunk_deg=4.0)
_TIRED = GaitStyle(speed=0.65, arm_swing=0.45, trunk_deg=10.0, head_deg=16.0)
_HAPPY = GaitStyle(speed=1.1, arm_swing=1.35, trunk_deg=-3.0, head_deg=-6.0)
_SAD = GaitStyle(speed=0.75, arm_swing=0.55, trunk_deg=6.0, head_deg=14.0)
MANNER_GAITS: dict[str, GaitStyle] = {
    "slowly": _SLOW,
    "slow": _SLOW,
    "leisurely": GaitStyle(speed=0.7, arm_swing=0.8),
    "briskly": _BRISK,
    "brisk": _BRISK,
    "quickly": _QUICK,
    "fast": _QUICK,
    "hurriedly": GaitStyle(speed=1.6, arm_swing=1.3, trunk_deg=6.0),
    "tiredly": _TIRED,
    "wearily": _TIRED,
    "sleepily": _TIRED,
    "happily": _HAPPY,
    "cheerfully": _HAPPY,
    "joyfully": _HAPPY,
    "sadly": _SAD,
    "proudly": GaitStyle(speed=1.0, arm_swing=1.15, trunk_deg=-4.0, head_deg=-8.0),
}
ARM_JOINTS = ("LeftArm", "RightArm")
FOREARM_JOINTS = ("LeftForeArm", "RightForeArm")
CYCLE_FRAMES = 31  # about one gait cycle at 30 fps: the moving average that leaves the swing out


def gait_style(manner: str) -> GaitStyle:
    """The walk a manner word asks for (neutral for words that say nothing about walking)."""
    return MANNER_GAITS.get(manner.strip().lower(), NEUTRAL)


def _slow_part(q: np.ndarray) -> np.ndarray:
    """(T, 4) moving average of unit quaternions over CYCLE_FRAMES (sign-aligned, renormalised)."""
    q = q.copy()
    flip = np.sum(q[1:] * q[:-1], axis=-1) < 0
    sign = np.cumprod(np.concatenate([[1.0], np.where(flip, -1.0, 1.0)]))
    q *= sign[:, None]
    half = CYCLE_FRAMES // 2
    padded = np.pad(q, ((half, half), (0, 0)), mode="edge")
    kernel = np.ones(CYCLE_FRAMES) / CYCLE_FRAMES
    mean = np.stack([np.convolve(padded[:, k], kernel, mode="valid") for k in range(4)], -1)
    return quat.normalize(mean)


def scale_swing(q: np.ndarray, factor: float) -> np.ndarray:
    """(T, 4) local rotations whose swing about their one-cycle mean is scaled by factor."""
    if len(q) < 3 or factor == 1.0:
        return q
    mean = _slow_part(q)
    dev = Rotation.from_quat(quat.mul(quat.inv(mean), q)).as_rotvec() * factor
    return quat.mul(mean, Rotation.from_rotvec(dev).as_quat())


def apply_gait_style(rotations: np.ndarray, style: GaitStyle) -> np.ndarray:
    """(T, J, 4) rotations of a walk with the style's arm swing and posture (speed is the planner's)."""
    if style == NEUTRAL or len(rotations) == 0:
        return rotations
    out = rotations.copy()
    for name in ARM_JOINTS:
        out[:, JOINT_INDEX[name]] = scale_swing(out[:, JOINT_INDEX[name]], style.arm_swing)
    for name in FOREARM_JOINTS:  # the elbow follows the swing, less
        out[:, JOINT_INDEX[name]] = scale_swing(
            out[:, JOINT_INDEX[name]], 1.0 + 0.5 * (style.arm_swing - 1.0)
        )
    x_axis = np.array([1.0, 0.0, 0.0])  # the character's left: a positive angle bends forward
    for names, deg in ((("Spine1", "Spine2"), style.trunk_deg), (("Neck", "Head"), style.head_deg)):
        if deg:
            bend = quat.from_axis_angle(x_axis, np.radians(deg / len(names)))
            for name in names:
                j = JOINT_INDEX[name]
                out[:, j] = quat.mul(out[:, j], np.broadcast_to(bend, out[:, j].shape))
    return out
