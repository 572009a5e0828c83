"""Which collision boxes the body's spheres hit, for K layouts at once, without scanning every box.

Catalog objects are voxelised: their boxes are the occupied cells of one regular grid in the object
frame. For such an object a sphere, taken into the object's (scaled) grid frame, can only touch the
few cells its bounding cube spans, so the exact sphere-box test runs on those cells alone: the cost
follows the number of spheres near the object, not the number of boxes (a desk has ~450). Objects
whose boxes are not one grid (imported ones) take the generic path: every near sphere against every
box of the object. Everything is vectorised over layouts and spheres; the loop is over objects.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from services.optimizer.costs import LayoutBatch, SceneGeometry

# Cell offsets within 1 and 2 cells (Chebyshev) of a centre cell.
_OFFSETS = {
    n: np.array([(i, j, k) for i in range(-n, n + 1) for j in range(-n, n + 1) for k in range(-n, n + 1)])
    for n in (1, 2)
}


@dataclass(frozen=True)
class VoxelGrid:
    """Boxes of one object as cells of a regular grid (object frame, before scale).

    Attributes:
        origin: (3,) min corner of cell (0, 0, 0).
        size: (3,) cell edge lengths.
        dims: (3,) cells per axis.
        cell_box: (dims) index of the object's box occupying each cell, -1 where empty.
    """

    origin: np.ndarray
    size: np.ndarray
    dims: np.ndarray
    cell_box: np.ndarray


def voxel_grid(lo: np.ndarray, hi: np.ndarray) -> VoxelGrid | None:
    """The grid the boxes (B, 3) min / (B, 3) max corners are cells of, or None when they are not one."""
    if len(lo) == 0:
        return None
    size = hi[0] - lo[0]
    if np.any(size <= 0) or not np.allclose(hi - lo, size, rtol=0, atol=1e-6):
        return None
    origin = lo.min(axis=0)
    idx = np.rint((lo - origin) / size).astype(np.int64)
    if not np.allclose(origin + idx * size, lo, rtol=0, atol=1e-5):
        return None
    dims = idx.max(axis=0) + 1
    if int(np.prod(dims)) > 4_000_000:
        return None
    cell_box = np.full(tuple(dims), -1, dtype=np.int64)
    cell_box[idx[:, 0], idx[:, 1], idx[:, 2]] = np.arange(len(lo))
    if (cell_box >= 0).sum() != len(lo):  # two boxes in one cell: not a voxel grid
        return None
    return VoxelGrid(origin, size, dims, cell_box)


class BodyCollider:
    """Per-object grids of a scene's boxes, built once per scene geometry."""

    def __init__(self, geom: SceneGeometry) -> None:
        self.geom = geom
        self.box_start = np.concatenate([[0], np.cumsum(geom.boxes_per_object)[:-1]]).astype(np.int64)
        self.local_lo = geom.box_centre - geom.box_half
        self.local_hi = geom.box_centre + geom.box_half
        self.grids: list[VoxelGrid | None] = []
        self.bounds: list[tuple[np.ndarray, np.ndarray]] = []
        for o in range(len(geom.ids)):
            sl = slice(self.box_start[o], self.box_start[o] + geom.boxes_per_object[o])
            lo, hi = self.local_lo[sl], self.local_hi[sl]
            self.grids.append(voxel_grid(lo, hi))
            self.bounds.append(
                (lo.min(axis=0) if len(lo) else np.zeros(3), hi.max(axis=0) if len(hi) else np.zeros(3))
            )

    def hits(
        self,
        centres: np.ndarray,
        reach: np.ndarray,
        layout: LayoutBatch,
        coarse: bool = False,
        group: int = 0,
        pose_bounds: tuple[np.ndarray, np.ndarray] | None = None,
    ) -> list[tuple[np.ndarray, np.ndarray]]:
        """Sphere/box hits for every object.

        Args:
            centres: (K, N, 3) sphere centres, world, per layout.
            reach: (K, N, O) sphere radius minus the tolerance towards each object; <= 0 never hits.
            layout: the K layouts.
            coarse: for voxel objects, mark the cells within ceil(radius / cell) of each sphere's
                centre cell instead of testing each sphere against each cell exactly: conservative
                (never misses a hit), several times faster, used to rank proposals; reports are exact.
            group: spheres come in consecutive groups of this size (one body pose each); groups
                whose bounding box misses an object are dropped before any per-sphere work. 0 = none.
            pose_bounds: (K, F, 3) min and max corners of each group's spheres (radius included), if
                known; computed here otherwise.

        Returns:
            per object: (hit_k (H,), hit_sphere (H,), hit_box (H,) global box index) stacked as
            ((H,) k, (H,) sphere) and (H,) box, one entry per sphere/box pair that touches.
        """
        k_, n_ = centres.shape[:2]
        if group and n_ % group == 0 and pose_bounds is None:
            cg = centres.reshape(k_, -1, group, 3)
            rg = reach.max(axis=-1).reshape(k_, -1, group)[..., None]
            pose_bounds = ((cg - rg).min(axis=2), (cg + rg).max(axis=2))
        out = []
        for o in range(len(self.geom.ids)):
            out.append(self._object_hits(o, centres, reach[..., o], layout, coarse, group, pose_bounds))
        return out

    def _object_hits(
        self,
        o: int,
        centres: np.ndarray,
        reach: np.ndarray,
        layout: LayoutBatch,
        coarse: bool = False,
        group: int = 0,
        pose_bounds: tuple[np.ndarray, np.ndarray] | None = None,
    ) -> tuple[np.ndarray, np.ndarray]:
        empty = (np.zeros((0, 2), np.int64), np.zeros(0, np.int64))
        if self.geom.boxes_per_object[o] == 0:
            return empty
        k_, n_ = reach.shape
        pos, yaw, scale = (
            layout.position[:, o],
            layout.yaw[:, o],
            np.abs(layout.scale[:, o]),
        )  # (K, 3), (K,), (K, 3)
        lo, hi = self.bounds[o]
        lo_s, hi_s = lo[None] * scale, hi[None] * scale  # (K, 3) object frame, scaled
        c, s = np.cos(yaw), np.sin(yaw)
        if group and pose_bounds is not None:
            # Pose-level broad phase: the world AABB of the object against each pose's sphere AABB.
            ctr, half = (lo_s + hi_s) / 2, (hi_s - lo_s) / 2
            w_ctr = (
                np.stack([c * ctr[:, 0] + s * ctr[:, 2], ctr[:, 1], -s * ctr[:, 0] + c * ctr[:, 2]], 1) + pos
            )
            w_half = np.stack(
                [
                    np.abs(c) * half[:, 0] + np.abs(s) * half[:, 2],
                    half[:, 1],
                    np.abs(s) * half[:, 0] + np.abs(c) * half[:, 2],
                ],
                1,
            )
            g_lo, g_hi = pose_bounds  # (K, F, 3)
            pose_near = np.all(
                (g_lo <= (w_ctr + w_half)[:, None]) & (g_hi >= (w_ctr - w_half)[:, None]), axis=-1
            )
            kf, ff = np.nonzero(pose_near)
            if len(kf) == 0:
                return empty
            kk = np.repeat(kf, group)
            nn = (ff[:, None] * group + np.arange(group)[None]).ravel()
        else:
            kk, nn = np.nonzero(reach > 0)
        d = centres[kk, nn] - pos[kk]
        cs, sn = c[kk], s[kk]
        # World -> object frame (scaled): R_y(-yaw).
        p = np.stack([cs * d[:, 0] - sn * d[:, 2], d[:, 1], sn * d[:, 0] + cs * d[:, 2]], axis=-1)  # (M, 3)
        rr = reach[kk, nn]
        near = (rr > 0) & np.all((p + rr[:, None] >= lo_s[kk]) & (p - rr[:, None] <= hi_s[kk]), axis=-1)
        kk, nn, p, rr = kk[near], nn[near], p[near], rr[near]
        if len(kk) == 0:
            return empty
        return self.local_hits(o, kk, nn, p, rr, scale[kk], k_, coarse)

    def local_hits(
        self,
        o: int,
        kk: np.ndarray,
        nn: np.ndarray,
        p: np.ndarray,
        rr: np.ndarray,
        sc: np.ndarray,
        k_: int,
        coarse: bool = False,
    ) -> tuple[np.ndarray, np.ndarray]:
        """Narrow phase of object ``o`` for spheres already in its frame (after the broad phase).

        Args:
            o: object index.
            kk: (M,) layout of each sphere.
            nn: (M,) sphere index (within its layout's list).
            p: (M, 3) sphere centres in the object's frame, scaled (rotated and translated, not
                divided by the scale), metres.
            rr: (M,) reach of each sphere (> 0).
            sc: (M, 3) the object's scale in each sphere's layout.
            k_: number of layouts.
            coarse: cell-level test (see ``hits``).

        Returns:
            ((H, 2) layout and sphere index, (H,) global box index) of the touching pairs.
        """
        empty = (np.zeros((0, 2), np.int64), np.zeros(0, np.int64))
        if len(kk) == 0 or self.geom.boxes_per_object[o] == 0:
            return empty
        grid = self.grids[o]
        start = self.box_start[o]
        if grid is None:  # generic: every box of the object
            sl = slice(start, start + self.geom.boxes_per_object[o])
            blo, bhi = self.local_lo[sl], self.local_hi[sl]  # (B, 3)
            q = np.maximum(blo[None] * sc[:, None] - p[:, None], 0) + np.maximum(
                p[:, None] - bhi[None] * sc[:, None], 0
            )
            touch = np.einsum("mbi,mbi->mb", q, q) < (rr * rr)[:, None]
            m, b = np.nonzero(touch)
            return np.stack([kk[m], nn[m]], axis=1), start + b
        if coarse:
            return self._coarse_hits(grid, start, kk, nn, p, rr, sc, k_)
        size_s = grid.size[None] * sc  # (M, 3) scaled cell size
        origin_s = grid.origin[None] * sc
        first = np.floor((p - rr[:, None] - origin_s) / size_s).astype(np.int64)
        last = np.floor((p + rr[:, None] - origin_s) / size_s).astype(np.int64)
        first = np.maximum(first, 0)
        last = np.minimum(last, grid.dims[None] - 1)
        ext = last - first + 1  # (M, 3)
        ok = np.all(ext > 0, axis=1)
        if not ok.all():
            p, rr, sc, first, ext, size_s, origin_s = (
                p[ok],
                rr[ok],
                sc[ok],
                first[ok],
                ext[ok],
                size_s[ok],
                origin_s[ok],
            )
            kk, nn = kk[ok], nn[ok]
        if len(p) == 0:
            return empty
        # Enumerate each sphere's own window of cells (ragged), not a common worst-case window.
        counts = ext.prod(axis=1)
        m = np.repeat(np.arange(len(p)), counts)
        j = np.arange(int(counts.sum())) - np.repeat(np.cumsum(counts) - counts, counts)
        e = ext[m]
        cell = first[m] + np.stack([j // (e[:, 1] * e[:, 2]), (j // e[:, 2]) % e[:, 1], j % e[:, 2]], axis=1)
        box = grid.cell_box[cell[:, 0], cell[:, 1], cell[:, 2]]
        filled = box >= 0
        m, cell, box = m[filled], cell[filled], box[filled]
        cmin = origin_s[m] + cell * size_s[m]
        q = np.maximum(cmin - p[m], 0) + np.maximum(p[m] - (cmin + size_s[m]), 0)
        touch = np.einsum("pi,pi->p", q, q) < rr[m] ** 2
        m, box = m[touch], box[touch]
        return np.stack([kk[m], nn[m]], axis=1), start + box

    @staticmethod
    def _coarse_hits(
        grid: VoxelGrid,
        start: int,
        kk: np.ndarray,
        nn: np.ndarray,
        p: np.ndarray,
        rr: np.ndarray,
        sc: np.ndarray,
        k_: int,
    ) -> tuple[np.ndarray, np.ndarray]:
        """Cell-level hits, conservative: a sphere marks every cell within ceil(r / cell) cells of its centre cell.

        Never misses a hit of the exact test (so a layout the search finds collision-free is), and
        overcounts only around the sphere's corners.
        """
        g = np.floor((p / sc - grid.origin) / grid.size).astype(np.int64)  # (M, 3) centre cells
        cells = np.minimum(np.ceil(rr / (grid.size * sc).min(axis=1)).astype(np.int64), 2)
        flat_box = grid.cell_box.ravel()
        ks, boxes = [], []
        for reach_cells in (1, 2):
            sel = cells == reach_cells
            if not sel.any():
                continue
            # Each sphere's neighbourhood, sparse: only cells inside the grid and occupied count.
            nb = g[sel][:, None, :] + _OFFSETS[reach_cells][None]  # (M', W, 3)
            inside = np.all((nb >= 0) & (nb < grid.dims), axis=-1)
            m, w = np.nonzero(inside)
            cell = nb[m, w]
            box = flat_box[(cell[:, 0] * grid.dims[1] + cell[:, 1]) * grid.dims[2] + cell[:, 2]]
            filled = box >= 0
            ks.append(kk[sel][m[filled]])
            boxes.append(box[filled])
        if not ks:
            return np.zeros((0, 2), np.int64), np.zeros(0, np.int64)
        hk = np.concatenate(ks)
        # One representative sphere index per hit (only the layout matters for the counts).
        return np.stack([hk, np.zeros_like(hk)], axis=1), start + np.concatenate(boxes)
