"""A fast screen for relation predicates on poses being searched (before the exact check).

The exact predicates are wana.assets.relations.relation_holds on proto.scene.PlacedObject; each call
rebuilds transforms from the catalog, which is too slow for thousands of candidate poses. This screen
reads the same geometry from the poses being searched (intrinsic frames: front +Z, left +X; footprint
gaps in metres) so that only a candidate passing it gets the exact check.
"""

from __future__ import annotations

import math

from services.retrieval.geometry import sits_at
from services.retrieval.placement import Placed

NEAR_M, NEXT_TO_M, REACH_M, AROUND_M = 1.0, 0.4, 2.5, 0.8
FACING_COS = math.cos(math.radians(45.0))


def _gap(s: Placed, a: Placed) -> float:
    dx = max(0.0, float(s.box[0, 0] - a.box[1, 0]), float(a.box[0, 0] - s.box[1, 0]))
    dz = max(0.0, float(s.box[0, 2] - a.box[1, 2]), float(a.box[0, 2] - s.box[1, 2]))
    return math.hypot(dx, dz)


def _centre(p: Placed) -> tuple[float, float, float]:
    c = (p.box[0] + p.box[1]) / 2.0
    return float(c[0]), float(c[1]), float(c[2])


def _local(a: Placed, x: float, z: float) -> tuple[float, float]:
    """World x/z -> the anchor's frame (its +X left, +Z front)."""
    dx, dz = x - float(a.position[0]), z - float(a.position[2])
    c, s = math.cos(a.yaw), math.sin(a.yaw)
    return c * dx - s * dz, s * dx + c * dz


def _side(s: Placed, a: Placed, axis: int, sign: float) -> bool:
    cx, _, cz = _centre(s)
    lx, lz = _local(a, cx, cz)
    b = a.fp.bounds
    half_x = float(b[1, 0] - b[0, 0]) / 2.0
    half_z = float(b[1, 2] - b[0, 2]) / 2.0
    along, other, half_along, half_other = (lz, lx, half_z, half_x) if axis == 2 else (lx, lz, half_x, half_z)
    beyond = sign * along - half_along
    return -0.05 <= beyond <= REACH_M and abs(other) <= half_other + 0.3


def _facing(s: Placed, a: Placed) -> bool:
    fx, fz = math.sin(s.yaw), math.cos(s.yaw)
    sx, _, sz = _centre(s)
    ax, _, az = _centre(a)
    tx, tz = ax - sx, az - sz
    n = math.hypot(tx, tz)
    return n > 1e-9 and (fx * tx + fz * tz) / n >= FACING_COS


def _over(s: Placed, a: Placed, margin: float) -> bool:
    cx, _, cz = _centre(s)
    return (a.box[0, 0] - margin <= cx <= a.box[1, 0] + margin) and (
        a.box[0, 2] - margin <= cz <= a.box[1, 2] + margin
    )


def screen(relation: str, s: Placed, a: Placed) -> bool:
    """Whether ``s relation a`` looks true of the two poses (a screen; the exact check follows)."""
    if relation in ("on", "in"):
        return s.support == a.id
    if relation == "near":
        return _gap(s, a) <= NEAR_M
    if relation == "next_to":
        return _gap(s, a) <= NEXT_TO_M and s.box[0, 1] < a.box[1, 1] and a.box[0, 1] < s.box[1, 1]
    if relation == "in_front_of":
        return _side(s, a, 2, 1.0)
    if relation == "behind":  # a seat at a table or desk: also the side one sits at (wana.assets.relations)
        return _side(s, a, 2, -1.0) or (sits_at(s.fp, a.fp) and _side(s, a, 2, 1.0) and _facing(s, a))
    if relation == "left_of":
        return _side(s, a, 0, 1.0)
    if relation == "right_of":
        return _side(s, a, 0, -1.0)
    if relation == "under":
        if a.fp.mount == "wall":  # a sink under the mirror stands against its wall, below it
            return s.box[0, 1] < a.box[0, 1] and _gap(s, a) <= NEAR_M
        return _over(s, a, 0.0) and s.box[1, 1] <= a.box[1, 1] - 0.02
    if relation == "above":
        return _over(s, a, 0.1) and s.box[0, 1] >= a.box[1, 1] - 0.01
    if relation == "hanging_above":
        return _over(s, a, 0.1) and s.box[0, 1] >= a.box[1, 1] + 0.1
    if relation == "facing":
        return _facing(s, a)
    if relation == "around":
        return _gap(s, a) <= AROUND_M and _facing(s, a)
    return True
