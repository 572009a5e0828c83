"""Story fidelity over the story corpus: does the animation show what each sentence says? (issue 13)

Usage:
    .venv/bin/python eval/story.py [--split dev|test|others|all] [--stories DIR] [--quick] [--json PATH]
                                   [--jobs N] [--no-gallery] [--seed 0] [--describe]

For each story the whole pipeline runs in-process (``Orchestrator(db, InProcessBackend(), seed)``), then the
story checks: ``wana.fidelity.story_checks`` (objects, relations, actions, contacts, support, penetration,
overlap, continuity, entrances) and the render service's ``camera_checks`` (in view, commands visible), joined
by ``wana.fidelity.verdicts`` into one verdict per sentence. The checks come from the parse and the computed
animation only, so ``--stories DIR`` runs them on any folder of ``.txt`` stories with no gold at all. A story
that crashes the pipeline is a failed story (with the traceback's last line), never a crash of the eval.
``--describe`` prints what the corpus covers (kind -> stories and sentences) without running anything.

JSON keys: sentence_fidelity (share of sentences whose every check passes), story_fidelity (share of stories
with every sentence ok), checks (check name -> sentences failing it), stories, sentences, per_story (each
sentence's verdict, failed reasons and ``results``: every check's name, ok, character, reason and frames),
seed, split; also verdicts, crashed, unchecked and timings; acting_in_frame_share and occluded_share (of all
acting characters' action frames: in the picture, and in it but less than 70 % unhidden; issue 16).
eval/agreement.py reads the same rows to compare the checks with a person's eye.
A failed sentence gets a contact sheet of its frames, the failing ones marked, under out/eval/story/<story>/.
Over 400 lines because the corpus description and split rule (what kinds a story covers) live here too, so
that one file both describes and measures the corpus.
"""

from __future__ import annotations

import argparse
import collections
import importlib
import json
import os
import pkgutil
import re
import shutil
import sys
import tempfile
import time
import traceback
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import Any

os.environ.setdefault("OMP_NUM_THREADS", "1")
REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from proto.fidelity import CHECK_NAMES  # noqa: E402
from services.nlp.commands import parse_command  # noqa: E402
from services.nlp.segment import split_sentences  # noqa: E402
from wana.assets.vocabulary import ROOM_TYPES  # noqa: E402

STORIES = REPO / "corpus" / "stories"
SPLITS = ("dev", "test", "others")
GALLERY = REPO / "out" / "eval" / "story"
QUICK_STORIES = 10
WIDTH, HEIGHT = 640, 480  # the video size `wana animate` renders by default
SHEET_TILES = 8

# --- what a story covers ------------------------------------------------------------------------------

# A corpus file is named <kind>-<room>-<n>.txt; the kind is what the split balances.
PRIMARY_KINDS = {
    "solo": "single character",
    "duo": "two characters",
    "group": "three or more characters",
    "mitty": "film: The Secret Life of Walter Mitty",
    "gump": "film: Forrest Gump",
    "limitless": "film: Limitless",
}
MULTI = ("duo", "group", "mitty", "gump", "limitless")
# Feature kinds, found in a story's action sentences (scene sentences name objects, not what is done).
FEATURES: dict[str, str] = {
    "sitting": r"\bsit(s|ting)?\b|\bsat\b|\bseated\b|take a seat",
    "lying": r"\bli(e|es|ying)\b|\bsleeps?\b|falls? asleep",
    "typing": r"\btyp(e|es|ing)\b|uses the computer",
    "tool use": r"\b(hammers?|saws?|drills?|screws|screwdriver|wrench|repairs?|sweeps?)\b",
    "eating": r"\beats?\b|\beating\b|\btastes?\b",
    "drinking": r"\bdrinks?\b|\bsips?\b",
    "phoning": r"\bphone\b|\bcalls?\b|\bdials?\b",
    "reading": r"\breads?\b|\breading\b|leafs through",
    "entrance": r"\b(walks?|runs?|comes?|goes?|steps?) in(to)?\b|\benters?\b|\barrives?\b|\bsqueezes in\b",
    "exit": r"\bleaves?\b|\b(walks?|goes?|strolls?|sneaks?|slips?) (out|away)\b",
    "hug": r"\bhug(s|ged)?\b",
    "handshake": r"\bshake(s)? hands\b|\bshakes \w+('s)? hand\b|\bhandshake\b",
    "high-five": r"\bhigh[- ]fives?\b",
    "conversation": r"\b(talks?|chats?|argues?|whispers?|explains?|tells?|yells?)\b",
    "handing over": r"\b(hands|gives|brings|offers)\b",
    "titled name": r"\b(Mr|Mrs|Ms|Dr|Prof)\.? [A-Z]",
}
_ROOM_WORDS = {name.replace("_", " "): name for name in ROOM_TYPES} | {
    syn: name for name, syns in ROOM_TYPES.items() for syn in syns
}


