"""Do the story checks agree with the eye? Sample checks, draw what they name, compare with a person's labels.

Usage:
    .venv/bin/python eval/agreement.py [--split dev|test|others|all] [--sample N | --blind N | --restale]
                                       [--sample-seed 0]
                                       [--seed 0] [--quick | --labelled] [--group NAME] [--json PATH]
                                       [--labels PATH] [--out DIR]

Each story of the split is computed once (the whole pipeline in-process, as eval/story.py does) and kept in a
cache keyed by the story, the seed and the source of every stage the checks do not own, so that a change to a
check reruns in seconds while a change to the motion recomputes. The checks then run as eval/story.py runs
them, and each (story, sentence, check, character) is one *unit*: ``fail`` when a check of that name about
that character fails in that sentence, else ``ok``.

``--sample N`` draws N units (seeded; round-robin over the strata check name x ok/fail, so a rare check and
its passes are drawn as often as the common failures) and writes a contact sheet per unit under
``out/eval/agreement/sheets/`` with the frames the check names (its failing frames, marked, else its own
frames) and the first and last frame of the sentence; ``samples.json`` there lists them. A person looks at
each sheet and writes a label into ``eval/data/agreement_labels.json``: the unit, ``human`` (``ok`` when what
the check is about looks right in the frames, ``fail`` when it looks wrong), a one-line ``why``, and the
``unit`` fingerprint of the frames judged (unit_fingerprint: the room, and every character, held object,
object state and, for a camera check, the camera over the unit's own frames, counted from the sentence's
start; older labels carry only ``animation``, the whole story's fingerprint).

The comparison runs on every labelled unit of the computed stories: agreement is the share of labels whose
human verdict is the check's verdict (a check that no longer exists claims nothing: ``ok``). A label whose
unit's frames changed since it was judged (another stage changed the motion there) is *stale*: it is not
counted and is listed to be looked at again; a change elsewhere in the story (another sentence, a longer walk
before it) leaves it counted. A label with no ``unit`` is stale when anything in its story changed. Each label records the pipeline seed of the animation judged, and its story is
computed with that seed. ``--labelled`` compares every label and computes nothing else; ``--quick`` checks only
the QUICK_STORIES stories with the most labels, from the cache (seconds once cached; a cold cache computes
them first).

``--restale`` draws a blind sheet of every stale label's unit as it is now (under
``out/eval/agreement/restale/``, with ``units.json``: each unit's key and its frames' fingerprints), to be judged
again on what it shows; the former verdict goes under the label's ``before``.

``--blind N`` draws N unlabelled units of the split's stories (at ``--seed``) and writes sheets under
``out/eval/agreement/blind/`` that show the frames but not the verdict, the reason or marked frames (only the
question the check answers): labels drawn that way are marked ``fresh`` and reported on their own. A body
check blames the sentence a fault began in and the character whose motion caused it, so the question of an
``overlap`` unit is whether that character moved into someone, of a ``penetration`` unit whether the part went
into furniture in that sentence.

JSON keys: check_agreement (share of counted labels that agree), per_check (name -> labels, agree,
agreement, false_alarms (check fails, eye says ok), misses (check passes, eye says fail)), counted, stale,
skipped, disagreements (each unit with both verdicts and the check's reason), by_group (dev, test, others,
fresh, fresh2, fresh3, fresh4, fresh5 -> agreement, counted, labels), agreement_dev / agreement_held_out /
agreement_fresh / agreement_fresh2 / agreement_fresh3 / agreement_fresh4 / agreement_fresh5, fidelity (for
--split: the split's sentence_fidelity and failures per check with these checks), samples (when --sample).
"""

from __future__ import annotations

import argparse
import collections
import hashlib
import json
import os
import pickle
import random
import sys
import time
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import Any

os.environ.setdefault("OMP_NUM_THREADS", "1")
REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))
sys.path.insert(0, str(REPO / "eval"))

import story as story_eval  # noqa: E402  (eval/story.py: the same pipeline run and checks)

LABELS = REPO / "eval" / "data" / "agreement_labels.json"
OUT = REPO / "out" / "eval" / "agreement"
QUICK_STORIES = 8  # --quick: the stories with the most labels
# What the checks own: a change here reruns the checks on the cached animation, anything else recomputes it.
CHECK_SOURCES = ("wana/fidelity/", "services/render/camera_checks.py", "services/render/gallery.py")
PIPELINE_ROOTS = ("proto", "services", "wana")
PIPELINE_SUFFIXES = (".py", ".json", ".yaml", ".yml", ".toml", ".txt", ".bvh", ".npz", ".npy")


