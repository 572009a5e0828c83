"""Candidate poses that make one stated relation true, best (seeded) first.

For a subject and an anchor already placed, each relation word yields poses in the anchor's frame:
"on"/"in" on one of the anchor's support surfaces, "in front of" past the anchor's front (+Z), "behind"
past its back, "left of" on its left (+X, a character's left when it faces +Z), "right of" on -X,
"next to" on either side, "near" on any side, "under" below its top, "above" over it, "facing" in front
of it turned towards it, "around" one side per instance. Against a wall-mounted anchor (window,
whiteboard) the subject keeps its back to that wall: below the anchor or beside it along the wall; "in front
of" it, a seat turns to face it and anything else keeps its back to it.
The first pose of each list comes from the subject's own random generator (seeded by its id), so a
subject's placement depends only on itself and its anchor; the rest are fixed alternatives.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from services.retrieval.geometry import Footprint, extents, footprint_boxes_at, sits_at, yaw_matrix

LEFT_SIGN = 1.0  # the anchor's left is its +X side (characters face +Z with their left on +X)
WALL_GAP = 0.005  # metres between a wall and what hangs on it
# metres from the wall to the front of a seat that faces what hangs on it ("a bench in front of the paintings"):
# room for the sitter's lower legs and feet (knees ~0.5 m ahead of the seat's front, feet under them) and to
# stand up and walk away; 0.05-0.3 m left the shins in the wall and the walk away through the bench
# (solo-gallery-12 s8/s11).
SEAT_FACING_GAPS = (0.9, 0.7, 1.2, 0.6)

# Centre height of the base of wall-mounted objects, metres above the floor.
WALL_MOUNT_Y: dict[str, float] = {
    "window": 0.9,
    "door": 0.0,
    "painting": 1.3,
    "poster": 1.3,
    "mirror": 1.2,  # over a 1.1 m wash basin with its tap
    "clock": 1.8,
    "whiteboard": 0.9,
    "blackboard": 0.9,
    "projector_screen": 1.0,
    "curtain": 0.0,
}

Candidate = tuple[np.ndarray, float, str]  # world position (3,), yaw, support id ("" = floor)


@dataclass
class Placed:
    """An object placed in the room being composed."""

    id: str
    fp: Footprint
    position: np.ndarray  # (3,) world, base centre
    yaw: float
    support: str = ""  # id of what it rests on, "" = floor
    from_text: bool = True

    def __post_init__(self) -> None:
        self.box = extents(self.fp, self.yaw) + self.position  # (2, 3) world AABB
        self._boxes: np.ndarray | None = None

    @property
    def boxes(self) -> np.ndarray:
        """(N, 2, 3) world collision boxes (computed on first use)."""
        if self._boxes is None:
            self._boxes = footprint_boxes_at(self.fp, self.position, self.yaw)
        return self._boxes


def mount_height(fp: Footprint, room_height: float) -> float:
    """Base height for a wall-mounted object, kept under the ceiling."""
    y = WALL_MOUNT_Y.get(fp.category, 1.0)
    return float(max(0.0, min(y, room_height - fp.height - 0.05)))


def _level(fp: Footprint, anchor: Placed, room_height: float) -> tuple[float, str]:
    """Base height and support of a subject standing beside an anchor."""
    if fp.mount == "wall":
        return mount_height(fp, room_height), ""
    if fp.mount == "surface" and anchor.support:
        return float(anchor.position[1]), anchor.support  # beside a lamp on a desk: on the same desk
    return 0.0, ""


def _to_world(
    anchor: Placed, local_x: float, local_z: float, y: float, rel_yaw: float, support: str
) -> Candidate:
    offset = yaw_matrix(anchor.yaw) @ np.array([local_x, 0.0, local_z])
    pos = np.array([anchor.position[0] + offset[0], y, anchor.position[2] + offset[2]])
    return pos, _wrap(anchor.yaw + rel_yaw), support


def _wrap(yaw: float) -> float:
    return float((yaw + math.pi) % (2.0 * math.pi) - math.pi)


def _side(
    anchor: Placed,
    fp: Footprint,
    side: str,
    gap: float,
    lateral: float,
    rel_yaw: float,
    y: float,
    support: str,
) -> Candidate:
    a = anchor.fp.bounds
    e = extents(fp, rel_yaw)
    if side == "front":
        lx, lz = lateral, a[1, 2] + gap - e[0, 2]
    elif side == "back":
        lx, lz = lateral, a[0, 2] - gap - e[1, 2]
    elif side == "left":
        lx, lz = (a[1, 0] + gap - e[0, 0], lateral) if LEFT_SIGN > 0 else (a[0, 0] - gap - e[1, 0], lateral)
    elif side == "right":
        lx, lz = (a[0, 0] - gap - e[1, 0], lateral) if LEFT_SIGN > 0 else (a[1, 0] + gap - e[0, 0], lateral)
    else:  # along a wall-mounted anchor: the subject's back on the wall plane
        wall_z = a[0, 2] - e[0, 2] + WALL_GAP
        if side == "below":
            lx, lz = lateral, wall_z
        else:
            on_plus_x = (side == "wall_left") == (LEFT_SIGN > 0)
            lx = a[1, 0] + gap - e[0, 0] if on_plus_x else a[0, 0] - gap - e[1, 0]
            lz = wall_z
    return _to_world(anchor, lx, lz, y, rel_yaw, support)


_SIDES: dict[str, tuple[list[str], list[float]]] = {
    "in_front_of": (["front"], [math.pi, 0.0]),
    "behind": (["back"], [0.0, math.pi]),
    "left_of": (["left"], [0.0, math.pi]),
    "right_of": (["right"], [0.0, math.pi]),
    "next_to": (["left", "right"], [0.0, math.pi]),
    "near": (["front", "left", "right", "back"], [0.0, math.pi]),
}
_WALL_SIDES: dict[str, list[str]] = {
    "in_front_of": ["front"],
    "left_of": ["wall_left"],
    "right_of": ["wall_right"],
    "next_to": ["wall_left", "wall_right", "below"],
    "near": ["below", "wall_left", "wall_right", "front"],
    "under": ["below"],
    "around": ["front", "wall_left", "wall_right"],
}


def relation_candidates(
    relation: str,
    fp: Footprint,
    anchor: Placed,
    rng: np.random.Generator,
    *,
    room_height: float,
    instance: int = 0,
) -> Iterator[Candidate]:
    """Poses for a subject that make ``subject <relation> anchor`` true, seeded pose first.

    Args:
        relation: a proto.ssg.RELATIONS word.
        fp: the subject's footprint.
        anchor: the placed anchor.
        rng: the subject's own generator (seeded by its id).
        room_height: metres, for hanging objects.
        instance: which copy of a counted subject ("four chairs around the table").

    Yields:
        (world position (3,), yaw, support id).
    """
    a = anchor.fp.bounds
    half_w = float(a[1, 0] - a[0, 0]) / 2.0
    half_d = float(a[1, 2] - a[0, 2]) / 2.0
    y, support = _level(fp, anchor, room_height)
    wall_anchor = anchor.fp.mount == "wall"
    if relation in ("on", "in"):
        yield from _on_surface(relation, fp, anchor, rng)
        return
    if relation in ("above", "hanging_above"):
        yield from _above(relation, fp, anchor, rng, room_height)
        return
    if relation == "under" and not wall_anchor:
        for lx, lz in [(rng.uniform(-0.3, 0.3) * half_w, rng.uniform(-0.3, 0.3) * half_d), (0.0, 0.0)]:
            for rel_yaw in (0.0, math.pi / 2.0):
                yield _to_world(anchor, lx, lz, float(anchor.position[1]), rel_yaw, "")
        return
    if relation == "facing":
        yield from _facing(fp, anchor, rng, y, support)
        return
    lateral0 = float(rng.uniform(-0.3, 0.3))
    if wall_anchor and relation in _WALL_SIDES:
        sides = list(_WALL_SIDES[relation])
        if relation == "around":
            sides = sides[instance % len(sides) :] + sides[: instance % len(sides)]
        gaps = [float(rng.uniform(0.05, 0.3)), 0.05, 0.3, 0.6]
        for side in sides:
            rel_yaws = [0.0]
            if side == "front" and relation == "in_front_of":
                # A seat faces what hangs on the wall (a sofa in front of the TV); what is used from its
                # front keeps its back to it (a teacher's desk in front of the chalkboard faces the class).
                rel_yaws = [math.pi, 0.0] if fp.sitters else [0.0, math.pi]
            lats = [lateral0 * half_w, 0.0, half_w, -half_w] if side in ("front", "below") else [0.0]
            for rel_yaw in rel_yaws:
                facing = side == "front" and bool(fp.sitters) and rel_yaw == math.pi
                for gap in SEAT_FACING_GAPS if facing else gaps:
                    for lat in lats:
                        yield _side(anchor, fp, side, gap, lat, rel_yaw, y, support)
        return
    if relation == "around":
        # Each copy takes its own side first (front, back, left, right in turn), then, where a wall or
        # another thing leaves that side no room (a table against the wall has no back), the others.
        order = ["front", "back", "left", "right"]
        start = instance % 4
        for k, side in enumerate(order[start:] + order[:start]):
            half = half_w if side in ("front", "back") else half_d
            lateral = ((instance // 4) % 3 - 1) * 0.6 * half
            offsets = (lateral, 0.0, -lateral) if k == 0 else (0.0, 0.5 * half, -0.5 * half)
            # Each copy turns to face the anchor: front copies face -Z, back +Z, side copies face inwards.
            rel_yaw = {"front": math.pi, "back": 0.0, "left": -math.pi / 2.0, "right": math.pi / 2.0}[side]
            if LEFT_SIGN < 0 and side in ("left", "right"):
                rel_yaw = -rel_yaw
            for gap in (float(rng.uniform(0.05, 0.2)), 0.05, 0.3, 0.6):
                for lat in offsets:
                    yield _side(anchor, fp, side, gap, lat, rel_yaw, y, support)
        return
    sides, rel_yaws = _SIDES.get(relation, (["front", "left", "right", "back"], [0.0, math.pi]))
    sides = list(sides)
    if len(sides) > 1:
        sides = (
            [sides[i] for i in rng.permutation(len(sides))]
            if relation == "next_to"
            else ([sides[int(rng.integers(len(sides)))]] + sides)
        )
        sides = list(dict.fromkeys(sides))
    near = relation == "near"
    gaps = [float(rng.uniform(0.1, 0.4) if near else rng.uniform(0.05, 0.2)), 0.05, 0.2, 0.4 if near else 0.3]
    lat_shares = [lateral0, 0.0, 0.5, -0.5, 1.0, -1.0]
    # "A chair is behind the desk": also the side one sits at (the desk's front), facing it, for a desk whose
    # back is against a wall (wana.assets.relations holds "behind" there too).
    seat_at = relation == "behind" and sits_at(fp, anchor.fp)
    # Sides vary fastest: a subject blocked on one side tries the others before finer shifts.
    for gap, share in itertools.product(gaps, lat_shares):
        for rel_yaw in rel_yaws:
            for side in sides:
                span = half_w if side in ("front", "back") else half_d
                yield _side(anchor, fp, side, gap, share * span, rel_yaw, y, support)
        if seat_at:
            yield _side(anchor, fp, "front", gap, share * half_w, math.pi, y, support)


def _on_surface(
    relation: str, fp: Footprint, anchor: Placed, rng: np.random.Generator
) -> Iterator[Candidate]:
    """Poses resting on the anchor's support surfaces ("in": lowest surfaces first, "on": highest first)."""
    surfaces = sorted(anchor.fp.surfaces, key=lambda s: s.height, reverse=relation == "on")
    if relation == "in":  # inside: on an inner shelf, else on the anchor's floor (a box, a basket)
        top = float(anchor.fp.bounds[1, 1])
        surfaces = [s for s in surfaces if s.height < top - 0.05]
        if not surfaces:
            for rel_yaw in (0.0, math.pi / 2.0):
                yield _to_world(anchor, 0.0, 0.0, float(anchor.position[1]) + 0.02, rel_yaw, anchor.id)
            return
    if not surfaces:  # nothing to rest on: stand on its top
        top = float(anchor.fp.bounds[1, 1])
        for rel_yaw in (0.0, math.pi / 2.0):
            yield _to_world(anchor, 0.0, 0.0, float(anchor.position[1]) + top, rel_yaw, anchor.id)
        return
    yaw0 = float(rng.choice([0.0, 0.0, math.pi / 2.0, -math.pi / 2.0]))
    fitted = False
    for s in surfaces:
        for rel_yaw in dict.fromkeys((yaw0, 0.0, math.pi / 2.0, -math.pi / 2.0, math.pi)):
            e = extents(fp, rel_yaw)
            lo_x, hi_x = s.min_xz[0] - e[0, 0], s.max_xz[0] - e[1, 0]
            lo_z, hi_z = s.min_xz[1] - e[0, 2], s.max_xz[1] - e[1, 2]
            if lo_x > hi_x or lo_z > hi_z:
                continue  # does not fit on this surface turned this way
            fitted = True
            xs = [float(rng.uniform(lo_x, hi_x)), (lo_x + hi_x) / 2.0, lo_x, hi_x]
            zs = [float(rng.uniform(lo_z, hi_z)), (lo_z + hi_z) / 2.0, lo_z, hi_z]
            for i, lx in enumerate(xs):
                for lz in zs if i else zs[:1]:
                    yield _to_world(
                        anchor, lx, lz, float(anchor.position[1]) + float(s.height), rel_yaw, anchor.id
                    )
            for lz in zs[1:]:
                yield _to_world(
                    anchor, xs[0], lz, float(anchor.position[1]) + float(s.height), rel_yaw, anchor.id
                )
    if not fitted:  # larger than every surface: centred on the largest one, overhanging its edges
        s = max(surfaces, key=lambda q: float(np.prod(q.max_xz - q.min_xz)))
        cx, cz = (s.min_xz + s.max_xz) / 2.0
        for rel_yaw in (0.0, math.pi / 2.0):
            yield _to_world(
                anchor, float(cx), float(cz), float(anchor.position[1]) + float(s.height), rel_yaw, anchor.id
            )
        # ... else slid to either end of it (a box too deep for a bench, kept off the sitter's place).
        for rel_yaw in (0.0, math.pi / 2.0):
            e = extents(fp, rel_yaw)
            room = float(s.max_xz[0] - s.min_xz[0]) / 2.0 - float(e[1, 0] - e[0, 0]) / 2.0
            for lx in (cx - room, cx + room) if room > 0.01 else ():
                yield _to_world(
                    anchor,
                    float(lx),
                    float(cz),
                    float(anchor.position[1]) + float(s.height),
                    rel_yaw,
                    anchor.id,
                )


