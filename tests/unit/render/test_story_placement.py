"""The render service places captions and commands itself when a request carries the document's story."""

from __future__ import annotations

import numpy as np
import pytest

from proto.common import Header
from proto.motion_data import Motion, Segment
from proto.render import Caption, ExportRequest, StorySentence, TimedCommand
from proto.scene import Room, Scene
from proto.ssg import Command
from services.render.handlers import placed
from wana.arrays import to_wire
from wana.bus.service import InvalidInput

SCENE = Scene(room=Room(room_type="office", width=5.0, depth=5.0, height=2.8))


def _eve() -> Motion:
    rot = np.zeros((90, 24, 4), np.float32)
    rot[..., 3] = 1
    return Motion(
        character="Eve",
        root_position=to_wire(np.zeros((90, 3), np.float32)),
        rotations=to_wire(rot),
        segments=[
            Segment(index=0, action="walk", start_frame=0, end_frame=40, sentence_id="s1", action_index=0),
            Segment(index=1, action="sit", start_frame=40, end_frame=90, sentence_id="s3", action_index=1),
        ],
    )


def test_a_command_takes_effect_where_the_next_sentence_with_motion_starts_and_follows_the_actor():
    story = [
        StorySentence(sentence_id="s1", text="Eve walks to the chair."),
        StorySentence(
            sentence_id="s2", text="camera close", commands=[Command(kind="camera", value="close")]
        ),
        StorySentence(sentence_id="s3", text="Eve sits."),
    ]
    req = ExportRequest(header=Header(), format="mp4", scene=SCENE, motions=[_eve()], story=story)
    commands, captions = placed(req)
    assert [(c.frame, c.command.value, c.command.target) for c in commands] == [(40, "close", "Eve")]
    assert [(c.start_frame, c.end_frame, c.text) for c in captions] == [
        (0, 40, "Eve walks to the chair."),
        (40, 90, "Eve sits."),
    ]


def test_without_a_story_the_placed_commands_and_captions_are_used_as_sent():
    cmd = TimedCommand(frame=5, command=Command(kind="weather", value="night"))
    cap = Caption(start_frame=0, end_frame=10, text="hi")
    req = ExportRequest(header=Header(), format="mp4", scene=SCENE, commands=[cmd], captions=[cap])
    assert placed(req) == ([cmd], [cap])


def test_a_story_and_placed_commands_together_are_refused():
    cmd = TimedCommand(frame=5, command=Command(kind="weather", value="night"))
    story = [StorySentence(sentence_id="s1", text="night")]
    with pytest.raises(InvalidInput, match="either a story"):
        placed(ExportRequest(header=Header(), format="mp4", scene=SCENE, commands=[cmd], story=story))