# --- the computed stories ---------------------------------------------------------------------------------


def pipeline_version(root: Path = REPO) -> str:
    """A hash of every pipeline source and data file the checks do not own (the cache key's code part)."""
    h = hashlib.blake2b(digest_size=12)
    for top in PIPELINE_ROOTS:
        for path in sorted((root / top).rglob("*")):
            rel = path.relative_to(root).as_posix()
            if not path.is_file() or path.suffix not in PIPELINE_SUFFIXES or "__pycache__" in rel:
                continue
            if any(rel.startswith(c) for c in CHECK_SOURCES):
                continue
            h.update(rel.encode())
            if path.suffix == ".py" or path.stat().st_size < 1 << 20:
                h.update(path.read_bytes())
            else:  # large data: its size stands for it (hashing every array would cost seconds)
                h.update(str(path.stat().st_size).encode())
    return h.hexdigest()


def animation_fingerprint(result: Any) -> str:
    """A hash of what a contact sheet shows: the room, every motion's arrays and segments, the commands."""
    import msgspec

    h = hashlib.blake2b(digest_size=8)
    h.update(msgspec.json.encode(result.scene) if result.scene is not None else b"")
    for name in sorted(result.motions):
        h.update(msgspec.json.encode(result.motions[name]))
    h.update(repr(result.commands).encode())
    return h.hexdigest()


def render_version(root: Path = REPO) -> str:
    """A hash of the render service's sources: the camera checks of an animation stay valid while it holds."""
    h = hashlib.blake2b(digest_size=12)
    for path in sorted((root / "services" / "render").glob("*.py")):
        h.update(path.name.encode() + path.read_bytes())
    return h.hexdigest()


def camera_checks_of(result: Any, fingerprint: str, cache: Path) -> dict[str, Any]:
    """The camera checks of one animation (see camera_of)."""
    return camera_of(result, fingerprint, cache)[0]


def camera_of(result: Any, fingerprint: str, cache: Path) -> tuple[dict[str, Any], dict[str, Any]]:
    """The camera checks of one animation and its camera track (eye, target, fov_deg per frame), cached by
    its fingerprint and the render sources (the camera planner and the visibility test take most of a
    story's checking time)."""
    file = cache / f"camera-{fingerprint}-{render_version()}.pkl"
    if file.exists():
        try:
            with file.open("rb") as f:
                checks, track = pickle.load(f)
            return dict(checks), dict(track)
        except Exception:
            file.unlink(missing_ok=True)
    checks, track = story_camera(result)
    cache.mkdir(parents=True, exist_ok=True)
    with file.open("wb") as f:
        pickle.dump((checks, track), f, protocol=pickle.HIGHEST_PROTOCOL)
    return checks, track


def story_camera(result: Any) -> tuple[dict[str, Any], dict[str, Any]]:
    """The render service's camera checks of one computed story (as eval/story.py runs them) and the camera
    track they judged: the picture an in_view or command_visible label was judged on."""
    from services.render.camera_checks import staged_checks
    from services.render.staging import Staging
    from services.render.timeline import as_motion_list, place_commands

    mlist = as_motion_list(result.motions)
    sents = list(result.sentences or [])
    stage = Staging.build(result.scene, mlist, place_commands(result.commands, sents, mlist))
    track = stage.camera_track(story_eval.WIDTH, story_eval.HEIGHT)
    checks = staged_checks(stage, sents, width=story_eval.WIDTH, height=story_eval.HEIGHT, track=track)
    return dict(checks), {"eye": track.eye, "target": track.target, "fov_deg": track.fov_deg}


# --- what one label is about: its unit's own frames ------------------------------------------------------

FINGERPRINT_STEP = 1e-3  # metres and quaternion units: far below what a sheet shows
CAMERA_CHECKS = ("in_view", "command_visible")


def unit_window(motions: dict[str, Any], sentence: str, check: str) -> tuple[int, int] | None:
    """The frames a unit's verdict is about: its sentence's frames, the frame before them for a jump
    (continuity), every frame up to its end for an entrance (unseen before), and to the video's end for a
    command (in force for the rest of the video); None for a sentence with no frames (a scene sentence)."""
    span = story_eval.sentence_frames(motions, sentence)
    if span is None:
        return None
    total = max((m.root_position.shape[0] for m in motions.values()), default=0)
    start, end = span
    if check == "continuity":
        start = max(0, start - 1)
    elif check == "entrance":
        start = 0
    elif check == "command_visible":
        end = total
    return start, min(end, total)


