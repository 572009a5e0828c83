"""Replicate the paper's Figure 8: relation-first matching (ours) against object-first LDS, and check
the composed scenes.

Usage:
    .venv/bin/python eval/retrieval.py [--quick] [--json PATH] [--png PATH] [--queries N] [--seed S]

Data: eval/data/retrieval/NN_name.txt (a scene script in the `$` syntax) and NN_name.json (its gold SSG,
hand-written: objects with catalog categories and attributes, relations), 23 scripts over 18 room kinds.
The evaluation does not depend on the NLP parser.

1. Matching (Fig. 8): for each query size k in {5, 10, 15} (nodes = objects + relations), N query SSGs
   are drawn from the scripts (a script at random, then a connected-first growth of its SSG to exactly k
   nodes; seeded). Each query is matched against the scene database by ours (Algorithm 1,
   services.retrieval.matching) and by LDS (services.retrieval.lds); both are scored by the same
   function (mean over the query's nodes of object similarity / relation agreement, in [0, 1]).
   Box-plot statistics per size and method are printed and drawn (PNG). Target: ours' median >= LDS's.
2. Composition: every script is composed (services.retrieval.compose, seed 0); reported are the share
   of stated relations that hold (target 100 %) and the number of overlapping object pairs (target 0).

JSON keys: ours_median and lds_median ({"5": .., "10": .., "15": ..}), relations_held (share in [0, 1]),
overlaps (count). --quick: 12 queries per size and 8 scripts composed (under 30 s).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from proto.ssg import ObjectNode, RelationNode  # noqa: E402

DATA = REPO / "eval" / "data" / "retrieval"
SIZES = (5, 10, 15)
SEED = 20210907  # fixed: the paper's venue date; recorded in the printed table


def load_scripts(folder: Path = DATA) -> list[dict]:
    """Each script: id, room_type, text, objects (ObjectNode), relations (RelationNode)."""
    scripts = []
    for path in sorted(folder.glob("*.json")):
        gold = json.loads(path.read_text())
        text_path = path.with_suffix(".txt")
        scripts.append(
            {
                "id": gold["id"],
                "room_type": gold["room_type"],
                "text": text_path.read_text() if text_path.exists() else "",
                "objects": [ObjectNode(**o) for o in gold["objects"]],
                "relations": [RelationNode(**r) for r in gold["relations"]],
            }
        )
    return scripts


def draw_query(
    script: dict, size: int, rng: np.random.Generator
) -> tuple[list[ObjectNode], list[RelationNode]]:
    """A sub-SSG of exactly ``size`` nodes: grow from a random object, preferring relations that touch it.

    Raises:
        ValueError: when the script has fewer than ``size`` nodes.
    """
    objects: list[ObjectNode] = script["objects"]
    relations: list[RelationNode] = script["relations"]
    if len(objects) + len(relations) < size:
        raise ValueError(f"{script['id']} has fewer than {size} nodes")
    by_id = {o.id: o for o in objects}
    chosen_o = [objects[int(rng.integers(len(objects)))].id]
    chosen_r: list[int] = []
    while len(chosen_o) + len(chosen_r) < size:
        left = size - len(chosen_o) - len(chosen_r)
        have = set(chosen_o)
        closing = [
            i for i, r in enumerate(relations) if i not in chosen_r and r.subject in have and r.object in have
        ]
        growing = [
            i
            for i, r in enumerate(relations)
            if i not in chosen_r and (r.subject in have) != (r.object in have)
        ]
        if closing and (left == 1 or not growing or rng.random() < 0.5):
            chosen_r.append(closing[int(rng.integers(len(closing)))])
        elif growing and left >= 2:
            i = growing[int(rng.integers(len(growing)))]
            r = relations[i]
            chosen_o.append(r.object if r.subject in have else r.subject)
            chosen_r.append(i)
        else:
            free = [o.id for o in objects if o.id not in have]
            if not free:  # nothing left to add but relations to far objects: restart from another seed
                return draw_query(script, size, rng)
            chosen_o.append(free[int(rng.integers(len(free)))])
    order = {o.id: k for k, o in enumerate(objects)}
    return (
        [by_id[i] for i in sorted(chosen_o, key=order.__getitem__)],
        [relations[i] for i in sorted(chosen_r)],
    )


def box_stats(values: list[float]) -> dict[str, float]:
    a = np.asarray(values, dtype=np.float64)
    q1, med, q3 = np.percentile(a, [25, 50, 75])
    return {
        "min": float(a.min()),
        "q1": float(q1),
        "median": float(med),
        "q3": float(q3),
        "max": float(a.max()),
        "mean": float(a.mean()),
    }


def plot(scores: dict[str, dict[int, list[float]]], path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=120)
    width = 0.32
    colours = {"ours": "#d95f02", "lds": "#1b9e77"}
    labels = {"ours": "ours (relation-first)", "lds": "LDS (object-first)"}
    for k, method in enumerate(("lds", "ours")):
        data = [scores[method][s] for s in SIZES]
        pos = np.arange(len(SIZES)) + (k - 0.5) * (width + 0.04)
        bp = ax.boxplot(data, positions=pos, widths=width, patch_artist=True, showfliers=True)
        for box in bp["boxes"]:
            box.set_facecolor(colours[method])
            box.set_alpha(0.75)
        for med in bp["medians"]:
            med.set_color("black")
        ax.plot([], [], color=colours[method], lw=8, alpha=0.75, label=labels[method])
    ax.set_xticks(np.arange(len(SIZES)))
    ax.set_xticklabels([f"{s} nodes" for s in SIZES])
    ax.set_ylabel("matching score")
    ax.set_ylim(0.0, 1.02)
    ax.set_title("Query SSG matching against the scene database (cf. paper Fig. 8)")
    ax.legend(loc="lower left")
    ax.grid(axis="y", alpha=0.3)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path)
    plt.close(fig)
    return path


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        description="Replicate the paper's Fig. 8 (ours vs LDS matching scores for 5/10/15-node query SSGs) "
        "and check composed scenes (relations held, overlapping pairs).",
    )
    parser.add_argument("--quick", action="store_true", help="fewer queries and scripts (under 30 s)")
    parser.add_argument(
        "--json", metavar="PATH", help="write ours_median, lds_median, relations_held, overlaps"
    )
    parser.add_argument(
        "--png",
        metavar="PATH",
        default=str(REPO / "out" / "eval" / "retrieval_fig8.png"),
        help="box plot of the matching scores (default: out/eval/retrieval_fig8.png)",
    )
    parser.add_argument("--queries", type=int, default=0, help="queries per size (default 60, --quick 12)")
    parser.add_argument("--seed", type=int, default=SEED, help=f"query sampling seed (default {SEED})")
    args = parser.parse_args(argv)

    from tqdm import tqdm

    from services.retrieval.compose import compose_scene
    from services.retrieval.database import default_db
    from services.retrieval.lds import match_object_first
    from services.retrieval.matching import match_relation_first

    t0 = time.perf_counter()
    scripts = load_scripts()
    db = default_db()
    n = args.queries or (12 if args.quick else 60)
    scores: dict[str, dict[int, list[float]]] = {
        "ours": {s: [] for s in SIZES},
        "lds": {s: [] for s in SIZES},
    }
    wins = {s: 0 for s in SIZES}
    for size in SIZES:
        rng = np.random.default_rng([args.seed, size])
        for _ in tqdm(range(n), desc=f"match {size:>2}-node queries", leave=False):
            script = scripts[int(rng.integers(len(scripts)))]
            objects, relations = draw_query(script, size, rng)
            ours = match_relation_first(objects, relations, db).score
            lds = match_object_first(objects, relations, db).score
            scores["ours"][size].append(ours)
            scores["lds"][size].append(lds)
            wins[size] += ours >= lds - 1e-12

    composed = scripts[:8] if args.quick else scripts
    held = stated = overlaps = 0
    failures: list[str] = []
    times = []
    for script in tqdm(composed, desc="compose scripts", leave=False):
        t = time.perf_counter()
        _, report = compose_scene(
            script["objects"], script["relations"], room_type=script["room_type"], seed=0
        )
        times.append(time.perf_counter() - t)
        held += sum(r.held for r in report.relations)
        stated += len(report.relations)
        overlaps += report.overlaps
        failures += [
            f"{script['id']}: {r.subject} {r.relation} {r.object}" for r in report.relations if not r.held
        ]
        failures += [f"{script['id']}: {a} overlaps {b}" for a, b in report.overlap_pairs]

    stats = {m: {s: box_stats(scores[m][s]) for s in SIZES} for m in scores}
    png = plot(scores, Path(args.png))
    print(
        f"\nQuery SSG matching (seed {args.seed}, {n} queries per size, {len(scripts)} scripts, "
        f"{len(db)} database scenes)"
    )
    print(
        f"{'size':>5} {'method':>6} {'min':>6} {'q1':>6} {'median':>7} {'q3':>6} {'max':>6} {'mean':>6}  ours>=lds"
    )
    for s in SIZES:
        for m in ("ours", "lds"):
            st = stats[m][s]
            tail = f"  {wins[s]}/{n}" if m == "ours" else ""
            print(
                f"{s:>5} {m:>6} {st['min']:6.3f} {st['q1']:6.3f} {st['median']:7.3f} {st['q3']:6.3f} "
                f"{st['max']:6.3f} {st['mean']:6.3f}{tail}"
            )
    share = held / stated if stated else 1.0
    print(
        f"\nComposition of {len(composed)} scripts (seed 0): relations held {held}/{stated} = {share:.1%} "
        f"(target 100 %), overlapping pairs {overlaps} (target 0), "
        f"compose time median {1000 * float(np.median(times)):.0f} ms"
    )
    for f in failures:
        print(f"  - {f}")
    print(f"box plot: {png}\n(total {time.perf_counter() - t0:.1f} s)")

    result = {
        "ours_median": {str(s): round(stats["ours"][s]["median"], 4) for s in SIZES},
        "lds_median": {str(s): round(stats["lds"][s]["median"], 4) for s in SIZES},
        "relations_held": round(share, 4),
        "overlaps": int(overlaps),
    }
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps(result, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
