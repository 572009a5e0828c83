"""Score K layouts whose motions are one base motion translated frame by frame (the anchored surrogate).

The annealing's fast path. ``InteractionScorer.score`` takes K motions and rebuilds, per proposal,
the body's sphere track, the reach table and every object's world-to-object transform. When every
proposal's motion is the same base motion plus a per-frame shift (K, T, 3) (what
``resynthesis.anchored_motion_fn`` makes), almost all of that is the same for all proposals:

* the sphere track, its flags and the reach table (N, O) are computed once, for the base motion;
* the body is taken into each object's (yaw-rotated) frame once; a proposal then only adds one
  rotated offset per frame, ``R(-yaw)·(shift_k(t) − Δposition_k)``, to the base's local centres;
* the broad phase is per pose in the object's frame (the pose's local AABB, shifted, against the
  object's scaled AABB), so whole poses are dropped before any per-sphere work;
* the joint means of eq. 2 are the base's means plus the shift's mean over the action.

The narrow phase is the collider's own (``BodyCollider.local_hits``), so the hits are those of
``InteractionScorer.score`` on the materialised motions (to rounding); no Motion is built per
proposal. Layouts must keep the base scene's yaws (the annealing never changes them).
"""

from __future__ import annotations

import numpy as np

from proto.motion_data import Motion
from services.optimizer.body import motion_joint_positions
from services.optimizer.collisions import _OFFSETS, BodyCollider
from services.optimizer.costs import (
    LayoutBatch,
    collision_cost,
    contact_distances,
    contact_points_world,
    part_table,
    total_cost,
)
from services.optimizer.scoring import InteractionScorer, Scores, action_frames