def from_wire(a: Any) -> Any:
    from wana.arrays import from_wire as unpack

    return unpack(a)


def _quantised(a: Any) -> bytes:
    import numpy as np

    return np.round(np.asarray(a, dtype=np.float64) / FINGERPRINT_STEP).astype(np.int64).tobytes()


def unit_fingerprint(
    result: Any, story: str, sentence: str, check: str, track: dict[str, Any] | None = None
) -> str:
    """A hash of what a label of (sentence, check) judged: the room and its objects, and over the unit's
    window (unit_window; frames counted from its start, so that a longer sentence before it does not
    count) every character's pose, presence, actions, held objects and the objects' states, and for a
    camera check the camera. A change elsewhere in the story (another sentence's motion) leaves it as it
    was; anything the label's frames show changes it. Values are rounded to FINGERPRINT_STEP."""
    import msgspec
    import numpy as np

    def arr(a: Any) -> Any:
        return a if isinstance(a, np.ndarray) else from_wire(a)

    h = hashlib.blake2b(digest_size=8)
    h.update(f"{story}|{sentence}|{check}".encode())
    scene = result.scene
    if scene is not None:
        h.update(msgspec.json.encode(scene.room))
        h.update(msgspec.json.encode(sorted(scene.objects, key=lambda o: o.id)))
    window = unit_window(result.motions, sentence, check)
    if window is not None:
        a, b = window
        frames = np.arange(a, b)
        for name in sorted(result.motions):
            m = result.motions[name]
            h.update(name.encode())
            h.update(_quantised(arr(m.root_position)[a:b]))
            h.update(_quantised(arr(m.rotations)[a:b]))
            if m.present is not None:
                h.update(np.asarray(arr(m.present)[a:b], dtype=np.uint8).tobytes())
            for g in m.segments:
                if g.start_frame < b and g.end_frame > a:
                    h.update(f"{g.action}|{g.sentence_id}|{g.start_frame - a}|{g.end_frame - a}".encode())
            for p in m.props:
                lo, hi = max(a, p.start_frame), min(b, p.end_frame)
                if lo < hi:
                    h.update(f"{p.object_id}|{p.joint}|{lo - a}|{hi - a}".encode())
                    h.update(_quantised(arr(p.position)[lo - p.start_frame : hi - p.start_frame]))
        if scene is not None:
            for st in sorted(scene.states, key=lambda t: (t.object_id, t.state)):
                h.update(f"{st.object_id}|{st.state}".encode())
                if st.frames:
                    h.update(_quantised(np.interp(frames, st.frames, st.values)))
        if check in CAMERA_CHECKS and track is not None:
            for key in ("eye", "target", "fov_deg"):
                h.update(_quantised(np.asarray(track[key])[a:b]))
    if check in CAMERA_CHECKS:
        h.update(repr(result.commands).encode())
    return h.hexdigest()


def computed(path: Path, seed: int, version: str, cache: Path, *, compute: bool = True) -> Any | None:
    """The PipelineResult of one story file, from the cache or computed and cached (None: not cached and
    compute is False)."""
    text = path.read_text(encoding="utf-8", errors="replace")
    key = hashlib.blake2b(f"{version}|{seed}|{text}".encode(), digest_size=10).hexdigest()
    file = cache / f"{path.stem}-s{seed}-{key}.pkl"
    if file.exists():
        try:
            with file.open("rb") as f:
                return pickle.load(f)
        except Exception:
            file.unlink(missing_ok=True)
    if not compute:
        return None
    result = story_eval._compute(text, path.stem, seed)
    cache.mkdir(parents=True, exist_ok=True)
    for old in cache.glob(f"{path.stem}-s{seed}-*.pkl"):
        old.unlink(missing_ok=True)
    tmp = file.with_suffix(".tmp")
    with tmp.open("wb") as f:
        pickle.dump(result, f, protocol=pickle.HIGHEST_PROTOCOL)
    tmp.replace(file)
    return result


# --- units: one (sentence, check, character) of one story --------------------------------------------------