def room_of_story(text: str) -> str:
    """The room type a story's scene sentences name ("In the nursery ..." -> kids_room), "" when none."""
    scene = " ".join(text[s:e] for s, e, kind in split_sentences(text) if kind == "scene") or text
    words = re.findall(r"[a-z']+", scene.lower().replace("’", "'"))
    for i in range(len(words)):
        for n in (3, 2, 1):
            room = _ROOM_WORDS.get(" ".join(words[i : i + n]))
            if room:
                return room
    return ""


def primary_kind(story: Path | str) -> str:
    """The kind in a corpus file name (``duo-office-01`` -> duo); "other" for any other name."""
    head = Path(story).stem.split("-")[0]
    return head if head in PRIMARY_KINDS else "other"


def story_kinds(story: Path | str, text: str) -> list[str]:
    """Every kind one story covers: its primary kind, feature kinds, commands and its room."""
    kind = primary_kind(story)
    kinds = [kind]
    if kind != "other":
        kinds.append("multi-character" if kind in MULTI else "single-character")
    if kind in ("mitty", "gump", "limitless"):
        kinds.append("film")
    actions = " ".join(text[s:e] for s, e, k in split_sentences(text) if k == "action")
    kinds += [name for name, pattern in FEATURES.items() if re.search(pattern, actions)]
    for s, e, k in split_sentences(text):
        command = parse_command(text[s:e]) if k == "command" else None
        if command is None:
            continue
        if command.kind in ("camera", "weather"):
            family = "camera" if command.kind == "camera" else "light"
            kinds += [family, f"{family}:{command.value}"]
        else:
            kinds.append(command.kind)  # wait, speed
    if room := room_of_story(text):
        kinds.append(f"room:{room}")
    return list(dict.fromkeys(kinds))


def assign_splits(names: Iterable[str]) -> dict[str, str]:
    """The split rule: in name order, each story goes where its kind, then its room, then all are fewest.

    Deterministic and blind to the text; a story whose name sorts last moves no other.
    """
    count: dict[str, collections.Counter[str]] = {s: collections.Counter() for s in ("dev", "test")}
    out: dict[str, str] = {}
    for name in sorted(names):
        parts = Path(name).stem.split("-")
        kind, room = parts[0], parts[1] if len(parts) > 1 else ""
        split = min(
            ("dev", "test"),
            key=lambda s: (count[s][f"k:{kind}"], count[s][f"r:{room}"], count[s]["all"], s != "dev"),
        )
        out[name] = split
        count[split].update([f"k:{kind}", f"r:{room}", "all"])
    return out


def describe(root: Path = STORIES) -> str:
    """A markdown table: kind -> stories and sentences per split (what the corpus covers)."""
    table: dict[str, dict[str, list[int]]] = collections.defaultdict(lambda: {s: [0, 0] for s in SPLITS})
    for split in SPLITS:
        for path in sorted((root / split).glob("*.txt")):
            text = path.read_text(encoding="utf-8")
            n = len(split_sentences(text))
            for kind in ["all", *story_kinds(path, text)]:
                table[kind][split][0] += 1
                table[kind][split][1] += n
    head = "| kind | " + " | ".join(f"{s} stories | {s} sentences" for s in SPLITS) + " |"
    lines = [head, "|" + "---|" * (1 + 2 * len(SPLITS))]
    order = ["all", *PRIMARY_KINDS, "single-character", "multi-character", "film", *FEATURES]
    for kind in order + sorted(k for k in table if k not in order):
        if kind in table:
            cells = " | ".join(f"{table[kind][s][0]} | {table[kind][s][1]}" for s in SPLITS)
            lines.append(f"| {kind} | {cells} |")
    return "\n".join(lines)


