"""Compose one room from the scene sentences' SSG: match (Algorithm 1), size the room, place, check.

    scene, report = compose_scene(objects, relations, room_type="office", seed=0)

1. The query SSG is matched against the scene database relation-first (services.retrieval.matching);
   the matching map decides the room kind when the text names none and which database scene lends
   context objects when it does.
2. Each object node becomes one placed catalog object per counted copy ("two chairs": chair, chair/2),
   with a variant seed derived from its id.
3. Objects are placed component by component so that each stated relation holds exactly and nothing
   interpenetrates (services.retrieval.layout); when something cannot fit, the room grows and the
   layout runs again. Context objects come last: against the walls, clear of the text objects'
   stand points, the entrance and the walkways between them (services.retrieval.clearance).
4. Every stated relation is checked with wana.assets.relations.relation_holds, and every pair of
   objects for interpenetrating collision boxes; the report carries both with the matching map.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

from proto.retrieval import ObjectMatch, RelationCheck
from proto.scene import Room, Scene
from proto.ssg import RELATIONS, Diagnostic, ObjectNode, RelationNode
from services.retrieval.checks import MemoHolds, default_holds, outer_bounds, overlapping_pairs
from services.retrieval.clearance import keep_clear_zones
from services.retrieval.database import SceneGraphDB, default_db
from services.retrieval.errors import code
from services.retrieval.geometry import footprint
from services.retrieval.layout import Holds, Item, Layout, RoomBox, object_seed, to_placed_object
from services.retrieval.matching import Matching, match_relation_first
from services.retrieval.room import base_size, context_objects, fit_size, normalize_room_type, vote_room_type
from wana.assets import catalog
from wana.assets.relations import anchor_copy

GROW_STEPS = 3  # times the room may grow by GROW_BY when objects do not fit
GROW_BY = 1.0  # metres added to width and depth
VARIANTS_PER_OBJECT = 1000  # catalog variant seeds are object seeds modulo this
# Relations that say where on the floor a thing stands: for a thing resting on another, its support's.
FLOOR_RELATIONS = frozenset({"next_to", "near", "left_of", "right_of", "in_front_of", "behind"})


@dataclass
class ComposeReport:
    """What composition decided and how well it kept the text."""

    matches: list[ObjectMatch] = field(default_factory=list)
    relations: list[RelationCheck] = field(default_factory=list)
    match_score: float = 0.0
    overlaps: int = 0
    overlap_pairs: list[tuple[str, str]] = field(default_factory=list)
    diagnostics: list[Diagnostic] = field(default_factory=list)
    room_type: str = ""
    context_scene: str = ""
    context_objects: list[str] = field(default_factory=list)
    matching: Matching | None = field(default=None, repr=False)

    @property
    def relations_held(self) -> float:
        """Share of the stated relations the scene keeps (1.0 when none were stated)."""
        return sum(r.held for r in self.relations) / len(self.relations) if self.relations else 1.0


def instance_ids(node: ObjectNode) -> list[str]:
    """Placed-object ids of a counted object node: "chair", "chair/2", ..."""
    return [node.id] + [f"{node.id}/{k}" for k in range(2, max(1, node.count) + 1)]


def _validate(
    objects: Sequence[ObjectNode], relations: Sequence[RelationNode]
) -> tuple[list[ObjectNode], list[RelationNode], list[Diagnostic]]:
    diags: list[Diagnostic] = []
    known = set(catalog.categories())
    kept: list[ObjectNode] = []
    ids: set[str] = set()
    for o in objects:
        if o.id in ids:
            diags.append(
                Diagnostic(code=code("W507"), message=f"object id {o.id!r} appears twice", span=o.span)
            )
            continue
        if o.category not in known:
            diags.append(
                Diagnostic(
                    code=code("W501"),
                    message=f"{o.word or o.id!r}: no catalog category {o.category!r}",
                    span=o.span,
                )
            )
            continue
        ids.add(o.id)
        kept.append(o)
    rels: list[RelationNode] = []
    for r in relations:
        if r.relation not in RELATIONS:
            diags.append(
                Diagnostic(
                    code=code("W502"),
                    message=f"relation {r.relation!r} is not one of {', '.join(RELATIONS)}",
                    span=r.span,
                )
            )
        elif r.subject not in ids or r.object not in ids or r.subject == r.object:
            diags.append(
                Diagnostic(
                    code=code("W503"),
                    message=f"{r.subject} {r.relation} {r.object}: an end is not a scene object",
                    span=r.span,
                )
            )
        else:
            rels.append(r)
    return kept, rels, diags


def _expand(objects: list[ObjectNode], relations: list[RelationNode]) -> list[tuple[int, RelationNode]]:
    """One relation per copy of a counted subject (with the stated relation's index); a counted
    anchor is its first copy, or, for "a chair at each desk" (``each``), copy k of the subject goes with
    copy k of the anchor."""
    copies = {o.id: instance_ids(o) for o in objects}
    out = []
    for i, r in enumerate(relations):
        for sid in copies[r.subject]:
            anchor = anchor_copy(sid, r, len(copies[r.object]))
            out.append(
                (i, RelationNode(subject=sid, relation=r.relation, object=anchor, span=r.span, each=r.each))
            )
    return out


def via_support(relations: Sequence[RelationNode]) -> list[RelationNode]:
    """The relations the layout places by: where a thing resting on another stands on the floor is where its
    support stands ("a towel hangs on the towel rack next to the sink": the rack stands next to the sink and
    the towel hangs on it). Kept on the thing when the anchor rests on the same support ("a lamp on the desk
    next to the monitor") or is that support's own support; dropped when the support already relates to the
    anchor."""
    support = {r.subject: r.object for r in relations if r.relation in ("on", "in")}
    have = {(r.subject, r.object) for r in relations}
    out: list[RelationNode] = []
    for r in relations:
        base = support.get(r.subject)
        if (
            r.relation in FLOOR_RELATIONS
            and base is not None
            and r.object != base
            and support.get(r.object) != base
            and support.get(base) != r.object
        ):
            if (base, r.object) in have or (r.object, base) in have:
                continue
            have.add((base, r.object))
            r = RelationNode(subject=base, relation=r.relation, object=r.object, span=r.span)
        out.append(r)
    return out


def _items(
    objects: list[ObjectNode], seed: int, previous: Scene | None, *, from_text: bool, start: int = 0
) -> list[Item]:
    before = {p.id: p for p in previous.objects} if previous is not None else {}
    items: list[Item] = []
    for o in objects:
        for k, oid in enumerate(instance_ids(o)):
            variant = object_seed(seed, oid) % VARIANTS_PER_OBJECT
            fp = footprint(o.category, dict(o.attributes), variant)
            prev = before.get(oid)
            if prev is not None and (
                prev.category != o.category or prev.attributes != dict(o.attributes) or prev.seed != variant
            ):
                prev = None
            items.append(
                Item(oid, o.category, dict(o.attributes), variant, fp, start + len(items), from_text, k, prev)
            )
    return items


def compose_scene(
    objects: list[ObjectNode],
    relations: list[RelationNode],
    *,
    room_type: str = "",
    seed: int = 0,
    previous: Scene | None = None,
    db: SceneGraphDB | None = None,
    holds: Holds | None = None,
) -> tuple[Scene, ComposeReport]:
    """Compose one room that keeps every stated relation with nothing interpenetrating.

    Args:
        objects: scene object nodes in document order (ids unique; count > 1 makes copies).
        relations: stated relations in document order.
        room_type: room kind the text names ("office", "working shop"); "" lets the matches decide.
        seed: composition seed; the same input and seed give the same scene.
        previous: the scene composed before an edit; objects whose placement still fits keep it.
        db: scene database (default: the project's, wana.assets.scenedb).
        holds: relation predicate (default: wana.assets.relations.relation_holds).

    Returns:
        (scene, report): placed objects (text objects keep their ids; copies get "id/2"...; context
        objects "ctx_..."), and the matching map, relation checks, overlaps and diagnostics.
    """
    db = db if db is not None else default_db()
    holds = MemoHolds(holds if holds is not None else default_holds())
    report = ComposeReport()
    kept, rels, report.diagnostics = _validate(objects, relations)
    matching = match_relation_first(kept, rels, db)
    report.matching = matching
    report.match_score = matching.score
    for o in kept:
        m = matching.nodes.get(o.id)
        if m is None:
            report.diagnostics.append(
                Diagnostic(
                    code=code("W506"),
                    message=f"{o.word or o.id!r}: placed from the catalog alone",
                    span=o.span,
                    severity="info",
                )
            )
            report.matches.append(ObjectMatch(object_id=o.id))
        else:
            node = db.objects[m.db_object].node
            report.matches.append(
                ObjectMatch(
                    object_id=o.id,
                    scene_id=db.scene_id(m.scene),
                    db_object_id=node.id,
                    db_category=node.category,
                    score=round(m.score, 6),
                    via=m.via,
                )
            )

    named = normalize_room_type(room_type, db)
    report.room_type = named or vote_room_type(matching, db) or "room"
    items = _items(kept, seed, previous, from_text=True)
    indexed = _expand(kept, rels)
    expanded = [r for _, r in indexed]
    context = context_objects(named, matching, db, kept) if named else None
    ctx_items = _items(context.objects, seed, previous, from_text=False, start=len(items)) if context else []
    ctx_rels = context.relations if context else []

    supported = {r.subject for r in expanded if r.relation in ("on", "in")}
    floor = [it.fp for it in items if it.id not in supported and it.fp.mount != "wall"]
    tallest = max((it.fp.height for it in items), default=0.0)
    w, d, h = fit_size(base_size(report.room_type, db), floor, tallest)
    if previous is not None and previous.room.room_type == report.room_type:
        w, d, h = max(w, previous.room.width), max(d, previous.room.depth), max(h, previous.room.height)

    layout = None
    for step in range(GROW_STEPS + 1):
        layout = Layout(items + ctx_items, via_support(expanded) + ctx_rels, RoomBox(w, d, h), seed, holds)
        for members in layout.components([it.id for it in items]):
            layout.place_component(members)
        if not layout.result.forced or not layout.result.crowded or step == GROW_STEPS:
            break
        w, d = w + GROW_BY, d + GROW_BY
        report.diagnostics.append(
            Diagnostic(
                code=code("I508"),
                message=f"room enlarged to {w:.1f} x {d:.1f} m to fit {', '.join(layout.result.forced)}",
                span=kept[0].span,
                severity="info",
            )
        )
    assert layout is not None
    if ctx_items:
        text_placed = [to_placed_object(p, layout.items[pid]) for pid, p in layout.result.placed.items()]
        layout.keep_clear = keep_clear_zones(text_placed, w, d)
        for members in layout.components([it.id for it in ctx_items]):
            layout.place_component(members, optional=True)
        report.context_scene = context.scene_id if context else ""
        report.context_objects = [it.id for it in ctx_items if it.id in layout.result.placed]

    by_id = {it.id: it for it in items + ctx_items}
    placed = [to_placed_object(p, by_id[pid]) for pid, p in layout.result.placed.items()]
    order = {it.id: it.order for it in items + ctx_items}
    placed.sort(key=lambda p: order[p.id])
    scene = Scene(
        room=Room(room_type=report.room_type, width=w, depth=d, height=h), objects=placed, seed=seed
    )
    _check(scene, kept, rels, indexed, holds, report)
    return scene, report


def _check(
    scene: Scene,
    objects: list[ObjectNode],
    relations: list[RelationNode],
    indexed: list[tuple[int, RelationNode]],
    holds: Holds,
    report: ComposeReport,
) -> None:
    """Fill the report's relation checks and overlaps from the finished scene (catalog geometry)."""
    placed = {p.id: p for p in scene.objects}
    rel_scores = report.matching.relation_scores if report.matching else []
    held_by_index: dict[int, bool] = {}
    for i, r in indexed:
        ok = r.subject in placed and r.object in placed and holds(r, placed[r.subject], placed[r.object])
        held_by_index[i] = held_by_index.get(i, True) and ok
    for i, r in enumerate(relations):
        held = held_by_index.get(i, False)
        score = rel_scores[i] if i < len(rel_scores) else 0.0
        report.relations.append(
            RelationCheck(
                subject=r.subject,
                relation=r.relation,
                object=r.object,
                held=held,
                match_score=round(score, 6),
            )
        )
        if not held:
            report.diagnostics.append(
                Diagnostic(
                    code=code("W504"),
                    message=f"{r.subject} {r.relation.replace('_', ' ')} {r.object} does not hold",
                    span=r.span,
                )
            )
    report.overlap_pairs = overlapping_pairs(scene)
    report.overlaps = len(report.overlap_pairs)
    spans = {oid: o.span for o in objects for oid in instance_ids(o)}
    for a, b in report.overlap_pairs:
        span = spans.get(a) or spans.get(b)
        if span is not None:
            report.diagnostics.append(
                Diagnostic(code=code("W505"), message=f"{a} and {b} overlap", span=span)
            )


__all__ = ["ComposeReport", "MemoHolds", "compose_scene", "instance_ids", "outer_bounds", "overlapping_pairs"]
