"""Motion style: how a mood changes any clip (tempo, amplitude, posture), not only the face.

An angry wave is fast and high, a sad walk slow with the head down. A manner word of the sentence
("angrily", "sadly", "happily") gives an action a mood as valence and arousal in [-1, 1]; the social
model gives each character one per sentence too (proto.social.StepEmotion). ``style_of`` maps the pair
to four parameters, and ``apply_style`` applies them to the upper body of a sampled clip:

- tempo: > 1 plays the clip faster (arousal);
- amplitude: how far each joint goes from the posture's rest pose (arousal, a little valence): an
  extrapolation past the keys for > 1, a damped gesture for < 1;
- chest: degrees the chest lifts (> 0, pride, joy) or slumps forward (< 0, sadness);
- head: degrees the head drops (> 0) or lifts (< 0).

Manner words are applied by the motion service as it samples a clip (services/motion/synthesis.py: the
tempo changes the clip's length). The social model's emotions are applied by ``restyle_motion`` to the
composed time line (amplitude and posture, no tempo): an emotion sampled anew after an edit elsewhere in
the story then re-runs no motion node. Clips that hold a contact (typing, sitting, shaking hands) keep
their tempo and amplitude (their contact windows and IK targets are timed in clip time); they still take
the posture, the head only where the hands touch something.
"""

from __future__ import annotations

from dataclasses import dataclass

import msgspec
import numpy as np

from proto.motion_data import Motion
from wana.arrays import from_wire, to_wire
from wana.domain import quat
from wana.domain.actions import get_clip
from wana.domain.skeleton import JOINT_INDEX, UPPER_BODY
from wana.domain.units import FPS

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


MOOD_RAMP_S = 0.5  # seconds over which a change of mood eases in on the time line
UPPER = np.array([JOINT_INDEX[n] for n in UPPER_BODY])


def _eased(x: np.ndarray, frames: int) -> np.ndarray:
    """(T,) x with its steps smoothed over about ``frames`` frames (a box filter run twice)."""
    if frames < 2 or len(x) < 2:
        return x
    k = np.ones(frames) / frames
    for _ in range(2):
        x = np.convolve(np.pad(x, (frames // 2, frames - 1 - frames // 2), mode="edge"), k, mode="valid")
    return x


def restyle_motion(motion: Motion, moods: dict[int, tuple[float, float]]) -> Motion:
    """A composed Motion played in the moods of its actions: amplitude and posture, no tempo.

    Args:
        motion: one character's composed motion (its segments carry action_index).
        moods: action index -> (valence, arousal). A mood lasts through the holds after its action; an
            action without one is played neutral.

    Returns:
        The motion with the gestures' departure from rest scaled (the clips without contacts: a piece
        starts and ends at its rest pose, which stays put) and the chest and head set; where the hands
        touch something or hold a prop only the head moves, so no contact or grip is pulled away.
    """
    if not moods:
        return motion
    rot = from_wire(motion.rotations).astype(np.float64)
    frames = len(rot)
    chest, head, amp = np.zeros(frames), np.zeros(frames), np.ones(frames)
    touch = np.zeros(frames)
    current = Style()
    for seg in sorted(motion.segments, key=lambda s: s.start_frame):
        a, b = max(0, seg.start_frame), min(frames, seg.end_frame)
        if seg.action_index in moods:
            current = style_of(*moods[seg.action_index])
        elif seg.action_index >= 0:
            current = Style()
        chest[a:b], head[a:b] = current.chest, current.head
        try:
            clip = get_clip(seg.action)
        except KeyError:
            continue
        if clip.interaction is not None and clip.interaction.object not in ("seat", "bed"):
            touch[a:b] = 1.0
        plain = clip.interaction is None and not clip.drives_lower_body and "locomotion" not in clip.tags
        if plain and b - a > 1:
            amp[a:b] = current.amplitude
    for p in motion.props:
        touch[max(0, p.start_frame) : min(frames, p.end_frame)] = 1.0
    ramp = int(MOOD_RAMP_S * FPS)
    chest = _eased(chest, ramp) * (1.0 - np.clip(_eased(touch, ramp) * 2.0, 0.0, 1.0))
    head = _eased(head, ramp)
    for seg in motion.segments:
        a, b = max(0, seg.start_frame), min(frames, seg.end_frame)
        if b - a > 1 and np.any(np.abs(amp[a:b] - 1.0) > 1e-6):
            rest = rot[a, UPPER]
            part = rot[a:b][:, UPPER]
            rot[a:b, UPPER] = quat.slerp(np.broadcast_to(rest, part.shape), part, amp[a:b, None])
    x = np.array([1.0, 0.0, 0.0])
    lift = quat.from_axis_angle(x, np.radians(-chest / len(SPINE)))
    nod = quat.from_axis_angle(x, np.radians((head + chest) / 2.0))
    for name in SPINE:
        rot[:, JOINT_INDEX[name]] = quat.mul(rot[:, JOINT_INDEX[name]], lift)
    for name in ("Neck", "Head"):
        rot[:, JOINT_INDEX[name]] = quat.mul(rot[:, JOINT_INDEX[name]], nod)
    return msgspec.structs.replace(motion, rotations=to_wire(quat.normalize(rot).astype(np.float32)))