def units(row: dict[str, Any], fingerprint: str, seed: int = 0) -> list[dict[str, Any]]:
    """Every (sentence, check, character) of one story row of eval/story.py, with the check's verdict."""
    out: dict[tuple[str, str, str], dict[str, Any]] = {}
    for s in row["per_sentence"]:
        for r in s.get("results", []):
            key = (s["id"], r["name"], r["character"])
            u = out.setdefault(
                key,
                {
                    "story": row["story"],
                    "sentence": s["id"],
                    "check": r["name"],
                    "character": r["character"],
                    "text": s["text"],
                    "check_verdict": "ok",
                    "reason": r["reason"],
                    "frames": [],
                    "animation": fingerprint,
                    "seed": seed,
                },
            )
            if not r["ok"] and u["check_verdict"] == "ok":  # the first failing one speaks for the unit
                u["check_verdict"], u["reason"], u["frames"] = "fail", r["reason"], list(r["frames"])
            elif r["ok"] == (u["check_verdict"] == "ok") and not u["frames"]:
                u["frames"] = list(r["frames"])
    return list(out.values())


def unit_key(u: dict[str, Any]) -> tuple[str, int, str, str, str]:
    """(story, pipeline seed, sentence, check, character): one check about one character in one sentence."""
    return (u["story"], int(u.get("seed", 0)), u["sentence"], u["check"], u["character"])


def stratified_sample(pool: Sequence[dict[str, Any]], n: int, seed: int) -> list[dict[str, Any]]:
    """n units, seeded: round-robin over the strata (check, verdict) in name order, random within each."""
    rng = random.Random(seed)
    strata: dict[tuple[str, str], list[dict[str, Any]]] = collections.defaultdict(list)
    for u in sorted(pool, key=unit_key):
        strata[(u["check"], u["check_verdict"])].append(u)
    queues = []
    for key in sorted(strata):
        q = strata[key][:]
        rng.shuffle(q)
        queues.append(q)
    picked: list[dict[str, Any]] = []
    while len(picked) < n and any(queues):
        for q in queues:
            if q and len(picked) < n:
                picked.append(q.pop())
    return picked


def draw_sheet(result: Any, u: dict[str, Any], path: Path, index: int) -> Path:
    """The contact sheet of one unit: the frames its check names (failing ones marked) and the sentence's
    first and last frame."""
    from services.render.gallery import contact_sheet

    total = max((m.root_position.shape[0] for m in result.motions.values()), default=1)
    span = story_eval.sentence_frames(result.motions, u["sentence"])
    failing = u["frames"] if u["check_verdict"] == "fail" else []
    frames = story_eval.sheet_frames(failing or u["frames"], span, total)
    if not failing and span and len(frames) < 4:
        frames = story_eval.sheet_frames([], span, total)
    who = f" ({u['character']})" if u["character"] else ""
    title = (
        f"[{index}] {u['story']} {u['sentence']}: {u['text']}\n"
        f"{u['check']}{who} says {u['check_verdict'].upper()}: {u['reason']}"
    )
    return contact_sheet(
        result.scene, result.motions, result.commands, result.sentences, frames,
        set(frames) & set(failing), title, path,
    )  # fmt: skip


# --- labels and agreement -------------------------------------------------------------------------------


def load_labels(path: Path) -> list[dict[str, Any]]:
    if not path.exists():
        return []
    data = json.loads(path.read_text(encoding="utf-8"))
    return list(data["labels"] if isinstance(data, dict) else data)


def compare(
    labels: Iterable[dict[str, Any]],
    found: dict[tuple[Any, ...], dict[str, Any]],
    fingerprints: dict[tuple[str, int], str],
    count_stale: bool = False,
    unit_fps: dict[tuple[Any, ...], str] | None = None,
) -> dict[str, Any]:
    """Agreement of each label with the current check verdict of its unit.

    Args:
        labels: the person's labels.
        found: unit key -> unit, over the stories computed this run.
        fingerprints: (story, seed) -> its animation's fingerprint (the stories computed this run).
        count_stale: count a stale label too (still listed under ``stale``): an indicative number only, the
            person judged an older animation of the unit.
        unit_fps: unit key -> its unit_fingerprint now: a label keyed by its unit's frames (``unit``) is
            stale when those changed; one keyed by the whole animation only (``animation``) when any changed.
    """
    per: dict[str, collections.Counter[str]] = collections.defaultdict(collections.Counter)
    stale, skipped, disagreements = [], [], []
    for lab in labels:
        key = unit_key(lab)
        story = (lab["story"], int(lab.get("seed", 0)))
        if story not in fingerprints:
            skipped.append(key)
            continue
        if is_stale(lab, fingerprints[story], (unit_fps or {}).get(key)):
            stale.append(key)
            if not count_stale:
                continue
        u = found.get(key)
        check = u["check_verdict"] if u is not None else "ok"  # no such check: it claims nothing
        c = per[lab["check"]]
        c["labels"] += 1
        if check == lab["human"]:
            c["agree"] += 1
        else:
            c["false_alarms" if check == "fail" else "misses"] += 1
            disagreements.append(
                {
                    **{
                        k: lab[k] for k in ("story", "seed", "sentence", "check", "character", "human", "why")
                    },
                    "check_verdict": check,
                    "reason": u["reason"] if u is not None else "(no such check now)",
                }
            )
    counted = sum(c["labels"] for c in per.values())
    agree = sum(c["agree"] for c in per.values())
    return {
        "check_agreement": agree / counted if counted else 0.0,
        "counted": counted,
        "per_check": {
            name: {
                "labels": c["labels"],
                "agree": c["agree"],
                "agreement": c["agree"] / c["labels"],
                "false_alarms": c["false_alarms"],
                "misses": c["misses"],
            }
            for name, c in sorted(per.items())
        },
        "stale": [list(k) for k in stale],
        "skipped": [list(k) for k in skipped],
        "disagreements": disagreements,
    }


