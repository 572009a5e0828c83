"""`wana animate FILE -o DIR`: the whole pipeline on one text, embedded, writing the outputs.

Writes DIR/animation.mp4, DIR/scene.glb, DIR/<character>.bvh and DIR/report.json; `--export` picks the
formats (mp4, glb, bvh, usd: DIR/animation.usdc, fbx: DIR/animation.fbx) and `zip` bundles every file
written with report.json in DIR/animation.zip. A stage whose logic is not in this build, or an export whose
optional package is missing, is named in a clear message; nothing is faked. `--cast NAME=FILE` plays a
story character with the user's own rigged humanoid (services/orchestrator/cast.py, wana.cast).
"""

from __future__ import annotations

import argparse
import contextlib
import importlib.util
import json
import os
import sys
import tempfile
import zipfile
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import msgspec

from proto.common import ErrorCode
from proto.fidelity import Check
from proto.render import CastMember, ExportFormat, ExportReply, Renderer
from services.orchestrator.backend import Backend, InProcessBackend, StageFailed, StageUnavailable
from services.orchestrator.budget import BUDGET_CODE, Budget
from services.orchestrator.exports import export
from services.orchestrator.pipeline import PipelineResult
from services.orchestrator.session import Orchestrator
from services.orchestrator.timeline import FPS

MAX_INPUT_BYTES = 1_000_000
FORMATS: tuple[ExportFormat, ...] = ("mp4", "glb", "bvh", "usd", "fbx")
DEFAULT_EXPORTS: tuple[ExportFormat, ...] = ("mp4", "glb", "bvh")
BUNDLE = "animation.zip"
PREVIEW_DEADLINE_S = 300.0  # one stage call through the embedded bus (services.orchestrator.embedded)
BLENDER_DEADLINE_S = 6 * 3600.0  # the Cycles render of a whole video is one call
# what each optional format needs on the machine that renders: (importable module, how to get it)
EXTRAS: dict[str, tuple[str, str]] = {
    "usd": ("pxr", "Pixar's usd-core: `make setup`, or `pip install usd-core`"),
    "fbx": (
        "bpy",
        "Blender as a Python module: `make setup` (the 'blender' extra), or set WANA_BLENDER_PYTHON",
    ),
}


def parse_exports(value: str) -> list[str]:
    """The --export list, in FORMATS order (plus "zip"); "zip" alone bundles the default formats.

    Raises:
        argparse.ArgumentTypeError: an unknown or empty entry.
    """
    asked = [v.strip().lower().lstrip(".") for v in value.split(",") if v.strip()]
    unknown = [v for v in asked if v not in (*FORMATS, "zip")]
    if unknown or not asked:
        raise argparse.ArgumentTypeError(
            f"unknown export {', '.join(unknown) or '(none)'}; choose from {','.join(FORMATS)},zip"
        )
    formats = [f for f in FORMATS if f in asked] or list(DEFAULT_EXPORTS)
    return formats + (["zip"] if "zip" in asked else [])


