"""The scene stage: the `scene` node composes one room from the scene sentences (retrieval service), and the
stated relations stay true through the layout's optimisation.

The optimiser (services/optimizer, paper §4.3) moves and scales furniture around each interaction to cut
collisions and bring contacts closer; it knows the interaction, not the sentences, so it can slide the rocking
chair 0.6 m away from the bunk bed it is "next to", or shrink the dining table the chairs are "around" to 64 %.
``keep_relations`` takes back as little of such a move as makes every stated relation that held before it hold
again (the share of the move kept drops 1 -> 0.75 -> ... -> 0), and undoes a move outright where taking part of
it back would make two objects overlap that overlapped neither before nor after.
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Sequence

import msgspec
import numpy as np

from proto.retrieval import ComposeReply, ComposeRequest
from proto.scene import PlacedObject, Room, Scene
from proto.ssg import RelationNode, SentenceGraph
from services.orchestrator.queries import content_hash
from services.orchestrator.stages import StageContext, content_of
from services.orchestrator.staging import with_door
from services.orchestrator.views import ScenePart, scene_part
from wana.assets.catalog import world_bounds
from wana.assets.relations import anchor_copy, relation_holds

KEPT_SHARES = (0.75, 0.5, 0.25, 0.0)  # shares of an optimiser's move tried, most of it first
OVERLAP_M = 1e-3  # metres two AABBs must interpenetrate on every axis to overlap (the optimiser's own test)


def compose(ctx: StageContext, part: ScenePart) -> tuple[Scene, ComposeReply | None]:
    """The composed room and the retrieval report; an empty room (no report) when nothing is described."""
    if not part.objects:  # nothing to retrieve: an empty room for the characters
        room = Room(room_type=part.room_type or "room", width=5.0, depth=5.0, height=2.8)
        return with_door(Scene(room=room, seed=ctx.seed)), None
    reply = ctx.backend.call(
        ComposeRequest(
            header=ctx.header(),
            objects=part.objects,
            relations=part.relations,
            room_type=part.room_type,
            seed=ctx.seed,
        )
    )
    return with_door(reply.scene), content_of(reply)  # every entrance and exit needs a door


def scene(ctx: StageContext, graphs: Sequence[SentenceGraph]) -> tuple[Scene, ComposeReply | None]:
    """The `scene` node: keyed by the scene sentences' objects, relations and room kind only."""
    part = scene_part(graphs)
    return ctx.engine.query("scene", part, lambda: compose(ctx, part))


def _holds(relation: str, subject: PlacedObject, anchor: PlacedObject) -> bool:
    try:
        return relation_holds(relation, subject, anchor)
    except (KeyError, ValueError):  # a category the catalog lacks, a relation without a predicate
        return False


def _bounds(placed: PlacedObject) -> np.ndarray | None:
    try:
        return world_bounds(placed)
    except KeyError:
        return None


def _overlap(a: np.ndarray | None, b: np.ndarray | None) -> bool:
    if a is None or b is None:
        return False
    return bool(np.all(a[0] < b[1] - OVERLAP_M) and np.all(b[0] < a[1] - OVERLAP_M))


class _Blend:
    """Placements between a layout before and after an optimisation, one share of the move per tree of
    supports (a laptop goes with the desk it rests on)."""

    def __init__(self, before: Scene, after: Scene) -> None:
        self.before = {o.id: o for o in before.objects}
        self.after = after
        by_id = {o.id: o for o in after.objects}

        def root(oid: str) -> str:
            seen = set()
            while by_id[oid].support in by_id and oid not in seen:
                seen.add(oid)
                oid = by_id[oid].support
            return oid

        self.root = {o.id: root(o.id) for o in after.objects}
        self.moved = {
            o.id
            for o in after.objects
            if o.id in self.before
            and (o.position != self.before[o.id].position or o.scale != self.before[o.id].scale)
        }

    def at(self, oid: str, share: dict[str, float]) -> PlacedObject:
        """The placement of ``oid`` with ``share[its root]`` of the optimiser's move kept (1 when absent)."""
        new = next(o for o in self.after.objects if o.id == oid)
        t = share.get(self.root[oid], 1.0)
        old = self.before.get(oid)
        if old is None or t >= 1.0 or oid not in self.moved:
            return new

        def mix(p: Sequence[float], q: Sequence[float]) -> tuple[float, float, float]:
            x, y, z = (float(a + t * (b - a)) for a, b in zip(p, q, strict=True))
            return x, y, z

        return msgspec.structs.replace(
            new, position=mix(old.position, new.position), scale=mix(old.scale, new.scale)
        )


