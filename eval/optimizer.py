"""Evaluate the layout/motion optimiser (paper §4.3, Algorithm 2) on interaction scenarios.

Usage:
    .venv/bin/python eval/optimizer.py [--quick] [--json PATH] [--png PATH] [--steps 100] [--seed 0]

Each scenario is a scene, a character's actions and the interaction to optimise (sit on a chair
behind a desk, type on a laptop, play the piano, walk to an occluded chair, punch a bag, write at a
table; 33 in all, 6 with --quick). The motion comes from the motion service (plan + synthesis with
A* routes; a walk with no route goes straight through). The optimiser anneals with the anchored
surrogate and re-synthesises the winner through the motion service, which is what is scored.

Per scenario: boxes hit while walking, C_D (eq. 1), C_T (eq. 2, metres) and the largest contact
distance, before and after. JSON keys: collision_free_share (walking hits no box after),
contact_ok_share (C_T <= 5 cm after), ms_per_optimisation (mean annealing wall time), their
"_before" counterparts, and per-scenario rows. Targets: collision_free_share >= 0.9,
contact_ok_share >= 0.9. The PNG plots the annealing's cost curves like the paper's Figure 12.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from dataclasses import dataclass, replace
from pathlib import Path

import msgspec
import numpy as np

os.environ.setdefault("OMP_NUM_THREADS", "1")
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from proto.optimizer import Interaction, OptimiseSettings  # noqa: E402
from proto.scene import PlacedObject, Room, Scene  # noqa: E402
from proto.ssg import ActionNode, CharacterNode  # noqa: E402
from services.optimizer.resynthesis import motion_service_fn, planned_contacts  # noqa: E402
from services.optimizer.scoring import InteractionScorer  # noqa: E402
from services.optimizer.verify import optimise_and_verify  # noqa: E402
from wana.compose import compose  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
CONTACT_OK_M = 0.05
ROOM = Room(room_type="office", width=5.0, depth=5.0, height=3.0)
PI = float(np.pi)


@dataclass(frozen=True)
class Scenario:
    name: str
    family: str
    scene: Scene
    character: CharacterNode
    start: tuple[float, float, float]  # x, z, yaw
    interaction: Interaction


def _obj(
    id_: str,
    category: str,
    x: float,
    z: float,
    yaw: float = 0.0,
    y: float = 0.0,
    support: str = "",
    seed: int = 0,
) -> PlacedObject:
    return PlacedObject(id=id_, category=category, position=(x, y, z), yaw=yaw, support=support, seed=seed)


def _acts(*steps: tuple[str, str]) -> CharacterNode:
    """(action, target) pairs -> the character "Eve"."""
    nodes = []
    for action, target in steps:
        if action == "walk":
            nodes.append(ActionNode(verb=action, action=action, destination=target))
        else:
            nodes.append(ActionNode(verb=action, action=action, target=target))
    return CharacterNode(name="Eve", actions=nodes)


def sit_behind_desk(gap: float, x: float) -> Scenario:
    """A chair pushed towards a desk; sitting down brings the knees against it."""
    desk_z = -0.9
    objs = [_obj("desk", "desk", x, desk_z), _obj("chair", "office_chair", x, desk_z + gap, yaw=PI)]
    inter = Interaction(character="Eve", action="sit", targets=["chair"])
    return Scenario(
        f"sit_behind_desk_gap{gap:.2f}_x{x:+.1f}",
        "sit on the chair behind a desk",
        Scene(room=ROOM, objects=objs),
        _acts(("sit", "chair")),
        (1.8, 1.8, PI),
        inter,
    )


def type_on_laptop(extra: float, side: float) -> Scenario:
    """Sit at a desk and type on a laptop, the chair ``extra`` metres further back than arm's reach allows."""
    desk_z = -0.9
    objs = [
        _obj("desk", "desk", 0.0, desk_z),
        _obj("chair", "office_chair", 0.0, desk_z + 0.78 + extra, yaw=PI),
        _obj("laptop", "laptop", side, desk_z - 0.1, y=0.75, support="desk"),
    ]
    inter = Interaction(character="Eve", action="type", targets=["chair", "laptop"])
    return Scenario(
        f"type_on_laptop_extra{extra:.2f}_side{side:+.2f}",
        "type on a laptop",
        Scene(room=ROOM, objects=objs),
        _acts(("sit", "chair"), ("type", "laptop")),
        (1.8, 1.8, PI),
        inter,
    )


def play_piano(gap: float, side: float) -> Scenario:
    """A piano bench too far from (or too close to) the piano's keys."""
    piano_z = -2.15
    objs = [
        _obj("piano", "piano", 0.0, piano_z),
        _obj("bench", "piano_bench", side, piano_z + 0.31 + gap, yaw=PI),
    ]
    inter = Interaction(character="Eve", action="play_piano", targets=["bench", "piano"])
    return Scenario(
        f"play_piano_gap{gap:.2f}_side{side:+.2f}",
        "play the piano",
        Scene(room=ROOM, objects=objs),
        _acts(("sit", "bench"), ("play_piano", "piano")),
        (1.5, 1.5, PI),
        inter,
    )


