"""Object states from timed actions (services/orchestrator/stages/states.py): the change starts at the frame
the hand touches the object and holds for the rest of the story, across sentences."""

from __future__ import annotations

import numpy as np

from proto.common import Span
from proto.motion_data import Motion, Segment
from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.orchestrator.document import Sentence
from services.orchestrator.stages.states import state_tracks, with_states
from wana.arrays import to_wire
from wana.domain.actions import get_clip
from wana.domain.object_state import state_at, value_at

ROOM = Scene(
    room=Room(room_type="office", width=5.0, depth=4.0, height=2.8),
    objects=[
        PlacedObject(id="door", category="door", position=(0.0, 0.0, -1.95)),
        PlacedObject(id="lamp", category="lamp", position=(1.0, 0.7, 0.0)),
        PlacedObject(id="laptop", category="laptop", position=(1.3, 0.7, 0.0)),
    ],
)
TEXT = ["Tom opens the door.", "Eve turns on the lamp.", "Tom closes the door.", "Eve switches off the lamp."]


def _sentences() -> list[Sentence]:
    out, at = [], 0
    for i, t in enumerate(TEXT):
        out.append(Sentence(id=f"s{i}", start=at, end=at + len(t), text=t))
        at += len(t) + 1
    return out


def _motion(name: str, pieces: list[tuple[str, int, int, int]], n: int) -> Motion:
    segs = [
        Segment(index=i, action=a, start_frame=s, end_frame=e, action_index=k)
        for i, (a, s, e, k) in enumerate(pieces)
    ]
    return Motion(
        character=name,
        root_position=to_wire(np.zeros((n, 3), np.float32)),
        rotations=to_wire(np.tile(np.array([0, 0, 0, 1], np.float32), (n, 1, 1))),
        segments=segs,
    )


def _story():
    sents = _sentences()
    tom = CharacterNode(
        name="Tom",
        actions=[
            ActionNode(
                verb="open",
                action="open_door",
                target="door",
                span=Span(sents[0].start + 4, sents[0].end - 1),
            ),
            ActionNode(
                verb="close",
                action="close_door",
                target="door",
                span=Span(sents[2].start + 4, sents[2].end - 1),
            ),
        ],
    )
    eve = CharacterNode(
        name="Eve",
        actions=[
            ActionNode(
                verb="turn on",
                action="press_switch",
                target="lamp",
                span=Span(sents[1].start + 4, sents[1].end - 1),
            ),
            ActionNode(
                verb="switch",
                action="press_switch",
                target="lamp",
                span=Span(sents[3].start + 4, sents[3].end - 1),
            ),
        ],
    )
    characters = {"Tom": (tom, ["s0", "s2"]), "Eve": (eve, ["s1", "s3"])}
    motions = {
        "Tom": _motion(
            "Tom", [("walk", 0, 30, 0), ("open_door", 30, 90, 0), ("close_door", 150, 210, 1)], 300
        ),
        "Eve": _motion("Eve", [("press_switch", 90, 126, 0), ("press_switch", 240, 276, 1)], 300),
    }
    return characters, motions, sents


def test_the_door_opens_from_the_touch_frame_and_stays_open_until_it_is_closed():
    characters, motions, sents = _story()
    tracks = {(t.object_id, t.state): t for t in state_tracks(ROOM, characters, motions, sents)}
    door = tracks[("door", "open")]
    clip = get_clip("open_door")
    touch = 30 + round(clip.interaction.window[0] / clip.duration_s * 60)
    assert door.frames[0] == touch
    assert value_at(door, touch - 1) == 0.0  # shut until the hand is on it
    assert 0.0 < value_at(door, touch + 9) < 1.0  # swinging
    assert value_at(door, touch + 18) == 1.0  # open ~0.6 s later
    assert value_at(door, 149) == 1.0  # still open through Eve's sentence
    assert value_at(door, 299) == 0.0  # "Tom closes the door" closed it


def test_the_lamp_turns_on_and_a_later_switch_off_turns_it_off():
    characters, motions, sents = _story()
    scene = with_states(ROOM, characters, motions, sents)
    assert state_at(scene.states, "lamp", "on", 0.0, 100) == 0.0
    assert state_at(scene.states, "lamp", "on", 0.0, 130) == 1.0
    assert state_at(scene.states, "lamp", "on", 0.0, 230) == 1.0  # on through "Tom closes the door"
    assert state_at(scene.states, "lamp", "on", 0.0, 290) == 0.0
    assert not [t for t in scene.states if t.object_id == "laptop"]  # nobody touched it


def test_a_story_without_state_changes_keeps_the_scene():
    characters, motions, sents = _story()
    walk_only = {"Tom": (CharacterNode(name="Tom", actions=[ActionNode(verb="walk", action="walk")]), ["s0"])}
    assert with_states(ROOM, walk_only, motions, sents) is ROOM
