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

import msgspec
import numpy as np

from proto.common import Span
from proto.retrieval import ComposeRequest
from proto.scene import PlacedObject, Scene
from proto.ssg import CharacterNode, Diagnostic, ObjectNode, RelationNode, SentenceGraph
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


def _sit_point(placed: PlacedObject) -> np.ndarray | None:
    """World (x, y, z) of an object's first "sit*" point at the hips, or None."""
    try:
        from wana.assets.catalog import asset_for, to_world

        points = asset_for(placed).contact_points
    except Exception:  # noqa: BLE001 - unknown category: no seat
        return None
    name = next((n for n, cp in sorted(points.items()) if n.startswith("sit") and cp.joint == "Hips"), None)
    return None if name is None else to_world(placed, np.asarray(points[name].position, float))


def _clear_of(scene: Scene, placed: PlacedObject, skip: set[str]) -> bool:
    """Whether the object's footprint keeps clear of every other floor object's (but ``skip``)."""
    from wana.assets.catalog import world_bounds

    b = np.asarray(world_bounds(placed), float)[:, [0, 2]]
    for o in scene.objects:
        if o.id in skip or o.support:
            continue
        try:
            c = np.asarray(world_bounds(o), float)[:, [0, 2]]
        except Exception:  # noqa: BLE001 - unknown category: nothing to keep clear of
            continue
        if np.all(b[0] < c[1]) and np.all(b[1] > c[0]):
            return False
    return True


def seat_at_instruments(
    scene: Scene, characters: dict[str, tuple[CharacterNode, list[str]]], sentences: Sequence[Sentence]
) -> tuple[Scene, list[tuple[str, Diagnostic]]]:
    """A seat sat on just before an action at an object with its own place to sit (a drum kit's "sit"
    point: where the player's throne goes), moved to that place: "Leo sits on the stool and plays the
    drums" with the stool "next to the drum kit" sat 1.5 m from the drums, the hands in the air. The seat
    faces the object; it stays where it was when the place is taken by other furniture."""
    by_id = {o.id: o for o in scene.objects}
    spans = {x.id: Span(x.start, x.end) for x in sentences}
    moved: dict[str, PlacedObject] = {}
    notes = []
    for name, (node, sids) in characters.items():
        for k in range(len(node.actions) - 1):
            sit, then = node.actions[k], node.actions[k + 1]
            seat = by_id.get(sit.target or sit.destination) if sit.action == "sit" else None
            at = next(
                (by_id[r] for r in (then.target, then.instrument, then.destination) if r in by_id), None
            )
            if seat is None or at is None or at.id == seat.id or seat.id in moved or seat.support:
                continue
            place, own = _sit_point(at), _sit_point(seat)
            if place is None or own is None or then.action == "sit":
                continue
            yaw = float(at.yaw) + np.pi  # facing the object, as a player there does
            there = msgspec.structs.replace(seat, yaw=yaw)
            offset = _sit_point(there) - np.array([there.position[0], 0.0, there.position[2]])  # type: ignore[operator]
            there = msgspec.structs.replace(
                there,
                position=(float(place[0] - offset[0]), float(seat.position[1]), float(place[2] - offset[2])),
            )
            if not _clear_of(Scene(room=scene.room, objects=list(by_id.values())), there, {seat.id, at.id}):
                continue
            moved[seat.id] = by_id[seat.id] = there
            what, to = (x.split("#")[0].split("/")[0].replace("_", " ") for x in (seat.id, at.id))
            message = f"moved the {what} to the {to}'s place to sit: {name} sits on it to {then.verb or then.action}"
            notes.append(
                (
                    sids[k],
                    Diagnostic(
                        code="I203", message=message, span=spans.get(sids[k], Span(0, 0)), severity="info"
                    ),
                )
            )
    if not moved:
        return scene, []
    return msgspec.structs.replace(scene, objects=[moved.get(o.id, o) for o in scene.objects]), notes


__all__ = ["extra_nodes", "furnish", "missing_seats", "seat_at_instruments", "seat_needs"]
