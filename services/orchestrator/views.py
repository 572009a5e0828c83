"""Dependency views: the part of a bigger value that one query node reads.

A query node is keyed by the hash of its inputs, so what a node is given decides what re-runs it. These
functions cut a node's input down to what its service actually reads (DESIGN.md §3, STYLE.md: the
riskiest code of the orchestrator): the scene node reads only the scene sentences' objects and relations
(no spans), the social node the action sentences' verbs and social nodes, a motion segment only the
objects its action can touch and where the characters it names stand. A view that leaves out something
its service reads makes that node go stale: tests/unit/orchestrator/test_views.py records what each
service is sent, and tests/integration/test_incremental_property.py checks that an incremental result
equals a cold one after random edits.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import msgspec

from proto.common import Span
from proto.motion import SegmentEndState
from proto.scene import Scene
from proto.social import SocialPlan
from proto.ssg import ActionNode, CharacterNode, ObjectNode, RelationNode, SentenceGraph

DISTANCE_STEP = (
    0.05  # metres: social distances are rounded to this, so a re-sampled plan moves no one for less
)

NO_SPAN = Span(0, 0)


class ScenePart(msgspec.Struct, frozen=True, kw_only=True):
    """What composing the room reads: the scene sentences' objects and relations (spans blanked)."""

    objects: list[ObjectNode]
    relations: list[RelationNode]
    room_type: str


def scene_part(graphs: Sequence[SentenceGraph]) -> ScenePart:
    """Everything the scene depends on: objects, relations and the room kind of the scene sentences."""
    objects: list[ObjectNode] = []
    relations: list[RelationNode] = []
    room_type = ""
    for g in graphs:
        if g.kind != "scene":
            continue
        objects.extend(msgspec.structs.replace(o, span=NO_SPAN) for o in g.objects)
        relations.extend(msgspec.structs.replace(r, span=NO_SPAN) for r in g.relations)
        room_type = room_type or g.room_type
    return ScenePart(objects=objects, relations=relations, room_type=room_type)


def social_part(graphs: Sequence[SentenceGraph]) -> list[Any]:
    """What the social model reads of the story (services/social/story.py): the action sentences'
    characters, their actions and the characters those aim at, and the social nodes; no spans."""
    names = {c.name for g in graphs for c in g.characters}
    return [
        [
            g.sentence_id,
            [
                [
                    c.name,
                    [
                        [a.verb, a.action, *(r if r in names else "" for r in (a.target, a.destination))]
                        for a in c.actions
                    ],
                ]
                for c in g.characters
            ],
            [[n.kind, n.subjects, n.label] for n in g.social],
        ]
        for g in graphs
        if g.kind == "action" and (g.characters or g.social)
    ]


def social_distances(plan: SocialPlan | None) -> dict[tuple[str, int], dict[str, float]]:
    """(character, action index) -> {other: metres} for actions aimed at another character."""
    out: dict[tuple[str, int], dict[str, float]] = {}
    for d in plan.action_distances if plan is not None else []:
        metres = round(round(d.distance_m / DISTANCE_STEP) * DISTANCE_STEP, 2)
        out.setdefault((d.character, d.action_index), {})[d.other] = metres
    return out


MOOD_STEP = 0.25  # valence / arousal are sent in steps of this (sampling noise below it changes nothing)


def social_moods(
    plan: SocialPlan | None, characters: dict[str, tuple[CharacterNode, list[str]]]
) -> dict[tuple[str, int], tuple[float, float]]:
    """(character, action index) -> (valence, arousal) of the emotion the social plan samples at that action's
    sentence, in MOOD_STEP steps; neutral moods are left out (their motion is played as authored)."""
    out: dict[tuple[str, int], tuple[float, float]] = {}
    for entry in plan.characters if plan is not None else []:
        at = {e.sentence_id: e.vad for e in entry.emotions}
        for k, sid in enumerate(characters.get(entry.name, (None, []))[1]):
            if sid not in at:
                continue
            v, a = (round(round(x / MOOD_STEP) * MOOD_STEP, 2) for x in at[sid][:2])
            if v or a:
                out[(entry.name, k)] = (v, a)
    return out


def characters_of(
    graphs: Sequence[SentenceGraph], sentence_ids: Sequence[str]
) -> dict[str, tuple[CharacterNode, list[str]]]:
    """Each character's actions over the document in order (spans blanked), with each action's sentence id."""
    out: dict[str, tuple[list[ActionNode], list[str]]] = {}
    for g, sid in zip(graphs, sentence_ids, strict=True):
        for c in g.characters:
            actions, sids = out.setdefault(c.name, ([], []))
            for a in c.actions:
                actions.append(msgspec.structs.replace(a, span=NO_SPAN))
                sids.append(sid)
    return {name: (CharacterNode(name=name, actions=acts), sids) for name, (acts, sids) in out.items()}


