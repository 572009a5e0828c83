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
    assert report["unavailable"] == {}
    assert report["characters"] == ["Ada", "Tom"]
    assert report["scene"]["room_type"] == "kitchen"
    commands = [c["value"] for s in report["sentences"] for c in (s["ssg"] or {}).get("commands", [])]
    assert "night" in commands and "left" in commands  # the heading's light, CUT TO: as a camera cut


def test_every_line_of_dialogue_is_a_talking_action_captioned_by_its_words(report):
    spoken = [s for s in report["sentences"] if '"' in s["text"]]
    assert len(spoken) == 5
    for s in spoken:
        actions = [a["action"] for c in s["ssg"]["characters"] for a in c["actions"]]
        assert actions == ["talk"], s["text"]
    assert any(s["text"] == 'Ada angrily says "Where is the milk?"' for s in spoken)
    assert not [d for s in report["sentences"] for d in s["diagnostics"]]