def occluded_chair(spread: float, seed: int) -> Scenario:
    """A chair closed in by boxes and plants: no route until one of them moves."""
    rng = np.random.default_rng(seed)
    cx, cz = float(rng.uniform(-1.2, 0.0)), float(rng.uniform(-1.6, -0.8))
    objs = [_obj("chair", "chair", cx, cz, yaw=float(rng.uniform(-0.3, 0.3)))]
    ring = [("box", 0.0), ("plant", PI / 2), ("box", PI), ("plant", 3 * PI / 2)]
    for i, (cat, ang) in enumerate(ring):
        a = ang + float(rng.uniform(-0.2, 0.2))
        objs.append(_obj(f"{cat}{i}", cat, cx + spread * np.sin(a), cz + spread * np.cos(a), yaw=a, seed=i))
    inter = Interaction(character="Eve", action="sit", targets=["chair"])
    return Scenario(
        f"occluded_chair_spread{spread:.2f}_s{seed}",
        "walk to an occluded chair",
        Scene(room=ROOM, objects=objs),
        _acts(("walk", "chair"), ("sit", "chair")),
        (1.8, 1.8, PI),
        inter,
    )


def punch_bag(offset: float, side: float) -> Scenario:
    """A boxing bag hung next to a bookshelf that the punching arm can hit."""
    objs = [
        _obj("bag", "boxing_bag", 0.0, -0.8),
        _obj("shelf", "bookshelf", side * (0.75 + offset), -0.55 + 0.2, yaw=-side * PI / 2),
    ]
    inter = Interaction(character="Eve", action="punch_bag", targets=["bag"])
    return Scenario(
        f"punch_bag_offset{offset:.2f}_side{side:+.0f}",
        "punch a bag",
        Scene(room=ROOM, objects=objs),
        _acts(("punch_bag", "bag")),
        (1.5, 1.5, PI),
        inter,
    )


def write_at_table(gap: float, x: float) -> Scenario:
    """A dining chair too far from a table to write on it."""
    objs = [_obj("table", "table", x, -0.9), _obj("chair", "dining_chair", x, -0.9 + gap, yaw=PI)]
    inter = Interaction(character="Eve", action="write", targets=["chair", "table"])
    return Scenario(
        f"write_at_table_gap{gap:.2f}_x{x:+.1f}",
        "write at a table",
        Scene(room=ROOM, objects=objs),
        _acts(("sit", "chair"), ("write", "table")),
        (1.8, 1.8, PI),
        inter,
    )


def scenarios() -> list[Scenario]:
    """All evaluation scenarios, in a fixed order."""
    out = [
        sit_behind_desk(g, x)
        for g, x in [(0.55, 0.0), (0.6, 0.5), (0.62, -0.5), (0.66, 0.0), (0.7, 0.3), (0.58, -0.2)]
    ]
    out += [
        type_on_laptop(e, s)
        for e, s in [(0.1, 0.0), (0.15, 0.0), (0.2, 0.2), (0.25, -0.2), (0.12, 0.3), (0.18, 0.0)]
    ]
    out += [play_piano(g, s) for g, s in [(0.2, 0.0), (0.35, 0.0), (0.5, 0.1), (0.6, -0.1), (0.45, 0.0)]]
    out += [
        occluded_chair(sp, s) for sp, s in [(0.65, 1), (0.7, 2), (0.6, 3), (0.75, 4), (0.65, 5), (0.7, 6)]
    ]
    out += [punch_bag(o, s) for o, s in [(0.0, 1), (0.05, -1), (0.1, 1), (-0.05, -1), (0.15, 1)]]
    out += [write_at_table(g, x) for g, x in [(0.95, 0.0), (1.0, 0.4), (0.9, -0.4), (1.05, 0.0), (0.85, 0.2)]]
    return out


def quick_subset(all_: list[Scenario]) -> list[Scenario]:
    """One scenario per family."""
    seen: dict[str, Scenario] = {}
    for s in all_:
        seen.setdefault(s.family, s)
    return list(seen.values())


def with_planned_contacts(sc: Scenario) -> Scenario:
    """The scenario with its interaction's contacts set to the pairs the motion service aims at."""
    pairs = [p for p in planned_contacts(sc.character, sc.scene) if p.object_id in sc.interaction.targets]
    return replace(sc, interaction=msgspec.structs.replace(sc.interaction, contacts=pairs))


