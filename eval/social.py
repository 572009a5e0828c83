"""Evaluate the social-interaction model on hand-written two-character stories with expected orderings.

Usage:
    .venv/bin/python eval/social.py [--quick] [--json PATH] [--seed 0]

Each case is one or two stories in the notation of ``services.social.sketch`` and an expectation that
compares the plans (friends stand closer than a boss and an employee; an angry character frowns; an
apology lowers the apologiser's dominance; ...). 24 cases; --quick times fewer repetitions.

JSON keys: expectations_met (share of cases whose expectation holds), energy_drop (mean over all plans of
(E_initial - E_final) / E_initial, the share of the initial energy the sampler removes), ms_per_plan (mean
wall time of plan_social per plan over the cases' stories and a two-character ten-action scene, one core).

The cast on screen (the whole pipeline, in-process, over CAST_STORIES or the .txt stories of --stories DIR):
overlap_frames (frames where two characters on stage overlap by more than the story checks' 3 cm, summed
over the stories; the frames of a two-person clip such as a hug touch on purpose and do not count), entrance_ok_share (share of "walks in" / "enters" / "comes in" actions whose character is
off stage before and first shown outside the room or within 1 m of a door), shared_slots (seated frames where
two characters' hips are within 0.35 m: one seat for two), hand_contact_cm (p95 over the contact frames of
every two-person action, its clip's interaction window, of how far the hands that should touch are apart: the
two hands of a handshake, high five or held hands from each other, the hands of a hug, a hand on the shoulder
or a push from the partner's body surface, and the partner's hands from the actor's back when it hugs back),
paired_actions (how many were measured). --no-cast skips them. Over 400 lines because the cases and the cast
stories are data that live with the measurement.
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


CAST_STORIES = {
    "sofa_visit": "A sofa is near a window$.\nEve sits on the sofa.\nEve laughs.\nTom walks in.\n"
    "He sits on the sofa.\nEve waves at Tom.\nTom leaves.\n",
    "three_on_a_sofa": "A sofa is near a window$.\nAda walks to the window.\nBen walks to the window.\n"
    "Eve walks to the window.\nThey sit on the sofa.\n",
    "kitchen_table": "In the kitchen there is a dining table$. Three chairs are around the table$.\n"
    "Tom and Sam come in.\nThey sit at the table.\nMom walks in.\nShe waves at Tom.\n",
    "office_entrance": "In the office there is a desk near a window$. A chair is in front of the desk$.\n"
    "Eve sits on the chair.\nEve nods.\nTom enters the office.\nHe walks to Eve.\nTom goes out.\n",
    "greetings": "In the living room there is a sofa$.\nAda walks to the sofa.\nBen walks in.\n"
    "He shakes hands with Ada.\nAda hugs Ben.\nThey high-five.\nBen comforts Ada.\n",
    "crossing": "In the office there is a desk$. A window is on the left wall$.\nEve stands near the window.\n"
    "Tom stands near the desk.\nEve walks to the desk.\nTom walks to the window.\nThey hug.\n",
}
# Two-person clips: the joints that meet (actor's, partner's) and the actor's joints that rest on the partner.
MEET = {
    "shake_hands": (("RightHand", "RightHand"),),
    "high_five": (("RightHandMiddle1", "RightHandMiddle1"),),
    "hold_hands": (("RightHand", "LeftHand"),),
}
ON_BODY = {
    "hug": ("LeftHand", "RightHand"),
    "comfort": ("RightHand",),
    "kiss_cheek": ("RightHand",),
    "push_person": ("LeftHand", "RightHand"),
}
ANSWERED = {"hug": ("LeftHand", "RightHand")}  # the partner's hands on the actor (a hug is returned)
DOOR_M = 1.0  # metres: an entrance shown this close to a door starts "at the door"
SHARED_SEAT_M = 0.35  # metres between two seated characters' hips that means one seat for two
OVERLAP_M = 0.03  # metres, as the story checks' body overlap


def cast_metrics(stories: dict[str, str], seed: int = 0) -> dict[str, float | int]:
    """overlap_frames, entrance_ok_share and shared_slots over stories run through the whole pipeline."""
    import tempfile

    import numpy as np

    from services.orchestrator.backend import InProcessBackend
    from services.orchestrator.session import Orchestrator
    from services.orchestrator.staging import is_entrance
    from wana.arrays import from_wire
    from wana.fidelity.bodies import body_of
    from wana.fidelity.body_checks import overlap

    overlaps, entrances, entrances_ok, shared = 0, 0, 0, 0
    gaps: list[float] = []
    paired = 0
    with tempfile.TemporaryDirectory(prefix="wana-cast-") as tmp:
        orch = Orchestrator(Path(tmp) / "s.db", InProcessBackend(), seed=seed)
        try:
            for text in stories.values():
                result = orch.create(text).compute()
                motions = {n: m for n, m in result.motions.items() if m.root_position.shape[0]}
                on = {
                    n: from_wire(m.present).astype(bool)
                    if m.present is not None
                    else np.ones(m.root_position.shape[0], bool)
                    for n, m in motions.items()
                }
                bodies = {n: body_of(m) for n, m in motions.items()}
                names = sorted(bodies)
                frames = max((b.frames for b in bodies.values()), default=0)
                bad = np.zeros(frames, bool)
                seated_close = np.zeros(frames, bool)
                touching = {n: np.zeros(bodies[n].frames, bool) for n in names}
                for n in names:  # a hug or a handshake touches on purpose (as the story checks allow)
                    for seg in motions[n].segments:
                        if seg.action in MEET or seg.action in ON_BODY:
                            touching[n][seg.start_frame : seg.end_frame] = True
                for i, a in enumerate(names):
                    for b in names[i + 1 :]:
                        n_ab = min(bodies[a].frames, bodies[b].frames)
                        fa, _ = overlap(bodies[a], bodies[b], touching[a][:n_ab] | touching[b][:n_ab])
                        both = on[a] & on[b]
                        bad |= fa.failing & (fa.amount > OVERLAP_M) & both
                        ha, hb = bodies[a].joint("Hips"), bodies[b].joint("Hips")
                        low = (ha[:, 1] < 0.7) & (hb[:, 1] < 0.7)  # both seated
                        near = np.hypot(ha[:, 0] - hb[:, 0], ha[:, 2] - hb[:, 2]) < SHARED_SEAT_M
                        seated_close |= low & near & both
                overlaps += int(bad.sum())
                shared += int(seated_close.sum())
                for name, motion in motions.items():
                    for seg in motion.segments:
                        found = hand_gaps(name, seg, bodies, on)
                        if found is not None:
                            paired += 1
                            gaps += found
                doors = [
                    np.array([o.position[0], o.position[2]])
                    for o in result.scene.objects
                    if o.category == "door"
                ]
                room = result.scene.room
                for g in result.graphs.values():
                    for c in g.characters:
                        motion = motions.get(c.name)
                        if motion is None or not c.actions or not is_entrance(c.actions[0]):
                            continue
                        mine = [s for s in motion.segments if s.sentence_id == g.sentence_id]
                        if not mine:
                            continue
                        entrances += 1
                        start = min(s.start_frame for s in mine)
                        shown = np.flatnonzero(on[c.name][start:])
                        if on[c.name][:start].any() or not len(shown):
                            continue
                        at = from_wire(motion.root_position)[start + shown[0], [0, 2]]
                        outside = abs(at[0]) > room.width / 2 or abs(at[1]) > room.depth / 2
                        if outside or any(np.linalg.norm(at - d) <= DOOR_M for d in doors):
                            entrances_ok += 1
        finally:
            orch.close()
    return {
        "hand_contact_cm": round(float(np.percentile(gaps, 95)) * 100, 2) if gaps else 0.0,
        "paired_actions": paired,
        "overlap_frames": overlaps,
        "entrance_ok_share": round(entrances_ok / entrances, 4) if entrances else 1.0,
        "entrances": entrances,
        "shared_slots": shared,
    }


def hand_gaps(name: str, seg, bodies: dict, on: dict) -> list[float] | None:  # noqa: ANN001
    """Metres the touching joints are apart at a two-person clip's contact frames (None: no such clip, or
    nobody on stage to do it to). The partner is the nearest character on stage during the clip."""
    import numpy as np

    from wana.domain.actions import get_clip

    if seg.action not in MEET and seg.action not in ON_BODY:
        return None
    clip = get_clip(seg.action)
    me = bodies[name]
    length = seg.end_frame - seg.start_frame
    w = clip.interaction.window if clip.interaction is not None else (0.0, clip.duration_s)
    a = seg.start_frame + round(w[0] / clip.duration_s * length)
    b = max(a + 1, seg.start_frame + round(w[1] / clip.duration_s * length))
    frames = np.arange(a, min(b, me.frames))
    mid = int(frames[len(frames) // 2]) if len(frames) else -1
    others = [
        n
        for n in bodies
        if n != name and mid >= 0 and mid < bodies[n].frames and on[n][mid] and on[name][mid]
    ]
    if not others:
        return None
    partner = min(
        others, key=lambda n: float(np.linalg.norm(me.joint("Hips")[mid] - bodies[n].joint("Hips")[mid]))
    )
    them = bodies[partner]
    frames = frames[frames < them.frames]

    def surface(joint: str, toucher, touched) -> np.ndarray:  # noqa: ANN001
        p = toucher.joint(joint)[frames]
        d = np.linalg.norm(touched.points[frames] - p[:, None], axis=2) - touched.radii[None]
        return np.maximum(d.min(axis=1), 0.0)

    out: list[np.ndarray] = []
    for ja, jb in MEET.get(seg.action, ()):
        out.append(np.linalg.norm(me.joint(ja)[frames] - them.joint(jb)[frames], axis=1))
    for joint in ON_BODY.get(seg.action, ()):
        out.append(surface(joint, me, them))
    for joint in ANSWERED.get(seg.action, ()):
        out.append(surface(joint, them, me))
    return [float(x) for x in np.concatenate(out)] if out else None


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
    parser.add_argument("--stories", type=Path, help="a folder of .txt stories for the cast metrics")
    parser.add_argument("--no-cast", action="store_true", help="skip the cast metrics (the whole pipeline)")
    parser.add_argument(
        "--per-story", action="store_true", help="also print the cast metrics of each story on its own"
    )
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
    if not args.no_cast:
        stories = (
            {
                p.stem: p.read_text(encoding="utf-8", errors="replace")
                for p in sorted(args.stories.glob("*.txt"))
            }
            if args.stories
            else CAST_STORIES
        )
        cast = cast_metrics(stories, args.seed)
        summary.update(cast)
        print(
            f"cast over {len(stories)} stories: overlap_frames {cast['overlap_frames']}  "
            f"entrance_ok_share {cast['entrance_ok_share']:.3f} ({cast['entrances']} entrances)  "
            f"shared_slots {cast['shared_slots']}  hand_contact_cm {cast['hand_contact_cm']:.1f} "
            f"({cast['paired_actions']} paired actions)"
        )
        if args.per_story:
            print(f"{'story':<24} {'overlap_frames':>14} {'shared_slots':>12} {'hand_contact_cm':>15}")
            for key, text in stories.items():
                one = cast_metrics({key: text}, args.seed)
                print(
                    f"{key:<24} {one['overlap_frames']:>14} {one['shared_slots']:>12} "
                    f"{one['hand_contact_cm']:>15.1f}"
                )
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(summary, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