def is_stale(lab: dict[str, Any], animation: str, unit: str | None) -> bool:
    """Whether what a label judged has changed: its unit's own frames when it records their fingerprint
    (``unit``), else the whole animation's (``animation``; a label with neither is never stale)."""
    if lab.get("unit"):
        return lab["unit"] != unit
    return bool(lab.get("animation")) and lab["animation"] != animation


def label_group(lab: dict[str, Any], splits: dict[str, str]) -> str:
    """The blind set a label was drawn in (``fresh``; ``fresh2``, drawn after ``fresh`` was tuned on), else
    its story's split."""
    fresh = lab.get("fresh")
    if fresh:
        return fresh if isinstance(fresh, str) else "fresh"
    return splits.get(lab["story"], "unknown")


def compare_groups(
    labels: Sequence[dict[str, Any]],
    found: dict[tuple[Any, ...], dict[str, Any]],
    fingerprints: dict[tuple[str, int], str],
    splits: dict[str, str],
    count_stale: bool = False,
    unit_fps: dict[tuple[Any, ...], str] | None = None,
) -> dict[str, dict[str, Any]]:
    """Group (dev, test, others, fresh) -> its agreement and counted labels: a target must hold on the labels
    the checks were not fixed on (held-out test, fresh), not only on the dev labels they were."""
    groups: dict[str, list[dict[str, Any]]] = collections.defaultdict(list)
    for lab in labels:
        groups[label_group(lab, splits)].append(lab)
    out = {}
    for name, labs in sorted(groups.items()):
        c = compare(labs, found, fingerprints, count_stale, unit_fps)
        out[name] = {"agreement": c["check_agreement"], "counted": c["counted"], "labels": len(labs)}
    return out


# What each check asks, in the words a blind sheet gives the person labelling it (no verdict, no reason).
QUESTIONS = {
    "object_exists": "is every object the sentence names in the room, as many as it says?",
    "relation_holds": "does the stated relation between the objects hold?",
    "performed": "does the character do what the sentence says?",
    "contact": "is the named object in the hand / under the body where the action needs it?",
    "placement": "is the character where the sentence puts them?",
    "supported": "is the character supported (no sitting, lying or leaning on air)?",
    "penetration": "does a part of the character go visibly into furniture, begun in this sentence?",
    "overlap": "does the character's own motion take its body into another's (not being walked into)?",
    "continuity": "does the character move without jumps or pops?",
    "entrance": "does the character come in from outside / a door, unseen before?",
    "in_view": "is the character in the picture and mostly unhidden while acting?",
    "command_visible": "is the command's effect shown for at least 1.5 s?",
}


def draw_blind_sheet(result: Any, u: dict[str, Any], path: Path, index: int) -> Path:
    """A contact sheet that shows the frames the check looked at but not what it concluded: no verdict, no
    reason, no marked frames (the person labels what they see, then the verdicts are compared)."""
    from services.render.gallery import contact_sheet

    total = max((m.root_position.shape[0] for m in result.motions.values()), default=1)
    span = story_eval.sentence_frames(result.motions, u["sentence"])
    named = list(u["frames"])
    if u["check"] == "continuity":  # a jump is seen between two frames: show the one before each named
        named = sorted({g for f in named[:4] for g in (f - 1, f) if g >= 0} | set(named))
    frames = story_eval.sheet_frames(named, span, total)
    if span and len(frames) < 4:
        frames = story_eval.sheet_frames([], span, total)
    who = f" about {u['character']}" if u["character"] else ""
    question = QUESTIONS.get(u["check"], "does it look right?")
    title = f"[{index}] {u['story']} {u['sentence']}: {u['text']}\n{u['check']}{who}: {question}"
    return contact_sheet(
        result.scene, result.motions, result.commands, result.sentences, frames, set(), title, path
    )


