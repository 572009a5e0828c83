"""Units and the frame rate: the one definition every stage reads.

Conventions (DESIGN.md §6): metres, Y up, right-handed as glTF, characters face +Z at rest, and
motion sampled at ``FPS`` frames per second. ``proto.motion_data.Motion.fps`` defaults to the same
number on the wire (``proto`` imports nothing of ours, so it repeats it; a test keeps the two equal).
"""

from __future__ import annotations

FPS = 30  # frames per second of every synthesised motion, render and timeline
FRAME_S = 1.0 / FPS  # seconds per frame


def seconds_to_frames(seconds: float, fps: int = FPS) -> int:
    """Whole frames (rounded) that ``seconds`` last at ``fps``."""
    return int(round(seconds * fps))


def frames_to_seconds(frames: int, fps: int = FPS) -> float:
    """Seconds that ``frames`` frames last at ``fps``."""
    return frames / float(fps)
