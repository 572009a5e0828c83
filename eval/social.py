"""Evaluate the social-interaction model on hand-written two-character stories with expected orderings.

Usage:
    .venv/bin/python eval/social.py [--quick] [--json PATH] [--seed 0]

Each case is one or two stories in the notation of ``services.social.sketch`` and an expectation that
compares the plans (friends stand closer than a boss and an employee; an angry character frowns; an
apology lowers the apologiser's dominance; ...). 24 cases; --quick times fewer repetitions.

JSON keys: expectations_met (share of cases whose expectation holds), energy_drop (mean over all plans of
(E_initial - E_final) / E_initial, the share of the initial energy the sampler removes), ms_per_plan (mean
wall time of plan_social per plan over the cases' stories and a two-character ten-action scene, one core).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from proto.social import SocialPlan  # noqa: E402
from services.social.face import face_weights  # noqa: E402
from services.social.plan import plan_social  # noqa: E402
from services.social.sketch import sketch_graphs  # noqa: E402
from wana.assets.characters import EXPRESSIONS  # noqa: E402

SMILE, FROWN = EXPRESSIONS.index("smile"), EXPRESSIONS.index("frown")
TEN_ACTIONS = (
    "rel Tom Mary colleagues; act Tom wave Mary; act Mary wave Tom; act Tom talk Mary; act Mary nod; "
    "emo Tom angry; act Tom criticize Mary; act Mary apologize Tom; act Tom shake_head; act Mary cry; "
    "act Tom comfort Mary; act Mary hug Tom"
)


def emo(plan: SocialPlan, who: str, step: int = -1) -> tuple[float, float, float]:
    c = next(c for c in plan.characters if c.name == who)
    return c.emotions[step].vad


def pair_d(plan: SocialPlan, a: str = "Tom", b: str = "Mary") -> float:
    return next(p.distance_m for p in plan.pairs if p.character == a and p.other == b)


def act_d(plan: SocialPlan, who: str, k: int = 0) -> float:
    return next(d.distance_m for d in plan.action_distances if d.character == who and d.action_index == k)


def delay(plan: SocialPlan, responder: str, k: int) -> float:
    return next(r.delay_s for r in plan.responses if r.responder == responder and r.action_index == k)


def frowns(plan: SocialPlan, who: str, step: int = -1) -> bool:
    w = face_weights(emo(plan, who, step))
    return bool(w[FROWN] > w[SMILE] and emo(plan, who, step)[0] < 0)


def smiles(plan: SocialPlan, who: str, step: int = -1) -> bool:
    w = face_weights(emo(plan, who, step))
    return bool(w[SMILE] > w[FROWN] and emo(plan, who, step)[0] > 0)


Check = Callable[[SocialPlan, SocialPlan | None], bool]
TALK = "act Tom talk Mary"
CASES: list[tuple[str, str, str | None, Check]] = [
    (
        "friends stand closer than boss and employee",
        f"rel Tom Mary friends; {TALK}",
        f"rel Mary Tom boss; {TALK}",
        lambda a, b: pair_d(a) < pair_d(b) and act_d(a, "Tom") < act_d(b, "Tom"),
    ),  # type: ignore[arg-type]
    (
        "a couple stands closer than strangers",
        f"rel Tom Mary couple; {TALK}",
        f"rel Tom Mary strangers; {TALK}",
        lambda a, b: pair_d(a) < pair_d(b),
    ),  # type: ignore[arg-type]
    (
        "friends stand closer than enemies",
        f"rel Tom Mary friends; {TALK}",
        f"rel Tom Mary enemies; {TALK}",
        lambda a, b: pair_d(a) < pair_d(b),
    ),  # type: ignore[arg-type]
    (
        "teacher and student stand farther apart than friends",
        f"rel Tom Mary teacher; {TALK}",
        f"rel Tom Mary friends; {TALK}",
        lambda a, b: pair_d(a) > pair_d(b),
    ),  # type: ignore[arg-type]
    (
        "colleagues stand closer than strangers",
        f"rel Tom Mary colleagues; {TALK}",
        f"rel Tom Mary strangers; {TALK}",
        lambda a, b: pair_d(a) < pair_d(b),
    ),  # type: ignore[arg-type]
    ("an angry character frowns", "emo Tom angry; act Tom talk Mary", None, lambda a, _: frowns(a, "Tom", 0)),
    (
        "a happy character smiles",
        "emo Mary happy; act Mary wave Tom",
        None,
        lambda a, _: smiles(a, "Mary", 0),
    ),
    ("a sad character frowns", "emo Mary sad", None, lambda a, _: frowns(a, "Mary", 0)),
    (
        "an apology lowers the apologiser's dominance",
        f"{TALK}; act Mary apologize Tom",
        f"{TALK}; act Mary talk Tom",
        lambda a, b: emo(a, "Mary", 1)[2] < emo(b, "Mary", 1)[2],
    ),  # type: ignore[arg-type]
    ("the one criticised feels worse", "act Tom criticize Mary", None, lambda a, _: emo(a, "Mary", 0)[0] < 0),
    ("the one hugged feels better", "act Tom hug Mary", None, lambda a, _: smiles(a, "Mary", 0)),
    (
        "a boss shows more dominance than the employee",
        "rel Mary Tom boss; act Mary talk Tom; act Tom talk Mary",
        None,
        lambda a, _: emo(a, "Mary", 1)[2] > emo(a, "Tom", 1)[2],
    ),
    (
        "an employee answers the boss sooner than the boss answers",
        "rel Mary Tom boss; act Mary talk Tom; act Tom talk Mary; act Mary talk Tom",
        None,
        lambda a, _: delay(a, "Tom", 0) < delay(a, "Mary", 0),
    ),
    (
        "a hug comes closer than talking",
        "rel Tom Mary friends; act Tom hug Mary",
        f"rel Tom Mary friends; {TALK}",
        lambda a, b: act_d(a, "Tom") < act_d(b, "Tom"),
    ),  # type: ignore[arg-type]
    (
        "the proposed reaction to criticism is negative",
        "act Tom criticize Mary",
        None,
        lambda a, _: (
            len(a.proposals) == 1 and a.proposals[0].character == "Mary" and a.proposals[0].vad[0] < 0
        ),
    ),
    (
        "the proposed reaction to a hug is positive",
        "act Tom hug Mary",
        None,
        lambda a, _: len(a.proposals) == 1 and a.proposals[0].vad[0] > 0,
    ),
    (
        "no reaction is proposed when the text gives one",
        "act Tom criticize Mary; act Mary apologize Tom",
        None,
        lambda a, _: (
            not any(p.character == "Mary" for p in a.proposals)
            and any(r.responder == "Mary" and r.response_index == 0 for r in a.responses)
        ),
    ),
    (
        "a hug between unrelated characters raises their intimacy",
        "act Tom hug Mary",
        f"{TALK}",
        lambda a, b: a.pairs[0].intimacy > b.pairs[0].intimacy,
    ),  # type: ignore[union-attr]
    (
        "enemies who quarrel both frown",
        "rel Tom Mary enemies; both Tom Mary quarrel",
        None,
        lambda a, _: frowns(a, "Tom", 1) and frowns(a, "Mary", 1),
    ),
    (
        "a furious character answers sooner than a calm one",
        "emo Tom furious; act Mary talk Tom; act Tom talk Mary",
        "emo Tom calm; act Mary talk Tom; act Tom talk Mary",
        lambda a, b: delay(a, "Tom", 0) < delay(b, "Tom", 0),
    ),  # type: ignore[arg-type]
    (
        "anger fades but lingers a sentence later",
        "emo Tom angry; act Tom talk Mary",
        None,
        lambda a, _: emo(a, "Tom", 0)[0] < emo(a, "Tom", 1)[0] < 0,
    ),
    (
        "a scared character keeps more distance than a happy one",
        f"emo Tom scared; {TALK}",
        f"emo Tom happy; {TALK}",
        lambda a, b: act_d(a, "Tom") > act_d(b, "Tom"),
    ),  # type: ignore[arg-type]
    (
        "friends who hug both smile",
        "rel Tom Mary friends; act Tom hug Mary; act Mary hug Tom",
        None,
        lambda a, _: smiles(a, "Tom", 2) and smiles(a, "Mary", 2),
    ),
    ("the same seed gives the same plan", TEN_ACTIONS, TEN_ACTIONS, lambda a, b: a == b),
]


def timed_plan(text: str, seed: int, reps: int) -> tuple[SocialPlan, list[float]]:
    graphs = sketch_graphs(text)
    times = []
    plan = plan_social(graphs, seed=seed)
    for _ in range(reps):
        t = time.perf_counter()
        plan_social(graphs, seed=seed)
        times.append((time.perf_counter() - t) * 1e3)
    return plan, times


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0], epilog="Cases: " + "; ".join(c[0] for c in CASES)
    )
    parser.add_argument("--quick", action="store_true", help="fewer timing repetitions (well under 30 s)")
    parser.add_argument("--json", type=Path, help="write the summary here")
    parser.add_argument("--seed", type=int, default=0, help="sampler seed (default 0)")
    args = parser.parse_args(argv)
    reps = 1 if args.quick else 5
    rows, drops, times = [], [], []
    for name, story_a, story_b, check in CASES:
        plan_a, ta = timed_plan(story_a, args.seed, reps)
        plan_b, tb = timed_plan(story_b, args.seed, reps) if story_b else (None, [])
        ok = bool(check(plan_a, plan_b))
        for p in (plan_a, plan_b):
            if p is not None and p.energy_initial > 0:
                drops.append((p.energy_initial - p.energy_final) / p.energy_initial)
        times += ta + tb
        rows.append({"case": name, "met": ok, "ms": round(statistics.mean(ta + tb), 2)})
    ten, t10 = timed_plan(TEN_ACTIONS, args.seed, 20 if args.quick else 100)
    times += t10
    summary = {
        "expectations_met": round(sum(r["met"] for r in rows) / len(rows), 4),
        "energy_drop": round(statistics.mean(drops), 4),
        "ms_per_plan": round(statistics.mean(times), 3),
    }
    width = max(len(r["case"]) for r in rows)
    print(f"{'case':<{width}}  met    ms")
    for r in rows:
        print(f"{r['case']:<{width}}  {'yes' if r['met'] else 'NO ':<5} {r['ms']:>5.2f}")
    print()
    print(
        f"two characters, ten actions: {statistics.mean(t10):.2f} ms per plan (median {statistics.median(t10):.2f}), "
        f"{ten.steps} MH steps, energy {ten.energy_initial:.2f} -> {ten.energy_final:.2f}"
    )
    print(
        f"expectations_met {summary['expectations_met']:.3f}  energy_drop {summary['energy_drop']:.3f}  "
        f"ms_per_plan {summary['ms_per_plan']:.2f}  (seed {args.seed})"
    )
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(summary, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