# --- the checks (written by the fidelity and render engineers; loaded lazily) --------------------------


class MissingStage(RuntimeError):
    """A module the measurement needs is not in this build."""


def fidelity_api() -> tuple[Callable[..., Any], Callable[..., Any]]:
    """``wana.fidelity.story_checks`` and ``verdicts``; MissingStage when the package is not there."""
    try:
        from wana.fidelity import story_checks, verdicts
    except ImportError as exc:
        raise MissingStage(f"wana.fidelity (the story checks) is not in this build: {exc}") from exc
    return story_checks, verdicts


def camera_api() -> Callable[..., Any]:
    """The render service's ``camera_checks(scene, motions, commands, sentences, *, width, height)``."""
    import services.render as render

    found = [m.name for m in pkgutil.iter_modules(render.__path__) if m.name not in ("worker", "demo")]
    for name in dict.fromkeys(["fidelity", "checks", "camera_checks", *found]):
        try:
            module = importlib.import_module(f"services.render.{name}")
        except ImportError:
            continue
        if callable(fn := getattr(module, "camera_checks", None)):
            return fn
    raise MissingStage("services.render has no camera_checks() yet (the camera and command checks)")


def gallery_api() -> Callable[..., Any] | None:
    """``services.render.gallery.contact_sheet``, or None (the gallery is skipped with a warning)."""
    try:
        from services.render.gallery import contact_sheet
    except ImportError:
        return None
    return contact_sheet


# --- one story -----------------------------------------------------------------------------------------


def sentence_frames(motions: dict[str, Any], sentence_id: str) -> tuple[int, int] | None:
    spans = [
        (g.start_frame, g.end_frame)
        for m in motions.values()
        for g in m.segments
        if g.sentence_id == sentence_id
    ]
    return (min(s for s, _ in spans), max(e for _, e in spans)) if spans else None


