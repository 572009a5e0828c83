"""Candidate poses of one object, checked in growing batches (the layout search's inner loop).

The layout search takes a member's candidate poses one by one and stops at the first that fits. Most
members fit at their first pose, but a root scanning a crowded floor may try a hundred; checking
each pose alone costs a dozen small numpy calls. Here poses are drawn in batches of 1, 2, 4, ... up
to MAX_BATCH, and the room and collision tests of a batch run as one broadcast (ObstacleIndex); the
search still consumes the poses one at a time, in the same order, with the same verdicts as
``Layout._check`` gives one pose, so the layout it finds is the same. The exact relation predicates
(the slow part) run only for the pose being consumed.

A batch is checked against the placed objects of the moment; the search returns to a member's
poses only with the same objects placed, and a changed set is noticed and the batch checked again.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable, Iterator
from typing import Protocol

import numpy as np

from services.retrieval.collide import ObstacleIndex
from services.retrieval.placement import Candidate, Placed

MAX_BATCH = 32  # poses checked together
ROOM_EPS = 0.01  # metres of tolerance at walls, floor and ceiling (as geometry.inside_room)

Verdict = tuple[str, str | None]  # ("ok" | "room" | "relation" | "collision", the other object id)


class Checks(Protocol):
    """What a batch needs from the layout."""

    @property
    def room_size(self) -> tuple[float, float, float]: ...

    def _supported(self, p: Placed, others: dict[str, Placed]) -> bool: ...
    def _screened(self, p: Placed, others: dict[str, Placed]) -> bool: ...
    def _relations_hold(self, p: Placed, others: dict[str, Placed]) -> bool: ...
    def _obstacles(self, others: dict[str, Placed]) -> ObstacleIndex: ...


def inside_room_many(
    box: np.ndarray, width: float, depth: float, height: float, eps: float = ROOM_EPS
) -> np.ndarray:
    """geometry.inside_room for many (2, 3) AABBs at once.

    Args:
        box: (C, 2, 3) world AABBs.

    Returns:
        (C,) bool, the same answers as inside_room gives each box.
    """
    hw, hd = width / 2.0 + eps, depth / 2.0 + eps
    lo, hi = box[:, 0], box[:, 1]
    return (
        (lo[:, 0] >= -hw)
        & (hi[:, 0] <= hw)
        & (lo[:, 2] >= -hd)
        & (hi[:, 2] <= hd)
        & (lo[:, 1] >= -eps)
        & (hi[:, 1] <= height + eps)
    )


class Trials:
    """Iterate (pose, verdict) over one member's candidate poses.

    Args:
        checks: the layout (its room, support, screen, relation and collision checks).
        candidates: one object's candidate poses, in the order to try them.
        make: builds the Placed of a candidate (position, yaw, support).
        local: the placed objects (the search's dict, read at each batch).
    """

    def __init__(
        self,
        checks: Checks,
        candidates: Iterator[Candidate],
        make: Callable[[np.ndarray, float, str], Placed],
        local: dict[str, Placed],
    ) -> None:
        self.checks = checks
        self.candidates = candidates
        self.make = make
        self.local = local
        self.batch = 1
        self.pending: deque[tuple[Placed, str, str | None]] = deque()
        self.key: tuple[int, ...] = ()

    def __iter__(self) -> Trials:
        return self

    def __next__(self) -> tuple[Placed, Verdict]:
        key = tuple(map(id, self.local.values()))
        if self.pending and key != self.key:  # other objects placed since the batch was checked
            poses = [p for p, _, _ in self.pending]
            self.pending = deque(zip(poses, *zip(*self._screen(poses), strict=True), strict=True))
            self.key = key
        if not self.pending:
            poses = [self.make(*c) for _, c in zip(range(self.batch), self.candidates, strict=False)]
            if not poses:
                raise StopIteration
            self.batch = min(2 * self.batch, MAX_BATCH)
            self.pending.extend(
                (p, why, other) for p, (why, other) in zip(poses, self._screen(poses), strict=True)
            )
            self.key = key
        p, why, other = self.pending.popleft()
        if why == "exact":
            why = "ok" if self.checks._relations_hold(p, self.local) else "relation"
        return p, (why, other)

    def _screen(self, poses: list[Placed]) -> list[Verdict]:
        """Everything of Layout._check but the exact relation predicates ("exact": still to run)."""
        inside = inside_room_many(np.array([p.box for p in poses]), *self.checks.room_size)
        verdicts: list[Verdict | None] = [None] * len(poses)
        open_ = []
        for k, p in enumerate(poses):
            if not inside[k]:
                verdicts[k] = ("room", None)
            elif not self.checks._supported(p, self.local) or not self.checks._screened(p, self.local):
                verdicts[k] = ("relation", None)
            else:
                open_.append(k)
        if open_:
            colliders = self.checks._obstacles(self.local).first_colliders([poses[k] for k in open_])
            for k, other in zip(open_, colliders, strict=True):
                verdicts[k] = ("collision", other) if other is not None else ("exact", None)
        return verdicts  # type: ignore[return-value]