def print_table(summary: dict[str, Any]) -> None:
    print(f"{'check':16s} {'labels':>6s} {'agree':>6s} {'share':>6s} {'false alarms':>13s} {'misses':>7s}")
    for name, c in summary["per_check"].items():
        print(
            f"{name:16s} {c['labels']:6d} {c['agree']:6d} {c['agreement']:6.2f} {c['false_alarms']:13d}"
            f" {c['misses']:7d}"
        )
    for d in summary["disagreements"]:
        who = f" ({d['character']})" if d["character"] else ""
        print(
            f"  disagree {d['story']} {d['sentence']} {d['check']}{who}: check {d['check_verdict']}, "
            f"eye {d['human']} -- {d['why']}"
        )
    if summary["stale"]:
        print(f"{len(summary['stale'])} labels are stale (the animation changed since): look again")
    if summary["skipped"]:
        print(f"{len(summary['skipped'])} labels skipped (their story was not computed this run)")
    print(f"check_agreement {summary['check_agreement']:.3f} over {summary['counted']} labels")
    for group, g in summary.get("by_group", {}).items():
        print(f"  {group:8s} {g['agreement']:.3f} over {g['counted']} labels ({g['labels']} given)")
    if "fidelity" in summary:
        f = summary["fidelity"]
        print(
            f"sentence_fidelity {f['sentence_fidelity']:.3f} over {f['sentences']} sentences ({f['split']})"
        )
        print("  failures per check: " + ", ".join(f"{k} {v}" for k, v in f["checks"].items() if v))


# --- the run --------------------------------------------------------------------------------------------


def quick_stories(labels: Sequence[dict[str, Any]], n: int = QUICK_STORIES) -> list[tuple[str, int]]:
    """The (story, seed) pairs --quick checks: the n with the most labels (ties in name order)."""
    count = collections.Counter((lab["story"], int(lab.get("seed", 0))) for lab in labels)
    return sorted(sorted(count), key=lambda k: -count[k])[:n]