def run_scenario(sc: Scenario, settings: OptimiseSettings, candidates: int = 4) -> dict:
    """Synthesise, optimise, verify; the row of the results table."""
    sc = with_planned_contacts(sc)
    synth = motion_service_fn(sc.character, sc.start)
    motion = synth(sc.scene)
    res = optimise_and_verify(
        sc.scene, sc.interaction, motion, settings=settings, verifier=synth, candidates=candidates
    )
    scorer = InteractionScorer(sc.scene, sc.interaction, frame_stride=1)
    b = scorer.score_scenes([sc.scene], [motion]).report(0, scorer.pairs)
    a = res.after
    return {
        "name": sc.name,
        "family": sc.family,
        "walk_hits_before": b.locomotion_collided_boxes,
        "walk_hits_after": a.locomotion_collided_boxes,
        "hits_before": b.collided_boxes,
        "hits_after": a.collided_boxes,
        "c_d_before": b.collision_cost,
        "c_d_after": a.collision_cost,
        "c_t_before": b.contact_cost,
        "c_t_after": a.contact_cost,
        "contact_max_before": max(b.contact_distances, default=0.0),
        "contact_max_after": max(a.contact_distances, default=0.0),
        "cost_before": b.cost,
        "cost_after": a.cost,
        "ms": res.search.elapsed_ms,
        "steps": res.search.steps_run,
        "result": res.made,
        "contacts": [f"{p.object_id}.{p.point}:{p.joint}" for p in sc.interaction.contacts],
        "moved": res.search.movable,
        "cost_curve": res.search.cost_curve,
        "best_curve": res.search.best_curve,
    }


def plot_curves(rows: list[dict], path: Path) -> None:
    """Cost of the current layout per annealing step, one line per family (as the paper's Figure 12)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    shown: set[str] = set()
    for r in rows:
        if r["family"] in shown:
            continue
        shown.add(r["family"])
        axes[0].plot(r["cost_curve"], label=r["family"], lw=1.2)
        axes[1].plot(np.asarray(r["best_curve"]) / max(r["best_curve"][0], 1e-9), label=r["family"], lw=1.2)
    axes[0].set(title="cost C of the current layout", xlabel="iteration", ylabel="C = C_D + 10 C_T")
    axes[1].set(title="best cost so far (relative to the input)", xlabel="iteration", ylabel="C / C_0")
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    compose()  # the optimiser re-synthesises through the motion service, as its runtimes wire it
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument(
        "--quick",
        action="store_true",
        help="one scenario per family, 30 steps, 2 verified candidates (< 30 s)",
    )
    ap.add_argument("--json", type=Path, default=None, help="write the metrics and per-scenario rows here")
    ap.add_argument(
        "--png",
        type=Path,
        default=REPO / "out" / "eval" / "optimizer_cost_curves.png",
        help="cost-curve figure (default out/eval/optimizer_cost_curves.png)",
    )
    ap.add_argument("--steps", type=int, default=None, help="annealing steps (default 100; 40 with --quick)")
    ap.add_argument("--seed", type=int, default=0, help="annealing seed (recorded in the JSON)")
    args = ap.parse_args(argv)
    from tqdm import tqdm

    todo = scenarios()
    if args.quick:
        todo = quick_subset(todo)
    steps = args.steps if args.steps is not None else (30 if args.quick else 100)
    candidates = 2 if args.quick else 4
    settings = OptimiseSettings(seed=args.seed, steps=steps)
    rows = []
    t0 = time.perf_counter()
    for sc in tqdm(todo, desc="scenarios", unit="scn"):
        rows.append(run_scenario(sc, settings, candidates))
    wall = time.perf_counter() - t0
    n = len(rows)
    metrics = {
        "collision_free_share": sum(r["walk_hits_after"] == 0 for r in rows) / n,
        "contact_ok_share": sum(r["c_t_after"] <= CONTACT_OK_M for r in rows) / n,
        "ms_per_optimisation": float(np.mean([r["ms"] for r in rows])),
        "collision_free_share_before": sum(r["walk_hits_before"] == 0 for r in rows) / n,
        "contact_ok_share_before": sum(r["c_t_before"] <= CONTACT_OK_M for r in rows) / n,
        "collision_cost_before": float(np.mean([r["c_d_before"] for r in rows])),
        "collision_cost_after": float(np.mean([r["c_d_after"] for r in rows])),
        "contact_cost_before": float(np.mean([r["c_t_before"] for r in rows])),
        "contact_cost_after": float(np.mean([r["c_t_after"] for r in rows])),
        "scenarios": n,
        "steps": steps,
        "candidates": candidates,
        "seed": args.seed,
        "quick": bool(args.quick),
        "wall_s": wall,
    }
    print(
        f"{'scenario':44s} {'walk hits':>11s} {'C_D':>13s} {'C_T cm':>13s} {'max cm':>13s} {'ms':>6s} result"
    )
    for r in rows:
        print(
            f"{r['name']:44s} {r['walk_hits_before']:4d} -> {r['walk_hits_after']:<4d} "
            f"{r['c_d_before']:.3f} -> {r['c_d_after']:.3f} {100 * r['c_t_before']:5.1f} -> {100 * r['c_t_after']:<5.1f} "
            f"{100 * r['contact_max_before']:5.1f} -> {100 * r['contact_max_after']:<5.1f} {r['ms']:6.0f} {r['result']}"
        )
    print()
    for key in ("collision_free_share", "contact_ok_share", "ms_per_optimisation"):
        print(f"{key:28s} {metrics[key]:8.3f}   (before: {metrics.get(key + '_before', float('nan')):.3f})")
    plot_curves(rows, args.png)
    print(f"cost curves: {args.png}")
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps({**metrics, "rows": rows}, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
