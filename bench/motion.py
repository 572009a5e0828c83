"""Benchmark motion synthesis: locomotion frames per second, and a 60 s multi-action motion.

Usage:
    .venv/bin/python bench/motion.py [--quick] [--json PATH]

JSON keys: frames_per_s (locomotion controller + the PFNN rollout, one character, one thread),
network_frames_per_s (the rollout alone, in the runtime the controller uses: network_runtime,
"fast" = pfnn_fast.onnx in onnxruntime, the default; "numpy" = services.motion.pfnn_tables on that
graph's phase tables, WANA_PFNN_RUNTIME=numpy), numpy_frames_per_s (the numpy rollout alone, for
comparison), multi_action_ms (plan + synthesise a ~60 s motion
of many actions), multi_action_frames, furnished_action_ms (median handle_synthesize of one action
of a story in a furnished scene-database office, A* routes on warm grid caches, as the editor
calls it), locomotion_source ("pfnn" or "procedural"), and the same timings by the wall clock
(frames_per_s_wall, network_frames_per_s_wall, multi_action_wall_ms).
Targets: frames_per_s >= 20000, multi_action_ms <= 150.

"One core" is measured as CPU time of this single-threaded process (time.process_time; onnxruntime
runs with one intra-op thread), best of N repeats: on a machine whose cores are shared, wall time
also counts the time other processes hold the core. Wall-clock figures are reported alongside.
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

from proto.scene import Room, Scene  # noqa: E402
from proto.ssg import ActionNode, CharacterNode  # noqa: E402
from services.motion.locomotion import (  # noqa: E402
    MODEL_DIR,
    locomote,
    runtime,
    standing_pose_features,
)
from services.motion.pfnn_tables import PhaseTableRuntime  # noqa: E402
from services.motion.planning import plan_actions  # noqa: E402
from services.motion.synthesis import synthesise  # noqa: E402


def _best(fn, repeats: int) -> tuple[float, float]:
    """Best CPU seconds and best wall seconds of fn() over repeats."""
    cpu, wall = np.inf, np.inf
    for _ in range(repeats):
        t0, c0 = time.perf_counter(), time.process_time()
        fn()
        wall = min(wall, time.perf_counter() - t0)
        cpu = min(cpu, time.process_time() - c0)
    return cpu, wall


def bench_locomotion(seconds: float, repeats: int) -> dict:
    rng = np.random.default_rng(3)
    wps = np.cumsum(rng.uniform(-3, 3, (int(seconds / 2) + 2, 2)), axis=0)
    locomote(wps[:3], 1.4)  # warm-up: loads the model
    loco = locomote(wps, 1.4, 0.0)
    frames = len(loco.root_position)
    cpu, wall = _best(lambda: locomote(wps, 1.4, 0.0), repeats)
    out = {
        "frames_per_s": frames / cpu,
        "frames_per_s_wall": frames / wall,
        "locomotion_source": loco.source,
        "locomotion_frames": frames,
        "network_frames_per_s": 0.0,
        "network_frames_per_s_wall": 0.0,
    }
    rt = runtime()
    if rt is not None:
        from services.motion.locomotion import plan_root
        from services.motion.locomotion_features import sensor_features, trajectory_features

        pos, heading, _ = plan_root(wps, 1.4, 0.0)
        ctrl = np.concatenate([trajectory_features(pos, heading), sensor_features(pos, heading)], axis=1)
        cpu, wall = _best(lambda: rt.run(ctrl, standing_pose_features(), 0.0), repeats)
        out |= {
            "network_frames_per_s": len(ctrl) / cpu,
            "network_frames_per_s_wall": len(ctrl) / wall,
            "network_runtime": rt.kind,
        }
        try:
            tables = PhaseTableRuntime(MODEL_DIR / "pfnn_fast.onnx")
        except Exception:  # noqa: BLE001 - no fast graph: nothing to compare
            tables = None
        if tables is not None:
            cpu, _ = _best(lambda: tables.run(ctrl, standing_pose_features(), 0.0), max(2, repeats // 3))
            out["numpy_frames_per_s"] = len(ctrl) / cpu
    return out


def bench_furnished_actions(repeats: int) -> dict:
    """Median ms of one handle_synthesize per action (the orchestrator's call) in a furnished office."""
    from proto.common import Header
    from proto.motion import SegmentEndState, SynthesizeRequest
    from services.motion.handlers import handle_synthesize
    from wana.assets.scenedb import load_scenedb

    scene = next(r.scene for r in load_scenedb() if r.room_type == "office")
    names = {o.category: o.id for o in scene.objects}
    seat = names.get("office_chair") or names.get("chair") or ""
    thing = names.get("computer") or names.get("desk") or ""
    away = names.get("door") or names.get("cabinet") or ""
    acts = [
        ActionNode(verb="walk", action="walk", destination=seat),
        ActionNode(verb="sit", action="sit", target=seat),
        ActionNode(verb="type", action="type", target=thing),
        ActionNode(verb="walk", action="walk", destination=away),
        ActionNode(verb="wave", action="wave"),
    ]
    times: list[float] = []
    for rep in range(repeats + 1):
        state = SegmentEndState(x=0.0, z=-scene.room.depth / 2 + 0.6, yaw=0.0)
        for a in acts:
            req = SynthesizeRequest(
                header=Header(),
                character=CharacterNode(name="bench", actions=[a]),
                scene=scene,
                start=(state.x, state.z, state.yaw),
                start_state=state,
            )
            c0 = time.process_time()
            reply = handle_synthesize(req)
            if rep:  # the first pass warms the catalog and the grid caches
                times.append(time.process_time() - c0)
            state = reply.end_states[-1] if reply.end_states else state
    return {"furnished_action_ms": float(np.median(times)) * 1000}


def bench_multi_action(repeats: int) -> dict:
    acts = [
        "wave",
        "clap",
        "walk",
        "think",
        "bow",
        "nod",
        "talk",
        "walk",
        "point",
        "shrug",
        "drink",
        "walk",
        "call_with_phone",
        "stretch",
        "look_around",
        "walk",
        "hug",
        "read",
        "salute",
        "walk",
        "celebrate",
        "idle",
    ]
    ch = CharacterNode(name="bench", actions=[ActionNode(verb=a, action=a) for a in acts])
    scene = Scene(room=Room(room_type="office", width=20, depth=20, height=3))
    motion, _, _ = synthesise(plan_actions(ch, scene, (0.0, 0.0, 0.0)))
    cpu, wall = _best(lambda: synthesise(plan_actions(ch, scene, (0.0, 0.0, 0.0))), repeats)
    return {
        "multi_action_ms": cpu * 1000,
        "multi_action_wall_ms": wall * 1000,
        "multi_action_frames": int(motion.rotations.shape[0]),
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--quick", action="store_true", help="fewer repeats (< 30 s)")
    parser.add_argument("--json", type=Path, default=None)
    args = parser.parse_args(argv)
    try:
        import torch

        torch.set_num_threads(1)
    except ImportError:
        pass
    result = (
        bench_locomotion(60.0, 3 if args.quick else 10)
        | bench_multi_action(3 if args.quick else 10)
        | bench_furnished_actions(1 if args.quick else 3)
    )
    result = {k: round(v, 2) if isinstance(v, float) else v for k, v in result.items()}
    print(f"{'metric':24s} value")
    for k, v in result.items():
        print(f"{k:24s} {v}")
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(result, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