def start_positions(scene: Scene, names: Sequence[str]) -> dict[str, tuple[float, float, float]]:
    """Characters enter along the front wall (-Z side), facing into the room, 0.9 m apart."""
    room = scene.room
    z = -room.depth / 2 + 0.6
    x0 = -min(room.width / 2 - 0.6, 0.45 * (len(names) - 1))
    return {name: (round(x0 + 0.9 * i, 3), round(z, 3), 0.0) for i, name in enumerate(names)}


def scene_view(scene: Scene, action: ActionNode | None) -> Scene:
    """The part of the layout an action can depend on: floor objects, plus what it names and their supports."""
    by_id = {o.id: o for o in scene.objects}
    wanted = {o.id for o in scene.objects if not o.support}
    named = [] if action is None else [action.target, action.instrument, action.destination]
    for name in named:
        if not name:
            continue
        # An action names an object by id ("chair", "chair/2") or, failing that, by category.
        refs = (
            [name]
            if name in by_id
            else [
                o.id for o in scene.objects if o.category == name or o.id.split("/")[0].split("#")[0] == name
            ]
        )
        for ref in refs:
            while ref and ref in by_id and ref not in wanted:
                wanted.add(ref)
                ref = by_id[ref].support
    return msgspec.structs.replace(scene, objects=[o for o in scene.objects if o.id in wanted])


APPEARANCE = frozenset({"colour", "material"})  # catalog knobs that paint an object and leave its shape


def _looks_only(value: str) -> bool:
    from wana.assets import vocabulary  # the catalog's own word table (a value may name another knob)

    norm = vocabulary.normalize_attribute(str(value))
    return norm is None or norm[0] in APPEARANCE


def geometry_view(scene: Scene) -> Scene:
    """The layout without what only paints it: every object's colour and material words dropped.

    Motion, the optimiser, seats and routes read an object's shape (category, size, style, state, seed,
    pose), never its paint (wana.assets.catalog builds the same boxes and contacts whatever the colour), so
    the motion stage runs on this view and a colour or material edit re-runs none of its nodes.
    ``with_looks`` puts the paint back on the final layout.
    """
    objects = [
        o
        if not any(_looks_only(v) for v in o.attributes.values())
        else msgspec.structs.replace(
            o, attributes={k: v for k, v in o.attributes.items() if not _looks_only(v)}
        )
        for o in scene.objects
    ]
    return msgspec.structs.replace(scene, objects=objects)


def with_looks(scene: Scene, looks: Scene) -> Scene:
    """``scene`` (a layout computed on ``geometry_view(looks)``) with each object's attributes from ``looks``."""
    attributes = {o.id: o.attributes for o in looks.objects}
    objects = [
        msgspec.structs.replace(o, attributes=attributes[o.id])
        if o.id in attributes and attributes[o.id] != o.attributes
        else o
        for o in scene.objects
    ]
    return msgspec.structs.replace(scene, objects=objects)


def others(
    action: ActionNode, name: str, states: dict[str, SegmentEndState], object_ids: set[str]
) -> dict[str, tuple[float, float]]:
    """Where the characters an action is aimed at stand (by the time it starts); {} when it names none.

    An action aimed at something that is neither an object nor a known character ("shakes hands") gets
    every other character, so that planning can pick the only one.
    """
    named = [r for r in (action.target, action.destination, action.instrument) if r]
    people = {c: (round(st.x, 3), round(st.z, 3)) for c, st in states.items() if c != name}
    chosen = {c: p for c, p in people.items() if c in named}
    if chosen:
        return chosen
    if action.target and action.target not in object_ids and action.target not in states:
        return people
    return {}


def map_span(span: Span, original: str) -> Span:
    """Map a span in the whitespace-normalised text back to the sentence as written."""
    mapping: list[int] = []  # normalised index -> original index
    prev_space = False
    started = False
    for i, ch in enumerate(original):
        if ch.isspace():
            if started and not prev_space:
                mapping.append(i)
            prev_space = True
        else:
            mapping.append(i)
            prev_space = False
            started = True
    mapping.append(len(original))

    def at(k: int) -> int:
        return mapping[min(max(k, 0), len(mapping) - 1)]

    return Span(at(span.start), at(span.end - 1) + 1 if span.end > span.start else at(span.start))
