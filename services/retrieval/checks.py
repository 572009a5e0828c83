"""Checks of a composed scene: the memoised relation predicate and the overlap test.

holds = MemoHolds(default_holds())     # relation_holds, each question answered once
overlapping_pairs(scene)               # [("chair", "desk"), ...]
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Callable, Sequence

import msgspec
import numpy as np

from proto.scene import PlacedObject, Scene
from proto.ssg import RelationNode
from services.retrieval.geometry import OVERLAP_EPS
from wana.assets import catalog

Holds = Callable[[RelationNode, PlacedObject, PlacedObject], bool]


def default_holds() -> Holds:
    """The project's relation predicate, wana.assets.relations.relation_holds."""
    from wana.assets.relations import relation_holds

    return relation_holds  # type: ignore[no-any-return]


class MemoHolds:
    """A relation predicate that answers each (relation, subject pose, anchor pose) only once.

    The layout checks a relation exactly when it keeps a pose, and the final report checks the same
    relation on the same poses again; after an edit, the objects that keep their places are checked
    on the same poses as before. The predicate is pure, so a repeated answer is the first one. The
    project's predicate (wana.assets.relations.relation_holds) shares one bounded memo across
    compositions, keyed also by the catalog objects imported for the two categories (an import
    under the same name changes the geometry); any other predicate gets a memo of its own.
    """

    def __init__(self, holds: Holds) -> None:
        self.holds = holds
        self.shared = holds is default_holds()
        self.answers: OrderedDict[bytes, bool] = _SHARED_ANSWERS if self.shared else OrderedDict()

    def __call__(self, rel: RelationNode, subject: PlacedObject, anchor: PlacedObject) -> bool:
        # relation_holds reads only the relation word (a span elsewhere asks the same question).
        key = _ENCODER.encode((rel.relation if self.shared else rel, subject, anchor))
        if self.shared:
            from wana.assets.importers.registry import imported_object

            imported = (imported_object(subject.category), imported_object(anchor.category))
            if imported != (None, None):
                key += repr(tuple(map(id, imported))).encode()
        answer = self.answers.get(key)
        if answer is None:
            answer = bool(self.holds(rel, subject, anchor))
            self.answers[key] = answer
            if len(self.answers) > HOLDS_MEMO_SIZE:
                self.answers.popitem(last=False)
        return answer


HOLDS_MEMO_SIZE = 20_000  # answers kept (a few MB)
_SHARED_ANSWERS: OrderedDict[bytes, bool] = OrderedDict()
_ENCODER = msgspec.msgpack.Encoder(order="deterministic")


def overlapping_pairs(scene: Scene, eps: float = OVERLAP_EPS) -> list[tuple[str, str]]:
    """Pairs of placed objects whose world collision boxes interpenetrate by more than eps.

    An object and the one it rests on count as touching, not overlapping. The test is the catalog's
    (wana.assets.catalog.world_collision_boxes); a broad phase on bounds that contain those boxes
    (the transformed AABB of each object's collision boxes, grown by BROAD_PHASE_SLACK) skips pairs
    that cannot touch, so world boxes are only computed for objects close to another.
    """
    from services.retrieval.geometry import aabb, boxes_overlap

    objs: list[PlacedObject] = list(scene.objects)
    if len(objs) < 2:
        return []
    outer = outer_bounds(objs)  # (K, 2, 3)
    apart = (outer[:, None, 0] >= outer[None, :, 1] - eps) | (outer[None, :, 0] >= outer[:, None, 1] - eps)
    close = ~(apart[..., 0] | apart[..., 1] | apart[..., 2])  # (K, K), symmetric
    boxes: dict[int, np.ndarray] = {}
    bounds: dict[int, np.ndarray] = {}

    def world(k: int) -> tuple[np.ndarray, np.ndarray]:
        if k not in boxes:
            boxes[k] = catalog.world_collision_boxes(objs[k])
            bounds[k] = aabb(boxes[k])
        return boxes[k], bounds[k]

    pairs = []
    for i, j in zip(*np.nonzero(np.triu(close, k=1)), strict=True):
        a, b = objs[i], objs[j]
        if a.support == b.id or b.support == a.id:
            continue
        (xa, ba), (xb, bb) = world(int(i)), world(int(j))
        if (ba[0] < bb[1] - eps).all() and (bb[0] < ba[1] - eps).all() and boxes_overlap(xa, xb, eps):
            pairs.append((a.id, b.id))
    return pairs


BROAD_PHASE_SLACK = 1e-6  # metres; covers rounding between the two ways of transforming a corner


def _local_bounds(asset: catalog.AssetObject) -> np.ndarray:
    """(2, 3) object-frame AABB of an asset's collision boxes (NaN without any), kept per asset."""
    key = id(asset)
    found = _LOCAL_BOUNDS.get(key)
    if found is None or found[0] is not asset:
        cells = asset.collision_boxes
        bounds = (
            np.stack([cells[:, 0].min(axis=0), cells[:, 1].max(axis=0)])
            if len(cells)
            else np.full((2, 3), np.nan)
        )
        if len(_LOCAL_BOUNDS) > 4096:
            _LOCAL_BOUNDS.clear()
        found = _LOCAL_BOUNDS[key] = (asset, bounds)
    return found[1]


_LOCAL_BOUNDS: dict[int, tuple[catalog.AssetObject, np.ndarray]] = {}


def outer_bounds(objects: Sequence[PlacedObject]) -> np.ndarray:
    """World boxes that contain every world collision box of each object (after yaw and scale).

    Each object's collision boxes are bounded in its own frame, that box is turned into the world
    (centre rotated, half size through the absolute rotation) and grown by BROAD_PHASE_SLACK.

    Returns:
        (K, 2, 3) min/max corners; an object without collision boxes gets an empty box (+inf, -inf).
    """
    local = np.array([_local_bounds(catalog.asset_for(p)) for p in objects]).reshape(-1, 2, 3)
    solid = ~np.isnan(local[:, 0, 0])
    local[~solid] = 0.0
    yaw = np.array([p.yaw for p in objects], dtype=np.float64)
    c, s = np.cos(yaw), np.sin(yaw)
    zero, one = np.zeros_like(yaw), np.ones_like(yaw)
    rot = np.stack(
        [np.stack([c, zero, s], -1), np.stack([zero, one, zero], -1), np.stack([-s, zero, c], -1)], 1
    )
    rot = rot * np.array([p.scale for p in objects], dtype=np.float64)[:, None, :]  # R @ diag(scale)
    centre = np.einsum("kij,kj->ki", rot, (local[:, 0] + local[:, 1]) / 2.0)
    centre += np.array([p.position for p in objects], dtype=np.float64)
    half = np.einsum("kij,kj->ki", np.abs(rot), (local[:, 1] - local[:, 0]) / 2.0) + BROAD_PHASE_SLACK
    out = np.stack([centre - half, centre + half], axis=1)
    out[~solid] = [[np.inf] * 3, [-np.inf] * 3]
    return out


__all__ = ["MemoHolds", "default_holds", "outer_bounds", "overlapping_pairs"]