def keep_relations(before: Scene, after: Scene, relations: Sequence[RelationNode]) -> Scene:
    """``after`` (an optimised layout of ``before``) with every stated relation that held in ``before`` true.

    Args:
        before: the layout the optimiser started from.
        after: its result (the same objects, some moved or scaled).
        relations: the scene sentences' relations (subject ids of counted objects match every copy: "chair",
            "chair/2", ...).

    Returns:
        ``after`` itself when no relation broke; else a layout where the moves that broke one are taken back
        in part or in full (see the module docstring).
    """
    blend = _Blend(before, after)
    ids = [o.id for o in after.objects]
    pairs = [
        (s, a, r.relation)
        for r in relations
        for s in ids
        if (s == r.subject or s.startswith(r.subject + "/"))
        for a in [anchor_copy(s, r, sum(i == r.object or i.startswith(r.object + "/") for i in ids))]
        if s in blend.before
        and a in blend.before
        and a in ids
        and _holds(r.relation, blend.before[s], blend.before[a])
    ]
    moved = {blend.root[m] for m in blend.moved}  # the trees the optimiser moved
    pairs = [p for p in pairs if blend.root[p[0]] in moved or blend.root[p[1]] in moved]
    if not pairs:
        return after
    share: dict[str, float] = {}
    for _ in range(len(KEPT_SHARES) * len(pairs)):
        broken = [p for p in pairs if not _holds(p[2], blend.at(p[0], share), blend.at(p[1], share))]
        if not broken:
            break
        s, anchor, relation = broken[0]
        roots = {blend.root[s], blend.root[anchor]} & moved
        now = min(share.get(r, 1.0) for r in roots) if roots else 0.0
        for kept in KEPT_SHARES:
            if kept >= now:
                continue
            trial = {**share, **{r: kept for r in roots}}
            share = trial
            if _holds(relation, blend.at(s, trial), blend.at(anchor, trial)):
                break
    if not share:
        return after
    # Taking a move back part way may put an object where another one went: undo both moves in full there.
    for _ in range(len(ids)):
        boxes = {i: _bounds(blend.at(i, share)) for i in ids}
        old = {i: _bounds(blend.before[i]) if i in blend.before else None for i in ids}
        new = {i: _bounds(next(o for o in after.objects if o.id == i)) for i in ids}
        clash = [
            (a, b)
            for n, a in enumerate(ids)
            for b in ids[n + 1 :]
            if blend.root[a] != blend.root[b]
            and _overlap(boxes[a], boxes[b])
            and not _overlap(old[a], old[b])
            and not _overlap(new[a], new[b])
        ]
        if not clash:
            break
        for a, b in clash:
            for r in (blend.root[a], blend.root[b]):
                if r in moved:
                    share[r] = 0.0
    return msgspec.structs.replace(after, objects=[blend.at(i, share) for i in ids])


KEPT_MEMO = 4096  # layouts remembered by kept_relations (one per interaction of the open documents)
_kept: OrderedDict[str, Scene] = OrderedDict()
_kept_lock = threading.Lock()  # sessions compute on threads of their own


def kept_relations(before: Scene, after: Scene, relations: Sequence[RelationNode]) -> Scene:
    """``keep_relations``, memoised by the content of its inputs: every compute walks every interaction's
    optimised layout, and an edit that re-runs none of them need not test every relation again (the
    relation tests were a quarter of an action edit at 160 sentences)."""
    key = content_hash([before, after, list(relations)])
    with _kept_lock:
        hit = _kept.get(key)
        if hit is not None:
            _kept.move_to_end(key)
            return hit
    out = keep_relations(before, after, relations)
    with _kept_lock:
        _kept[key] = out
        if len(_kept) > KEPT_MEMO:
            _kept.popitem(last=False)
    return out


__all__ = ["compose", "keep_relations", "kept_relations", "scene"]
