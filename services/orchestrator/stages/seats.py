"""Seats the story's actions need, added to the room when the scene sentences did not give enough.

"Sam and Zoe sit at the school desks" with one chair at the desk, "He sits at the table" with none:
each sit / lie action aimed at an object that is no seat itself (a table, a desk, a piano) needs a free
seat slot near that object, one per character sitting there. After the room is composed, the slots
near each such object are counted (the catalog's seat points within NEAR_M); where they fall short,
the room is composed again (earlier placements kept) with a chair per missing slot near the object,
and the sentence gets a diagnostic saying what was added. Motion planning then finds them as the
nearest free seats (services/motion/planning.py, pick_seat).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from proto.common import Span
from proto.retrieval import ComposeRequest
from proto.scene import PlacedObject, Scene
from proto.ssg import Diagnostic, ObjectNode, RelationNode, SentenceGraph
from services.orchestrator.document import Sentence
from services.orchestrator.stages import StageContext, content_of
from services.orchestrator.views import scene_part
from wana.domain.actions import get_clip

NEAR_M = 1.6  # metres from the object sat at to a seat used with it (motion planning's NEAR_NAMED)
ADDED = "chair"  # the catalog category added at a table or desk


def _seat_points(placed: PlacedObject) -> int:
    """How many seat slots (catalog "sit*" points at the hips) an object has; 0 without a catalog entry."""
    try:
        from wana.assets.catalog import asset_for
    except Exception:  # noqa: BLE001 - the catalog is optional
        return 0
    try:
        obj = asset_for(placed)
    except Exception:  # noqa: BLE001 - unknown category: no seat
        return 0
    return sum(1 for n, cp in obj.contact_points.items() if n.startswith("sit") and cp.joint == "Hips")


def seat_needs(
    graphs: Sequence[SentenceGraph], sentence_ids: Sequence[str]
) -> dict[str, tuple[list[str], str]]:
    """Object id sat at -> (the characters who sit there, the sentence id of the first such action)."""
    out: dict[str, tuple[list[str], str]] = {}
    for g, sid in zip(graphs, sentence_ids, strict=True):
        if g.kind != "action":
            continue
        for c in g.characters:
            for a in c.actions:
                try:
                    clip = get_clip(a.action) if a.action else None
                except KeyError:
                    clip = None
                if clip is None or clip.interaction is None or clip.interaction.object != "seat":
                    continue
                ref = a.target or a.destination
                if not ref:
                    continue
                names, _ = out.setdefault(ref, ([], sid))
                if c.name not in names:
                    names.append(c.name)
    return out


def missing_seats(scene: Scene, needs: dict[str, tuple[list[str], str]]) -> dict[str, int]:
    """Object id -> how many seats to add near it (only objects of the scene that are no seat themselves)."""
    by_id = {o.id: o for o in scene.objects}
    out: dict[str, int] = {}
    for ref, (names, _) in needs.items():
        at = by_id.get(ref)
        if at is None or _seat_points(at):
            continue
        here = np.array([at.position[0], at.position[2]])
        slots = sum(
            _seat_points(o)
            for o in scene.objects
            if o.id != ref and np.hypot(o.position[0] - here[0], o.position[2] - here[1]) <= NEAR_M
        )
        if slots < len(names):
            out[ref] = len(names) - slots
    return out


def extra_nodes(missing: dict[str, int]) -> tuple[list[ObjectNode], list[RelationNode]]:
    """The chairs to add (ids "<object>_seat<k>") and their relations (next to the object sat at)."""
    objects, relations = [], []
    for ref, n in sorted(missing.items()):
        for k in range(n):
            oid = f"{ref.split('#')[0]}_seat{k + 1}"
            objects.append(ObjectNode(id=oid, category=ADDED, word=ADDED))
            relations.append(RelationNode(subject=oid, relation="near", object=ref))
    return objects, relations


def furnish(
    ctx: StageContext, scene: Scene, graphs: Sequence[SentenceGraph], sentences: Sequence[Sentence]
) -> tuple[Scene, list[tuple[str, Diagnostic]]]:
    """The scene with a chair added per missing seat (composed again by retrieval, earlier placements
    kept), and (sentence id, diagnostic) saying what was added; the scene unchanged when nothing is missing."""
    needs = seat_needs(graphs, [s.id for s in sentences])
    missing = missing_seats(scene, needs)
    if not missing:
        return scene, []
    part = scene_part(graphs)
    objects, relations = extra_nodes(missing)

    def run() -> Scene:
        request = ComposeRequest(
            header=ctx.header(),
            objects=[*part.objects, *objects],
            relations=[*part.relations, *relations],
            room_type=part.room_type,
            seed=ctx.seed,
            previous=scene,
        )
        return content_of(ctx.backend.call(request)).scene

    furnished = ctx.engine.query("seats", [part, objects, relations, scene], run)
    spans = {s.id: Span(s.start, s.end) for s in sentences}
    by_id = {o.id for o in furnished.objects}
    notes = []
    for ref in sorted(missing):
        names, sid = needs[ref]
        placed = sum(1 for o in objects if o.id in by_id and o.id.startswith(ref.split("#")[0] + "_seat"))
        if not placed:
            continue
        what = "a chair" if placed == 1 else f"{placed} chairs"
        place = ref.split("#")[0].replace("_", " ")
        message = f"added {what} at the {place}: no free seat there for {' and '.join(names)}"
        notes.append(
            (sid, Diagnostic(code="I201", message=message, span=spans.get(sid, Span(0, 0)), severity="info"))
        )
    return furnished, notes


__all__ = ["extra_nodes", "furnish", "missing_seats", "seat_needs"]
