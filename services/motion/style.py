"""The motion service's side of motion style: a manner word plays a clip faster or slower, wider or smaller.

The parameters and their mapping from a mood live in the domain library (wana.domain.style), because the
orchestrator applies the social model's emotions to the composed time line with the same ones; here is
what only sampling a clip can do: change its tempo.
"""

from __future__ import annotations

from wana.domain.style import MANNER_MOOD, Style, apply_style, mood_of, style_of

__all__ = ["MANNER_MOOD", "Style", "apply_style", "mood_of", "resample_fps", "style_of"]


def resample_fps(fps: int, style: Style) -> int:
    """The rate to sample a clip at so that played at fps it runs style.tempo times as fast."""
    return max(1, int(round(fps / max(style.tempo, 0.2))))
