"""Where a character hides at a thing: "hides behind the door", "ducks behind the sofa".

The parse keeps the thing but not the preposition, and hiding is about not being seen, so the spots are
the ones a thing hides you at: beside a door or a curtain, back to the wall it hangs on (where the door
swings open over you), and behind anything standing free (its back; catalog objects face +Z), else beside
it when its back is against a wall. Two hiders take two of the spots (services.orchestrator.slotting).
"""

from __future__ import annotations

import numpy as np

from proto.scene import PlacedObject, Room, Scene

HIDE_ACTIONS = frozenset({"hide"})
WALL_OUT_M = 0.2  # metres in front of a door's face a hider beside it stands (its hips), back to the wall
SIDE_GAP_M = 0.3  # metres past the door's (or the sofa's) edge
BESIDE_EACH_OTHER_M = 0.6  # metres between two hiders on one side of a door (two crouching bodies)
BEHIND_M = 0.35  # metres behind a free-standing thing's back
ROOM_MARGIN_M = 0.25  # a spot is kept this far inside the walls
ARM_ROOM_M = 0.4  # metres from the hips to anything else for the arms to move without touching it


def hiding_spots(placed: PlacedObject, scene: Scene, need: int = 1) -> list[tuple[float, float]]:
    """World (x, z) spots to hide at by ``placed``, preferred first: only those with arm room from everything
    else in the room (not under the whiteboard beside the door) when there are ``need`` of them (one per
    hider), else those first; [] when none is inside the room."""
    from wana.assets.catalog import world_bounds

    spots = _spots(placed, scene.room)
    boxes = [np.asarray(world_bounds(o), float)[:, [0, 2]] for o in scene.objects if o.id != placed.id]

    def roomy(xz: tuple[float, float]) -> bool:
        p = np.asarray(xz)
        return all(float(np.linalg.norm(np.clip(p, b[0], b[1]) - p)) >= ARM_ROOM_M for b in boxes)

    clear = [xz for xz in spots if roomy(xz)]
    return clear if len(clear) >= need else clear + [xz for xz in spots if xz not in clear]


def _spots(placed: PlacedObject, room: Room) -> list[tuple[float, float]]:
    from wana.assets import vocabulary
    from wana.assets.catalog import asset_for, object_to_world

    half = np.asarray(asset_for(placed).dims, float) / 2.0
    info = vocabulary.CATEGORIES.get(placed.category)
    beside = [(s * (half[0] + SIDE_GAP_M), 0.0) for s in (1.0, -1.0)]
    if info is not None and info.mount == "wall":
        local = [
            (s * (half[0] + g), half[2] + WALL_OUT_M)
            for g in (SIDE_GAP_M, SIDE_GAP_M + BESIDE_EACH_OTHER_M)
            for s in (1.0, -1.0)
        ]
    else:
        local = [(lat, -(half[2] + BEHIND_M)) for lat in (0.0, 0.45, -0.45)] + beside
    m = object_to_world(placed)
    out = []
    for lx, lz in local:
        w = m[:3, :3] @ np.array([lx, 0.0, lz]) + m[:3, 3]
        xz = (float(w[0]), float(w[2]))
        if abs(xz[0]) <= room.width / 2.0 - ROOM_MARGIN_M and abs(xz[1]) <= room.depth / 2.0 - ROOM_MARGIN_M:
            out.append(xz)
    return out


__all__ = ["HIDE_ACTIONS", "hiding_spots"]
