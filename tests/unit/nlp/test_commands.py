"""Command lines: camera, weather/light, wait, speed."""

from __future__ import annotations

import pytest

from services.nlp.commands import parse_command


@pytest.mark.parametrize(
    "line,kind,value",
    [
        ("camera front", "camera", "front"),
        ("camera back", "camera", "back"),
        ("Camera left.", "camera", "left"),
        ("camera right", "camera", "right"),
        ("camera top", "camera", "top"),
        ("camera follow", "camera", "follow"),
        ("camera close", "camera", "close"),
        ("camera behind", "camera", "back"),
        ("sunny", "weather", "sunny"),
        ("night", "weather", "night"),
        ("rainy", "weather", "rainy"),
        ("foggy", "weather", "foggy"),
        ("snowy", "weather", "snowy"),
        ("It is raining.", "weather", "rainy"),
        ("faster", "speed", "faster"),
        ("slower.", "speed", "slower"),
        ("slow down", "speed", "slower"),
    ],
)
def test_command_lines_parse_to_kind_and_value(line, kind, value):
    cmd = parse_command(line)
    assert cmd is not None and (cmd.kind, cmd.value) == (kind, value)


@pytest.mark.parametrize(
    "line,seconds",
    [
        ("wait 2 seconds", 2.0),
        ("Wait for 3 seconds.", 3.0),
        ("wait 1.5 s", 1.5),
        ("wait two seconds", 2.0),
        ("wait 1 minute", 60.0),
        ("wait", 1.0),
        ("pause half a second", 0.5),
    ],
)
def test_wait_commands_carry_seconds(line, seconds):
    cmd = parse_command(line)
    assert cmd is not None and cmd.kind == "wait" and cmd.seconds == pytest.approx(seconds)


def test_camera_follow_names_its_target_and_span_is_in_document_coordinates():
    cmd = parse_command("camera follow Tom", offset=100)
    assert cmd.target == "Tom" and (cmd.span.start, cmd.span.end) == (100, 117)


@pytest.mark.parametrize(
    "line",
    [
        "Tom waits for his friend.",
        "Eve walks to the door.",
        "camera sideways",
        "wait forever",
        "A desk is near the window$.",
    ],
)
def test_sentences_that_are_not_commands_give_none(line):
    assert parse_command(line) is None


@pytest.mark.parametrize(
    "line,value,target",
    [
        ("camera close on Professor Okafor", "close", "Professor Okafor"),
        ("camera close on Ms Lee", "close", "Ms Lee"),
        ("follow Prof. Kim", "follow", "Prof. Kim"),
        ("camera close on the teacher", "close", "teacher"),
        ("camera front on Uncle Bob", "front", "Uncle Bob"),
    ],
)
def test_a_camera_subject_of_several_words_is_one_character(line, value, target):
    cmd = parse_command(line)
    assert cmd is not None and (cmd.kind, cmd.value, cmd.target) == ("camera", value, target)


def test_two_camera_subjects_are_no_command_rather_than_one_called_ben_and_anna():
    assert parse_command("camera close on Ben and Anna") is None
