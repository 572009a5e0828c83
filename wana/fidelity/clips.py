"""What an action clip asks of its target: the interaction metadata of the action catalogue.

The checks need only the interaction (kind of object point, contact joints, contact window) and the clip's
length, not the keyframes; this is the view of `wana.domain.actions` they read.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

from wana.domain.actions import load_library


@dataclass(frozen=True)
class ClipNeeds:
    """One clip's interaction metadata.

    Attributes:
        name: action-library name.
        duration_s: the clip's natural length in seconds.
        looping: a looping clip repeats; its window covers every repetition.
        tags: the clip's tags ("posture", "locomotion", ...).
        object: kind of object point it needs ("seat", "keyboard", "handheld", "tool", "person", ...), "" none.
        contacts: canonical joints brought to the object's contact points.
        window: (start, end) seconds of the clip during which the contacts hold.
    """

    name: str
    duration_s: float
    looping: bool
    tags: tuple[str, ...]
    object: str = ""
    contacts: tuple[str, ...] = ()
    window: tuple[float, float] = (0.0, 0.0)


@functools.lru_cache(maxsize=1)
def _all_clips() -> dict[str, ClipNeeds]:
    out: dict[str, ClipNeeds] = {}
    for name, clip in load_library().items():
        inter = clip.interaction
        out[name] = ClipNeeds(
            name=name,
            duration_s=float(clip.duration_s),
            looping=bool(clip.looping),
            tags=tuple(clip.tags),
            object=inter.object if inter else "",
            contacts=tuple(inter.contacts) if inter else (),
            window=(float(inter.window[0]), float(inter.window[1])) if inter else (0.0, 0.0),
        )
    return out


def clip_needs(action: str) -> ClipNeeds | None:
    """The metadata of one action clip, None for a name the library does not hold."""
    return _all_clips().get(action)
