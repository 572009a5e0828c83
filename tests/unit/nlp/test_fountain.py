"""Fountain screenplays become wana stories (wana.screenplay, parsed by screenplain) and parse."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from services.nlp.parse import parse_document
from wana.screenplay import looks_like_fountain, to_story

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"

SCRIPT = """Title: Test

INT. ADA'S SMALL KITCHEN - NIGHT

A fridge stands next to the counter.

ADA (30s, tired) walks to the fridge.

ADA
(angrily)
Where is the milk? I bought it.

TOM (V.O.)
(to Ada)
Dr. Jones drank it.
(beat)
Sorry.

CUT TO:

EXT. GARDEN - DAY

Tom waves at ADA.
"""


def test_a_scene_heading_gives_the_room_and_the_light():
    lines = to_story(SCRIPT).splitlines()
    assert lines[:2] == ["In the kitchen$.", "night"]
    assert "sunny" in lines  # EXT. GARDEN - DAY: no room the catalog knows, but daylight


def test_action_lines_are_sentences_with_names_spelled_as_their_cue():
    lines = to_story(SCRIPT).splitlines()
    assert "Ada walks to the fridge." in lines  # capitals and the (30s, tired) note gone
    assert "Tom waves at Ada." in lines


def test_dialogue_is_one_said_line_per_sentence_with_manner_and_listener():
    lines = to_story(SCRIPT).splitlines()
    assert 'Ada angrily says "Where is the milk"' in lines
    assert 'Ada angrily says "I bought it"' in lines
    assert 'Tom says to Ada "Dr Jones drank it"' in lines  # (V.O.) is no part of the name


def test_a_beat_is_a_wait_and_a_transition_is_a_camera_cut():
    lines = to_story(SCRIPT).splitlines()
    at = lines.index('Tom says to Ada "Dr Jones drank it"')
    assert lines[at + 1 : at + 4] == ["wait 1 second", 'Tom says to Ada "Sorry"', "camera close"]


def test_fade_in_and_fade_out_open_and_close_the_film_and_are_no_sentences():
    story = to_story("FADE IN:\n\nINT. OFFICE - DAY\n\nEve sits.\n\nFADE OUT.\n\nTHE END\n")
    assert story.splitlines() == ["In the office$.", "sunny", "Eve sits."]


def test_fountain_is_detected_by_extension_or_by_content():
    assert looks_like_fountain("anything", "play.fountain")
    assert looks_like_fountain(SCRIPT)
    assert looks_like_fountain("INT. OFFICE - DAY\n\nEve sits.\n")
    assert not looks_like_fountain(
        "A chair is near a desk$.\nEve walks to the chair. Eve sits.\ncamera top\n"
    )
    assert not looks_like_fountain("EVE\nwalks to the chair.\n")


def test_the_converted_screenplay_parses_without_a_diagnostic():
    graphs = parse_document(to_story(SCRIPT))
    assert [d.message for g in graphs for d in g.diagnostics] == []
    said = [a for g in graphs for c in g.characters for a in c.actions if a.action == "talk"]
    assert [(a.manner, a.target) for a in said] == [
        ("angrily", ""),
        ("angrily", ""),
        ("", "Ada"),
        ("", "Ada"),
    ]
    assert [c.seconds for g in graphs for c in g.commands if c.kind == "wait"] == [1.0]
    assert {g.room_type for g in graphs} >= {"kitchen"}


@pytest.mark.parametrize(
    "name",
    [
        "kitchen_night.fountain",
        "office_morning.fountain",
        "classroom_day.fountain",
        "living_room_evening.fountain",
    ],
)
def test_every_example_screenplay_parses_cleanly(name):
    graphs = parse_document(to_story((EXAMPLES / name).read_text()))
    # info notes (a part of the room the layout does not honour) are no fault of the screenplay
    assert [d.message for g in graphs for d in g.diagnostics if d.severity != "info"] == []
    assert sum(1 for g in graphs for c in g.characters for a in c.actions if a.action == "talk") >= 2
    assert any(g.room_type for g in graphs)


def test_wana_parse_reads_a_fountain_file(tmp_path):
    script = tmp_path / "scene.fountain"
    script.write_text(SCRIPT)
    proc = subprocess.run(
        [sys.executable, "-m", "wana.cli", "parse", str(script), "--compact"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 0, proc.stderr
    entries = json.loads(proc.stdout)
    assert entries[0]["room_type"] == "kitchen"
    assert any(c["kind"] == "camera" for e in entries for c in e["commands"])
