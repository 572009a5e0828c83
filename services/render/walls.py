"""Which wall a thing hangs on, and which walls a camera stands behind: the walls are one-sided and culled
from behind, so what hangs on them is cut away with them (the renderer does not draw it, the visibility
checks do not count it as hiding anyone)."""

from __future__ import annotations

import numpy as np

from proto.scene import PlacedObject, Room

WALLS = ("wall_back", "wall_front", "wall_left", "wall_right")


def wall_of(placed: PlacedObject, room: Room) -> str:
    """The wall a window, door, painting or mirror hangs on (the nearest one to it), "" for anything else."""
    from wana.assets import vocabulary

    info = vocabulary.CATEGORIES.get(placed.category)
    if info is None or info.mount != "wall":
        return ""
    x, _, z = placed.position
    w, d = room.width / 2.0, room.depth / 2.0
    gaps = (abs(z + d), abs(z - d), abs(x + w), abs(x - w))
    return WALLS[int(np.argmin(gaps))]


def walls_behind(eye: np.ndarray, room: Room) -> frozenset[str]:
    """The walls a camera at ``eye`` stands behind: culled, so what hangs on them is cut away with them
    (a window on the wall behind the camera would stand free in the room)."""
    w, d = room.width / 2.0, room.depth / 2.0
    x, z = float(eye[0]), float(eye[2])
    out = (("wall_back", z < -d), ("wall_front", z > d), ("wall_left", x < -w), ("wall_right", x > w))
    return frozenset(name for name, behind in out if behind)


__all__ = ["WALLS", "wall_of", "walls_behind"]
