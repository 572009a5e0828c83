"""Each dependency view, through the stage that keys a node by it, with a recording fake backend.

The views are the unit under test, so the services are stand-ins here: the backend answers from a table
and records every request, and each test asserts which requests an input change causes (salsa style).
"""

from __future__ import annotations

from typing import Any

import msgspec
import numpy as np

from proto.common import Span, reply_header
from proto.motion import SegmentEndState
from proto.retrieval import ComposeReply, ComposeRequest
from proto.scene import PlacedObject, Room, Scene
from proto.social import ActionDistance, SocialPlan, SocialPlanReply, SocialPlanRequest
from proto.ssg import ActionNode, CharacterNode, ObjectNode, RelationNode, SentenceGraph, SocialNode
from services.orchestrator.queries import QueryEngine
from services.orchestrator.stages import StageContext
from services.orchestrator.stages.scene import scene
from services.orchestrator.stages.social import social_plan
from services.orchestrator.views import (
    characters_of,
    map_span,
    others,
    scene_part,
    scene_view,
    social_distances,
    social_part,
)

ROOM = Room(room_type="office", width=5.0, depth=5.0, height=2.8)


class RecordingBackend:
    """Answers compose and social-plan requests with fixed replies and records what it was sent."""

    def __init__(self) -> None:
        self.sent: list[Any] = []

    def call(self, request: Any) -> Any:
        self.sent.append(request)
        if isinstance(request, ComposeRequest):
            objects = [PlacedObject(id=o.id, category=o.category) for o in request.objects]
            return ComposeReply(header=reply_header(request), scene=Scene(room=ROOM, objects=objects))
        if isinstance(request, SocialPlanRequest):
            return SocialPlanReply(header=reply_header(request), plan=SocialPlan(expression_names=[]))
        raise AssertionError(f"unexpected {type(request).__name__}")


def ctx(backend: RecordingBackend, engine: QueryEngine) -> StageContext:
    return StageContext(backend, engine, "doc", engine.new_revision())


def scene_graph(
    sid: str, at: int, *objects: str, relation: tuple[str, str, str] | None = None
) -> SentenceGraph:
    nodes = [ObjectNode(id=o, category=o, word=o, span=Span(at, at + len(o))) for o in objects]
    rels = (
        []
        if relation is None
        else [RelationNode(subject=relation[0], relation=relation[1], object=relation[2])]
    )
    return SentenceGraph(sentence_id=sid, text="", kind="scene", objects=nodes, relations=rels)


def action_graph(sid: str, name: str, verb: str, target: str = "", at: int = 0) -> SentenceGraph:
    action = ActionNode(verb=verb, action=verb, target=target, span=Span(at, at + 4))
    return SentenceGraph(
        sentence_id=sid, text="", kind="action", characters=[CharacterNode(name=name, actions=[action])]
    )


def test_the_scene_is_not_recomposed_when_only_spans_or_action_sentences_change():
    backend, engine = RecordingBackend(), QueryEngine()
    first = [scene_graph("s1", 0, "desk"), action_graph("s2", "Eve", "walk")]
    scene(ctx(backend, engine), first)
    moved = [scene_graph("s1", 7, "desk"), action_graph("s2", "Eve", "run", at=3)]
    scene(ctx(backend, engine), moved)
    assert [type(r).__name__ for r in backend.sent] == ["ComposeRequest"]
    assert scene_part(moved).objects[0].span == Span(0, 0)


def test_a_new_relation_recomposes_the_scene():
    backend, engine = RecordingBackend(), QueryEngine()
    scene(ctx(backend, engine), [scene_graph("s1", 0, "desk", "chair")])
    scene(ctx(backend, engine), [scene_graph("s1", 0, "desk", "chair", relation=("chair", "near", "desk"))])
    assert len(backend.sent) == 2 and backend.sent[1].relations[0].relation == "near"


def test_no_scene_object_gives_an_empty_room_with_only_a_door_without_asking_retrieval():
    backend, engine = RecordingBackend(), QueryEngine()
    room, report = scene(ctx(backend, engine), [action_graph("s1", "Eve", "walk")])
    assert backend.sent == [] and report is None and [o.category for o in room.objects] == ["door"]


def test_the_social_plan_reads_verbs_and_social_nodes_but_not_scene_sentences():
    backend, engine = RecordingBackend(), QueryEngine()
    story = [action_graph("s1", "Tom", "wave", target="Eve"), action_graph("s2", "Eve", "walk")]
    social_plan(ctx(backend, engine), [scene_graph("s0", 0, "desk"), *story])
    social_plan(ctx(backend, engine), [scene_graph("s0", 0, "lamp"), *story])  # a scene edit
    assert len(backend.sent) == 1
    friends = SentenceGraph(
        sentence_id="s3",
        text="",
        kind="action",
        social=[SocialNode(kind="relation", subjects=["Tom", "Eve"], label="friends")],
    )
    social_plan(ctx(backend, engine), [*story, friends])
    assert len(backend.sent) == 2


