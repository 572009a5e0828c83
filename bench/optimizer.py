"""Benchmark one interaction optimisation (100 annealing steps) on one core.

Usage:
    .venv/bin/python bench/optimizer.py [--quick] [--json PATH] [--repeats 7] [--proposals 4]

The interaction: Eve sits on an office chair pushed against a desk and types on a laptop (motion from
the motion service, made once, outside the timing). Timed: ``optimise_interaction`` with the anchored
surrogate, 100 steps, ``--proposals`` proposals per step, exact before/after reports included; also
``plan_route`` across the room and one exact cost evaluation. Single-threaded (OMP_NUM_THREADS=1).
JSON keys: ms_per_optimisation (median), p50_ms, p90_ms, route_ms, cost_eval_ms, steps, proposals.
Target: ms_per_optimisation <= 300 on one core.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np  # noqa: E402

from proto.optimizer import Interaction, OptimiseSettings  # noqa: E402
from proto.scene import PlacedObject, Room, Scene  # noqa: E402
from proto.ssg import ActionNode, CharacterNode  # noqa: E402
from services.optimizer.annealing import optimise_interaction  # noqa: E402
from services.optimizer.costs import SceneGeometry  # noqa: E402
from services.optimizer.resynthesis import anchored_motion_fn, motion_service_fn, planned_contacts  # noqa: E402
from services.optimizer.scoring import InteractionScorer  # noqa: E402
from wana.compose import compose  # noqa: E402
from wana.domain.routes import plan_route  # noqa: E402


def bench_case() -> tuple[Scene, CharacterNode, Interaction]:
    """The benchmark scene: desk, office chair close to it, laptop on the desk."""
    scene = Scene(
        room=Room(room_type="office", width=5.0, depth=5.0, height=3.0),
        objects=[
            PlacedObject(id="desk", category="desk", position=(0.0, 0.0, -0.9)),
            PlacedObject(id="chair", category="office_chair", position=(0.0, 0.0, -0.2), yaw=float(np.pi)),
            PlacedObject(id="laptop", category="laptop", position=(0.0, 0.75, -0.95), support="desk"),
        ],
    )
    character = CharacterNode(
        name="Eve",
        actions=[
            ActionNode(verb="sit", action="sit", target="chair"),
            ActionNode(verb="type", action="type", target="laptop"),
        ],
    )
    contacts = planned_contacts(character, scene)
    return (
        scene,
        character,
        Interaction(character="Eve", action="type", targets=["chair", "laptop"], contacts=contacts),
    )


def main(argv: list[str] | None = None) -> int:
    compose()  # the optimiser re-synthesises through the motion service, as its runtimes wire it
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="3 repeats (< 30 s)")
    ap.add_argument("--json", type=Path, default=None, help="write the timings here")
    ap.add_argument("--repeats", type=int, default=7, help="timed optimisations (default 7)")
    ap.add_argument("--proposals", type=int, default=4, help="proposals per annealing step (default 4)")
    ap.add_argument("--steps", type=int, default=100, help="annealing steps (default 100, the paper's)")
    args = ap.parse_args(argv)
    from tqdm import tqdm

    repeats = 3 if args.quick else max(1, args.repeats)
    scene, character, inter = bench_case()
    motion = motion_service_fn(character, (1.8, 1.8, float(np.pi)))(scene)
    geom = SceneGeometry.from_scene(scene)
    settings = OptimiseSettings(proposals=args.proposals, steps=args.steps)
    motion_fn = anchored_motion_fn(scene, motion, inter, geom)
    optimise_interaction(
        scene, motion_fn, inter, steps=5, settings=settings, motion=motion, geometry=geom
    )  # warm
    times, cpu = [], []
    result = None
    for seed in tqdm(range(repeats), desc="optimisations", unit="opt"):
        t0, c0 = time.perf_counter(), time.process_time()
        result = optimise_interaction(
            scene,
            motion_fn,
            inter,
            seed=seed,
            steps=args.steps,
            settings=settings,
            motion=motion,
            geometry=geom,
        )
        times.append((time.perf_counter() - t0) * 1000)
        cpu.append((time.process_time() - c0) * 1000)
    route_ms = []
    for _ in range(5):
        t0 = time.perf_counter()
        plan_route(scene, np.array([2.0, 2.0]), np.array([-2.0, -2.0]))
        route_ms.append((time.perf_counter() - t0) * 1000)
    scorer = InteractionScorer(scene, inter, frame_stride=1, geometry=geom)
    scorer.score_scenes([scene], [motion])
    t0 = time.perf_counter()
    scorer.score_scenes([scene], [motion])
    cost_ms = (time.perf_counter() - t0) * 1000
    out = {
        "ms_per_optimisation": float(np.median(times)),
        "p50_ms": float(np.median(times)),
        "p90_ms": float(np.percentile(times, 90)),
        "cpu_ms_median": float(np.median(cpu)),
        "route_ms": float(np.median(route_ms)),
        "cost_eval_ms": cost_ms,
        "steps": args.steps,
        "proposals": args.proposals,
        "repeats": repeats,
        "frames": int(motion.root_position.shape[0]),
        "boxes": int(len(geom.box_owner)),
        "cost_before": result.before.cost if result else None,
        "cost_after": result.after.cost if result else None,
    }
    print(f"{'measure':30s} {'value':>10s}")
    for key in ("ms_per_optimisation", "p50_ms", "p90_ms", "cpu_ms_median", "route_ms", "cost_eval_ms"):
        print(f"{key:30s} {out[key]:10.1f}")
    print(f"{'steps x proposals':30s} {args.steps:>6d} x {args.proposals}")
    print(f"{'motion frames / boxes':30s} {out['frames']:>6d} / {out['boxes']}")
    print(f"{'cost before -> after':30s} {out['cost_before']:.3f} -> {out['cost_after']:.3f}")
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
