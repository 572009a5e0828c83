"""Geometric predicates for SSG relations between two placed objects (shared with retrieval).

Frames: directions like "in front of" and "left of" are the anchor's own (intrinsic) directions: an
object's front is its +Z and, like a character facing +Z, its left is +X. Distances are metres
between footprints (world XZ bounding rectangles), so big objects are not penalised.

    relation_holds("on", laptop_placed, desk_placed) -> bool
"""

from __future__ import annotations

import numpy as np

from proto.scene import PlacedObject
from proto.ssg import RELATIONS, RelationNode
from wana.assets import vocabulary
from wana.assets.catalog import asset_for, object_to_world, world_bounds

NEAR_M = 1.0  # footprint gap for "near"
NEXT_TO_M = 0.4  # footprint gap for "next to"
SIDE_REACH_M = 2.5  # how far "in front of"/"behind"/"left of"/"right of" reach from the anchor
ON_TOL_M = 0.02  # vertical tolerance for resting on a surface
FACING_COS = float(np.cos(np.radians(45.0)))
AROUND_M = 0.8


def footprint_gap(a: PlacedObject, b: PlacedObject) -> float:
    """Distance between the world XZ bounding rectangles of two objects (0 when they overlap)."""
    ba, bb = world_bounds(a), world_bounds(b)
    d = np.maximum(0.0, np.maximum(ba[0, [0, 2]] - bb[1, [0, 2]], bb[0, [0, 2]] - ba[1, [0, 2]]))
    return float(np.hypot(*d))


def to_anchor_frame(anchor: PlacedObject, points: np.ndarray) -> np.ndarray:
    """World points (..., 3) -> the anchor's object frame (undoing position, yaw and scale)."""
    m = np.linalg.inv(object_to_world(anchor))
    return np.asarray(points, float) @ m[:3, :3].T + m[:3, 3]


def _centre(placed: PlacedObject) -> np.ndarray:
    b = world_bounds(placed)
    return (b[0] + b[1]) / 2.0


def _on(s: PlacedObject, a: PlacedObject) -> bool:
    base = to_anchor_frame(a, np.array(s.position))
    for surf in asset_for(a).support_surfaces:
        if (
            abs(base[1] - surf.height) <= ON_TOL_M / max(a.scale[1], 1e-6)
            and np.all(base[[0, 2]] >= surf.min_xz - 0.02)
            and np.all(base[[0, 2]] <= surf.max_xz + 0.02)
        ):
            return True
    return False


WALL_UNDER_REACH_M = 0.3  # how far from the wall a subject "under" a window or mirror may stand
WALL_UNDER_SLACK_M = 0.1  # metres its centre may reach past the side of the window
# share of the window's height that a tap or a lamp on the subject may rise in front of
WALL_UNDER_RISE = 1.0 / 3.0


def _on_wall(a: PlacedObject) -> bool:
    info = vocabulary.CATEGORIES.get(a.category)
    return info is not None and info.mount == "wall"


def _under_wall(s: PlacedObject, a: PlacedObject) -> bool:
    """Under a window, mirror or painting: against its wall, below its bottom, centred within its width
    (a desk under the window, a sink under the mirror, its tap in front of the window's lowest third);
    nothing can stand inside a window's thin box, so the floor-object rule never holds against a wall."""
    bs, ba = world_bounds(s), world_bounds(a)
    corners = np.array([[x, 0.0, z] for x in bs[:, 0] for z in bs[:, 2]])
    local = to_anchor_frame(a, corners)
    centre = to_anchor_frame(a, _centre(s))
    half = asset_for(a).dims / 2.0
    back = float(local[:, 2].min())  # the subject's face nearest the wall, anchor frame (+Z into the room)
    return bool(
        abs(centre[0]) <= half[0] + WALL_UNDER_SLACK_M
        and -half[2] - 0.05 <= back <= half[2] + WALL_UNDER_REACH_M
        and bs[1, 1] <= ba[0, 1] + max(WALL_UNDER_SLACK_M, WALL_UNDER_RISE * float(ba[1, 1] - ba[0, 1]))
    )


def _under(s: PlacedObject, a: PlacedObject) -> bool:
    if _on_wall(a):
        return _under_wall(s, a)
    bs, ba = world_bounds(s), world_bounds(a)
    c = _centre(s)
    inside = ba[0, 0] <= c[0] <= ba[1, 0] and ba[0, 2] <= c[2] <= ba[1, 2]
    return bool(inside and bs[1, 1] <= ba[1, 1] - 0.02 and bs[0, 1] < ba[1, 1])


def _above(s: PlacedObject, a: PlacedObject, gap: float = -0.01) -> bool:
    bs, ba = world_bounds(s), world_bounds(a)
    c = _centre(s)
    over = ba[0, 0] - 0.1 <= c[0] <= ba[1, 0] + 0.1 and ba[0, 2] - 0.1 <= c[2] <= ba[1, 2] + 0.1
    return bool(over and bs[0, 1] >= ba[1, 1] + gap)