def run(args: argparse.Namespace) -> dict[str, Any]:
    t0 = time.perf_counter()
    labels = load_labels(args.labels)
    every = {p.stem: p for p in story_paths_all()}
    if args.group:  # one blind set or split of the labels (their stories only are computed with --labelled)
        splits_of = {p.stem: p.parent.name for p in every.values()}
        known = sorted({label_group(lab, splits_of) for lab in labels})
        labels = [lab for lab in labels if label_group(lab, splits_of) == args.group]
        if not labels:
            raise SystemExit(f"no labels in group {args.group!r}; the groups are: {', '.join(known)}")
    wanted: list[tuple[str, int]] = []
    if args.quick:
        wanted = quick_stories(labels)
        labels = [lab for lab in labels if (lab["story"], int(lab.get("seed", 0))) in set(wanted)]
    elif args.labelled:
        wanted = sorted({(lab["story"], int(lab.get("seed", 0))) for lab in labels})
    else:
        wanted = [(p.stem, args.seed) for p in story_eval.story_paths(args.split)]
        wanted += sorted({(lab["story"], int(lab.get("seed", 0))) for lab in labels} - set(wanted))
    version = pipeline_version()
    cache = args.out / "cache"
    found: dict[tuple[Any, ...], dict[str, Any]] = {}
    fingerprints: dict[tuple[str, int], str] = {}
    results: dict[tuple[str, int], Any] = {}
    rows: dict[tuple[str, int], dict[str, Any]] = {}
    tracks: dict[tuple[str, int], dict[str, Any]] = {}
    for stem, seed in wanted:
        path = every.get(stem)
        if path is None:
            continue
        result = computed(path, seed, version, cache)
        text = path.read_text(encoding="utf-8", errors="replace")
        fingerprints[(stem, seed)] = fp = animation_fingerprint(result)
        camera, track = camera_of(result, fp, cache / "camera")
        row = story_eval.check_result(stem, text, result, camera=camera)
        results[(stem, seed)] = result
        rows[(stem, seed)] = row
        tracks[(stem, seed)] = track
        for u in units(row, fp, seed):
            found[unit_key(u)] = u
    unit_fps = {
        unit_key(lab): unit_fingerprint(
            results[(lab["story"], int(lab.get("seed", 0)))], lab["story"], lab["sentence"], lab["check"],
            tracks[(lab["story"], int(lab.get("seed", 0)))],
        )
        for lab in labels
        if (lab["story"], int(lab.get("seed", 0))) in results
    }  # fmt: skip
    summary = compare(labels, found, fingerprints, args.count_stale, unit_fps)
    splits = {p.stem: p.parent.name for p in every.values()}
    summary["by_group"] = compare_groups(labels, found, fingerprints, splits, args.count_stale, unit_fps)
    for group, key in (
        ("test", "agreement_held_out"),
        ("fresh", "agreement_fresh"),
        ("fresh2", "agreement_fresh2"),
        ("fresh3", "agreement_fresh3"),
        ("fresh4", "agreement_fresh4"),
        ("fresh5", "agreement_fresh5"),
        ("dev", "agreement_dev"),
    ):
        if group in summary["by_group"]:
            summary[key] = summary["by_group"][group]["agreement"]
    if not (args.quick or args.labelled):  # the split's own stories: its sentence_fidelity with these checks
        mine = [
            rows[(p.stem, args.seed)]
            for p in story_eval.story_paths(args.split)
            if (p.stem, args.seed) in rows
        ]
        fidelity = story_eval.summarise(mine, args.seed, args.split)
        summary["fidelity"] = {k: v for k, v in fidelity.items() if k != "per_story"}
    if args.blind:
        labelled = {unit_key(lab) for lab in labels}
        mine = {(p.stem, args.seed) for p in story_eval.story_paths(args.split)}
        pool = [u for u in found.values() if (u["story"], u["seed"]) in mine and unit_key(u) not in labelled]
        picked = stratified_sample(pool, args.blind, args.sample_seed)
        keyed(picked, results, tracks)
        sheets = draw_sheets(picked, results, args.out / "blind", draw_blind_sheet)
        for i, u in enumerate(picked):
            who = f" about {u['character']}" if u["character"] else ""
            print(f"[{i}] {u['story']} {u['sentence']} {u['check']}{who}: {u['text']}")
        keep = ("story", "seed", "sentence", "check", "character", "text", "animation", "unit", "sheet")
        (sheets / "units.json").write_text(json.dumps([{k: u[k] for k in keep} for u in picked], indent=1))
    if args.restale:
        summary["restale"] = draw_restale(summary["stale"], labels, found, rows, results, tracks, args.out)
    if args.sample:
        labelled = {unit_key(lab) for lab in labels}
        pool = [
            u
            for u in found.values()
            if u["seed"] == args.seed and (unit_key(u) not in labelled or args.relabel)
        ]
        picked = stratified_sample(pool, args.sample, args.sample_seed)
        keyed(picked, results, tracks)
        draw_sheets(picked, results, args.out / "sheets", draw_sheet)
        for i, u in enumerate(picked):
            who = f" ({u['character']})" if u["character"] else ""
            print(f"[{i}] {u['story']} {u['sentence']} {u['check']}{who} {u['check_verdict']}: {u['reason']}")
        (args.out / "samples.json").write_text(json.dumps(picked, indent=1))
        summary["samples"] = picked
    summary["quick"] = bool(args.quick)
    summary["wall_s"] = time.perf_counter() - t0
    return summary


def restale_units(
    stale: Sequence[Sequence[Any]],
    labels: Sequence[dict[str, Any]],
    found: dict[tuple[Any, ...], dict[str, Any]],
    rows: dict[tuple[str, int], dict[str, Any]],
) -> list[dict[str, Any]]:
    """The unit of each stale label (in label file order) as the checks see it now, to be judged again; a
    unit whose check is no longer made is drawn over its sentence's frames (its check claims ``ok``)."""
    wanted = {tuple(k) for k in stale}
    out = []
    for lab in labels:
        key = unit_key(lab)
        if key not in wanted:
            continue
        u = found.get(key)
        if u is None:
            row = rows[(lab["story"], int(lab.get("seed", 0)))]
            text = next((s["text"] for s in row["per_sentence"] if s["id"] == lab["sentence"]), "")
            u = {**{k: lab[k] for k in ("story", "sentence", "check", "character")}, "seed": key[1],
                 "text": text, "check_verdict": "ok", "reason": "(no such check now)", "frames": []}  # fmt: skip
        out.append({**u, "frames": list(u["frames"])})
        wanted.discard(key)
    return out


