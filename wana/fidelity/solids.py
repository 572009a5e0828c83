"""How deep a body sphere is inside a piece of furniture, measured on the object's own solid parts.

The catalog's collision boxes are a voxel grid of at most 12 cells a side (a 1.6 m table's cells are 13 cm),
and a yawed object's boxes become world AABBs larger still: measured against them, a seated person's belly
15 cm short of the table edge reads "12 cm inside the table" on every frame. The checks therefore measure the
primitives an object is built from (boxes, lathes, ellipsoids, in the object frame), with a signed distance
each: negative inside. Imported objects (no parts) fall back to their collision boxes.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from proto.scene import PlacedObject
from wana.assets import catalog
from wana.assets.geometry import build_mesh


@dataclass(frozen=True)
class Solid:
    """One solid primitive in the object frame (see wana.assets.geometry.Part)."""

    kind: str  # "box" | "lathe" | "ellipsoid" | "aabb" (an imported object's collision box)
    params: np.ndarray
    rotation: np.ndarray  # (3, 3) local -> object frame
    translation: np.ndarray  # (3,)

    def signed_distance(self, points: np.ndarray) -> np.ndarray:
        """(n,) metres from each (n, 3) object-frame point to the surface, negative inside."""
        q = (points - self.translation) @ self.rotation
        if self.kind in ("box", "aabb"):
            d = np.abs(q) - self.params
            outside = np.linalg.norm(np.maximum(d, 0.0), axis=1)
            return outside + np.minimum(d.max(axis=1), 0.0)
        if self.kind == "ellipsoid":  # the usual first-order estimate: exact on the axes, close elsewhere
            r = self.params
            k0 = np.linalg.norm(q / r, axis=1)
            k1 = np.linalg.norm(q / (r * r), axis=1)
            return np.where(k1 > 1e-9, k0 * (k0 - 1.0) / np.maximum(k1, 1e-9), -float(r.min()))
        return _lathe_distance(self.params, np.hypot(q[:, 0], q[:, 2]), q[:, 1])


def _lathe_distance(profile: np.ndarray, radial: np.ndarray, height: np.ndarray) -> np.ndarray:
    """Signed distance in the (radius, y) half-plane to the region the profile closes with the axis.

    The profile's rows may repeat a height (a table top is (0, y0), (R, y0), (R, y1), (0, y1)), so the
    region is a polygon, not a radius per height: distance to its edges, sign by the even-odd rule.
    """
    poly = np.asarray(profile, float)
    if poly[0, 0] > 1e-9:
        poly = np.vstack([[0.0, poly[0, 1]], poly])
    if poly[-1, 0] > 1e-9:
        poly = np.vstack([poly, [0.0, poly[-1, 1]]])
    a, b = poly, np.roll(poly, -1, axis=0)  # edges a -> b, the last one back along the axis
    p = np.stack([radial, height], axis=1)[:, None, :]  # (n, 1, 2)
    ab = (b - a)[None]
    t = np.clip(np.sum((p - a[None]) * ab, axis=2) / np.maximum(np.sum(ab * ab, axis=2), 1e-12), 0.0, 1.0)
    dist = np.linalg.norm(p - (a[None] + t[..., None] * ab), axis=2).min(axis=1)
    y, r = height[:, None], radial[:, None]
    crosses = (a[None, :, 1] > y) != (b[None, :, 1] > y)
    with np.errstate(divide="ignore", invalid="ignore"):
        at = a[None, :, 0] + (y - a[None, :, 1]) * (b[None, :, 0] - a[None, :, 0]) / (
            b[None, :, 1] - a[None, :, 1]
        )
    inside = (np.sum(crosses & (r < at), axis=1) % 2) == 1
    return np.where(inside, -dist, dist)


@lru_cache(maxsize=512)
def object_solids(category: str, attributes: tuple[tuple[str, str], ...], seed: int) -> tuple[Solid, ...]:
    """The solid parts of one catalog object, object frame (the catalog's recentring applied)."""
    from wana.assets.catalog import REGISTRY, Builder, _params, normalize_attributes, run
    from wana.assets.importers.registry import imported_object

    if imported_object(category) is not None or category not in REGISTRY:
        boxes = np.asarray(catalog.make_object(category, dict(attributes), seed).collision_boxes)
        return tuple(
            Solid("aabb", (b[1] - b[0]) / 2.0, np.eye(3), (b[1] + b[0]) / 2.0)
            for b in boxes.reshape(-1, 2, 3)
        )
    attrs = normalize_attributes(category, dict(attributes))
    builder = Builder()
    run(REGISTRY[category], builder, _params(category, REGISTRY[category], attrs, seed))
    lo, hi = build_mesh(builder.parts).bounds
    shift = np.array([-(lo[0] + hi[0]) / 2.0, -lo[1], -(lo[2] + hi[2]) / 2.0])
    return tuple(
        Solid(p.kind, np.asarray(p.params, float), np.asarray(p.rotation, float), p.translation + shift)
        for p in builder.parts
        if p.solid
    )


def solids_of(placed: PlacedObject) -> tuple[Solid, ...]:
    """The solid parts of a placed object (object frame; see `depth_inside` for world points)."""
    try:
        return object_solids(placed.category, tuple(sorted(placed.attributes.items())), placed.seed)
    except KeyError:
        return ()


def depth_inside(placed: PlacedObject, centres: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """(n,) how far each world sphere (centre (n, 3), radius (n,)) reaches into the object, metres (<= 0: clear).

    Points go into the object frame by the inverse of `catalog.object_to_world`; a scaled object's distances
    are taken back to metres by its mean scale (placements are scaled uniformly or nearly so).
    """
    solids = solids_of(placed)
    if not solids or not len(centres):
        return np.full(len(centres), -np.inf)
    m = catalog.object_to_world(placed)
    local = (centres - m[:3, 3]) @ np.linalg.inv(m[:3, :3]).T
    inside = np.min([s.signed_distance(local) for s in solids], axis=0)
    return radii - inside * float(np.mean(placed.scale))


def depth_inside_at(
    placed: PlacedObject, centres: np.ndarray, radii: np.ndarray, poses: np.ndarray
) -> np.ndarray:
    """(n,) as `depth_inside`, with the object at its own pose per sphere: (n, 4, 4) object -> world (the
    placement's scale included), for an object that moves (carried in a hand)."""
    solids = solids_of(placed)
    if not solids or not len(centres):
        return np.full(len(centres), -np.inf)
    inv = np.linalg.inv(poses[:, :3, :3])
    local = np.einsum("nij,nj->ni", inv, centres - poses[:, :3, 3])
    inside = np.min([s.signed_distance(local) for s in solids], axis=0)
    return radii - inside * float(np.mean(placed.scale))


@lru_cache(maxsize=256)
def object_leaves(
    category: str, attributes: tuple[tuple[str, str], ...], seed: int, scale: tuple[float, float, float]
) -> tuple[tuple[int, ...], dict[int, np.ndarray]]:
    """Which leaf an "open" state turns each solid part with (0: still; wana.domain.object_state), and each
    leaf's (2, 3) bounds, in the scaled object frame the renderer poses the leaf in (render.object_states)."""
    from wana.assets.geometry import Part
    from wana.domain.object_state import moving_faces

    placed = PlacedObject(id="", category=category, attributes=dict(attributes), seed=seed, scale=scale)
    mesh = catalog.asset_for(placed).mesh
    k = np.asarray(scale, float)
    tri = np.asarray(mesh.vertices, float)[np.asarray(mesh.faces)] * k
    faces = moving_faces(category, tri)
    parts = {
        int(leaf): np.stack(
            [tri[faces == leaf].reshape(-1, 3).min(axis=0), tri[faces == leaf].reshape(-1, 3).max(axis=0)]
        )
        for leaf in np.unique(faces)
        if leaf > 0
    }
    leaves = []
    for solid in solids_of(placed):
        part = build_mesh([Part(solid.kind, solid.params, solid.rotation, solid.translation, (0, 0, 0, 255))])
        own = np.asarray(part.vertices, float)[np.asarray(part.faces)] * k
        # the part's faces judged among the whole mesh's (the rule reads the mesh's extent)
        votes = moving_faces(category, np.concatenate([tri, own]))[len(tri) :]
        leaves.append(int(np.bincount(votes, minlength=3).argmax()) if len(votes) else 0)
    return tuple(leaves), parts


def leaf_transforms(placed: PlacedObject, value: float) -> dict[int, np.ndarray]:
    """Leaf -> (4, 4) scaled-object-frame transform of that leaf at an "open" value (as the renderer poses it)."""
    from wana.domain.object_state import open_transform

    _, parts = object_leaves(
        placed.category, tuple(sorted(placed.attributes.items())), placed.seed, placed.scale
    )
    return {k: open_transform(placed.category, part, value, k) for k, part in parts.items()}


def depth_inside_open(
    placed: PlacedObject, centres: np.ndarray, radii: np.ndarray, values: np.ndarray
) -> np.ndarray:
    """(n,) as `depth_inside`, with the object's door leaves, lids or fronts turned to each sphere's "open"
    value (n,) (Scene.states): an open door's leaf stands out in the room, its doorway is clear."""
    solids = solids_of(placed)
    if not solids or not len(centres):
        return np.full(len(centres), -np.inf)
    leaves, _ = object_leaves(
        placed.category, tuple(sorted(placed.attributes.items())), placed.seed, placed.scale
    )
    k = np.asarray(placed.scale, float)
    m = catalog.object_to_world(placed)
    local = (centres - m[:3, 3]) @ np.linalg.inv(m[:3, :3]).T  # unscaled object frame
    inside = np.full(len(centres), np.inf)
    for value in np.unique(np.round(values, 3)):
        at = np.nonzero(np.round(values, 3) == value)[0]
        turns = leaf_transforms(placed, float(value))
        for solid, leaf in zip(solids, leaves, strict=True):
            q = local[at]
            if leaf in turns:  # back into the leaf's shut pose: where the solid is modelled
                t = turns[leaf]
                q = ((q * k - t[:3, 3]) @ t[:3, :3]) / k
            inside[at] = np.minimum(inside[at], solid.signed_distance(q))
    return radii - inside * float(np.mean(placed.scale))


def rests_on(placed: PlacedObject, points: np.ndarray, below: float, above: float, step: float) -> np.ndarray:
    """(n,) whether a solid part of the object lies under each world point, from `below` under it up to
    `above` over it (probed every `step` metres down from the point): the point rests on the object, or sinks
    into it a little."""
    if not len(points):
        return np.zeros(0, bool)
    drops = np.arange(-below, above + 1e-9, step)
    probes = points[:, None, :] - drops[None, :, None] * np.array([0.0, 1.0, 0.0])
    depth = depth_inside(placed, probes.reshape(-1, 3), np.zeros(probes.shape[0] * probes.shape[1]))
    return np.asarray((depth.reshape(probes.shape[:2]) >= 0.0).any(axis=1), bool)


__all__ = [
    "Solid",
    "depth_inside",
    "depth_inside_at",
    "depth_inside_open",
    "leaf_transforms",
    "object_leaves",
    "object_solids",
    "rests_on",
    "solids_of",
]
