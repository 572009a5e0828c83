"""Camera commands as people write them: every camera word of issue 16 parses (with its subject), the
render service knows every value the parser gives, and an unknown camera word lists the known ones."""

from __future__ import annotations

import pytest

from proto.render import TimedCommand
from proto.ssg import Command
from services.nlp.commands import CAMERA_VALUES, KNOWN_CAMERA_WORDS, parse_command
from services.nlp.parse import parse_document
from services.render.timeline import COMMAND_MODES, camera_keys


@pytest.mark.parametrize(
    "text,value,target",
    [
        ("camera front", "front", ""),
        ("camera back.", "back", ""),
        ("camera left", "left", ""),
        ("camera right", "right", ""),
        ("camera top", "top", ""),
        ("camera wide", "wide", ""),
        ("Camera wide shot.", "wide", ""),
        ("camera close", "close", ""),
        ("camera close on Ben", "close", "Ben"),
        ("camera follow", "follow", ""),
        ("follow Anna.", "follow", "Anna"),
        ("Follow Anna", "follow", "Anna"),
        ("camera over the shoulder", "over_shoulder", ""),
        ("camera over the shoulder of Tom", "over_shoulder", "Tom"),
        ("camera over Tom's shoulder.", "over_shoulder", "Tom"),
    ],
)
def test_every_camera_word_parses_with_its_subject(text: str, value: str, target: str) -> None:
    cmd = parse_command(text)
    assert cmd is not None and (cmd.kind, cmd.value, cmd.target) == ("camera", value, target)


def test_a_character_who_follows_someone_is_not_a_command() -> None:
    assert parse_command("Tom follows Anna.") is None
    assert parse_command("follow the cat") is None


def test_the_render_service_knows_every_camera_value_the_parser_gives() -> None:
    for value in set(CAMERA_VALUES.values()):
        (key,) = camera_keys([TimedCommand(frame=0, command=Command(kind="camera", value=value))])
        assert key.mode in COMMAND_MODES
    assert KNOWN_CAMERA_WORDS.replace("over the shoulder", "over_shoulder").split(", ") == list(COMMAND_MODES)


def test_an_unknown_camera_word_gets_a_diagnostic_listing_the_known_ones() -> None:
    (graph,) = parse_document("camera sideways")
    (diag,) = graph.diagnostics
    assert diag.code == "W104" and "sideways" in diag.message
    for word in ("front", "wide", "close", "follow", "over the shoulder"):
        assert word in diag.message