def draw_restale(
    stale: Sequence[Sequence[Any]],
    labels: Sequence[dict[str, Any]],
    found: dict[tuple[Any, ...], dict[str, Any]],
    rows: dict[tuple[str, int], dict[str, Any]],
    results: dict[Any, Any],
    tracks: dict[Any, Any],
    out: Path,
) -> list[dict[str, Any]]:
    """Blind sheets (draw_blind_sheet: frames and the question only) of every stale label's unit under
    ``out/restale/``, with ``units.json`` listing each unit's key, its frames' fingerprints now and its sheet:
    what a person judging them again needs, and nothing of the former verdict."""
    picked = restale_units(stale, labels, found, rows)
    keyed(picked, results, tracks)
    for u in picked:
        u["animation"] = animation_fingerprint(results[(u["story"], u["seed"])])
    folder = out / "restale"
    for old in folder.glob("*.png"):
        old.unlink()
    draw_sheets(picked, results, folder, draw_blind_sheet)
    keep = ("story", "seed", "sentence", "check", "character", "text", "animation", "unit", "sheet")
    (folder / "units.json").write_text(json.dumps([{k: u.get(k) for k in keep} for u in picked], indent=1))
    for i, u in enumerate(picked):
        who = f" about {u['character']}" if u["character"] else ""
        print(f"[{i}] {u['story']} {u['sentence']} {u['check']}{who}: {u['text']}")
    return [{k: u.get(k) for k in keep} for u in picked]


def keyed(picked: list[dict[str, Any]], results: dict[Any, Any], tracks: dict[Any, Any]) -> None:
    """Note each picked unit's ``unit`` fingerprint: the frames a label of it judges (its key for staleness)."""
    for u in picked:
        story = (u["story"], u["seed"])
        u["unit"] = unit_fingerprint(results[story], u["story"], u["sentence"], u["check"], tracks[story])


def story_paths_all() -> list[Path]:
    return story_eval.story_paths("all")


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--split", choices=(*story_eval.SPLITS, "all"), default="dev")
    ap.add_argument("--sample", type=int, default=0, help="draw this many units and write their sheets")
    ap.add_argument("--blind", type=int, default=0,
                    help="draw this many unlabelled units of every computed story, sheets with no verdict")  # fmt: skip
    ap.add_argument("--restale", action="store_true",
                    help="draw blind sheets (no verdict) of every stale label's unit, to judge it again")  # fmt: skip
    ap.add_argument("--relabel", action="store_true", help="let --sample draw units already labelled")
    ap.add_argument("--seed", type=int, default=0, help="the pipeline's seed for --split (default 0)")
    ap.add_argument("--sample-seed", type=int, default=0, help="the sample's seed (default 0)")
    ap.add_argument("--quick", action="store_true", help=f"the {QUICK_STORIES} most labelled stories only")
    ap.add_argument("--labelled", action="store_true", help="every labelled story, and no --split")
    ap.add_argument(
        "--count-stale",
        action="store_true",
        help="count labels of an animation that changed since (indicative only: judged on an older animation)",
    )
    ap.add_argument("--group", default="", help="only the labels of this group (fresh3, test, dev ...)")
    ap.add_argument("--labels", type=Path, default=LABELS, help="default eval/data/agreement_labels.json")
    ap.add_argument("--out", type=Path, default=OUT, help="cache, sheets and samples (out/eval/agreement)")
    ap.add_argument("--json", type=Path, default=None, help="write the agreement summary here")
    return ap


def draw_sheets(
    picked: list[dict[str, Any]],
    results: dict[Any, Any],
    folder: Path,
    draw: Callable[[Any, dict[str, Any], Path, int], Path],
) -> Path:
    """Draw each picked unit's sheet with ``draw`` (verdict or blind) into ``folder``, numbered in order, and
    note its path in the unit's "sheet"; returns the folder."""
    folder.mkdir(parents=True, exist_ok=True)
    for i, u in enumerate(picked):
        name = f"{i:02d}-{u['story']}-{u['sentence']}-{u['check']}-{u['character'] or 'scene'}"
        result = results[(u["story"], u["seed"])]
        u["sheet"] = str(draw(result, u, folder / f"{name.replace(' ', '_')}.png", i))
    return folder


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    summary = run(args)
    print_table(summary)
    print(f"wall {summary['wall_s']:.1f} s")
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(summary, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
