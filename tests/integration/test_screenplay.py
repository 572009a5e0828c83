"""`wana animate` on a Fountain screenplay: its heading sets the room and light, its cues speak."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = [pytest.mark.integration, pytest.mark.slow]

SCRIPT = Path(__file__).resolve().parents[2] / "examples" / "kitchen_night.fountain"


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    out = tmp_path_factory.mktemp("out")
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "wana.cli",
            "animate",
            str(SCRIPT),
            "-o",
            str(out),
            "--width",
            "160",
            "--height",
            "120",
            "--no-progress",
        ],
        capture_output=True,
        text=True,
        timeout=1200,
    )
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert (out / "animation.mp4").stat().st_size > 0
    return json.loads((out / "report.json").read_text())


def test_the_screenplay_animates_its_characters_in_the_kitchen_at_night(report):
    stages = {"parse", "resolve", "scene", "motion", "social", "render"}
    assert not stages & set(report["unavailable"])  # every stage ran (sentence ids there are story checks)
    assert report["characters"] == ["Ada", "Tom"]
    assert report["scene"]["room"]["room_type"] == "kitchen"
    placed = {(c["kind"], c["value"]) for c in report["render"]["commands"]}
    assert {("weather", "night"), ("camera", "close")} <= placed  # the heading's light; CUT TO: a cut


def test_every_line_of_dialogue_is_a_talking_action_captioned_by_its_words(report):
    spoken = [s for s in report["sentences"] if '"' in s["text"]]
    assert len(spoken) == 4
    for s in spoken:
        actions = [a["action"] for c in s["ssg"]["characters"] for a in c["actions"]]
        assert actions == ["talk"], s["text"]
    captions = {c["text"] for c in report["render"]["captions"]}
    assert {s["text"] for s in spoken} <= captions  # the line is on screen while it is said
    assert 'Ada angrily says "Where is the milk"' in captions
    # nothing to warn about (an info note, e.g. "at the back of the room" placed relative to things, is fine)
    assert not [d for s in report["sentences"] for d in s["diagnostics"] if d["severity"] != "info"]
