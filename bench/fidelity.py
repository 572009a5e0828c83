#!/usr/bin/env python
"""How long the story checks take on a computed animation (the editor runs them after every edit).

Computes each story once through the real pipeline (in-process services), then times
wana.fidelity.story_checks on the result: the first call (cold: catalog objects voxelised for the checks,
FK for every character) and the best of several warm calls on the same result (objects and bodies cached:
what an edit that leaves the motions alone costs; an edit pays FK again only for the characters it changed).

    .venv/bin/python bench/fidelity.py --quick --json out/bench_fidelity.json

Stories: examples/office.txt and a generated 40-sentence story (4 characters, 8 objects).
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

REPO = Path(__file__).resolve().parents[1]
SCENE = (
    "In the living room there is a sofa near a window$. A table is in front of the sofa$. A laptop is on the "
    "table$. A chair is near the table$. A cup is on the table$. A bookshelf is behind the sofa$. A lamp is "
    "next to the sofa$. A plant is near the window$.\n"
)
BEATS = (
    "{a} walks to the chair. {a} sits on the chair. {a} types on the laptop. {b} walks in. {b} waves at {a}. "
    "{b} walks to the window. {b} looks around. {a} stands up. {a} walks to the sofa. {a} sits on the sofa. "
    "{b} drinks from the cup. {b} nods. {a} waves at {b}. {b} walks to the lamp. {a} claps. {b} sits on the chair.\n"
)


def long_story() -> str:
    text = SCENE + BEATS.format(a="Eve", b="Tom") + BEATS.format(a="Mary", b="John")
    return text


def measure(text: str, repeats: int) -> dict[str, float | int]:
    from services.orchestrator.backend import InProcessBackend
    from services.orchestrator.session import Orchestrator
    from wana.arrays import from_wire
    from wana.fidelity import bodies, story_checks
    from wana.fidelity.world import fine_collision_boxes

    with tempfile.TemporaryDirectory() as tmp:
        orchestrator = Orchestrator(Path(tmp) / "s.db", InProcessBackend())
        result = orchestrator.create(text).compute()
        orchestrator.close()
    args = ([(s.id, s.kind) for s in result.sentences], result.graphs, result.scene, result.motions)
    fine_collision_boxes.cache_clear()
    bodies._BODIES.clear()
    started = time.perf_counter()
    checks = story_checks(*args, result.unavailable)
    cold = time.perf_counter() - started
    warm = []
    for _ in range(repeats):
        started = time.perf_counter()
        story_checks(*args, result.unavailable)
        warm.append(time.perf_counter() - started)
    frames = max((len(from_wire(m.root_position)) for m in result.motions.values()), default=0)
    return {
        "sentences": len(result.sentences),
        "characters": len(result.motions),
        "frames": frames,
        "checks": sum(len(c) for c in checks.values()),
        "cold_ms": round(cold * 1000, 1),
        "warm_ms": round(min(warm) * 1000, 1),
    }


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="fewer warm repeats")
    p.add_argument("--json", type=Path, help="write the numbers here")
    args = p.parse_args()
    repeats = 3 if args.quick else 10
    rows = {
        "office": measure((REPO / "examples" / "office.txt").read_text(), repeats),
        "story_40": measure(long_story(), repeats),
    }
    print(
        f"{'story':<10} {'sent.':>5} {'chars':>5} {'frames':>6} {'checks':>6} {'cold ms':>8} {'warm ms':>8}"
    )
    for name, r in rows.items():
        print(
            f"{name:<10} {r['sentences']:>5} {r['characters']:>5} {r['frames']:>6} {r['checks']:>6} "
            f"{r['cold_ms']:>8} {r['warm_ms']:>8}"
        )
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(rows, indent=2))


if __name__ == "__main__":
    main()