def missing_extras(formats: Sequence[str], renderer: str = "open3d") -> list[str]:
    """One message per asked format (and the Blender renderer) whose optional package this machine lacks
    (the embedded render runs here; a remote render worker answers for itself)."""
    asked = [(f"--export {fmt}", fmt) for fmt in formats if fmt in EXTRAS]
    if renderer == "blender" and "mp4" in formats:
        asked.append(("--renderer blender", "fbx"))  # the same Blender
    out = []
    for what, fmt in asked:
        module, how = EXTRAS[fmt]
        chosen = os.environ.get("WANA_BLENDER_PYTHON", "") if fmt == "fbx" else ""
        if chosen and not Path(chosen).is_file():
            out.append(f"{what} needs {how} (WANA_BLENDER_PYTHON={chosen} is not a file)")
        elif not chosen and importlib.util.find_spec(module) is None:  # found without importing it
            out.append(f"{what} needs {how}")
    return out


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="wana animate",
        description="Turn a story file into an animation: animation.mp4, scene.glb, one BVH per character and "
        "report.json in the output folder (--export picks the formats, USD and FBX among them). Runs the broker "
        "and one worker per service in this process.",
    )
    p.add_argument("file", help="the story text file ('-' reads standard input)")
    p.add_argument("-o", "--out", default="out", help="output folder (created; default: out)")
    p.add_argument("--seed", type=int, default=0, help="seed for every random choice (default 0)")
    p.add_argument("--width", type=int, default=640, help="video width in pixels (default 640)")
    p.add_argument("--height", type=int, default=480, help="video height in pixels (default 480)")
    p.add_argument(
        "--in-process",
        action="store_true",
        help="call the services' handlers directly instead of through the embedded bus",
    )
    p.add_argument("--no-progress", action="store_true", help="no progress bars")
    p.add_argument(
        "--export",
        type=parse_exports,
        default=list(DEFAULT_EXPORTS),
        metavar="LIST",
        help="comma-separated files to write: mp4,glb,bvh (default), usd (animation.usdc, needs usd-core), "
        "fbx (animation.fbx, needs Blender's bpy), zip (animation.zip: every file written and report.json)",
    )
    p.add_argument(
        "--renderer",
        choices=("open3d", "blender"),
        default="open3d",
        help="who draws animation.mp4: open3d (the fast preview, default) or blender (Blender's Cycles path "
        "tracer on the CPU, needs bpy: the same shots, frames and size, soft shadows and bounce light; your "
        "--cast characters wear their own mesh)",
    )
    p.add_argument(
        "--samples",
        type=int,
        default=0,
        metavar="N",
        help="--renderer blender: Cycles samples per pixel (default 16; denoised with OpenImageDenoise)",
    )
    p.add_argument(
        "--render-workers",
        type=int,
        default=0,
        metavar="N",
        help="processes rendering frame ranges of the video at once (default: as the free cores allow)",
    )
    p.add_argument(
        "--cast",
        action="append",
        default=[],
        metavar="NAME=FILE",
        help="play the story's character NAME with your own rigged humanoid (.glb, .vrm, or .fbx with Blender's "
        "bpy); its joints are found by name (Mixamo, VRM, Unity and Unreal humanoids); every output wears it. "
        "Repeatable",
    )
    p.add_argument(
        "--cast-map",
        action="append",
        default=[],
        metavar="[NAME=]FILE",
        help="a JSON object, canonical joint -> your joint name (Hips, Spine, Head, LeftArm, LeftForeArm, LeftHand, "
        "LeftUpLeg, LeftLeg, LeftFoot, the Right ones...), for a --cast rig whose names no table knows",
    )
    limits = p.add_argument_group(
        "compute budget",
        "what one story may spend; what goes over is cut with a W501 warning naming it, and the rest of "
        "the story still animates",
    )
    d = Budget()
    limits.add_argument(
        "--max-seconds",
        type=float,
        default=d.max_seconds,
        metavar="S",
        help=f"wall time of the pipeline (default {d.max_seconds:g}); sentences are parsed only in its first "
        "half, and stages after it are cut",
    )
    limits.add_argument(
        "--max-sentences",
        type=int,
        default=d.max_sentences,
        metavar="N",
        help=f"sentences animated; later ones are cut (default {d.max_sentences})",
    )
    limits.add_argument(
        "--max-sentence-chars",
        type=int,
        default=d.max_sentence_chars,
        metavar="N",
        help=f"longest sentence parsed; longer ones are cut (default {d.max_sentence_chars})",
    )
    limits.add_argument(
        "--max-wait-s",
        type=float,
        default=d.max_wait_s,
        metavar="S",
        help=f"longest 'wait N seconds' (default {d.max_wait_s:g})",
    )
    limits.add_argument(
        "--max-duration-s",
        type=float,
        default=d.max_duration_s,
        metavar="S",
        help=f"all waits of the story together (default {d.max_duration_s:g})",
    )
    return p


def budget_of(args: argparse.Namespace) -> Budget:
    """The compute budget the command line asks for (SystemExit 2 with a message for a bad value)."""
    budget = Budget(
        max_seconds=args.max_seconds,
        max_sentences=args.max_sentences,
        max_sentence_chars=args.max_sentence_chars,
        max_wait_s=args.max_wait_s,
        max_duration_s=args.max_duration_s,
    )
    try:
        budget.check()
    except ValueError as exc:
        raise SystemExit(f"wana animate: {exc}") from exc
    return budget


