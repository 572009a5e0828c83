"""Slots: the places on and around a piece of furniture that one character each can take.

A seat's slots are its hip contact points (a sofa has one per cushion: "sit" in the middle, "sit_0",
"sit_2" beside it; a chair has one). An object's stand slots are spots along its front (a counter, a
desk, a reception desk: one body width apart) and, for a table, along its back too. A `SlotBook` keeps
who holds which slot while the story runs, so that two characters sent to one sofa take two cushions and
two sent to one counter stand side by side instead of in one body.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

import numpy as np

from proto.scene import PlacedObject

SEAT_JOINT = "Hips"
STAND_APART_M = 0.65  # metres between neighbouring stand slots (a body and a little room)
STAND_OUT_M = 0.45  # metres in front of an object's edge where a stand slot is
TABLE_WORDS = ("table", "desk")  # stand slots on both long sides


COVERED_M = 0.1  # metres around what rests on a seat within which a slot's hips point is taken by it


def seat_slots(placed: PlacedObject, kind: str = "sit", resting: Iterable[PlacedObject] = ()) -> list[str]:
    """Names of an object's seat slots for ``kind`` ("sit" or "lie": contact points with a hip target
    named so, "sit", "sit_0", ...), the preferred first.

    ``kind`` itself (the catalog's default, the middle of a sofa) comes first, then the others by their
    distance from it, so one sitter takes the middle and the next one the cushion beside it. Given the
    room's objects as ``resting``, a slot under one that rests on the seat (a box of chocolates on the
    bench, a laptop on the sofa's middle cushion) is left out: nobody sits on it.
    """
    from wana.assets.catalog import asset_for, to_world, world_bounds

    try:
        obj = asset_for(placed)
    except Exception:  # noqa: BLE001 - an unknown category has no slots
        return []
    points = {
        name: np.asarray(cp.position, float)
        for name, cp in obj.contact_points.items()
        if (cp.joint == SEAT_JOINT or SEAT_JOINT in cp.extra)
        and (name == kind or name.startswith(kind + "_"))
    }
    if not points:
        return []
    first = kind if kind in points else sorted(points)[0]
    names = sorted(points, key=lambda n: (n != first, float(np.linalg.norm(points[n] - points[first])), n))
    on_it = []
    for o in resting:
        if o.support == placed.id:
            try:
                on_it.append(world_bounds(o)[:, [0, 2]])
            except KeyError:  # not in the catalog: no footprint to keep off
                continue
    if not on_it:
        return names
    hips = {n: to_world(placed, points[n])[[0, 2]] for n in names}
    return [
        n
        for n in names
        if not any(np.all(hips[n] >= b[0] - COVERED_M) and np.all(hips[n] <= b[1] + COVERED_M) for b in on_it)
    ]


def stand_slots(placed: PlacedObject, rows: int = 1, across: int = 1) -> list[tuple[float, float]]:
    """World (x, z) spots where characters stand at an object, the middle of its front first.

    Spots run along the front edge one STAND_APART_M apart (as many as its width holds, at least
    ``across``: two who walk to one painting stand side by side before it, the row wider than the frame,
    rather than one behind the other); tables and desks get the same along their back. ``rows`` > 1 adds
    rows further out, one STAND_APART_M behind the other (a crowd at a window), after all the spots of the
    rows before.
    """
    from wana.assets.catalog import asset_for, to_world

    try:
        dims = np.asarray(asset_for(placed).dims, float)
    except Exception:  # noqa: BLE001 - unknown category: a spot in front of its position
        dims = np.array([0.6, 0.0, 0.6])
    width, depth = float(dims[0]) * placed.scale[0], float(dims[2]) * placed.scale[2]
    n = max(1, across, int(width / STAND_APART_M + 0.6))  # a 1 m counter: two; a 2 m table side: three
    offsets = sorted(((i - (n - 1) / 2) * STAND_APART_M for i in range(n)), key=abs)
    sides = [1.0, -1.0] if any(w in placed.category for w in TABLE_WORDS) else [1.0]
    local = np.array(
        [
            [
                along / placed.scale[0],
                0.0,
                side * (depth / 2 + STAND_OUT_M + row * STAND_APART_M) / placed.scale[2],
            ]
            for row in range(rows)
            for side in sides
            for along in offsets
        ]
    )
    world = to_world(placed, local)
    return [(round(float(p[0]), 3), round(float(p[2]), 3)) for p in world]


@dataclass
class SlotBook:
    """Who holds which slot: (object id, slot) -> character, taken and given back as the story runs."""

    held: dict[tuple[str, str], str] = field(default_factory=dict)

    def holder(self, object_id: str, slot: str) -> str:
        return self.held.get((object_id, slot), "")

    def take(self, object_id: str, slots: list[str], who: str) -> str | None:
        """The first of ``slots`` free (or already ``who``'s) on the object, now held by ``who``; None when all
        are held by others. ``who`` gives back whatever else it held."""
        mine = [k for k, v in self.held.items() if v == who and k[0] == object_id and k[1] in slots]
        if mine:
            return mine[0][1]
        for slot in slots:
            if self.holder(object_id, slot) in ("", who):
                self.release(who)
                self.held[(object_id, slot)] = who
                return slot
        return None

    def release(self, who: str) -> None:
        """``who`` leaves every slot it holds (it stood up, walked away or left)."""
        for key in [k for k, v in self.held.items() if v == who]:
            del self.held[key]


__all__ = ["SlotBook", "seat_slots", "stand_slots"]
