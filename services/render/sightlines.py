"""Sight lines against the furniture as the renderer draws it: the object's box first, then its mesh.

The catalog's collision boxes are voxels of about a twelfth of an object's largest side, so a 4 cm desk
leg blocks like an 11 cm post, and a ray that passes beside the leg in the picture counts as hidden.
The rays that pass through an object's bounding box are tested against its triangles (Möller-Trumbore),
the pixels' own geometry (the catalog's meshes are small: 36 to ~1000 triangles, often fewer than their
voxels). The voxels still say which joints are buried inside an object (``first_blocker``).

    furniture = Furniture.from_scene(scene)
    blocker = furniture.first_blocker(starts, ends)  # (S,) object index, -1 where the line is clear
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from proto.scene import Scene
from services.render.framing import segments_hit_boxes

CHUNK = 400_000  # ray x triangle pairs per numpy batch (memory stays under ~50 MB)
BURIED_STEP = 0.025  # metres between samples when walking back from a buried point toward the eye
BURIED_MAX = 1.0  # metres walked at most
BURIED_SLACK = 0.05  # metres: a surface this far beyond the buried stretch is still the one it is under


def box_triangles(boxes: np.ndarray) -> np.ndarray:
    """(B, 2, 3) axis-aligned boxes -> (12 B, 3, 3) triangles of their surfaces."""
    corner = np.array([[i >> 2 & 1, i >> 1 & 1, i & 1] for i in range(8)])  # (8, 3) 0/1 per axis: x, y, z
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    tri_idx = np.array([t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))])  # (12, 3)
    boxes = np.asarray(boxes, dtype=np.float64).reshape(-1, 2, 3)
    verts = boxes[:, 0][:, None, :] + corner[None] * (boxes[:, 1] - boxes[:, 0])[:, None, :]  # (B, 8, 3)
    return verts[:, tri_idx].reshape(-1, 3, 3)


def segments_hit_triangles(starts: np.ndarray, ends: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """(S,) True where the segment starts (S, 3) -> ends (S, 3) crosses any triangle of (T, 3, 3)."""
    return np.isfinite(first_crossings(starts, ends, triangles))


def first_crossings(starts: np.ndarray, ends: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """(S,) where along each segment (0 = start, 1 = end) it first crosses a triangle; inf where never."""
    out = np.full(len(starts), np.inf)
    if not len(starts) or not len(triangles):
        return out
    v0 = triangles[:, 0]
    e1, e2 = triangles[:, 1] - v0, triangles[:, 2] - v0  # (T, 3)
    step = max(1, CHUNK // len(triangles))
    for a in range(0, len(starts), step):
        s, d = starts[a : a + step, None, :], (ends - starts)[a : a + step, None, :]  # (C, 1, 3)
        p = np.cross(d, e2[None])  # (C, T, 3)
        det = (e1[None] * p).sum(-1)
        ok = np.abs(det) > 1e-12
        inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
        tvec = s - v0[None]
        u = (tvec * p).sum(-1) * inv
        q = np.cross(tvec, e1[None])
        v = (d * q).sum(-1) * inv
        t = (e2[None] * q).sum(-1) * inv
        hit = ok & (u >= 0.0) & (v >= 0.0) & (u + v <= 1.0) & (t >= 0.0) & (t <= 1.0)
        out[a : a + step] = np.where(hit, t, np.inf).min(axis=1)
    return out


@dataclass(frozen=True)
class Furniture:
    """Each placed object's name, voxel boxes (broad phase) and triangles (exact), world frame.

    Attributes:
        names: what each object is, in words ("bookshelf").
        boxes: per object (N_i, 2, 3) collision boxes.
        triangles: per object (T_i, 3, 3) drawn triangles.
        walls: per object the wall it hangs on ("" when it stands free; services.render.walls.wall_of).
    """

    names: list[str]
    boxes: list[np.ndarray]
    triangles: list[np.ndarray]
    walls: list[str] = field(default_factory=list)

    @classmethod
    def from_scene(cls, scene: Scene) -> Furniture:
        """The scene's objects (ones the catalog lacks are skipped, as the camera's occluders skip them)."""
        from services.render.walls import wall_of
        from wana.assets.catalog import asset_for, object_to_world, world_collision_boxes

        names, boxes, tris, walls = [], [], [], []
        for p in scene.objects:
            try:
                asset = asset_for(p)
                b = world_collision_boxes(p)
            except KeyError:
                continue
            m = object_to_world(p)
            v = np.asarray(asset.mesh.vertices, dtype=np.float64) @ m[:3, :3].T + m[:3, 3]
            names.append(p.category.replace("_", " "))
            boxes.append(np.asarray(b, dtype=np.float64).reshape(-1, 2, 3))
            tris.append(v[np.asarray(asset.mesh.faces, dtype=np.int64)])
            walls.append(wall_of(p, scene.room))
        return cls(names, boxes, tris, walls)

    @classmethod
    def from_boxes(cls, boxes: Sequence[np.ndarray], names: Sequence[str]) -> Furniture:
        """Objects that are their boxes (solid blocks): tests, and scenes known only by their boxes."""
        groups = [np.asarray(b, dtype=np.float64).reshape(-1, 2, 3) for b in boxes]
        return cls(list(names), groups, [box_triangles(g) for g in groups])

    def first_blocker(
        self, starts: np.ndarray, ends: np.ndarray, points: np.ndarray | None = None
    ) -> np.ndarray:
        """(S,) index of an object the segment passes through (the lowest), -1 where it passes none.

        Args:
            starts, ends: (S, 3) sight lines.
            points: (S, 3) what each line looks at (its end before stopping short). When given, a point
                sunk into an object (inside its collision boxes) is hidden by that object only if the
                line crosses one of its surfaces before the stretch of the object the point is buried
                in (the backrest in front of seated legs), not by the surface it is buried under (feet
                through a sofa's front: no camera could show them, the penetration check reports them).
        """
        out = np.full(len(starts), -1, dtype=np.int64)
        if not self.names or not len(starts):
            return out
        bounds = np.array([[g[:, 0].min(axis=0), g[:, 1].max(axis=0)] for g in self.boxes])
        coarse = segments_hit_boxes(starts, ends, bounds)  # (S, K)
        for k in np.nonzero(coarse.any(axis=0))[0]:
            rows = np.nonzero(coarse[:, k] & (out < 0))[0]
            if not len(rows):
                continue
            t = first_crossings(starts[rows], ends[rows], self.triangles[k])
            hit = np.isfinite(t)
            if points is not None:
                sunk = hit & _inside(points[rows], self.boxes[k])
                if sunk.any():
                    r = np.nonzero(sunk)[0]
                    s0, e0, pt = starts[rows[r]], ends[rows[r]], points[rows[r]]
                    crossing = s0 + (e0 - s0) * t[r, None]  # first surface of the object on the line
                    buried = _buried_length(pt, s0, self.boxes[k])
                    hit[r] = np.linalg.norm(pt - crossing, axis=1) > buried + BURIED_SLACK
            out[rows[hit]] = k
        return out

    def contains(self, points: np.ndarray) -> np.ndarray:
        """(S,) True where a point (S, 3) lies inside an object's collision boxes (sunk into it)."""
        out = np.zeros(len(points), dtype=bool)
        for g in self.boxes:
            out |= _inside(points, g)
        return out


def _buried_length(points: np.ndarray, eyes: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """(S,) metres from each point (S, 3) back toward its eye (S, 3) that stay inside the boxes (B, 2, 3)."""
    d = eyes - points
    d = d / np.maximum(np.linalg.norm(d, axis=1, keepdims=True), 1e-9)
    out = np.full(len(points), BURIED_MAX)
    open_rows = np.ones(len(points), dtype=bool)
    for step in np.arange(BURIED_STEP, BURIED_MAX + 1e-9, BURIED_STEP):
        rows = np.nonzero(open_rows)[0]
        if not len(rows):
            break
        left = ~_inside(points[rows] + d[rows] * step, boxes)
        out[rows[left]] = step
        open_rows[rows[left]] = False
    return out


def _inside(points: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """(S,) True where a point (S, 3) is inside any of the boxes (B, 2, 3)."""
    lo, hi = boxes[:, 0].min(axis=0), boxes[:, 1].max(axis=0)
    out = np.zeros(len(points), dtype=bool)
    rows = np.nonzero(np.all((points >= lo) & (points <= hi), axis=1))[0]
    if len(rows):
        p = points[rows, None, :]
        out[rows] = np.all((p >= boxes[None, :, 0]) & (p <= boxes[None, :, 1]), axis=2).any(axis=1)
    return out