def sheet_frames(failing: Sequence[int], span: tuple[int, int] | None, total: int) -> list[int]:
    """At most SHEET_TILES frames for one sentence's contact sheet: failing ones, and its first and last.

    Failing frames inside the sentence's own frames come first (a check may also name frames elsewhere).
    """

    def spread(frames: Sequence[int], n: int) -> list[int]:
        frames = sorted(set(frames))
        if len(frames) <= n:
            return frames
        return [frames[round(i * (len(frames) - 1) / (n - 1))] for i in range(n)]

    context = [span[0], max(span[0], span[1] - 1)] if span else []
    inside = [f for f in failing if span and span[0] <= f < span[1]]
    failing = inside or failing
    if failing:
        picked = spread(failing, SHEET_TILES - len(context)) + context
    elif span:
        picked = spread(range(span[0], span[1]), 4)
    else:
        picked = [0, total // 2, max(total - 1, 0)]
    return sorted({min(max(f, 0), max(total - 1, 0)) for f in picked})


def _compute(text: str, doc_id: str, seed: int) -> Any:
    from services.orchestrator.backend import InProcessBackend
    from services.orchestrator.session import Orchestrator

    with tempfile.TemporaryDirectory(prefix="wana-eval-") as tmp:
        orchestrator = Orchestrator(Path(tmp) / "sessions.db", InProcessBackend(), seed=seed)
        try:
            return orchestrator.create(text, doc_id=doc_id).compute()
        finally:
            orchestrator.close()


def evaluate_story(path: Path, seed: int = 0, gallery: Path | None = None) -> dict[str, Any]:
    """One story file (read as `wana animate` reads it: undecodable bytes replaced, a Fountain screenplay
    turned into the story it tells)."""
    text = path.read_text(encoding="utf-8", errors="replace")
    from wana.screenplay import looks_like_fountain, to_story

    if looks_like_fountain(text, str(path)):
        text = to_story(text)
    return evaluate_text(path.stem, text, seed, gallery)


def evaluate_text(story: str, text: str, seed: int = 0, gallery: Path | None = None) -> dict[str, Any]:
    """Compute one story, check every sentence; a crash anywhere is this story's failure, with its reason."""
    t0 = time.perf_counter()
    try:
        result = _compute(text, story, seed)
    except Exception:
        return crashed_row(story, text, traceback.format_exc(), time.perf_counter() - t0)
    return check_result(story, text, result, gallery, compute_s=time.perf_counter() - t0)


def crashed_row(story: str, text: str, trace: str, compute_s: float) -> dict[str, Any]:
    """The row of a story whose pipeline or checks crashed: every sentence failed with the traceback's last line."""
    row: dict[str, Any] = {"story": story, "kinds": story_kinds(story, text), "gallery": []}
    row["error"] = trace.strip().splitlines()[-1]
    row["compute_s"] = compute_s
    row["per_sentence"] = [
        {"id": f"s{i + 1}", "kind": k, "text": text[s:e], "verdict": "failed", "checks": [], "results": [],
         "failed": [{"name": "pipeline", "reason": row["error"], "frames": [], "character": ""}]}
        for i, (s, e, k) in enumerate(split_sentences(text))
    ]  # fmt: skip
    row["sentences"], row["ok"] = len(row["per_sentence"]), False
    return row


def story_camera_checks(result: Any, tally: list[Any] | None = None) -> dict[str, Any]:
    """Sentence id -> the render service's camera checks of one computed story (the video's size); ``tally``
    gathers a services.render.camera_checks.ViewTally per in_view check."""
    return dict(
        camera_api()(
            result.scene, result.motions, result.commands, result.sentences, width=WIDTH, height=HEIGHT,
            tally=tally,
        )
    )  # fmt: skip


def story_verdicts(
    result: Any, camera: dict[str, Any] | None = None, tally: list[Any] | None = None
) -> dict[str, Any]:
    """Sentence id -> SentenceVerdict of one computed story: the fidelity checks and the camera checks
    (``camera`` when already computed for this animation)."""
    story_checks, verdicts = fidelity_api()
    sentences = [(s.id, s.kind) for s in result.sentences]
    body = story_checks(sentences, result.graphs, result.scene, result.motions, result.unavailable)
    if camera is None:
        camera = story_camera_checks(result, tally)
    return dict(verdicts(body, extra=camera))


def check_result(
    story: str,
    text: str,
    result: Any,
    gallery: Path | None = None,
    *,
    compute_s: float = 0.0,
    camera: dict[str, Any] | None = None,
) -> dict[str, Any]:
    """The row of one computed story: each sentence's verdict, its checks (``results``: name, ok, character,
    frames) and the failed ones' reasons; a crash in the checks is this story's failure."""
    t0 = time.perf_counter()
    tally: list[Any] = []  # a ViewTally per in_view check, when the camera checks are computed here
    try:
        verdict = story_verdicts(result, camera, tally)
    except Exception:
        return crashed_row(story, text, traceback.format_exc(), compute_s)
    row: dict[str, Any] = {"story": story, "kinds": story_kinds(story, text), "error": "", "gallery": []}
    row["compute_s"] = compute_s
    row["view"] = {k: sum(getattr(t, k) for t in tally) for k in ("frames", "in_frame", "occluded")}
    row["checks_s"] = time.perf_counter() - t0
    row["per_sentence"] = []
    for s in result.sentences:
        v = verdict.get(s.id)
        checks = list(v.checks) if v is not None else []
        failed = [
            {"name": c.name, "reason": c.reason, "frames": list(c.frames)[:30], "character": c.character}
            for c in checks
            if not c.ok
        ]
        row["per_sentence"].append(
            {
                "id": s.id,
                "kind": s.kind,
                "text": s.text,
                "verdict": v.verdict if v is not None else "ok",
                "checks": sorted({c.name for c in checks}),
                "results": [
                    {
                        "name": c.name,
                        "ok": c.ok,
                        "character": c.character,
                        "reason": c.reason,
                        "frames": frame_sample(c.frames),
                    }
                    for c in checks
                ],  # fmt: skip
                "failed": failed,
                "failing_frames": sorted({f for c in checks if not c.ok for f in c.frames}),
            }
        )
    row["sentences"] = len(row["per_sentence"])
    row["ok"] = all(s["verdict"] == "ok" for s in row["per_sentence"])
    t1 = time.perf_counter()
    if gallery is not None:
        try:
            row["gallery"] = _gallery(result, row, gallery / story)
        except Exception:
            row.setdefault("gallery_errors", []).append(traceback.format_exc().strip().splitlines()[-1])
    row["gallery_s"] = time.perf_counter() - t1
    for s in row["per_sentence"]:
        del s["failing_frames"]
    return row


def frame_sample(frames: Sequence[int], most: int = 30) -> list[int]:
    """At most `most` of a check's frames, evenly spread with the first and last kept (for the JSON)."""
    frames = list(frames)
    if len(frames) <= most:
        return [int(f) for f in frames]
    return [int(frames[round(i * (len(frames) - 1) / (most - 1))]) for i in range(most)]


def _gallery(result: Any, row: dict[str, Any], folder: Path) -> list[str]:
    """One contact sheet per failed sentence; a sheet that cannot be drawn is noted, never fatal."""
    contact_sheet = gallery_api()
    if contact_sheet is None:
        return []
    shutil.rmtree(folder, ignore_errors=True)  # no sheet left from an earlier run of a sentence now ok
    total = max((m.root_position.shape[0] for m in result.motions.values()), default=1)
    written = []
    for s in row["per_sentence"]:
        if s["verdict"] == "ok":
            continue
        failing = s["failing_frames"]
        frames = sheet_frames(failing, sentence_frames(result.motions, s["id"]), total)
        reasons = "; ".join(f"{f['name']}: {f['reason']}" for f in s["failed"])
        path = folder / f"{s['id']}.png"
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            contact_sheet(
                result.scene, result.motions, result.commands, result.sentences, frames,
                set(frames) & set(failing), f"{row['story']} {s['id']}: {s['text']} -- {reasons}", path,
            )  # fmt: skip
            written.append(str(path))
        except Exception:
            row.setdefault("gallery_errors", []).append(traceback.format_exc().strip().splitlines()[-1])
    return written


# --- the corpus run ------------------------------------------------------------------------------------


def story_paths(split: str, stories: Path | None = None) -> list[Path]:
    if stories is not None:
        return sorted(stories.glob("*.txt"))
    splits = SPLITS if split == "all" else (split,)
    return [p for s in splits for p in sorted((STORIES / s).glob("*.txt"))]


def quick_subset(paths: Sequence[Path], n: int = QUICK_STORIES) -> list[Path]:
    """A fixed subset: round-robin over the kinds (sorted), stories in name order within each kind."""
    by_kind: dict[str, list[Path]] = collections.defaultdict(list)
    for p in sorted(paths, key=lambda p: p.name):
        by_kind[primary_kind(p)].append(p)
    queues = [by_kind[k] for k in sorted(by_kind)]
    out: list[Path] = []
    while len(out) < n and any(queues):
        for q in queues:
            if q and len(out) < n:
                out.append(q.pop(0))
    return out


def run_all(paths: Sequence[Path], seed: int, gallery: Path | None, jobs: int) -> list[dict[str, Any]]:
    from tqdm import tqdm

    if jobs <= 1:
        return [evaluate_story(p, seed, gallery) for p in tqdm(paths, desc="stories", unit="story")]
    from concurrent.futures import ProcessPoolExecutor, as_completed

    with ProcessPoolExecutor(max_workers=jobs) as pool:
        futures = {pool.submit(evaluate_story, p, seed, gallery): i for i, p in enumerate(paths)}
        rows: list[Any] = [None] * len(paths)
        for fut in tqdm(as_completed(futures), total=len(futures), desc="stories", unit="story"):
            rows[futures[fut]] = fut.result()
    return rows


def summarise(rows: Sequence[dict[str, Any]], seed: int, split: str) -> dict[str, Any]:
    """The JSON summary: fidelity shares, failures per check, verdict counts, timings and per-story rows."""
    sentences = [s for r in rows for s in r["per_sentence"]]
    names = list(CHECK_NAMES) + sorted({c for s in sentences for c in s["checks"]} - set(CHECK_NAMES))
    checked = {n: sum(n in s["checks"] for s in sentences) for n in names}
    failures = {n: sum(any(f["name"] == n for f in s["failed"]) for s in sentences) for n in names}
    compute = [r["compute_s"] for r in rows]
    view = {k: sum(r.get("view", {}).get(k, 0) for r in rows) for k in ("frames", "in_frame", "occluded")}
    return {
        "sentence_fidelity": sum(s["verdict"] == "ok" for s in sentences) / max(len(sentences), 1),
        # of every acting character's action frames: in the picture; in it but under 70 % unhidden
        "acting_in_frame_share": view["in_frame"] / max(view["frames"], 1),
        "occluded_share": view["occluded"] / max(view["frames"], 1),
        "story_fidelity": sum(r["ok"] for r in rows) / max(len(rows), 1),
        "checks": failures,
        "checked": checked,
        "stories": len(rows),
        "sentences": len(sentences),
        "verdicts": dict(collections.Counter(s["verdict"] for s in sentences)),
        "crashed": sum(bool(r["error"]) for r in rows),
        "unchecked": sum(not s["checks"] and not s["failed"] for s in sentences),
        "compute_s_mean": sum(compute) / max(len(compute), 1),
        "compute_s_max": max(compute, default=0.0),
        "seed": seed,
        "split": split,
        "per_story": list(rows),
    }


def print_tables(summary: dict[str, Any]) -> None:
    print(f"{'check':18s} {'checked':>8s} {'failures':>9s} {'rate':>7s}")
    for name, fails in summary["checks"].items():
        n = summary["checked"][name]
        print(f"{name:18s} {n:8d} {fails:9d} {fails / n if n else 0.0:7.3f}")
    print()
    for r in summary["per_story"]:
        if not r["ok"]:
            bad = [s for s in r["per_sentence"] if s["verdict"] != "ok"]
            print(f"{r['story']:32s} {len(bad):3d}/{r['sentences']:<3d} not ok  {r['error']}")
    print()
    for key in ("sentence_fidelity", "story_fidelity", "acting_in_frame_share", "occluded_share"):
        print(f"{key:20s} {summary[key]:.3f}")
    print(
        f"{'stories':20s} {summary['stories']} ({summary['crashed']} crashed), sentences {summary['sentences']}"
        f" ({summary['unchecked']} with no check), verdicts {summary['verdicts']}"
    )
    print(f"{'compute s/story':20s} mean {summary['compute_s_mean']:.1f}, max {summary['compute_s_max']:.1f}")


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--split", choices=(*SPLITS, "all"), default="test", help="corpus split (default test)")
    ap.add_argument(
        "--stories", type=Path, default=None, help="any folder of .txt stories instead of a split"
    )
    ap.add_argument("--quick", action="store_true", help=f"a fixed {QUICK_STORIES}-story subset of the split")
    ap.add_argument("--json", type=Path, default=None, help="write the summary and per-story rows here")
    ap.add_argument("--gallery", action=argparse.BooleanOptionalAction, default=True,
                    help="a contact sheet per failed sentence under --gallery-dir (default on)")  # fmt: skip
    ap.add_argument("--gallery-dir", type=Path, default=GALLERY, help="default out/eval/story")
    ap.add_argument("--jobs", type=int, default=1, help="stories computed in parallel processes (default 1)")
    ap.add_argument(
        "--seed", type=int, default=0, help="the pipeline's seed (default 0, recorded in the JSON)"
    )
    ap.add_argument("--describe", action="store_true", help="print what the corpus covers and exit")
    return ap


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    if args.describe:
        print(describe())
        return 0
    try:
        fidelity_api()
        camera_api()
    except MissingStage as exc:
        print(f"eval/story.py: cannot measure: {exc}", file=sys.stderr)
        return 2
    gallery: Path | None = args.gallery_dir if args.gallery else None
    if gallery is not None and gallery_api() is None:
        print(
            "eval/story.py: warning: services.render.gallery is not in this build: no gallery",
            file=sys.stderr,
        )
        gallery = None
    paths = story_paths(args.split, args.stories)
    if not paths:
        print(f"eval/story.py: no .txt stories in {args.stories or STORIES / args.split}", file=sys.stderr)
        return 2
    if args.quick:
        paths = quick_subset(paths)
    t0 = time.perf_counter()
    rows = run_all(paths, args.seed, gallery, args.jobs)
    split = str(args.stories) if args.stories is not None else args.split
    summary = {
        **summarise(rows, args.seed, split),
        "quick": bool(args.quick),
        "wall_s": time.perf_counter() - t0,
    }
    print_tables(summary)
    if gallery is not None:
        print(f"gallery: {gallery} ({sum(len(r['gallery']) for r in rows)} sheets)")
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(summary, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
