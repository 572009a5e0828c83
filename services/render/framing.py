"""Keep the character in sight: test camera rays against the scene's boxes and move the camera until clear.

A commanded camera (left of Tom, behind Eve) is a wish; a tall cabinet between it and the character
makes it useless. Here the scene's world collision boxes (wana.assets.catalog.world_collision_boxes)
become occluders; a camera sees a character when the segments from the eye to the head, chest and hips
pass through no box. When the commanded pose is blocked, the camera tries, in order of preference,
moving along the arc around the character, rising, and coming closer (ADJUSTMENTS), and takes the
first clear one (the least blocked one when none is). A pose is clear only when nothing stands close in
front of the lens either: a fan of rays across the frame (NEAR_FAN), each as long as NEAR_SHARE of the
distance to the character, must hit no box — a cabinet beside the eye would otherwise fill a third of
the picture while the character stays in sight.

    occluders = Occluders.from_scene(scene)
    share = occluders.blocked_share(eye, points)  # 0.0 = every point visible

Everything here is a pure function of its inputs, so frames rendered apart agree.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from proto.scene import Scene

STOP_SHORT = 0.25  # metres a sight line stops before its point (a seat under the hips does not hide them)
HIPS_TO_CHEST = 0.35  # metres from the hips joint up to the chest
MAX_MOVE = 1.6  # metres the eye may move from one decision to the next when it has a choice
NEAR_SHARE = 0.4  # the fan's rays reach this share of the way from the eye to the target
NEAR_TOLERANCE = 1  # fan rays per view that may hit before a pose counts as blocked
# (horizontal, vertical) radians off the view axis: the frame's corners and edge midpoints, a little inside
NEAR_FAN = tuple((h, v) for v in (-0.3, 0.0, 0.3) for h in (-0.4, 0.0, 0.4) if (h, v) != (0.0, 0.0))


@dataclass(frozen=True)
class Adjust:
    """A change of a camera pose about its target: turn along the arc, rise, come closer."""

    turn: float = 0.0  # radians about +Y around the target
    rise: float = 0.0  # metres added to the eye height
    scale: float = 1.0  # factor on the horizontal eye-target distance


def _adjustments() -> tuple[Adjust, ...]:
    deg = math.radians
    out = [Adjust()]
    out += [Adjust(turn=s * deg(a)) for a in (20, 40) for s in (1, -1)]
    out += [
        Adjust(turn=s * deg(a), rise=r)
        for r in (0.7, 1.4)
        for a in (0, 20, 40)
        for s in ((1,) if a == 0 else (1, -1))
    ]
    out += [
        Adjust(turn=s * deg(a), scale=k)
        for k in (0.7, 0.5)
        for a in (0, 25)
        for s in ((1,) if a == 0 else (1, -1))
    ]
    out += [Adjust(turn=s * deg(a), rise=r) for a in (65, 90) for r in (0.0, 0.8) for s in (1, -1)]
    out += [
        Adjust(turn=s * deg(a), rise=1.0, scale=0.6)
        for a in (0, 45, 90, 135)
        for s in ((1,) if a == 0 else (1, -1))
    ]
    return tuple(out)


ADJUSTMENTS = _adjustments()  # preference order: the commanded pose first


def adjust_eye(eye: np.ndarray, target: np.ndarray, adj: Adjust) -> np.ndarray:
    """The eye (3,) moved by an adjustment about the target (3,)."""
    v = eye - target
    c, s = math.cos(adj.turn), math.sin(adj.turn)
    x = (c * v[0] + s * v[2]) * adj.scale
    z = (-s * v[0] + c * v[2]) * adj.scale
    return np.array([target[0] + x, eye[1] + adj.rise, target[2] + z])


def blend_adjust(a: Adjust, b: Adjust, s: float) -> Adjust:
    """Interpolate two adjustments (s = 0: a, s = 1: b)."""
    return Adjust(
        turn=a.turn + (b.turn - a.turn) * s,
        rise=a.rise + (b.rise - a.rise) * s,
        scale=a.scale + (b.scale - a.scale) * s,
    )


def segments_hit_boxes(starts: np.ndarray, ends: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """Slab test of segments against axis-aligned boxes.

    Args:
        starts, ends: (S, 3) segment end points.
        boxes: (B, 2, 3) min/max corners, the same for every segment; or (S, B, 2, 3), each segment's own.

    Returns:
        (S, B) bool, True where the segment passes through the box.
    """
    per = boxes if boxes.ndim == 4 else boxes[None]  # (S or 1, B, 2, 3)
    d = ends - starts  # (S, 3)
    safe = np.where(np.abs(d) < 1e-12, 1e-12, d)
    inv = 1.0 / safe
    t0 = (per[:, :, 0, :] - starts[:, None, :]) * inv[:, None, :]  # (S, B, 3)
    t1 = (per[:, :, 1, :] - starts[:, None, :]) * inv[:, None, :]
    lo = np.minimum(t0, t1)
    hi = np.maximum(t0, t1)
    # A segment parallel to a slab is inside it or misses the box.
    parallel = np.abs(d) < 1e-12
    inside = (starts[:, None, :] >= per[:, :, 0, :]) & (starts[:, None, :] <= per[:, :, 1, :])
    lo = np.where(parallel[:, None, :], np.where(inside, -np.inf, np.inf), lo)
    hi = np.where(parallel[:, None, :], np.where(inside, np.inf, -np.inf), hi)
    enter = np.maximum(lo.max(axis=2), 0.0)
    leave = np.minimum(hi.min(axis=2), 1.0)
    return enter <= leave


class Occluders:
    """The scene's collision boxes, grouped per object for a broad phase.

    Args:
        groups: one (N_i, 2, 3) array of world boxes per object.
        names: what each group is, in words ("bookshelf"), for the checks' reasons; default "object i".
    """

    def __init__(self, groups: Sequence[np.ndarray], names: Sequence[str] | None = None) -> None:
        kept = [np.asarray(g, dtype=np.float64).reshape(-1, 2, 3) for g in groups]
        labels = list(names) if names is not None else [f"object {i}" for i in range(len(kept))]
        self.groups = [g for g in kept if len(g)]
        self.names = [n for n, g in zip(labels, kept, strict=True) if len(g)]
        self.bounds = (
            np.array([[g[:, 0].min(axis=0), g[:, 1].max(axis=0)] for g in self.groups])
            if self.groups
            else np.zeros((0, 2, 3))
        )  # (K, 2, 3)
        self.memo: dict[object, Adjust] = {}  # camera decisions (pure functions of their keys), see camera.py

    @classmethod
    def from_scene(cls, scene: Scene) -> Occluders:
        """Every placed object's world collision boxes (objects the catalog lacks are skipped)."""
        from wana.assets.catalog import world_collision_boxes

        groups, names = [], []
        for p in scene.objects:
            try:
                groups.append(world_collision_boxes(p))
            except KeyError:
                continue
            names.append(p.category.replace("_", " "))
        return cls(groups, names)

    def blocked(self, starts: np.ndarray, ends: np.ndarray) -> np.ndarray:
        """(S,) bool: which sight lines from starts (S, 3) to ends (S, 3) pass through a box.

        Each line stops STOP_SHORT metres before its end point.
        """
        starts = np.asarray(starts, dtype=np.float64).reshape(-1, 3)
        ends = np.asarray(ends, dtype=np.float64).reshape(-1, 3)
        out = np.zeros(len(starts), dtype=bool)
        if not len(self.groups) or not len(starts):
            return out
        ends = _stop_short(starts, ends)
        coarse = segments_hit_boxes(starts, ends, self.bounds)  # (S, K)
        for k in np.nonzero(coarse.any(axis=0))[0]:
            rows = np.nonzero(coarse[:, k] & ~out)[0]
            if len(rows):
                out[rows] |= segments_hit_boxes(starts[rows], ends[rows], self.groups[k]).any(axis=1)
        return out

    def blocked_share(self, eye: np.ndarray, points: np.ndarray) -> float:
        """Share of the points (P, 3) the eye (3,) cannot see."""
        points = np.asarray(points, dtype=np.float64).reshape(-1, 3)
        if not len(points):
            return 0.0
        return float(self.blocked(np.broadcast_to(eye, points.shape), points).mean())

    def shares(
        self,
        views: Sequence[tuple[np.ndarray, ...]],
        adjustments: Sequence[Adjust] = ADJUSTMENTS,
    ) -> np.ndarray:
        """(A,) share of the sight lines each adjustment leaves blocked over all the views.

        Args:
            views: (eye (3,), target (3,), points (P, 3)) of the commanded camera at a few frames, optionally
                with a fourth item: (M, 2, 3) boxes of the other characters at that frame (see person_box),
                which hide sight lines too (Tom's back in a close-up of Mary during a hug).
            adjustments: A candidate changes of that camera.
        """
        people_in_view = any(len(v) > 3 and len(v[3]) for v in views)
        if not views or not (self.groups or people_in_view):
            return np.zeros(len(adjustments))
        starts, ends, owner = [], [], []
        people: list[tuple[int, np.ndarray, np.ndarray, np.ndarray]] = []  # (first ray, eye, points, boxes)
        first = 0
        for a, adj in enumerate(adjustments):
            for view in views:
                eye, target, points = view[0], view[1], view[2]
                e = adjust_eye(eye, target, adj)
                pts = np.asarray(points, dtype=np.float64).reshape(-1, 3)
                fan = near_fan(e, target)
                starts.append(np.broadcast_to(e, (len(pts) + len(fan), 3)))
                ends.append(np.concatenate([pts, fan]))
                owner.append(np.concatenate([np.full(len(pts), a), np.full(len(fan), len(adjustments) + a)]))
                if len(view) > 3 and len(view[3]):
                    people.append((first, e, pts, np.asarray(view[3], dtype=np.float64).reshape(-1, 2, 3)))
                first += len(pts) + len(fan)
        who = np.concatenate(owner)
        hit = self.blocked(np.concatenate(starts), np.concatenate(ends))
        by_count: dict[int, list[tuple[int, np.ndarray, np.ndarray, np.ndarray]]] = {}
        for item in people:  # one batched test per number of other characters
            by_count.setdefault(len(item[3]), []).append(item)
        for batch in by_count.values():
            rows = np.concatenate([np.arange(at, at + len(pts)) for at, _, pts, _ in batch])
            eyes = np.concatenate([np.broadcast_to(e, pts.shape) for _, e, pts, _ in batch])
            targets = np.concatenate([pts for _, _, pts, _ in batch])
            boxes = np.concatenate([np.broadcast_to(b, (len(pts), *b.shape)) for _, _, pts, b in batch])
            hit[rows] |= segments_hit_boxes(eyes, _stop_short(eyes, targets), boxes).any(axis=1)
        hit = hit.astype(float)
        n = len(adjustments)
        per = np.bincount(who, weights=hit, minlength=2 * n)
        total = np.bincount(who, minlength=2 * n)
        sight = per[:n] / np.maximum(total[:n], 1)
        # A fan ray per view may graze something (a table edge low in the frame); more is clutter.
        clutter = np.maximum(per[n:] - NEAR_TOLERANCE * len(views), 0.0) / np.maximum(total[n:], 1)
        return sight + clutter

    def choose(
        self,
        views: Sequence[tuple[np.ndarray, ...]],
        adjustments: Sequence[Adjust] = ADJUSTMENTS,
        previous: Adjust | None = None,
    ) -> Adjust:
        """The adjustment of a camera that sees the points from every view.

        Without a previous choice: the most preferred clear one. With one: the most preferred clear one
        within MAX_MOVE metres of it (so the camera returns to the commanded pose step by step), else
        the clear one nearest to it. When nothing is clear: the least blocked.

        Args:
            views: (eye (3,), target (3,), points (P, 3)[, other characters' boxes (M, 2, 3)]) of the
                commanded camera at a few frames (see shares).
            adjustments: candidates, most preferred first.
            previous: what the camera chose at the decision before (None: none).
        """
        candidates = list(adjustments)
        if previous is not None and previous not in candidates:
            candidates.append(previous)
        share = self.shares(views, candidates)
        clear = np.nonzero(share == 0.0)[0]
        if not len(clear):
            rank = np.arange(len(candidates)) / (100.0 * len(candidates))  # ties go to the preferred one
            return candidates[int(np.argmin(share + rank))]
        if previous is None:
            return candidates[int(clear[0])]
        eye, target = views[len(views) // 2][:2]
        here = adjust_eye(eye, target, previous)
        gaps = np.array([np.linalg.norm(adjust_eye(eye, target, candidates[k]) - here) for k in clear])
        within = clear[gaps <= MAX_MOVE]
        return candidates[int(within[0])] if len(within) else candidates[int(clear[int(np.argmin(gaps))])]


def _stop_short(starts: np.ndarray, ends: np.ndarray) -> np.ndarray:
    """Ends (S, 3) moved STOP_SHORT metres back toward their starts (S, 3)."""
    d = ends - starts
    length = np.linalg.norm(d, axis=1, keepdims=True)
    return starts + d * np.clip(1.0 - STOP_SHORT / np.maximum(length, 1e-9), 0.0, 1.0)


PERSON_HALF_WIDTH = 0.17  # metres: a character's box around the line from the floor to above its head


def person_box(hips: np.ndarray, head: np.ndarray) -> np.ndarray:
    """(2, 3) a standing or seated character's box, from the floor to a little above the head."""
    lo = np.array([min(hips[0], head[0]) - PERSON_HALF_WIDTH, 0.0, min(hips[2], head[2]) - PERSON_HALF_WIDTH])
    hi = np.array(
        [max(hips[0], head[0]) + PERSON_HALF_WIDTH, head[1] + 0.12, max(hips[2], head[2]) + PERSON_HALF_WIDTH]
    )
    return np.stack([lo, hi])


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Cross product of two 3-vectors (np.cross is slow on single vectors, and this runs per candidate)."""
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


_FAN_TAN = np.array([[math.tan(h), math.tan(v)] for h, v in NEAR_FAN])  # (len(NEAR_FAN), 2)
_WORLD_UP = np.array([0.0, 1.0, 0.0])


def near_fan(eye: np.ndarray, target: np.ndarray) -> np.ndarray:
    """(len(NEAR_FAN), 3) ends of the rays across the frame that must not hit a box (see the module doc)."""
    eye, target = np.asarray(eye, dtype=np.float64), np.asarray(target, dtype=np.float64)
    forward = target - eye
    dist = float(np.sqrt(forward @ forward))
    if dist < 1e-6:
        return np.zeros((0, 3))
    forward = forward / dist
    right = _cross(forward, _WORLD_UP)
    norm = float(np.sqrt(right @ right))
    if norm < 1e-6:  # looking straight down: any horizontal axis will do
        right, norm = np.array([1.0, 0.0, 0.0]), 1.0
    right = right / norm
    up = _cross(right, forward)
    dirs = forward + _FAN_TAN[:, :1] * right + _FAN_TAN[:, 1:] * up
    return eye + NEAR_SHARE * dist * dirs


def sight_points(hips: np.ndarray, head: np.ndarray) -> np.ndarray:
    """(3, 3) head, chest and hips: what a camera must see of a character."""
    return np.stack([head, hips + np.array([0.0, HIPS_TO_CHEST, 0.0]), hips])