def read_story(path: str) -> str:
    if path == "-":
        data = sys.stdin.buffer.read(MAX_INPUT_BYTES + 1)
    else:
        p = Path(path)
        if not p.is_file():
            raise SystemExit(f"wana animate: no such file: {path}")
        data = p.read_bytes()[: MAX_INPUT_BYTES + 1]
    if len(data) > MAX_INPUT_BYTES:
        raise SystemExit(f"wana animate: the story is larger than {MAX_INPUT_BYTES} bytes")
    text = data.decode("utf-8", errors="replace")
    from wana.screenplay import looks_like_fountain, to_story

    if looks_like_fountain(text, "" if path == "-" else path):
        return to_story(text)  # a Fountain screenplay: headings, action lines, dialogue -> our sentences
    return text


def _progress_bar(enabled: bool) -> tuple[Any, Any]:
    if not enabled:
        return None, lambda: None
    from tqdm import tqdm

    bars: dict[str, Any] = {}

    def tick(stage: str, done: int, total: int) -> None:
        bar = bars.get(stage)
        if bar is None:
            bar = bars[stage] = tqdm(total=max(total, 1), desc=f"{stage:>9}", unit="step", leave=True)
        bar.total = max(total, 1)
        bar.n = done
        bar.refresh()

    def close() -> None:
        for bar in bars.values():
            bar.close()

    return tick, close


def _without_header(value: Any) -> Any:
    """Drop message headers (random ids) so that the same story gives the same report."""
    if isinstance(value, dict):
        return {k: v for k, v in value.items() if k not in ("header", "motion", "scene")}
    return value


def _dropped(result: PipelineResult, checks: Mapping[str, list[Check]]) -> dict[str, str]:
    """The report's `unavailable`: the stages that did not run, and each sentence whose essential checks fail
    (what it asked for was dropped: an unknown verb, a missing object), keyed by sentence id."""
    out = dict(result.unavailable)
    for sid, items in checks.items():
        lost = [c.reason for c in items if c.essential and not c.ok]
        if lost:
            out[sid] = "; ".join(dict.fromkeys(lost))
    return out


def summary(result: PipelineResult, extra_checks: Mapping[str, list[Check]] | None = None) -> dict[str, Any]:
    """The report: sentences (each with its verdict and story checks), SSG, retrieval choices, diagnostics,
    what was dropped and what ran.

    Args:
        result: the pipeline's result.
        extra_checks: sentence id -> more checks to join into the verdicts (the render service's camera and
            command checks, which only it can compute).
    """
    from wana.fidelity import story_checks, verdicts  # after the compute: not part of the start-up

    to_builtins = msgspec.to_builtins
    checks = story_checks(
        [(s.id, s.kind) for s in result.sentences],
        result.graphs,
        result.scene,
        result.motions,
        result.unavailable,
    )
    judged = verdicts(checks, extra_checks)
    return {
        "doc_version": result.version,
        "sentences": [
            {
                "id": s.id,
                "start": s.start,
                "end": s.end,
                "text": s.text,
                "kind": s.kind,
                "ssg": to_builtins(result.graphs.get(s.id)),
                "diagnostics": to_builtins(result.diagnostics.get(s.id, [])),
                "verdict": judged[s.id].verdict if s.id in judged else "ok",
                "checks": [
                    {
                        "name": c.name,
                        "ok": c.ok,
                        "reason": c.reason,
                        "frames": list(c.frames),
                        "character": c.character,
                    }
                    for c in (judged[s.id].checks if s.id in judged else [])
                ],
            }
            for s in result.sentences
        ],
        "scene": to_builtins(result.scene) if result.scene is not None else None,
        "retrieval": _without_header(to_builtins(result.scene_report))
        if result.scene_report is not None
        else None,
        "optimisation": [_without_header(to_builtins(o)) for o in result.optimisations],
        "characters": sorted(result.motions),
        "unavailable": _dropped(result, {sid: v.checks for sid, v in judged.items()}),
        "nodes_ran": result.ran,
        "cut": dict(result.cut),  # sentence id -> what the compute budget cut (W501)
    }