def test_the_social_part_keeps_targets_that_are_characters_only():
    part = social_part(
        [action_graph("s1", "Tom", "wave", target="Eve"), action_graph("s2", "Eve", "sit", target="chair")]
    )
    assert part[0][1] == [["Tom", [["wave", "wave", "Eve", ""]]]]
    assert part[1][1] == [["Eve", [["sit", "sit", "", ""]]]]


def test_an_action_sees_the_floor_and_what_it_names_with_its_supports():
    objects = [
        PlacedObject(id="desk", category="desk"),
        PlacedObject(id="laptop", category="laptop", support="desk"),
        PlacedObject(id="lamp", category="lamp", support="desk"),
        PlacedObject(id="chair", category="chair"),
    ]
    room = Scene(room=ROOM, objects=objects)
    assert [
        o.id for o in scene_view(room, ActionNode(verb="type", action="type", target="laptop")).objects
    ] == [
        "desk",
        "laptop",
        "chair",
    ]
    assert [o.id for o in scene_view(room, None).objects] == ["desk", "chair"]
    moved_lamp = msgspec.structs.replace(
        room, objects=[*objects[:2], msgspec.structs.replace(objects[2], yaw=1.0), objects[3]]
    )
    walk = ActionNode(verb="walk", action="walk", destination="chair")
    assert scene_view(moved_lamp, walk) == scene_view(
        room, walk
    )  # the lamp on the desk is not in a walk's view


def test_others_are_the_named_characters_or_everyone_for_an_unknown_target():
    states = {
        "Eve": SegmentEndState(x=1.0, z=2.0),
        "Tom": SegmentEndState(x=-1.0, z=0.5),
        "Mia": SegmentEndState(),
    }
    assert others(ActionNode(verb="wave", action="wave", target="Eve"), "Tom", states, set()) == {
        "Eve": (1.0, 2.0)
    }
    assert others(ActionNode(verb="sit", action="sit", target="chair"), "Tom", states, {"chair"}) == {}
    shake = ActionNode(verb="shake", action="shake_hands", target="hands")
    assert set(others(shake, "Tom", states, {"chair"})) == {"Eve", "Mia"}


def test_social_distances_are_rounded_so_a_resampled_plan_moves_no_one_for_less():
    plan = SocialPlan(
        expression_names=[],
        action_distances=[ActionDistance(character="Tom", action_index=0, other="Eve", distance_m=0.81)],
    )
    again = SocialPlan(
        expression_names=[],
        action_distances=[ActionDistance(character="Tom", action_index=0, other="Eve", distance_m=0.79)],
    )
    assert social_distances(plan) == social_distances(again) == {("Tom", 0): {"Eve": 0.8}}
    assert social_distances(None) == {}


def test_characters_collect_their_actions_in_order_without_spans():
    graphs = [
        action_graph("s1", "Eve", "walk", at=5),
        action_graph("s2", "Tom", "wave"),
        action_graph("s3", "Eve", "sit"),
    ]
    chars = characters_of(graphs, ["s1", "s2", "s3"])
    node, sids = chars["Eve"]
    assert [a.action for a in node.actions] == ["walk", "sit"] and sids == ["s1", "s3"]
    assert all(a.span == Span(0, 0) for a in node.actions)


def test_spans_of_the_normalised_text_map_back_to_the_text_as_written():
    written = "Eve   walks  to the chair."
    assert map_span(Span(4, 9), written) == Span(6, 11)  # "walks"


def test_the_geometry_view_drops_paint_only_and_the_looks_come_back():
    from services.orchestrator.views import geometry_view, with_looks
    from wana.domain.object_geometry import object_shape

    painted = Scene(
        room=Room(room_type="office", width=5.0, depth=4.0, height=2.8),
        objects=[
            PlacedObject(id="chair", category="chair", attributes={"colour": "red", "material": "wooden"}),
            # a size word under the colour knob is still a size (the catalog moves it to its own knob)
            PlacedObject(id="desk", category="desk", attributes={"colour": "big", "style": "modern"}),
        ],
    )
    shapes = geometry_view(painted)
    assert [o.attributes for o in shapes.objects] == [{}, {"colour": "big", "style": "modern"}]
    for a, b in zip(painted.objects, shapes.objects, strict=True):  # the catalog builds the same shape
        assert np.array_equal(object_shape(a).boxes, object_shape(b).boxes)
    moved = msgspec.structs.replace(
        shapes, objects=[msgspec.structs.replace(o, position=(1.0, 0.0, 0.5)) for o in shapes.objects]
    )
    back = with_looks(moved, painted)
    assert [o.attributes for o in back.objects] == [o.attributes for o in painted.objects]
    assert all(o.position == (1.0, 0.0, 0.5) for o in back.objects)
