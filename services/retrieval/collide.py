"""Which placed object a candidate pose runs into: a broad phase over every placed object at once,
then one broadcast box test over the collision boxes of the objects near it.

The layout asks this for every candidate pose it tries (hundreds per room) while the set of placed
objects changes only when a pose is kept or a search backs up, so the placed objects are indexed
once per set (their AABBs as arrays, their supports, the concatenated boxes of each group of near
objects) and reused across the candidates.

    index = ObstacleIndex(list(placed.values()))
    index.first_collider(candidate)  # -> "desk", or None
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Sequence

import numpy as np

from services.retrieval.geometry import OVERLAP_EPS, SITTER_Y_M, first_overlapping
from services.retrieval.placement import Placed

HIPS_BELOW_M = 0.15  # metres below a seat slot's hips point that a sitter's hips and thighs take
NEAR_GROUPS_KEPT = 256  # concatenated box sets kept per index (distinct groups of near objects)


class ObstacleIndex:
    """Placed objects, in placement order, indexed for collision queries.

    Attributes:
        objects: the placed objects (K).
        lower: (K, 3) world AABB minima.
        upper_less_eps: (K, 3) world AABB maxima minus OVERLAP_EPS.
    """

    def __init__(self, objects: Sequence[Placed]) -> None:
        self.objects = list(objects)
        boxes = np.array([q.box for q in self.objects]).reshape(-1, 2, 3)  # (K, 2, 3)
        self.lower = boxes[:, 0]
        self.upper_less_eps = boxes[:, 1] - OVERLAP_EPS
        self._index = {q.id: k for k, q in enumerate(self.objects)}
        self._resting_on: dict[str, list[int]] = {}
        for k, q in enumerate(self.objects):
            if q.support:
                self._resting_on.setdefault(q.support, []).append(k)
        self._groups: OrderedDict[bytes, tuple[np.ndarray, np.ndarray | None]] = OrderedDict()
        self._all: tuple[np.ndarray, np.ndarray] | None = None

    def near(self, p: Placed) -> np.ndarray:
        """Indices (ascending) of the objects whose AABBs interpenetrate p's by more than OVERLAP_EPS,
        what p rests on and what rests on p aside."""
        box = p.box
        inside = (box[0] < self.upper_less_eps) & (self.lower < box[1] - OVERLAP_EPS)  # (K, 3)
        near = inside[:, 0] & inside[:, 1] & inside[:, 2]
        k = self._index.get(p.support)
        if k is not None:
            near[k] = False
        for k in self._resting_on.get(p.id, ()):
            near[k] = False
        (found,) = np.nonzero(near)
        return found

    def on_a_sitter(self, p: Placed) -> bool:
        """Whether p rests where someone would sit on a seat of one slot (a box of chocolates in the middle of
        the bench); on a sofa the cushions go where they will and the sitters take the free slots."""
        k = self._index.get(p.support)
        if k is None:
            return False
        seat = self.objects[k]
        if seat.fp.sitters != 1:
            return False
        sitters = seat.boxes[-seat.fp.sitters :].copy()
        sitters[:, 0, 1] -= SITTER_Y_M[0] + HIPS_BELOW_M  # down to the seat: where the hips and thighs go
        return first_overlapping(p.boxes, sitters) >= 0

    def first_collider(self, p: Placed) -> str | None:
        """The first placed object (in placement order) whose collision boxes p's interpenetrate by
        more than OVERLAP_EPS, what p rests on and what rests on p aside (but for the sitter boxes of
        the seat p rests on); None when there is none."""
        if not self.objects:
            return None
        if self.on_a_sitter(p):
            return p.support
        near = self.near(p)
        if len(near) == 0:
            return None
        boxes, owner = self._group(near)
        k = first_overlapping(p.boxes, boxes, owner)
        return None if k < 0 else self.objects[int(near[0]) if owner is None else k].id

    def first_colliders(self, poses: Sequence[Placed]) -> list[str | None]:
        """``[self.first_collider(p) for p in poses]`` in one broadcast test, for poses of one object.

        Args:
            poses: candidate poses of one object (one footprint, so each has the same N boxes).

        Returns:
            Per pose, the id of the first placed object it runs into, or None.
        """
        out: list[str | None] = [None] * len(poses)
        if not self.objects or not poses:
            return out
        sitting = [c for c, p in enumerate(poses) if self.on_a_sitter(p)]
        if sitting:  # rare (a prop on a bench): those poses one by one, the others as one batch
            rest = [c for c in range(len(poses)) if c not in set(sitting)]
            found = self.first_colliders([poses[c] for c in rest])
            for c in sitting:
                out[c] = poses[c].support
            for c, f in zip(rest, found, strict=True):
                out[c] = f
            return out
        box = np.array([p.box for p in poses])  # (C, 2, 3)
        inside = (box[:, None, 0] < self.upper_less_eps[None]) & (
            self.lower[None] < (box[:, 1] - OVERLAP_EPS)[:, None]
        )  # (C, K, 3)
        near = inside[..., 0] & inside[..., 1] & inside[..., 2]  # (C, K)
        resting = self._resting_on.get(poses[0].id, ())
        for c, p in enumerate(poses):
            k = self._index.get(p.support)
            if k is not None:
                near[c, k] = False
            for k in resting:
                near[c, k] = False
        (rows,) = np.nonzero(near.any(axis=1))
        if len(rows) == 0:
            return out
        near = near[rows]  # (C', K)
        all_boxes, all_owner = self._all_boxes()
        near_any: np.ndarray = np.any(near, axis=0)  # (K,)
        (cols,) = np.nonzero(near_any[all_owner])  # boxes of objects near any pose
        theirs, owner = all_boxes[cols], all_owner[cols]  # (M', 2, 3), (M',)
        mine = np.stack([poses[int(c)].boxes for c in rows])  # (C', N, 2, 3)
        sep = (mine[:, :, None, 0] >= theirs[None, None, :, 1] - OVERLAP_EPS) | (
            theirs[None, None, :, 0] >= mine[:, :, None, 1] - OVERLAP_EPS
        )  # (C', N, M', 3)
        touching = ~(sep[..., 0] | sep[..., 1] | sep[..., 2])  # (C', N, M')
        hit = touching.any(axis=1) & near[:, owner]  # (C', M')
        first = np.where(hit, owner[None, :], len(self.objects)).min(axis=1, initial=len(self.objects))
        for c, k in zip(rows.tolist(), first.tolist(), strict=True):
            if k < len(self.objects):
                out[c] = self.objects[k].id
        return out

    def _all_boxes(self) -> tuple[np.ndarray, np.ndarray]:
        """Every placed object's world boxes, concatenated (M, 2, 3), and each box's owner (M,)."""
        if self._all is None:
            parts = [q.boxes for q in self.objects]
            self._all = (
                np.concatenate(parts).reshape(-1, 2, 3),
                np.repeat(np.arange(len(parts)), [len(b) for b in parts]),
            )
        return self._all

    def _group(self, near: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
        """The concatenated world boxes of the near objects and the owner of each box."""
        key = near.tobytes()
        found = self._groups.get(key)
        if found is not None:
            self._groups.move_to_end(key)
            return found
        if len(near) == 1:
            found = (self.objects[int(near[0])].boxes, None)
        else:
            parts = [self.objects[int(k)].boxes for k in near]
            found = (np.concatenate(parts), np.repeat(near, [len(b) for b in parts]))
        self._groups[key] = found
        if len(self._groups) > NEAR_GROUPS_KEPT:
            self._groups.popitem(last=False)
        return found