def nothing_to_animate(result: PipelineResult) -> str:
    """Why a story cannot be animated at all ("" when it can): no text, or no character and no object."""
    if not any(s.text.strip() for s in result.sentences):
        return "the story is empty"
    if "parse" in result.unavailable:
        return ""
    people = any(g.characters for g in result.graphs.values())
    things = any(g.objects for g in result.graphs.values() if g.kind == "scene")
    if not people and not things:
        return "the story names no character and no object to put in a room (nothing to animate)"
    return ""


def write_exports(
    backend: Backend,
    result: PipelineResult,
    report: dict[str, Any],
    out: Path,
    *,
    width: int = 640,
    height: int = 480,
    formats: Sequence[str] = DEFAULT_EXPORTS,
    cast: Sequence[CastMember] = (),
    renderer: Renderer = "open3d",
    samples: int = 0,
    render_workers: int = 0,
) -> dict[str, Path]:
    """The asked files (ExportRequests through the backend, as the gateway sends them: animation.mp4,
    scene.glb, one BVH per character, animation.usdc, animation.fbx), report.json with a "render" section,
    and with "zip" animation.zip holding all of them; file name -> path.

    The video's camera and command checks (only the render service knows the camera) join the verdicts of
    the report's sentences; without the MP4 the report has the story checks alone.
    """
    paths: dict[str, Path] = {}
    replies: list[ExportReply] = []
    for fmt in FORMATS:
        if fmt not in formats:
            continue
        if fmt == "bvh":
            replies += [
                export(backend, result, "bvh", character=name, cast=cast) for name in sorted(result.motions)
            ]
        else:
            replies.append(
                export(
                    backend,
                    result,
                    fmt,
                    width=width,
                    height=height,
                    cast=cast,
                    renderer=renderer,
                    samples=samples,
                    render_workers=render_workers,
                )
            )
    for reply in replies:
        paths[reply.filename] = out / reply.filename
        paths[reply.filename].write_bytes(reply.data)
    video = next((r for r in replies if r.format == "mp4"), None)
    timed = video or next((r for r in replies if r.n_frames), None)  # the GLB, USD and FBX know the shots
    report.update(summary(result, extra_checks=video.checks if video else None))
    fps = next(iter(result.motions.values())).fps if result.motions else FPS
    n_frames = timed.n_frames if timed else 0
    written = sorted([*paths, "report.json"])
    report["render"] = {
        "frames": n_frames,
        "fps": fps,
        "width": width,
        "height": height,
        "duration_s": n_frames / fps,
        "renderer": renderer if video else "",
        "commands": [
            {"frame": c.frame, "kind": c.command.kind, "value": c.command.value, "target": c.command.target}
            for c in (video.commands if video else [])
        ],
        "captions": msgspec.to_builtins(video.captions) if video else [],
        "shots": msgspec.to_builtins(timed.shots) if timed else [],
        "characters": sorted(result.motions),
        "files": sorted([*written, BUNDLE]) if "zip" in formats else written,
    }
    paths["report.json"] = out / "report.json"
    paths["report.json"].write_text(json.dumps(report, indent=2, ensure_ascii=False))
    if "zip" in formats:
        paths[BUNDLE] = out / BUNDLE
        with zipfile.ZipFile(paths[BUNDLE], "w", compression=zipfile.ZIP_DEFLATED) as bundle:
            for name in written:
                bundle.write(paths[name], arcname=name)
    return paths


def print_verdicts(report: dict[str, Any]) -> None:
    """One line per sentence the animation does not fully show, and the share that it does."""
    sentences = [s for s in report.get("sentences", []) if s.get("kind") != "empty"]
    for s in sentences:
        if s.get("verdict", "ok") == "ok":
            continue
        reasons = "; ".join(dict.fromkeys(c["reason"] for c in s.get("checks", []) if not c["ok"]))
        print(f"{s['id']} {s['verdict']}: {s['text'].strip()!r}: {reasons}", file=sys.stderr)
    shown = sum(1 for s in sentences if s.get("verdict", "ok") == "ok")
    print(f"wana animate: the animation shows {shown} of {len(sentences)} sentences fully", file=sys.stderr)


