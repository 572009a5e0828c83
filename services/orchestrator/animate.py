"""`wana animate FILE -o DIR`: the whole pipeline on one text, embedded, writing the outputs.

Writes DIR/animation.mp4, DIR/scene.glb, DIR/<character>.bvh and DIR/report.json. A stage whose logic is
not in this build is named in a clear message and in the report; nothing is faked.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
from pathlib import Path
from typing import Any

import msgspec

from services.orchestrator.backend import InProcessBackend
from services.orchestrator.pipeline import PipelineResult
from services.orchestrator.session import Orchestrator

MAX_INPUT_BYTES = 1_000_000


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="wana animate",
        description="Turn a story file into an animation: animation.mp4, scene.glb, one BVH per character and "
        "report.json in the output folder. Runs the broker and one worker per service in this process.",
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
    return p


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


def summary(result: PipelineResult) -> dict[str, Any]:
    """The report: sentences, SSG, retrieval choices, diagnostics and what ran."""
    to_builtins = msgspec.to_builtins
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
            }
            for s in result.sentences
        ],
        "scene": to_builtins(result.scene) if result.scene is not None else None,
        "retrieval": _without_header(to_builtins(result.scene_report))
        if result.scene_report is not None
        else None,
        "optimisation": [_without_header(to_builtins(o)) for o in result.optimisations],
        "characters": sorted(result.motions),
        "unavailable": result.unavailable,
        "nodes_ran": result.ran,
    }


def main(argv: list[str]) -> int:
    args = build_parser().parse_args(argv)
    text = read_story(args.file)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    tick, close = _progress_bar(not args.no_progress and sys.stderr.isatty())
    with tempfile.TemporaryDirectory(prefix="wana-") as tmp:
        if args.in_process:
            orchestrator = Orchestrator(Path(tmp) / "sessions.db", InProcessBackend(), seed=args.seed)
            result = orchestrator.create(text, doc_id="story").compute(progress=tick)
            orchestrator.close()
        else:
            from services.orchestrator.embedded import Embedded

            with Embedded() as backend:
                orchestrator = Orchestrator(Path(tmp) / "sessions.db", backend, seed=args.seed)
                result = orchestrator.create(text, doc_id="story").compute(progress=tick)
                orchestrator.close()
    close()
    report = summary(result)
    (out / "report.json").write_text(json.dumps(report, indent=2))
    if result.scene is not None and not result.unavailable:
        try:
            from services.render.export import write_outputs
        except ImportError as exc:
            result.unavailable["render"] = f"the render stage is not available yet: {exc}"
        else:
            paths = write_outputs(
                out,
                result.scene,
                result.motions,
                result.commands,
                result.sentences,
                report,
                width=args.width,
                height=args.height,
                progress=not args.no_progress,
            )
    for sid, diags in result.diagnostics.items():
        for d in diags:
            if d.code != "E011":
                print(f"{sid} [{d.span.start}:{d.span.end}] {d.severity}: {d.message}", file=sys.stderr)
    if result.unavailable:
        for why in result.unavailable.values():
            print(f"wana animate: {why}", file=sys.stderr)
        print(
            f"wana animate: wrote only {out / 'report.json'}; the animation needs the stages above",
            file=sys.stderr,
        )
        return 3
    for name in sorted(paths):
        print(f"wrote {paths[name]}")
    return 0
