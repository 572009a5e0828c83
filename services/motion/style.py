"""The motion service's side of motion style: a manner word plays a clip faster or slower, wider or smaller.

The parameters and their mapping from a mood live in the domain library (wana.domain.style), because the
orchestrator applies the social model's emotions to the composed time line with the same ones; here is
what only sampling a clip can do: change its tempo, and keep a clip played faster and wider within what a
body can do (wana.domain.body_limits): "Ivy jumps happily" played the jump 14 % faster and wider, and its
hands swung at 11 m/s.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from services.motion.ik import joint_globals
from wana.domain.actions import ActionClip
from wana.domain.body_limits import HIPS_MAX_MS, hand_limit
from wana.domain.skeleton import JOINT_INDEX
from wana.domain.style import MANNER_MOOD, Style, apply_style, mood_of, style_of
from wana.domain.units import FPS

SPEED_MARGIN = 0.9  # a styled clip's fastest hand or hips stays within this share of the body's limit


def resample_fps(fps: int, style: Style) -> int:
    """The rate to sample a clip at so that played at fps it runs style.tempo times as fast."""
    return max(1, int(round(fps / max(style.tempo, 0.2))))


_PEAKS: dict[tuple[str, float], float] = {}


def peak_share(clip: ActionClip) -> float:
    """The clip's fastest hand or hips, played as authored, as a share of how fast a body may move them
    (memoised by name and length: a clip made from another, "press_switch_upright", has its own name)."""
    key = (clip.name, clip.duration_s)
    if key not in _PEAKS:
        rot, root, _ = clip.sample(FPS)
        share = 0.0
        limits = (
            ("LeftHand", hand_limit(clip.name)),
            ("RightHand", hand_limit(clip.name)),
            ("Hips", HIPS_MAX_MS),
        )
        for joint, limit in limits if len(rot) >= 2 else ():
            pos, _ = joint_globals(rot, root, JOINT_INDEX[joint])
            share = max(share, float(np.linalg.norm(np.diff(pos, axis=0), axis=1).max()) * FPS / limit)
        _PEAKS[key] = share
    return _PEAKS[key]


def within_body_limits(style: Style, clip: ActionClip) -> Style:
    """``style`` with the tempo, then the amplitude, brought down (never below the clip's own) where playing
    the clip that much faster and wider would move a hand or the hips faster than a body can."""
    share = peak_share(clip)
    room = SPEED_MARGIN / share if share > 0 else np.inf
    tempo, amplitude = style.tempo, style.amplitude
    if tempo * max(amplitude, 1.0) <= room:
        return style
    if tempo > 1.0:
        tempo = max(1.0, room / max(amplitude, 1.0))
    if amplitude > 1.0 and tempo * amplitude > room:
        amplitude = max(1.0, room / tempo)
    return replace(style, tempo=round(tempo, 3), amplitude=round(amplitude, 3))


__all__ = ["MANNER_MOOD", "Style", "apply_style", "mood_of", "resample_fps", "style_of", "within_body_limits"]
