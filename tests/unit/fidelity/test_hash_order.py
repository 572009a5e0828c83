"""The checks say the same thing in every process: Python salts the hash of every string per process, so an
iteration over a set of joint names named "Anna's left hand stays 0.38 m from the laptop" in one run of
group-meeting_room-01 and "Anna's right hand stays 0.60 m" in another. Run in two interpreters with
different PYTHONHASHSEED, the reasons must agree."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]

SCRIPT = """
import sys
sys.path.insert(0, {root!r})
sys.path.insert(0, {tests!r})
from conftest import motion, still, scene
from proto.scene import PlacedObject
from proto.ssg import ActionNode, CharacterNode, ObjectNode, SentenceGraph
from wana.fidelity import story_checks

laptop = PlacedObject(id="laptop", category="laptop", position=(1.2, 0.75, 0.0))
node = ActionNode(verb="type", action="type", target="laptop")
graph = SentenceGraph(
    sentence_id="s1", text="Anna types on the laptop.", kind="action",
    objects=[ObjectNode(id="laptop", category="laptop", word="laptop")],
    characters=[CharacterNode(name="Anna", actions=[node], mention="Anna")],
)
anna = motion("Anna", still(0.0, 0.95, 0.0, 60), [("type", 0, 60, "s1", 0)])
checks = story_checks([("s1", "action")], {{"s1": graph}}, scene(laptop), {{"Anna": anna}})["s1"]
print([c.reason for c in checks if c.name == "contact"])
"""


def _reasons(seed: str) -> str:
    code = SCRIPT.format(root=str(ROOT), tests=str(Path(__file__).parent))
    env = {**os.environ, "PYTHONHASHSEED": seed}
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr[-2000:]
    return out.stdout.strip().splitlines()[-1]


def test_the_contact_reason_of_a_two_handed_action_is_the_same_under_any_string_hash():
    reasons = {_reasons(seed) for seed in ("0", "1", "2", "3")}
    assert len(reasons) == 1, reasons
    assert "from the laptop" in reasons.pop()
