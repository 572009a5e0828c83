"""What an action clip asks of its target, read from the clip files' metadata (assets/actions/*.json).

The checks need only the interaction (kind of object point, contact joints, contact window) and the clip's
length, not the keyframes; the full action library lives with the motion service. Kept to this one module
on purpose: the library is moving into the domain layer, and this reader is then replaced by it.
"""

from __future__ import annotations

import functools
import json
from dataclasses import dataclass
from pathlib import Path

ACTIONS_DIR = Path(__file__).resolve().parents[2] / "assets" / "actions"


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
def _all_clips(directory: Path = ACTIONS_DIR) -> dict[str, ClipNeeds]:
    out: dict[str, ClipNeeds] = {}
    for path in sorted(directory.glob("*.json")) + sorted((directory / "imported").glob("*.json")):
        try:
            data = json.loads(path.read_text())
        except (OSError, ValueError):
            continue
        inter = data.get("interaction") or {}
        window = inter.get("window") or (0.0, 0.0)
        out[str(data.get("name", path.stem))] = ClipNeeds(
            name=str(data.get("name", path.stem)),
            duration_s=float(data.get("duration_s", 0.0)),
            looping=bool(data.get("looping", False)),
            tags=tuple(data.get("tags", ())),
            object=str(inter.get("object", "")),
            contacts=tuple(inter.get("contacts", ())),
            window=(float(window[0]), float(window[1])),
        )
    return out


def clip_needs(action: str) -> ClipNeeds | None:
    """The metadata of one action clip, None for a name the library does not hold."""
    return _all_clips().get(action)