def _above(
    relation: str, fp: Footprint, anchor: Placed, rng: np.random.Generator, room_height: float
) -> Iterator[Candidate]:
    top = float(anchor.position[1] + anchor.fp.bounds[1, 1])
    ceiling = room_height - fp.height - 0.05
    heights = [ceiling] if relation == "hanging_above" else [top + float(rng.uniform(0.2, 0.5)), top + 0.1]
    heights = [h for h in heights if h >= top + 0.05 and h <= ceiling] or [
        max(top + 0.05, min(ceiling, top + 0.3))
    ]
    for h in heights:
        for rel_yaw in (0.0, math.pi / 2.0):
            yield _to_world(anchor, 0.0, 0.0, h, rel_yaw, "")


def _facing(
    fp: Footprint, anchor: Placed, rng: np.random.Generator, y: float, support: str
) -> Iterator[Candidate]:
    """In front of the anchor at a distance, turned to face it."""
    a = anchor.fp.bounds
    for dist in (float(rng.uniform(0.8, 1.8)), 0.8, 1.2, 2.0, 2.8):
        for angle in (float(rng.uniform(-0.4, 0.4)), 0.0, 0.6, -0.6, 1.2, -1.2):
            reach = a[1, 2] + dist
            lx, lz = reach * math.sin(angle), reach * math.cos(angle)
            rel_yaw = math.atan2(-lx, -lz)  # turn the subject's +Z towards the anchor
            pos, yaw, sup = _to_world(anchor, lx, lz, y, rel_yaw, support)
            yield pos, yaw, sup
