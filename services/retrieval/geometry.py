"""Boxes, poses and overlap tests for composing a room (metres, world frame, Y up).

An object is placed by a pose: the world position of its base centre and a yaw about +Y (0 keeps its
front on +Z), as proto.scene.PlacedObject and wana.assets.catalog.object_to_world define it. Collision
boxes are the catalog's small voxel boxes; in the world they are axis-aligned boxes of the rotated
boxes, as wana.assets.catalog.world_collision_boxes computes them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from wana.assets import vocabulary
from wana.assets.catalog import SupportSurface, make_object

OVERLAP_EPS = 0.01  # metres two boxes must interpenetrate on every axis to count as overlapping

# The space a seated person's torso takes above each seat slot (object frame, about the slot's hips point,
# the sitter facing +Z): kept free like the seat itself, so that no table top, shelf or second table comes
# to stand where the chest will be. A chair may still go under a table's top as far as the sitter's thighs
# and knees (they sit below the top); its torso stays in front of the edge. Metres: half width, from the
# hips' height up (above the thighs) to the top of the head's reach, and from just behind the hips to a
# little past the belly (the torso's capsules are 0.11-0.12 m thick, wana.fidelity.bodies).
SITTER_HALF_WIDTH_M = 0.17
SITTER_Y_M = (0.12, 0.65)
SITTER_Z_M = (-0.08, 0.16)


@dataclass(frozen=True, eq=False)
class Footprint:
    """What composition needs to know of a catalog object.

    Attributes:
        category, attributes, seed: the catalog variant.
        boxes: (N, 2, 3) collision boxes, object frame: the catalog's voxel cells merged into larger
            boxes covering exactly the same cells (far fewer boxes to test), then one box per seat slot
            for the sitter's torso (sitter_boxes).
        bounds: (2, 3) object-frame AABB of the solid boxes (the sitters' aside: a chair is no taller).
        surfaces: support surfaces, object frame.
        mount: "floor", "surface" or "wall".
        sitters: how many of the boxes, at the end, are sitter boxes (what rests on the seat keeps off them).
    """

    category: str
    attributes: tuple[tuple[str, str], ...]
    seed: int
    boxes: np.ndarray = field(repr=False)
    bounds: np.ndarray
    surfaces: tuple[SupportSurface, ...] = field(repr=False)
    mount: str
    extents_by_yaw: dict[float, np.ndarray] = field(default_factory=dict, repr=False)
    sitters: int = 0

    @property
    def height(self) -> float:
        return float(self.bounds[1, 1] - self.bounds[0, 1])


@lru_cache(maxsize=4096)
def _footprint(category: str, attributes: tuple[tuple[str, str], ...], seed: int) -> Footprint:
    asset = make_object(category, dict(attributes), seed)
    boxes = merge_cells(np.asarray(asset.collision_boxes, dtype=np.float64))
    if len(boxes) == 0:  # a generator without solid parts still occupies its mesh box
        half = np.asarray(asset.dims) / 2.0
        boxes = np.array([[[-half[0], 0.0, -half[2]], [half[0], asset.dims[1], half[2]]]])
    bounds = np.stack([boxes[:, 0].min(axis=0), boxes[:, 1].max(axis=0)])  # the solid object's
    sitters = sitter_boxes(asset)
    boxes = np.concatenate([boxes, sitters])
    info = vocabulary.CATEGORIES.get(category)
    return Footprint(
        category,
        attributes,
        seed,
        boxes,
        bounds,
        tuple(asset.support_surfaces),
        info.mount if info else "floor",
        sitters=len(sitters),
    )


def sitter_boxes(asset: object) -> np.ndarray:
    """(S, 2, 3) object-frame boxes of the seated torsos above a catalog object's seat slots ("sit*" points at
    the hips; none for objects without one)."""
    points = getattr(asset, "contact_points", {})
    hips = [
        np.asarray(cp.position, dtype=np.float64)
        for name, cp in sorted(points.items())
        if name.startswith("sit") and cp.joint == "Hips"
    ]
    out = [
        [
            [h[0] - SITTER_HALF_WIDTH_M, h[1] + SITTER_Y_M[0], h[2] + SITTER_Z_M[0]],
            [h[0] + SITTER_HALF_WIDTH_M, h[1] + SITTER_Y_M[1], h[2] + SITTER_Z_M[1]],
        ]
        for h in hips
    ]
    return np.asarray(out, dtype=np.float64).reshape(-1, 2, 3)


def merge_cells(cells: np.ndarray) -> np.ndarray:
    """Merge equal voxel cells on a regular grid into fewer boxes with the same union (greedy meshing).

    Args:
        cells: (N, 2, 3) min/max corners of equal-sized cells on one grid.

    Returns:
        (M, 2, 3) boxes, M <= N; cells that do not sit on one grid come back unchanged.
    """
    if len(cells) < 2:
        return cells
    size = cells[0, 1] - cells[0, 0]
    if np.any(size <= 0) or not np.allclose(cells[:, 1] - cells[:, 0], size, atol=1e-6):
        return cells
    origin = cells[:, 0].min(axis=0)
    idx = np.rint((cells[:, 0] - origin) / size).astype(int)
    if not np.allclose(origin + idx * size, cells[:, 0], atol=1e-5):
        return cells
    shape = idx.max(axis=0) + 1
    occ = np.zeros(shape, dtype=bool)
    occ[idx[:, 0], idx[:, 1], idx[:, 2]] = True
    free = occ.copy()
    out = []
    for y in range(shape[1]):
        for z in range(shape[2]):
            for x in range(shape[0]):
                if not free[x, y, z]:
                    continue
                x1 = x + 1
                while x1 < shape[0] and free[x1, y, z]:
                    x1 += 1
                z1 = z + 1
                while z1 < shape[2] and free[x:x1, y, z1].all():
                    z1 += 1
                y1 = y + 1
                while y1 < shape[1] and free[x:x1, y1, z:z1].all():
                    y1 += 1
                free[x:x1, y:y1, z:z1] = False
                out.append([origin + np.array([x, y, z]) * size, origin + np.array([x1, y1, z1]) * size])
    return np.array(out, dtype=np.float64)


def footprint(category: str, attributes: dict[str, str], seed: int) -> Footprint:
    """The (cached) footprint of a catalog variant; raises KeyError for an unknown category."""
    return _footprint(category, tuple(sorted(attributes.items())), seed)


def yaw_matrix(yaw: float) -> np.ndarray:
    """(3, 3) rotation about +Y (same convention as wana.assets.catalog.yaw_matrix); read-only, cached."""
    return _yaw_matrix(float(yaw))


@lru_cache(maxsize=4096)
def _yaw_matrix(yaw: float) -> np.ndarray:
    c, s = np.cos(yaw), np.sin(yaw)
    r = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
    r.setflags(write=False)
    return r


def boxes_at(boxes: np.ndarray, position: np.ndarray, yaw: float) -> np.ndarray:
    """World AABBs of object-frame boxes.

    Args:
        boxes: (N, 2, 3) min/max corners, object frame.
        position: (3,) world position of the object's base centre.
        yaw: radians about +Y.

    Returns:
        (N, 2, 3) world min/max corners.
    """
    r = yaw_matrix(yaw)
    centre = (boxes[:, 0] + boxes[:, 1]) * 0.5 @ r.T + position
    half = (boxes[:, 1] - boxes[:, 0]) * 0.5 @ np.abs(r).T
    return np.stack([centre - half, centre + half], axis=1)


@lru_cache(maxsize=65536)
def _rotated(fp: Footprint, yaw: float) -> tuple[np.ndarray, np.ndarray]:
    r = yaw_matrix(yaw)
    centre = (fp.boxes[:, 0] + fp.boxes[:, 1]) * 0.5 @ r.T
    half = (fp.boxes[:, 1] - fp.boxes[:, 0]) * 0.5 @ np.abs(r).T
    centre.setflags(write=False)
    half.setflags(write=False)
    return centre, half


def footprint_boxes_at(fp: Footprint, position: np.ndarray, yaw: float) -> np.ndarray:
    """World AABBs of a footprint's boxes: ``boxes_at(fp.boxes, position, yaw)``, bit for bit.

    The rotated box centres and half sizes are cached per (footprint, yaw), so a pose costs one
    addition; the arithmetic is the same as boxes_at's, in the same order, so the corners are equal.

    Returns:
        (N, 2, 3) world min/max corners.
    """
    centre, half = _rotated(fp, float(yaw))
    centre = centre + position
    return np.stack([centre - half, centre + half], axis=1)


def aabb(boxes: np.ndarray) -> np.ndarray:
    """(2, 3) AABB of (N, 2, 3) boxes."""
    return np.stack([boxes[:, 0].min(axis=0), boxes[:, 1].max(axis=0)])


@lru_cache(maxsize=65536)
def _extents(fp: Footprint, yaw: float) -> np.ndarray:
    e = aabb(boxes_at(fp.boxes, np.zeros(3), yaw))
    e.setflags(write=False)
    return e


def extents(fp: Footprint, yaw: float) -> np.ndarray:
    """(2, 3) AABB of the footprint's boxes after a yaw, relative to its origin (cached).

    Yaws equal to 9 decimals share one entry; each exact yaw seen is also remembered on the
    footprint itself, so a repeated yaw costs one dict lookup.
    """
    found = fp.extents_by_yaw.get(yaw)
    if found is None:
        if len(fp.extents_by_yaw) >= 4096:  # continuous yaws ("facing") would grow it without end
            fp.extents_by_yaw.clear()
        found = fp.extents_by_yaw[yaw] = _extents(fp, round(float(yaw), 9))
    return found


def boxes_overlap(a: np.ndarray, b: np.ndarray, eps: float = OVERLAP_EPS) -> bool:
    """True when any box of a (N, 2, 3) interpenetrates any box of b (M, 2, 3) by more than eps."""
    lo = np.maximum(a[:, 0].min(axis=0), b[:, 0].min(axis=0)) - eps
    hi = np.minimum(a[:, 1].max(axis=0), b[:, 1].max(axis=0)) + eps
    if np.any(lo >= hi):
        return False
    # Only boxes inside the common region can touch; prune before the pairwise test.
    a = a[np.all((a[:, 1] > lo) & (a[:, 0] < hi), axis=1)]
    b = b[np.all((b[:, 1] > lo) & (b[:, 0] < hi), axis=1)]
    if len(a) == 0 or len(b) == 0:
        return False
    sep = (a[:, None, 0] >= b[None, :, 1] - eps) | (b[None, :, 0] >= a[:, None, 1] - eps)  # (N, M, 3)
    return bool(np.any(~np.any(sep, axis=2)))


def first_overlapping(
    boxes: np.ndarray, others: np.ndarray, owner: np.ndarray | None = None, eps: float = OVERLAP_EPS
) -> int:
    """The lowest owner of any box in ``others`` that interpenetrates a box of ``boxes``, or -1.

    One broadcast test over every pair of boxes at once; for each owner it agrees with
    ``boxes_overlap(boxes, others[owner == k], eps)`` (whose pruning to the common region never
    changes the answer).

    Args:
        boxes: (N, 2, 3) world boxes of one object.
        others: (M, 2, 3) world boxes of several objects, concatenated.
        owner: (M,) int owner number of each box in ``others`` (any order); None: all one owner, 0.
        eps: metres the boxes must interpenetrate on every axis.

    Returns:
        The smallest owner number that overlaps, -1 when none does.
    """
    if len(boxes) == 0 or len(others) == 0:
        return -1
    sep = (boxes[:, None, 0] >= others[None, :, 1] - eps) | (others[None, :, 0] >= boxes[:, None, 1] - eps)
    hit = ~(sep[..., 0] | sep[..., 1] | sep[..., 2])  # (N, M)
    cols = hit.any(axis=0)
    if not cols.any():
        return -1
    return 0 if owner is None else int(owner[cols].min())


def aabbs_overlap(a: np.ndarray, b: np.ndarray, eps: float = OVERLAP_EPS) -> bool:
    """True when two (2, 3) AABBs interpenetrate by more than eps on every axis."""
    return bool(np.all(a[0] < b[1] - eps) and np.all(b[0] < a[1] - eps))


def inside_room(box: np.ndarray, width: float, depth: float, height: float, eps: float = 0.01) -> bool:
    """True when a (2, 3) AABB lies inside the room x in [-w/2, w/2], y in [0, h], z in [-d/2, d/2]."""
    (x0, y0, z0), (x1, y1, z1) = box.tolist()
    hw, hd = width / 2.0 + eps, depth / 2.0 + eps
    return x0 >= -hw and x1 <= hw and z0 >= -hd and z1 <= hd and y0 >= -eps and y1 <= height + eps


def surface_rects(fp: Footprint, position: np.ndarray, yaw: float) -> list[tuple[float, np.ndarray]]:
    """World support surfaces as (height y, (2, 2) x/z AABB of the rectangle)."""
    out = []
    for s in fp.surfaces:
        box = np.array([[[s.min_xz[0], s.height, s.min_xz[1]], [s.max_xz[0], s.height, s.max_xz[1]]]])
        w = boxes_at(box, position, yaw)[0]
        out.append((float(w[0, 1]), w[:, [0, 2]]))
    return out


def sits_at(seat: Footprint, anchor: Footprint) -> bool:
    """A seat and a table, desk or counter (not itself a seat): one sits at its front (its working side)."""
    from wana.assets.relations import is_worktop

    if not seat.sitters or anchor.sitters:
        return False
    return is_worktop(float(anchor.bounds[1, 1]), [float(x.height) for x in anchor.surfaces])