class ShiftedScorer:
    """Costs of K layouts, the k-th with ``base`` shifted by ``shift[k]`` (T, 3), as one batch."""

    def __init__(self, scorer: InteractionScorer, base: Motion, base_layout: LayoutBatch) -> None:
        """Args:
        scorer: the interaction's scorer (frames, body, tolerances, coarse or exact test).
        base: the base motion.
        base_layout: (1 layout) the scene the base motion was made in; its yaws are fixed.
        """
        self.scorer = scorer
        positions = motion_joint_positions(base)
        self.n_frames = len(positions)
        centres, act, appr, loco, _, _ = scorer._track(base, positions)
        frames, *_ = scorer.frames(base, len(positions))
        self.frames = frames  # (F,)
        s_ = len(scorer.spheres.radius)
        self.group = s_
        f_ = len(frames)
        self.loco = loco  # (N,)
        radius = np.tile(scorer.spheres.radius, f_)  # (N,)
        bones = np.tile(scorer.contact_bones, (f_, 1))  # (N, O)
        target = scorer.is_target[None, :]
        reach = radius[:, None] - scorer.contact_tolerance * (act[:, None] & target)
        reach[(bones & act[:, None]) | (appr[:, None] & target)] = 0.0
        self.reach = reach  # (N, O)
        self.yaw = base_layout.yaw[0].copy()  # (O,)
        self.pos0 = base_layout.position[0].copy()  # (O, 3)
        geom = scorer.geom
        collider = scorer.collider
        rots: list[np.ndarray] = []  # per reachable object (3, 3) world -> object rotation R_y(-yaw)
        local: list[np.ndarray] = []  # per reachable object (F, S, 3) base centres in its frame
        pose_lo: list[np.ndarray] = []  # per reachable object (F, G, 3) part bounds
        pose_hi: list[np.ndarray] = []
        reachable: list[int] = []  # the objects the body can reach at all
        c3 = centres.reshape(f_, s_, 3)
        self.part_table, self.part_valid = part_table(
            scorer.spheres.part.astype(np.int64).tobytes()
        )  # (G, W)
        for o in range(len(geom.ids)):
            r_o = reach[:, o].reshape(f_, s_)
            if geom.boxes_per_object[o] == 0 or not (r_o > 0).any():
                continue
            c, s = np.cos(self.yaw[o]), np.sin(self.yaw[o])
            rot = np.array([[c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c]])
            q = (c3 - self.pos0[o]) @ rot.T  # (F, S, 3)
            live = (r_o > 0)[..., None]
            # Bounds of each body part's live spheres per pose, (F, G, 3) (padding repeats a member).
            pose_lo.append(np.where(live, q - r_o[..., None], np.inf)[:, self.part_table].min(axis=2))
            pose_hi.append(np.where(live, q + r_o[..., None], -np.inf)[:, self.part_table].max(axis=2))
            reachable.append(o)
            rots.append(rot)
            local.append(q)
        # Stacked, for one broad phase over all reachable objects at once.
        self.active = np.array(reachable, dtype=np.int64)
        n_parts = self.part_table.shape[0]
        self.q_all = np.stack(local) if local else np.zeros((0, f_, s_, 3))
        self.lo_all = np.stack(pose_lo) if local else np.zeros((0, f_, n_parts, 3))
        self.hi_all = np.stack(pose_hi) if local else np.zeros((0, f_, n_parts, 3))
        self.rot_all = np.stack(rots) if local else np.zeros((0, 3, 3))
        self.obj_lo = np.array([collider.bounds[o][0] for o in reachable]).reshape(-1, 3)
        self.obj_hi = np.array([collider.bounds[o][1] for o in reachable]).reshape(-1, 3)
        self.reach_act = reach[:, reachable]  # (N, O')
        self.cells = _CellTable(collider, reachable)
        # Eq. 2's joint means of the base motion, and the action frames the shift is averaged over.
        self.a0, self.a1 = action_frames(base, scorer.interaction, len(positions))
        window = positions[self.a0 : self.a1]
        self.joint_mean0 = window[:, scorer.joint_idx].mean(axis=0)  # (P, 3)
        self.root_mean0 = window[:, scorer.ik_root].mean(axis=0)  # (P, 3)

    def score(self, layout: LayoutBatch, shift: np.ndarray) -> Scores:
        """Costs of K layouts.

        Args:
            layout: K layouts of the scorer's objects, with the base layout's yaws.
            shift: (K, T, 3) per-frame translation of the base motion in each layout, metres.

        Returns:
            The Scores (as InteractionScorer.score's).
        """
        sc_ = self.scorer
        k_ = layout.position.shape[0]
        if shift.shape != (k_, self.n_frames, 3):
            raise ValueError(f"shift must be ({k_}, {self.n_frames}, 3), got {shift.shape}")
        if (layout.yaw != self.yaw[None]).any():
            raise ValueError("ShiftedScorer layouts must keep the base layout's yaws")
        geom = sc_.geom
        fs = shift[:, self.frames]  # (K, F, 3)
        box_hit = np.zeros((k_, len(geom.box_owner)), dtype=bool)
        loco_hit = np.zeros_like(box_hit)
        scale = np.abs(layout.scale)
        if len(self.active):
            self._hits(layout, fs, scale, box_hit, loco_hit)
        c_d = collision_cost(box_hit, geom)
        if len(sc_.pairs):
            mean_shift = shift[:, self.a0 : self.a1].mean(axis=1)  # (K, 3)
            points = contact_points_world(geom, layout, sc_.contact_idx)
            dist = contact_distances(points, self.joint_mean0[None] + mean_shift[:, None])
            if sc_.ik_mask.any():
                root_mean = self.root_mean0[None] + mean_shift[:, None]
                over = np.maximum(np.linalg.norm(points - root_mean, axis=-1) - sc_.ik_len[None], 0.0)
                dist = np.where(sc_.ik_mask[None], over, dist)
            c_t = dist.mean(axis=1)
        else:
            dist, c_t = np.zeros((k_, 0)), np.zeros(k_)
        return Scores(total_cost(c_d, c_t, sc_.lambda_d, sc_.lambda_t), c_d, c_t, dist, box_hit, loco_hit)

    def _hits(
        self,
        layout: LayoutBatch,
        fs: np.ndarray,
        scale: np.ndarray,
        box_hit: np.ndarray,
        loco_hit: np.ndarray,
    ) -> None:
        """Mark (K, B) box hits (and walking hits, for the exact test) of all reachable objects."""
        sc_ = self.scorer
        k_, s_, act = fs.shape[0], self.group, self.active
        sc = scale[:, act]  # (K, O', 3)
        lo_s, hi_s = self.obj_lo[None] * sc, self.obj_hi[None] * sc  # (K, O', 3)
        # Per-frame offset of the body in each object's frame: R(-yaw)(shift - Δposition).
        rel = fs[:, None] - (layout.position[:, act] - self.pos0[act][None])[:, :, None]  # (K, O', F, 3)
        e = np.einsum("kofj,oij->kofi", rel, self.rot_all)
        # Broad phase per pose and body part: its local AABB, shifted, against the object's.
        el = e[:, :, :, None]
        both = (self.lo_all[None] + el <= hi_s[:, :, None, None]) & (
            self.hi_all[None] + el >= lo_s[:, :, None, None]
        )
        near = both[..., 0] & both[..., 1] & both[..., 2]  # (K, O', F, G); cheaper than all(axis=-1)
        kf, oi, ff, gg = np.nonzero(near)
        if len(kf) == 0:
            return
        members = self.part_table[gg]  # (P, W)
        valid = self.part_valid[gg]
        p = (self.q_all[oi[:, None], ff[:, None], members] + e[kf, oi, ff][:, None, :])[valid]  # (M, 3)
        kk = np.broadcast_to(kf[:, None], members.shape)[valid]
        oo = np.broadcast_to(oi[:, None], members.shape)[valid]
        nn = (ff[:, None] * s_ + members)[valid]
        rr = self.reach_act[nn, oo]
        inside = (p + rr[:, None] >= lo_s[kk, oo]) & (p - rr[:, None] <= hi_s[kk, oo])
        keep = (rr > 0) & inside[:, 0] & inside[:, 1] & inside[:, 2]
        kk, oo, nn, p, rr = kk[keep], oo[keep], nn[keep], p[keep], rr[keep]
        if len(kk) == 0:
            return
        scm = sc[kk, oo]  # (M, 3)
        if sc_.coarse and self.cells.all_grids:
            hk, hb = self.cells.coarse(oo, kk, p, rr, scm)
            box_hit[hk, hb] = True
            return
        for i in np.unique(oo):
            mine = oo == i
            ks, b = sc_.collider.local_hits(
                int(act[i]), kk[mine], nn[mine], p[mine], rr[mine], scm[mine], k_, sc_.coarse
            )
            box_hit[ks[:, 0], b] = True
            if not sc_.coarse:
                lh = self.loco[ks[:, 1]]
                loco_hit[ks[lh, 0], b[lh]] = True