def _side(s: PlacedObject, a: PlacedObject, axis: int, sign: float) -> bool:
    """Subject's centre beyond the anchor's face on (axis, sign), within reach and roughly in line."""
    local = to_anchor_frame(a, _centre(s))
    half = asset_for(a).dims / 2.0
    other = 0 if axis == 2 else 2
    beyond = sign * local[axis] - half[axis]
    return bool(-0.05 <= beyond <= SIDE_REACH_M and abs(local[other]) <= half[other] + 0.3)


WORKTOP_M = (0.6, 1.1)  # metres: the top of a table, desk or counter one sits or stands at


def is_worktop(top: float, surface_heights: list[float]) -> bool:
    """A table, desk or counter: its top (metres) at working height, with a support surface there."""
    lo, hi = WORKTOP_M
    return lo <= top <= hi and any(lo <= h <= hi and h >= top - 0.1 for h in surface_heights)


def _seat_at_worktop(s: PlacedObject, a: PlacedObject) -> bool:
    """A seat (a 'sit' point) and a table or desk: "the chair is behind the desk" is the side one sits at."""
    seat, anchor = asset_for(s), asset_for(a)
    if not any(name.startswith("sit") for name in seat.contact_points):
        return False
    if any(name.startswith("sit") for name in anchor.contact_points):
        return False
    return is_worktop(float(anchor.dims[1]), [float(x.height) for x in anchor.support_surfaces])


def _behind(s: PlacedObject, a: PlacedObject) -> bool:
    """Past the anchor's back; for a seat at a table or desk also the side one sits at, facing it (in English
    one sits *behind* a desk: a desk under a window has its back to the wall and its chair at its front)."""
    return _side(s, a, 2, -1.0) or (_seat_at_worktop(s, a) and _side(s, a, 2, 1.0) and _facing(s, a))


def _facing(s: PlacedObject, a: PlacedObject) -> bool:
    front = object_to_world(s)[:3, :3] @ np.array([0.0, 0.0, 1.0])
    front[1] = 0.0
    to = _centre(a) - _centre(s)
    to[1] = 0.0
    n = np.linalg.norm(to) * np.linalg.norm(front)
    return bool(n > 1e-9 and float(front @ to) / n >= FACING_COS)


def _in(s: PlacedObject, a: PlacedObject) -> bool:
    ba = world_bounds(a)
    c = _centre(s)
    return bool(np.all(c >= ba[0] - 1e-6) and np.all(c <= ba[1] + 1e-6))


def _vertical_overlap(s: PlacedObject, a: PlacedObject) -> bool:
    bs, ba = world_bounds(s), world_bounds(a)
    return bool(bs[0, 1] < ba[1, 1] and ba[0, 1] < bs[1, 1])


PREDICATES = {
    "on": _on,
    "near": lambda s, a: footprint_gap(s, a) <= NEAR_M,
    "next_to": lambda s, a: footprint_gap(s, a) <= NEXT_TO_M and _vertical_overlap(s, a),
    "in_front_of": lambda s, a: _side(s, a, 2, 1.0),
    "behind": _behind,
    "left_of": lambda s, a: _side(s, a, 0, 1.0),
    "right_of": lambda s, a: _side(s, a, 0, -1.0),
    "under": _under,
    "above": _above,
    "hanging_above": lambda s, a: _above(s, a, gap=0.1) and not _on(s, a),
    "facing": _facing,
    "in": _in,
    "around": lambda s, a: footprint_gap(s, a) <= AROUND_M and _facing(s, a),
}
assert set(PREDICATES) == set(RELATIONS), "every SSG relation needs a predicate"


def relation_holds(
    rel: str | RelationNode, subject_placed: PlacedObject, anchor_placed: PlacedObject
) -> bool:
    """Whether ``subject rel anchor`` is true of the two placements.

    Args:
        rel: a relation name from proto.ssg.RELATIONS, or a RelationNode (its .relation is used).
        subject_placed: the subject's placement (world frame).
        anchor_placed: the anchor's placement.

    Raises:
        ValueError: for an unknown relation name.
    """
    name = rel.relation if isinstance(rel, RelationNode) else rel
    if name not in PREDICATES:
        raise ValueError(f"unknown relation {name!r}; expected one of {RELATIONS}")
    return bool(PREDICATES[name](subject_placed, anchor_placed))


def relations_between(subject_placed: PlacedObject, anchor_placed: PlacedObject) -> list[str]:
    """All relation names that hold from subject to anchor."""
    return [r for r in RELATIONS if PREDICATES[r](subject_placed, anchor_placed)]


def anchor_copy(subject_copy: str, relation: RelationNode, anchor_copies: int) -> str:
    """The placed id of the anchor copy one subject copy is placed by ("chair/2" of "a chair at each desk" ->
    "desk/2", counting round when there are fewer desks); the anchor itself for a relation without ``each``.
    Copy ids are the layout's: "desk", "desk/2", ... (services.retrieval.compose.instance_ids)."""
    if not relation.each or anchor_copies <= 1:
        return relation.object
    k = int(subject_copy.rsplit("/", 1)[1]) if "/" in subject_copy else 1
    j = (k - 1) % anchor_copies + 1
    return relation.object if j == 1 else f"{relation.object}/{j}"
