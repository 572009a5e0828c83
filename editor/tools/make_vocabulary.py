"""Write editor/src/vocabulary.json: what a writer can say, for the editor's completion and help panel.

Generated from the object catalog (wana.assets.vocabulary), the action library (wana.domain.actions) and the
command set (services.nlp.commands), plus example stories from examples/ and corpus/stories/dev/. Run it
again after any of those changes: `PYTHONPATH=. python editor/tools/make_vocabulary.py`.
"""

from __future__ import annotations

import json
from pathlib import Path

from services.nlp import commands
from wana.assets import vocabulary
from wana.domain import actions

REPO = Path(__file__).resolve().parents[2]
OUT = REPO / "editor" / "src" / "vocabulary.json"
EXAMPLES = [
    ("An office", REPO / "examples" / "office.txt"),
    ("A bedroom for two", REPO / "corpus" / "stories" / "dev" / "duo-bedroom-10.txt"),
    ("At the gym", REPO / "corpus" / "stories" / "dev" / "duo-gym-22.txt"),
    ("A living room", REPO / "corpus" / "stories" / "dev" / "duo-living_room-02.txt"),
    ("In the kitchen", REPO / "corpus" / "stories" / "dev" / "duo-kitchen-23.txt"),
    ("Alone in a cafe", REPO / "corpus" / "stories" / "dev" / "solo-cafe-15.txt"),
    ("A meeting room", REPO / "corpus" / "stories" / "dev" / "duo-meeting_room-07.txt"),
]
LOCOMOTION = ["walks to", "runs to", "walks in", "walks out", "turns left", "turns right"]


def third_person(verb: str) -> str:
    """'sit' -> 'sits', 'brush teeth' -> 'brushes teeth' (the form a story uses)."""
    head, _, rest = verb.partition(" ")
    if head.endswith(("s", "sh", "ch", "x", "z")):
        head += "es"
    elif head.endswith("y") and head[-2:-1] not in "aeiou":
        head = head[:-1] + "ies"
    else:
        head += "s"
    return f"{head} {rest}".strip()


def build() -> dict[str, object]:
    objects = sorted({name.replace("_", " ") for name in vocabulary.CATEGORIES})
    verbs = sorted({third_person(a.replace("_", " ")) for a in actions.action_names()})
    camera = sorted(set(commands.CAMERA_VALUES.values()))
    return {
        "objects": objects,
        "actions": sorted(set(LOCOMOTION) | set(verbs)),
        "commands": [f"camera {c.replace('_', ' ')}" for c in camera]
        + sorted(set(commands.WEATHER_VALUES.values()))
        + ["wait 2 seconds", "faster", "slower"],
        "examples": [
            {"title": t, "text": p.read_text(encoding="utf-8").strip()} for t, p in EXAMPLES if p.is_file()
        ],
    }


if __name__ == "__main__":
    OUT.write_text(json.dumps(build(), indent=1) + "\n", encoding="utf-8")
    print(f"wrote {OUT}")