class _CellTable:
    """The voxel grids of several objects as one neighbourhood table, for a coarse test of all at once.

    For every cell of each object's grid padded by 2 cells, and for a reach of 1 and of 2 cells, the
    occupied cells (as global box indices) within that Chebyshev distance, in CSR form: a coarse
    query is then one lookup per distinct (layout, centre cell, reach), with no per-sphere
    neighbourhood enumeration. Same hits as BodyCollider's coarse test.
    """

    PAD = 2

    def __init__(self, collider: BodyCollider, objects: list[int]) -> None:
        grids = [collider.grids[o] for o in objects]
        self.all_grids = bool(objects) and all(g is not None for g in grids)
        if not self.all_grids:
            return
        pad = self.PAD
        self.origin = np.array([g.origin for g in grids])  # type: ignore[union-attr]  # (O', 3)
        self.size = np.array([g.size for g in grids])  # type: ignore[union-attr]
        self.pdims = np.array([g.dims for g in grids], dtype=np.int64) + 2 * pad  # type: ignore[union-attr]
        counts = self.pdims.prod(axis=1)
        self.base = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.int64)
        n_keys = int(counts.sum()) * 2
        keys, boxes = [], []
        for g, o, b0, pd in zip(grids, objects, self.base, self.pdims, strict=True):
            occ = np.argwhere(g.cell_box >= 0)  # type: ignore[union-attr]  # (C, 3)
            box = g.cell_box[tuple(occ.T)] + collider.box_start[o]  # type: ignore[union-attr]
            for reach in (1, 2):
                # A centre cell c sees occupied cell x when |c - x| <= reach: c = x - offset.
                centre = (occ[:, None, :] - _OFFSETS[reach][None] + pad).reshape(-1, 3)
                flat = b0 + (centre[:, 0] * pd[1] + centre[:, 1]) * pd[2] + centre[:, 2]
                keys.append(flat * 2 + (reach - 1))
                boxes.append(np.repeat(box, len(_OFFSETS[reach])))
        key = np.concatenate(keys)
        order = np.argsort(key, kind="stable")
        self.boxes = np.concatenate(boxes)[order]
        self.indptr = np.concatenate([[0], np.cumsum(np.bincount(key, minlength=n_keys))]).astype(np.int64)
        self.n_keys = n_keys

    def coarse(
        self, oo: np.ndarray, kk: np.ndarray, p: np.ndarray, rr: np.ndarray, sc: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """BodyCollider's coarse test (cells within ceil(r / cell), at most 2, of the centre cell) for
        spheres of several objects: (M,) object (index into the table), layout, (M, 3) centre in the
        object's scaled frame, reach, scale -> (H,) layout and (H,) global box index."""
        size, pd = self.size[oo], self.pdims[oo]
        g = np.floor((p / sc - self.origin[oo]) / size).astype(np.int64) + self.PAD  # (M, 3)
        cells = np.minimum(np.ceil(rr / (size * sc).min(axis=1)).astype(np.int64), 2)
        ok = (
            (g[:, 0] >= 0)
            & (g[:, 0] < pd[:, 0])
            & (g[:, 1] >= 0)
            & (g[:, 1] < pd[:, 1])
            & (g[:, 2] >= 0)
            & (g[:, 2] < pd[:, 2])
        )
        flat = self.base[oo] + (g[:, 0] * pd[:, 1] + g[:, 1]) * pd[:, 2] + g[:, 2]
        # Distinct (layout, centre cell, reach) first: the poses of a motion overlap a lot.
        uniq = np.unique(kk[ok] * self.n_keys + flat[ok] * 2 + (cells[ok] - 1))
        k, key = np.divmod(uniq, self.n_keys)
        start, count = self.indptr[key], self.indptr[key + 1] - self.indptr[key]
        total = int(count.sum())
        offs = np.arange(total) - np.repeat(np.cumsum(count) - count, count)
        return np.repeat(k, count), self.boxes[np.repeat(start, count) + offs]
