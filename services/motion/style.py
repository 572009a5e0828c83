"""Motion style: how a mood changes any clip (tempo, amplitude, posture), not only the face.

An angry wave is fast and high, a sad walk slow with the head down. The social model gives each
character an emotion per sentence as valence and arousal (proto.social.StepEmotion, [-1, 1]); a manner
word of the sentence ("angrily", "sadly", "happily") gives one too. ``style_of`` maps the pair to four
parameters, and ``apply_style`` applies them to the upper body of a sampled clip:

- tempo: > 1 plays the clip faster (arousal);
- amplitude: how far each joint goes from the posture's rest pose (arousal, a little valence): an
  extrapolation past the keys for > 1, a damped gesture for < 1;
- chest: degrees the chest lifts (> 0, pride, joy) or slumps forward (< 0, sadness);
- head: degrees the head drops (> 0) or lifts (< 0).

Clips that hold a contact (typing, sitting, shaking hands) keep their tempo and amplitude (their
contact windows and IK targets are timed in clip time); they still take the posture.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wana.domain import quat
from wana.domain.skeleton import JOINT_INDEX, UPPER_BODY

NEUTRAL_BAND = 0.2  # |valence|, |arousal| below this leave the motion as authored
TEMPO_PER_AROUSAL = 0.35  # tempo = 1 + this * arousal
AMPLITUDE_PER_AROUSAL = 0.3
AMPLITUDE_PER_VALENCE = 0.08
CHEST_PER_VALENCE = 6.0  # degrees
CHEST_PER_AROUSAL = 2.0
HEAD_PER_SADNESS = 12.0  # degrees the head drops for valence -1 at rest arousal
SPINE = ("Spine", "Spine1", "Spine2")

# Manner words (ActionNode.manner) as (valence, arousal); speed words are locomotion's, not moods.
MANNER_MOOD: dict[str, tuple[float, float]] = {
    "angrily": (-0.7, 0.8),
    "madly": (-0.6, 0.9),
    "furiously": (-0.8, 0.9),
    "sadly": (-0.7, -0.5),
    "sorrowfully": (-0.7, -0.5),
    "gloomily": (-0.6, -0.5),
    "tiredly": (-0.3, -0.8),
    "wearily": (-0.3, -0.8),
    "sleepily": (-0.1, -0.8),
    "happily": (0.8, 0.4),
    "cheerfully": (0.8, 0.5),
    "joyfully": (0.9, 0.6),
    "excitedly": (0.6, 0.9),
    "eagerly": (0.5, 0.7),
    "calmly": (0.3, -0.5),
    "nervously": (-0.4, 0.6),
    "proudly": (0.6, 0.3),
    "shyly": (-0.1, -0.3),
}


@dataclass(frozen=True)
class Style:
    """The few parameters a mood sets (the neutral style changes nothing)."""

    tempo: float = 1.0  # > 1 faster
    amplitude: float = 1.0  # scale of each joint's departure from the rest pose
    chest: float = 0.0  # degrees, > 0 chest up, < 0 slumped forward
    head: float = 0.0  # degrees, > 0 head down

    @property
    def neutral(self) -> bool:
        return self == Style()


def style_of(valence: float, arousal: float) -> Style:
    """The style of a mood (valence, arousal in [-1, 1]); neutral inside NEUTRAL_BAND."""
    v = float(np.clip(valence, -1.0, 1.0))
    a = float(np.clip(arousal, -1.0, 1.0))
    if abs(v) < NEUTRAL_BAND and abs(a) < NEUTRAL_BAND:
        return Style()
    sad = max(0.0, -v) * (1.0 - max(0.0, a))  # low valence without high arousal: the head hangs
    return Style(
        tempo=round(1.0 + TEMPO_PER_AROUSAL * a, 3),
        amplitude=round(1.0 + AMPLITUDE_PER_AROUSAL * a + AMPLITUDE_PER_VALENCE * v, 3),
        chest=round(CHEST_PER_VALENCE * v + CHEST_PER_AROUSAL * a, 2),
        head=round(HEAD_PER_SADNESS * sad - 3.0 * max(0.0, v), 2),
    )


def mood_of(manner: str, emotion: tuple[float, float] | None = None) -> tuple[float, float]:
    """(valence, arousal) of an action: its manner word wins over the social model's emotion."""
    if manner in MANNER_MOOD:
        return MANNER_MOOD[manner]
    return emotion if emotion is not None else (0.0, 0.0)


def resample_fps(fps: int, style: Style) -> int:
    """The rate to sample a clip at so that played at fps it runs style.tempo times as fast."""
    return max(1, int(round(fps / max(style.tempo, 0.2))))


def apply_style(rot: np.ndarray, rest: np.ndarray, style: Style, amplitude: bool = True) -> np.ndarray:
    """A clip's rotations with the style's amplitude and posture.

    Args:
        rot: (T, J, 4) local rotations of the sampled clip (root not yet yawed).
        rest: (J, 4) the posture's rest pose the clip departs from and returns to.
        style: from ``style_of``.
        amplitude: scale the upper body's departure from rest (False for contact clips).

    Returns:
        (T, J, 4) rotations; the hips and legs keep the clip's (feet stay where the clip put them).
    """
    out = np.array(rot, dtype=np.float64, copy=True)
    if style.neutral or len(out) == 0:
        return out
    if amplitude and abs(style.amplitude - 1.0) > 1e-6:
        for name in UPPER_BODY:
            j = JOINT_INDEX[name]
            out[:, j] = quat.slerp(np.broadcast_to(rest[j], out[:, j].shape), out[:, j], style.amplitude)
    x = np.array([1.0, 0.0, 0.0])
    chest = quat.from_axis_angle(x, np.radians(-style.chest / len(SPINE)))  # pitch < 0 lifts the chest
    head = quat.from_axis_angle(x, np.radians((style.head + style.chest) / 2.0))  # eyes follow the chest
    for name in SPINE:
        out[:, JOINT_INDEX[name]] = quat.mul(out[:, JOINT_INDEX[name]], chest)
    for name in ("Neck", "Head"):
        out[:, JOINT_INDEX[name]] = quat.mul(out[:, JOINT_INDEX[name]], head)
    return quat.normalize(out)
