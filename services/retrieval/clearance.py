"""Where furniture the text did not ask for may stand: against the walls, clear of where people walk.

Two rules keep a composed room usable for the characters and visible to the camera:

1. **Against a wall.** Storage and other wall-backed furniture (bookshelves, cabinets, wardrobes,
   refrigerators, pianos...) and anything tall stand with their back to a wall, whether the text
   named them or they came as context objects; context floor furniture that is not a centre piece
   (a coffee table, a dining table) does too. Walls are tried with the back wall (-Z) and the side
   walls first and the front wall (+Z, the overview camera's side) last; context objects go to the
   least used wall first so that they spread out instead of lining up side by side.
2. **Keep clear.** Context floor furniture stays off the text objects' interaction zones (a disc
   around each catalog stand point, ``wana.assets.catalog.make_object(...).stand_point``), off the
   entrance where characters come in (the -Z side, as the orchestrator's start positions), and off a
   walkway from the entrance to each stand point.

    zones = keep_clear_zones(text_objects, width, depth)
    zones.blocks(world_aabb)  # -> True when a pose would stand in someone's way
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass

import numpy as np

from proto.scene import PlacedObject
from services.retrieval.geometry import Footprint, extents
from wana.assets.catalog import asset_for, to_world

TALL = 1.3  # metres: floor objects at least this tall stand against a wall
STAND_RADIUS = 0.45  # metres kept free around each stand point (a person and a step)
WALKWAY_HALF_WIDTH = 0.35  # metres either side of the line from the entrance to a stand point
ENTRANCE_INSET = 0.6  # metres from the -Z wall where characters enter (orchestrator start positions)
ENTRANCE_RADIUS = 0.8  # metres kept free around the entrance point
WALL_GAP = 0.02  # metres between a wall and the back of furniture standing against it
WALL_STEP = 0.25  # metres between positions tried along a wall
PATH_STEP = 0.1  # metres between the points that sample a walkway

# Wall-backed furniture, wherever it comes from (the catalog's storage family and its likes).
WALL_FURNITURE = frozenset(
    {
        "bookshelf",
        "shelf",
        "wardrobe",
        "cabinet",
        "filing_cabinet",
        "dresser",
        "kitchen_cabinet",
        "tv_stand",
        "locker",
        "tool_cabinet",
        "shoe_rack",
        "coat_rack",
        "display_case",
        "refrigerator",
        "stove",
        "dishwasher",
        "kitchen_sink",
        "kitchen_counter",
        "washing_machine",
        "piano",
        "water_cooler",
        "radiator",
        "fireplace",
        "bathroom_sink",
        "towel_rack",
        "toilet",
        "bathtub",
        "shower",
        "chest",
        "dressing_table",
        "bunk_bed",
        "bed",
        "crib",
        "sofa",
        "loveseat",
    }
)
# Furniture that belongs in the open even when it comes as context (people sit or stand around it).
CENTRE_PIECES = frozenset(
    {
        "table",
        "dining_table",
        "coffee_table",
        "conference_table",
        "kitchen_island",
        "cafe_table",
        "boxing_ring",
        "boxing_bag",
        "grand_piano",
        "drum_kit",
        "rug",
        "carpet",
    }
)

# Walls as (yaw turning the object's front into the room, fixed coordinate sign, axis along the wall):
# back (-Z), left (-X), right (+X), front (+Z).
WALLS: dict[str, tuple[float, float, int]] = {
    "back": (0.0, -1.0, 0),
    "left": (math.pi / 2.0, -1.0, 2),
    "right": (-math.pi / 2.0, 1.0, 2),
    "front": (math.pi, 1.0, 0),
}


def against_wall(fp: Footprint, from_text: bool) -> bool:
    """Whether a floor object should stand with its back to a wall (see the module docstring)."""
    if fp.mount != "floor" or fp.category in CENTRE_PIECES:
        return False
    return fp.category in WALL_FURNITURE or fp.height >= TALL or not from_text


def wall_of(box: np.ndarray, width: float, depth: float, tol: float = 0.1) -> str:
    """The wall a world AABB (2, 3) stands against ("" when none is within tol metres)."""
    gaps = {
        "back": box[0, 2] + depth / 2.0,
        "front": depth / 2.0 - box[1, 2],
        "left": box[0, 0] + width / 2.0,
        "right": width / 2.0 - box[1, 0],
    }
    name = min(gaps, key=lambda k: gaps[k])
    return name if gaps[name] <= tol else ""


def along_walls(
    fp: Footprint, width: float, depth: float, walls: Sequence[str], rng: np.random.Generator, y: float = 0.0
) -> Iterator[tuple[np.ndarray, float, str]]:
    """Poses with the object's back on each wall in turn, its front into the room.

    Args:
        fp: the object's footprint.
        width, depth: room size (metres; the room is centred on the origin).
        walls: names from WALLS, in the order to try them.
        rng: the object's own generator (picks where along each wall to start).
        y: base height.

    Yields:
        (world position (3,), yaw, support "") candidates.
    """
    for name in walls:
        yaw, sign, axis = WALLS[name]
        e = extents(fp, yaw)  # (2, 3) object-frame AABB turned by yaw
        length = width if axis == 0 else depth
        half = (e[1, axis] - e[0, axis]) / 2.0
        span = length / 2.0 - half - 0.05
        if span < 0:
            continue
        t0 = float(rng.uniform(-span, span))
        ts = [t0] + sorted(np.arange(-span, span + 1e-9, WALL_STEP).tolist(), key=lambda t: (abs(t - t0), t))
        for t in ts:
            centre_along = t - (e[0, axis] + e[1, axis]) / 2.0
            if axis == 0:  # a wall of constant z
                z = -depth / 2.0 - e[0, 2] + WALL_GAP if sign < 0 else depth / 2.0 - e[1, 2] - WALL_GAP
                yield np.array([centre_along, y, z]), yaw, ""
            else:
                x = -width / 2.0 - e[0, 0] + WALL_GAP if sign < 0 else width / 2.0 - e[1, 0] - WALL_GAP
                yield np.array([x, y, centre_along]), yaw, ""


def wall_order(rng: np.random.Generator, load: dict[str, int] | None = None) -> list[str]:
    """Back and side walls in a seeded order, the front wall last; with ``load``, least used first."""
    first = ["back", "left", "right"]
    order = [first[i] for i in rng.permutation(3)] + ["front"]
    if load is not None:
        rank = {w: k for k, w in enumerate(order)}
        order = sorted(order, key=lambda w: (load.get(w, 0) + (w == "front"), rank[w]))
    return order


@dataclass(frozen=True)
class KeepClear:
    """Floor areas furniture must not cover.

    Attributes:
        discs: (K, 3) x, z centre and radius (metres) of each disc.
        path_points: (M, 2) x, z samples of the walkways.
        half_width: metres kept free around each walkway sample.
    """

    discs: np.ndarray
    path_points: np.ndarray
    half_width: float = WALKWAY_HALF_WIDTH

    def blocks(self, box: np.ndarray) -> bool:
        """Whether a world AABB (2, 3) covers any part of a zone (seen from above)."""
        lo, hi = box[0, [0, 2]], box[1, [0, 2]]
        if len(self.discs):
            gap = np.maximum(np.maximum(lo - self.discs[:, :2], self.discs[:, :2] - hi), 0.0)
            if np.any(np.einsum("ij,ij->i", gap, gap) < self.discs[:, 2] ** 2):
                return True
        if len(self.path_points):
            gap = np.maximum(np.maximum(lo - self.path_points, self.path_points - hi), 0.0)
            if np.any(np.einsum("ij,ij->i", gap, gap) < self.half_width**2):
                return True
        return False


def entrance(depth: float) -> np.ndarray:
    """(2,) x, z where characters come into the room."""
    return np.array([0.0, -depth / 2.0 + ENTRANCE_INSET])


def stand_points(objects: Iterable[PlacedObject]) -> np.ndarray:
    """(N, 2) world x, z of each object's catalog stand point (objects the catalog lacks are skipped)."""
    out = []
    for p in objects:
        try:
            sp = asset_for(p).stand_point
        except KeyError:
            continue
        w = to_world(p, np.asarray(sp, dtype=np.float64))
        out.append([float(w[0]), float(w[2])])
    return np.array(out, dtype=np.float64).reshape(-1, 2)


def keep_clear_zones(objects: Iterable[PlacedObject], width: float, depth: float) -> KeepClear:
    """The interaction zones of these (text) objects, the entrance and the walkways between them.

    Args:
        objects: placed objects whose stand points must stay reachable.
        width, depth: room size in metres.
    """
    stands = stand_points(objects)
    door = entrance(depth)
    discs = [[door[0], door[1], ENTRANCE_RADIUS]] + [[s[0], s[1], STAND_RADIUS] for s in stands]
    points = []
    for s in stands:
        n = max(2, int(np.ceil(np.linalg.norm(s - door) / PATH_STEP)) + 1)
        points.append(door + np.linspace(0.0, 1.0, n)[:, None] * (s - door))
    path = np.concatenate(points) if points else np.zeros((0, 2))
    return KeepClear(discs=np.array(discs, dtype=np.float64), path_points=path)
