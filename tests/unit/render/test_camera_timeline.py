"""Cameras, weather looks and the placement of commands on frames."""

from __future__ import annotations

import numpy as np
import pytest

from proto.render import TimedCommand
from proto.ssg import Command
from services.render.camera import TRANSITION_FRAMES, CameraKey, CameraPose, camera_at, project
from services.render.demo import demo_scene, walk_motion
from services.render.skinning import Rig
from services.render.timeline import (
    camera_keys,
    caption_at,
    chunk_ranges,
    make_captions,
    place_commands,
    weather_keys,
)
from services.render.weather import LOOKS, WeatherKey, look_at


def test_projection_puts_the_target_at_the_image_centre_and_up_is_up():
    pose = CameraPose(
        eye=np.array([1.0, 2.0, 5.0]), target=np.array([0.0, 1.0, 0.0]), up=np.array([0.0, 1.0, 0.0])
    )
    uv, z = project(np.array([[0.0, 1.0, 0.0], [0.0, 2.0, 0.0]]), pose, 640, 480)
    np.testing.assert_allclose(uv[0], [319.5, 239.5], atol=1e-6)
    assert z[0] > 0 and uv[1, 1] < uv[0, 1]  # a higher point is higher in the picture (smaller row)


@pytest.fixture(scope="module")
def eve():
    return Rig.from_motion(walk_motion("Eve", (-2.0, 1.0), (1.0, -1.0), 90)).track()


@pytest.mark.parametrize("mode,sign", [("front", 1.0), ("back", -1.0), ("follow", -1.0), ("close", 1.0)])
def test_front_back_follow_close_sit_on_the_right_side_of_the_character(eve, mode, sign):
    room = demo_scene().room
    pose = camera_at(60, [CameraKey(frame=0, mode=mode, character="Eve")], {"Eve": eve}, room)
    hips, facing, _ = eve.at(60)
    offset = pose.eye - hips
    offset[1] = 0
    assert sign * float(offset @ facing) > 0.5


def test_left_camera_looks_at_the_characters_left_side(eve):
    room = demo_scene().room
    pose = camera_at(60, [CameraKey(frame=0, mode="left", character="Eve")], {"Eve": eve}, room)
    hips, facing, _ = eve.at(60)
    left = np.array([facing[2], 0.0, -facing[0]])
    assert float((pose.eye - hips) @ left) > 2.0


def test_camera_changes_ease_in_without_jumps(eve):
    room = demo_scene().room
    keys = [CameraKey(frame=20, mode="top", character="Eve")]
    eyes = np.array(
        [camera_at(f, keys, {"Eve": eve}, room).eye for f in range(10, 20 + TRANSITION_FRAMES + 5)]
    )
    steps = np.linalg.norm(np.diff(eyes, axis=0), axis=1)
    total = np.linalg.norm(eyes[-1] - eyes[0])
    assert total > 2.0 and steps.max() < total / 8  # spread over many frames, no cut


def test_weather_eases_from_sunny_to_night():
    keys = [WeatherKey(frame=10, weather="night")]
    assert np.allclose(look_at(5, keys).gain, LOOKS["sunny"].gain)
    mid = look_at(25, keys).gain.mean()
    assert LOOKS["night"].gain.mean() < mid < LOOKS["sunny"].gain.mean()
    assert np.allclose(look_at(200, keys).gain, LOOKS["night"].gain)


def test_a_story_that_opens_at_night_is_night_from_its_first_frame():
    keys = [WeatherKey(frame=0, weather="night"), WeatherKey(frame=90, weather="foggy")]
    assert np.allclose(look_at(0, keys).gain, LOOKS["night"].gain)  # no flash of daylight before the fade
    assert not np.allclose(look_at(100, keys).gain, LOOKS["foggy"].gain)  # later changes still ease in


def test_commands_take_effect_when_the_next_sentence_with_motion_starts():
    eve = walk_motion("Eve", (0, 0), (1, 0), 60, sentence_id="s1")
    tom_raw = walk_motion("Tom", (0, 1), (1, 1), 90, sentence_id="s3")
    import msgspec

    from proto.motion_data import Segment

    tom = msgspec.structs.replace(
        tom_raw, segments=[Segment(index=0, action="walk", start_frame=60, end_frame=90, sentence_id="s3")]
    )
    sentences = [
        ("s1", "Eve walks."),
        ("s2", "camera left. night"),
        ("s3", "Tom walks in."),
        ("s4", "camera top"),
    ]
    cmds = [
        ("s2", Command(kind="camera", value="left")),
        ("s2", Command(kind="weather", value="night")),
        ("s4", Command(kind="camera", value="top")),
        ("s2", Command(kind="speed", value="faster")),
    ]
    timed = place_commands(cmds, sentences, [eve, tom])
    assert [(t.frame, t.command.value, t.command.target) for t in timed] == [
        (60, "left", "Eve"),
        (60, "night", ""),
        (90, "top", "Tom"),
    ]
    assert [k.mode for k in camera_keys(timed)] == ["left", "top"]
    assert [k.weather for k in weather_keys(timed)] == ["night"]
    caps = make_captions(sentences, [eve, tom])
    assert (
        caption_at(caps, 10) == "Eve walks."
        and caption_at(caps, 70) == "Tom walks in."
        and caption_at(caps, 95) == ""
    )


def test_unknown_camera_word_is_a_clear_error():
    with pytest.raises(ValueError, match="unknown camera command"):
        camera_keys([TimedCommand(frame=0, command=Command(kind="camera", value="sideways"))])


def test_chunk_ranges_cover_every_frame_once():
    ranges = chunk_ranges(101, 4)
    assert ranges[0][0] == 0 and ranges[-1][1] == 101
    assert all(a[1] == b[0] for a, b in zip(ranges, ranges[1:], strict=False))
    assert chunk_ranges(2, 5) == [(0, 1), (1, 2)]


@pytest.mark.parametrize(
    "said,meant",
    [
        ("Mom", "mom"),
        ("the teacher", "teacher"),
        ("Okafor", "Professor Okafor"),
        ("Professor Okafor", "Professor Okafor"),
    ],
)
def test_a_camera_command_names_the_character_as_the_motions_do(said, meant):
    people = [walk_motion(n, (0.0, 0.0), (1.0, 0.0), 30) for n in ("mom", "teacher", "Professor Okafor")]
    (timed,) = place_commands([("", Command(kind="camera", value="close", target=said))], [], people)
    assert timed.command.target == meant


def test_a_camera_subject_two_characters_share_is_left_as_written():
    people = [walk_motion(n, (0.0, 0.0), (1.0, 0.0), 30) for n in ("Ms Lee", "Mr Lee")]
    (timed,) = place_commands([("", Command(kind="camera", value="close", target="Lee"))], [], people)
    assert timed.command.target == "Lee"