def print_diagnostics(result: PipelineResult) -> None:
    """Every diagnostic but the stage-unavailable ones, one line each; the same budget cut (W501) on many
    sentences is one line naming the first and last of them."""
    cuts: dict[str, list[str]] = {}
    for sid, diags in result.diagnostics.items():
        for d in diags:
            if d.code == BUDGET_CODE:
                cuts.setdefault(d.message, []).append(sid)
            elif d.code != ErrorCode.UNAVAILABLE:
                print(f"{sid} [{d.span.start}:{d.span.end}] {d.severity}: {d.message}", file=sys.stderr)
    for message, sids in cuts.items():
        where = sids[0] if len(sids) == 1 else f"{sids[0]}..{sids[-1]} ({len(sids)} sentences)"
        print(f"{where} warning: {message}", file=sys.stderr)


def _unknown_names(cast: list[CastMember], characters: list[str]) -> list[str]:
    if not cast:
        return []
    from services.orchestrator.cast import unknown_names

    return unknown_names(cast, characters)


def main(argv: list[str]) -> int:
    args = build_parser().parse_args(argv)
    budget = budget_of(args)
    missing = missing_extras(args.export, args.renderer)
    if args.samples < 0 or args.render_workers < 0:
        print("wana animate: --samples and --render-workers must be >= 0", file=sys.stderr)
        return 2
    if missing:
        for why in missing:
            print(f"wana animate: {why}", file=sys.stderr)
        return 2
    text = read_story(args.file)
    cast = []
    if args.cast or args.cast_map:  # rig reading (scipy, glTF) is imported only for a story with a cast
        from services.orchestrator.cast import load_cast
        from wana.cast import CastError

        try:
            cast = load_cast(args.cast, args.cast_map)
        except CastError as exc:
            print(f"wana animate: {exc}", file=sys.stderr)
            return 2
    out = Path(args.out)
    if not text.strip():
        print("wana animate: the story is empty; wrote nothing", file=sys.stderr)
        return 2
    tick, close = _progress_bar(not args.no_progress and sys.stderr.isatty())
    with tempfile.TemporaryDirectory(prefix="wana-") as tmp, contextlib.ExitStack() as stack:
        if args.in_process:
            backend: Backend = InProcessBackend()
        else:
            from services.orchestrator.embedded import Embedded

            # a Cycles video takes far longer than the preview's (seconds per frame, not frames per second)
            deadline = BLENDER_DEADLINE_S if args.renderer == "blender" else PREVIEW_DEADLINE_S
            backend = stack.enter_context(Embedded(deadline_s=deadline))
        orchestrator = Orchestrator(Path(tmp) / "sessions.db", backend, seed=args.seed, budget=budget)
        result = orchestrator.create(text, doc_id="story").compute(progress=tick)
        orchestrator.close()
        close()
        empty = nothing_to_animate(result)
        if empty:
            for sid, diags in result.diagnostics.items():
                for d in diags:
                    print(f"{sid} [{d.span.start}:{d.span.end}] {d.severity}: {d.message}", file=sys.stderr)
            print(f"wana animate: {empty}; wrote nothing", file=sys.stderr)
            return 2
        strangers = _unknown_names(cast, sorted(result.motions))
        if strangers:
            for why in strangers:
                print(f"wana animate: {why}", file=sys.stderr)
            return 2
        out.mkdir(parents=True, exist_ok=True)
        report = summary(result)
        (out / "report.json").write_text(json.dumps(report, indent=2, ensure_ascii=False))
        paths: dict[str, Path] = {}
        if result.scene is not None and not result.unavailable:
            try:
                paths = write_exports(
                    backend,
                    result,
                    report,
                    out,
                    width=args.width,
                    height=args.height,
                    formats=args.export,
                    cast=cast,
                    renderer=args.renderer,
                    samples=args.samples,
                    render_workers=args.render_workers,
                )
            except (StageFailed, StageUnavailable) as exc:
                result.unavailable["render"] = str(exc)
    print_diagnostics(result)
    if result.unavailable:
        for why in result.unavailable.values():
            print(f"wana animate: {why}", file=sys.stderr)
        print(
            f"wana animate: wrote only {out / 'report.json'}; the animation needs the stages above",
            file=sys.stderr,
        )
        return 3
    print_verdicts(report)
    for name in sorted(paths):
        print(f"wrote {paths[name]}")
    return 0
