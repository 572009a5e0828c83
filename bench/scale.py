"""Where users wait, at every document size: edit latency, full recompute, start-up, render and encode.

    .venv/bin/python bench/scale.py [--quick] [--json PATH] [--sizes 10,40,160,640] [--reps 3]

Edits (the orchestrator in this process over the in-process backend, as the embedded default calls the
handlers; a document of 6 scene sentences, one of them an object no action uses, then two characters
alternating actions up to N sentences): after a cold compute, each edit is applied and the document
recomputed; the time is edit + compute, its median over ``--reps`` edits (each a real change: a word
changed to one not computed before: walks -> runs -> jogs -> marches). Edits: ``action`` (a verb in the middle), ``late_action`` (the last action),
``scene_unused`` (the colour of the plant no action uses), ``scene_used`` (the chair's material), and
``full`` (a cold compute of a fresh session). The nodes each edit ran are counted.

Start-up and ``wana animate`` (a child process per story, the embedded bus, 640x480): ``startup_s`` is
launch -> the first progress tick of the pipeline (imports, bus and workers up, spaCy loaded when the
first sentence is parsed); compute ends at the last tick; the rest (render + encode + GLB/BVH) is
``export_s``. ``animate_realtime_factor`` = animation seconds / wall seconds of the 8-action story.

Render: ``render_fps_640`` / ``render_fps_1280``, frames per second of one FrameRenderer on the demo
office (bench/render.py's measure), encoding not counted; ``encode_overlap`` renders and encodes the
same frames with the encoder on its own thread. ``render_speedup_2_workers`` comes from bench/render.py
(not run here).

``parse_ms``: the parse stage alone (split, parse, resolve) cold over a document of that many sentences,
all different (the 6 scene sentences, then actions no two alike), so the NLP service's cache by
sentence text answers none of them.

JSON keys: action_edit_p50_ms, late_action_edit_p50_ms, scene_edit_p50_ms, scene_used_edit_p50_ms,
full_ms, parse_ms (each a map size -> ms), nodes (size -> kind -> nodes run), edit_cpu_p50_ms (size ->
kind -> CPU ms of this process, time.process_time: the edits' cost as load does not distort it), startup_s, animate (per story),
serve_ready_s, serve_first_ack_s, serve_first_edit_s (``wana serve`` launched on a fresh database: seconds to
answer HTTP, to acknowledge a new document's first edit and to send its animation),
animate_realtime_factor, render_fps_640, render_fps_1280, render_cpu_ms_per_frame_640 and _1280 (CPU time per
frame, all threads: what load does not distort), cpu_count, load_average.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))
sys.path.insert(0, str(REPO / "bench"))

SCENE = [
    "In the office there is a desk near a window$.",
    "A laptop is on the desk$.",
    "A chair is in front of the desk$.",
    "A sofa is next to the bookshelf$.",
    "A lamp is on the side table$.",
    "A green plant is in the corner$.",  # no action uses it
]
ACTIONS = [
    "Eve walks to the chair.",
    "Tom walks to the sofa.",
    "Eve sits on the chair.",
    "Tom waves at Eve.",
    "Eve types on the laptop.",
    "Tom sits on the sofa.",
    "Eve stands up.",
    "Tom stands up.",
    "Eve walks to the window.",
    "Tom walks to the lamp.",
]
SEED = 0
WARM_UP = "In the kitchen there is a table$. A cup is on the table$. Ann walks to the table. Ann drinks."


def document(size: int) -> str:
    """6 scene sentences, then ``size - 6`` action sentences, the two characters taking turns."""
    actions = [ACTIONS[i % len(ACTIONS)] for i in range(max(size - len(SCENE), 2))]
    return " ".join(SCENE) + "\n" + "\n".join(actions)


def _swap(text: str, old: str, new: str, at: int) -> tuple[int, int, str]:
    """(start, end, replacement) of the ``old`` nearest after character ``at``."""
    i = text.find(old, at)
    if i < 0:
        i = text.rfind(old)
    return i, i + len(old), new


def edit_latency(size: int, reps: int) -> dict[str, Any]:
    from services.orchestrator.backend import InProcessBackend
    from services.orchestrator.document import TextChange
    from services.orchestrator.session import Orchestrator

    out: dict[str, Any] = {"ms": {}, "cpu_ms": {}, "nodes": {}}
    with tempfile.TemporaryDirectory(prefix="wana-scale-") as tmp:
        orch = Orchestrator(Path(tmp) / "s.db", InProcessBackend(), seed=SEED)
        orch.create(WARM_UP, doc_id="warm").compute()  # models loaded, caches warm: not part of any time
        text = document(size)
        t0, c0 = time.perf_counter(), time.process_time()
        session = orch.create(text, doc_id="cold")
        result = session.compute()
        out["ms"]["full"] = 1000 * (time.perf_counter() - t0)
        out["cpu_ms"]["full"] = 1000 * (time.process_time() - c0)
        out["nodes"]["full"] = len(result.ran)
        edits = {  # kind -> (the phrases it goes through, one edit from each to the next; where to look)
            "action": (["walks", "runs", "jogs", "marches", "walks"], len(text) // 2),
            "late_action": (["walks", "runs", "jogs", "marches", "walks"], text.rfind("walks") - 1),
            "scene_unused": (["green plant", "red plant", "blue plant", "yellow plant", "green plant"], 0),
            "scene_used": (["A chair", "A wooden chair", "A metal chair", "A plastic chair", "A chair"], 0),
        }
        for kind, (phrases, at) in edits.items():
            times, cpu, nodes = [], [], []
            for rep in range(reps):
                cur = session.doc.text
                old, new = phrases[rep % 4], phrases[rep % 4 + 1]  # never back to a text computed just before
                start, end, repl = _swap(cur, old, new, min(at, len(cur) - 1))
                t0, c0 = time.perf_counter(), time.process_time()
                session.edit(session.doc.version, [TextChange(start=start, end=end, text=repl)])
                result = session.compute()
                times.append(1000 * (time.perf_counter() - t0))
                cpu.append(1000 * (time.process_time() - c0))
                nodes.append(len(result.ran))
            out["ms"][kind] = statistics.median(times)
            out["cpu_ms"][kind] = statistics.median(cpu)
            out["nodes"][kind] = int(statistics.median(nodes))
        orch.close()
    return out


NAMES = ["Eve", "Tom", "Ann", "Bob", "Kim", "Max", "Zoe", "Ian", "Lea", "Sam"]
VERBS = [
    "walks to the {o}.",
    "looks at the {o}.",
    "points at the {o}.",
    "runs to the {o}.",
    "stands near the {o}.",
]
ADVERBS = ["", "slowly ", "quickly ", "then ", "calmly ", "again "]  # 3000 different sentences in all
OBJECTS = ["chair", "sofa", "window", "lamp", "desk", "laptop", "plant", "bookshelf", "side table", "door"]


def unique_actions(n: int, first: int = 0) -> list[str]:
    """``n`` action sentences no two alike (name x verb x object), from combination ``first`` on: the NLP
    service's own cache by sentence text never answers them."""
    out = []
    for k in range(first, first + n):
        name, rest = NAMES[k % len(NAMES)], k // len(NAMES)
        verb, obj = VERBS[rest % len(VERBS)], OBJECTS[(rest // len(VERBS)) % len(OBJECTS)]
        how = ADVERBS[(rest // (len(VERBS) * len(OBJECTS))) % len(ADVERBS)]
        out.append(f"{name} {how}{verb.format(o=obj)}")
    return out


def parse_latency(sizes: list[int]) -> dict[str, float]:
    """Size -> ms of a cold parse stage (split, parse, resolve; a fresh session's engine) of a document of
    ``size`` sentences, all different (what a first open of a hand-written story costs in the parser)."""
    from services.orchestrator.backend import InProcessBackend
    from services.orchestrator.document import Document
    from services.orchestrator.pipeline import Pipeline
    from services.orchestrator.queries import QueryEngine

    backend = InProcessBackend()
    warm = Document.from_text("warm", WARM_UP)
    Pipeline(backend, doc_id="warm").run(warm, QueryEngine(), stages=("parse",))  # spaCy loaded
    out: dict[str, float] = {}
    first = 0
    for size in sizes:
        doc = Document.from_text(
            "p", " ".join(SCENE) + "\n" + "\n".join(unique_actions(size - len(SCENE), first))
        )
        first += size
        t0 = time.perf_counter()
        Pipeline(backend, doc_id="p").run(doc, QueryEngine(), stages=("parse",))
        out[str(size)] = round(1000 * (time.perf_counter() - t0), 1)
    return out


CHILD = r"""
import json, os, sys, time
import services.orchestrator.animate as animate
ticks = []
STARTUP_ONLY = os.environ.get("WANA_BENCH_STARTUP_ONLY") == "1"
def tick(stage, done, total):
    ticks.append(time.time())
    if STARTUP_ONLY:  # launch -> first step is all that is asked: stop here
        print("TIMES " + json.dumps({"rc": 0, "main": t_main, "first": ticks[0], "last": ticks[0], "end": ticks[0]}))
        sys.stdout.flush()
        os._exit(0)
def bar(enabled):
    return tick, (lambda: None)
animate._progress_bar = bar  # the pipeline's own progress callback, to time its first and last step
t_main = time.time()
rc = animate.main(sys.argv[1:])
t_end = time.time()
import multiprocessing.forkserver as forkserver  # reap the render processes' fork server (after the timing):
getattr(forkserver._forkserver, "_stop", lambda: None)()  # its CPU and its workers' join this child's
print("TIMES " + json.dumps({"rc": rc, "main": t_main, "first": ticks[0] if ticks else t_end,
                              "last": ticks[-1] if ticks else t_end, "end": t_end}))
"""


def story(actions: int, characters: int) -> str:
    names = ["Eve", "Tom", "Ann", "Bob", "Kim", "Max", "Zoe", "Ian"][:characters]
    verbs = ["walks to the chair.", "waves.", "walks to the window.", "nods.", "walks to the sofa."]
    lines = [" ".join(SCENE)]
    lines += [f"{names[i % characters]} {verbs[(i // characters) % len(verbs)]}" for i in range(actions)]
    return "\n".join(lines)


def _children_cpu_s() -> float:
    """User + system CPU seconds of this process's finished children (and theirs)."""
    try:
        import resource
    except ImportError:  # pragma: no cover - not on Unix
        return 0.0
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def animate_run(actions: int, characters: int, startup_only: bool = False) -> dict[str, Any]:
    """One `wana animate` in a child process: start-up, compute, export seconds, peak RSS, real-time factor
    (``startup_only``: the child stops at the pipeline's first step, as ``--quick`` does)."""
    with tempfile.TemporaryDirectory(prefix="wana-scale-") as tmp:
        path = Path(tmp) / "story.txt"
        path.write_text(story(actions, characters))
        env = {**os.environ, "PYTHONPATH": str(REPO), "WANA_BENCH_STARTUP_ONLY": "1" if startup_only else "0"}
        cmd = [sys.executable, "-c", CHILD, str(path), "-o", str(Path(tmp) / "out"), "--no-progress"]
        cpu0 = _children_cpu_s()
        launch = time.time()
        proc = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=900, cwd=REPO)
        wall = time.time() - launch
        cpu = _children_cpu_s() - cpu0
        line = next((x for x in proc.stdout.splitlines() if x.startswith("TIMES ")), None)
        if line is None:
            raise RuntimeError(f"wana animate failed: {proc.stderr[-2000:]}")
        t = json.loads(line[6:])
        report_path = Path(tmp) / "out" / "report.json"
        duration = (
            json.loads(report_path.read_text())["render"]["duration_s"] if report_path.exists() else 0.0
        )
        rss_kb = 0
        try:  # children's peak RSS (ru_maxrss, kB on Linux): this child is the only one finished so far
            import resource

            rss_kb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
        except ImportError:  # pragma: no cover - not on Linux
            pass
        return {
            "actions": actions,
            "characters": characters,
            "rc": t["rc"],
            "startup_s": round(t["first"] - launch, 3),
            "compute_s": round(t["last"] - t["first"], 3),
            "export_s": round(t["end"] - t["last"], 3),
            "wall_s": round(wall, 3),
            "animation_s": duration,
            "realtime_factor": round(duration / wall, 3) if wall > 0 else 0.0,
            # the child's CPU time, its render processes included (their fork server is reaped before the
            # child exits): load does not distort it
            "cpu_s": round(cpu, 2),
            "load_average": [round(x, 2) for x in os.getloadavg()],
            "peak_rss_mb_max_so_far": round(rss_kb / 1024, 1),
        }


def serve_first_edit(
    text: str = "In the office there is a desk$. Eve walks to the desk.",
) -> dict[str, float]:
    """`wana serve` in a child process on a free port and a fresh database: seconds from launch until it
    answers HTTP (``serve_ready_s``), acknowledges the first edit of a new document (``serve_first_ack_s``)
    and sends that edit's animation (``serve_first_edit_s``, what the user waits for; issue 22: <= 3 s)."""
    import socket

    import httpx
    from websockets.sync.client import connect

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    with tempfile.TemporaryDirectory(prefix="wana-serve-") as tmp:
        env = {**os.environ, "PYTHONPATH": str(REPO)}
        cmd = [
            sys.executable,
            "-c",
            "import sys; from wana.cli import main; sys.exit(main())",
            "serve",
            "--port",
            str(port),
            "--db",
            str(Path(tmp) / "s.db"),
        ]
        log = Path(tmp) / "serve.log"  # a file, not a pipe: a chatty server never blocks on a full pipe
        launch = time.time()
        with log.open("wb") as out:
            proc = subprocess.Popen(cmd, env=env, cwd=REPO, stdout=subprocess.DEVNULL, stderr=out)
        try:
            base = f"http://127.0.0.1:{port}"
            while True:
                if proc.poll() is not None:
                    raise RuntimeError(f"wana serve exited: {log.read_text(errors='replace')[-2000:]}")
                if time.time() - launch > 120:
                    raise RuntimeError("wana serve did not answer within 120 s")
                try:
                    if httpx.get(f"{base}/api/documents", timeout=1.0).status_code == 200:
                        break
                except httpx.HTTPError:
                    time.sleep(0.02)
            ready = time.time()
            doc = httpx.post(f"{base}/api/documents", json={"text": ""}, timeout=30.0).json()["doc_id"]
            with connect(f"ws://127.0.0.1:{port}/api/documents/{doc}/live", max_size=None) as ws:
                state = _until(ws, lambda m: m["type"] == "state")
                edit = {"start": 0, "end": 0, "text": text}
                ws.send(json.dumps({"type": "edit", "base_version": state["version"], "changes": [edit]}))
                ack = _until(ws, lambda m: m["type"] in ("ack", "stale"))
                acked = time.time()
                _until(ws, lambda m: m["type"] == "animation" and m["version"] == ack["version"])
                animated = time.time()
        finally:
            proc.terminate()
            proc.wait(timeout=30)
    return {
        "serve_ready_s": round(ready - launch, 3),
        "serve_first_ack_s": round(acked - launch, 3),
        "serve_first_edit_s": round(animated - launch, 3),
    }


def _until(ws: Any, wanted: Any, timeout: float = 300.0) -> dict[str, Any]:
    """The next JSON message on the WebSocket that ``wanted`` accepts (binary frames are skipped)."""
    deadline = time.monotonic() + timeout
    while True:
        raw = ws.recv(timeout=max(deadline - time.monotonic(), 0.01))
        if isinstance(raw, bytes):
            continue
        msg = json.loads(raw)
        if msg.get("type") == "error":
            raise RuntimeError(f"gateway error: {msg}")
        if wanted(msg):
            return msg


def render_fps(width: int, height: int, frames: int) -> tuple[float, float]:
    """(frames per second, CPU ms per frame): bench/render.py's measure."""
    from render import measure_frames  # bench/render.py

    return measure_frames(frames, width, height)


def encode_overlap(frames: int) -> dict[str, float]:
    """Seconds to render + encode the demo video, the encoder on its own thread, vs rendering alone."""
    import io

    from render import demo_motions  # bench/render.py

    from services.render.demo import demo_scene
    from services.render.renderer import FrameRenderer
    from services.render.video import encode_mp4

    with FrameRenderer(demo_scene(), demo_motions(frames + 1), [], width=640, height=480) as r:
        r.render(0)
        t0 = time.perf_counter()
        for _ in r.frames(1, frames + 1):
            pass
        render_only = time.perf_counter() - t0
        t0 = time.perf_counter()
        encode_mp4(r.frames(1, frames + 1), io.BytesIO())
        both = time.perf_counter() - t0
    return {"render_only_s": round(render_only, 3), "render_and_encode_s": round(both, 3)}


def main(argv: list[str] | None = None) -> dict[str, Any]:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument(
        "--quick", action="store_true", help="size 10, one rep, start-up only (no full animate), 8 frames"
    )
    ap.add_argument("--json", help="write the results here")
    ap.add_argument("--sizes", default="", help="comma-separated sentence counts (default 10,40,160,640)")
    ap.add_argument("--reps", type=int, default=0, help="edits per kind (default 3; --quick 1)")
    ap.add_argument("--no-animate", action="store_true", help="skip the `wana animate` runs")
    ap.add_argument("--no-render", action="store_true", help="skip the render fps")
    args = ap.parse_args(argv)
    sizes = [int(s) for s in args.sizes.split(",") if s] or ([10] if args.quick else [10, 40, 160, 640])
    reps = args.reps or (1 if args.quick else 3)
    res: dict[str, Any] = {
        "action_edit_p50_ms": {},
        "late_action_edit_p50_ms": {},
        "scene_edit_p50_ms": {},
        "scene_used_edit_p50_ms": {},
        "full_ms": {},
        "nodes": {},
        "edit_cpu_p50_ms": {},
        "cpu_count": os.cpu_count(),
        "load_average": list(os.getloadavg()),
    }
    print(
        f"{'sentences':>9} {'action':>9} {'late':>9} {'scene-unused':>13} {'scene-used':>11} {'full':>9}  nodes a/l/su/sx/full"
    )
    for size in sizes:
        e = edit_latency(size, reps)
        ms, nodes = e["ms"], e["nodes"]
        res["action_edit_p50_ms"][str(size)] = round(ms["action"], 1)
        res["late_action_edit_p50_ms"][str(size)] = round(ms["late_action"], 1)
        res["scene_edit_p50_ms"][str(size)] = round(ms["scene_unused"], 1)
        res["scene_used_edit_p50_ms"][str(size)] = round(ms["scene_used"], 1)
        res["full_ms"][str(size)] = round(ms["full"], 1)
        res["nodes"][str(size)] = nodes
        res["edit_cpu_p50_ms"][str(size)] = {kind: round(v, 1) for kind, v in e["cpu_ms"].items()}
        print(
            f"{size:>9} {ms['action']:>7.0f}ms {ms['late_action']:>7.0f}ms {ms['scene_unused']:>11.0f}ms "
            f"{ms['scene_used']:>9.0f}ms {ms['full']:>7.0f}ms  "
            f"{nodes['action']}/{nodes['late_action']}/{nodes['scene_unused']}/{nodes['scene_used']}/{nodes['full']}",
            flush=True,
        )
        cpu = e["cpu_ms"]
        print(
            f"{'CPU':>9} {cpu['action']:>7.0f}ms {cpu['late_action']:>7.0f}ms {cpu['scene_unused']:>11.0f}ms "
            f"{cpu['scene_used']:>9.0f}ms {cpu['full']:>7.0f}ms  (process time: what load does not distort)",
            flush=True,
        )
    res["parse_ms"] = parse_latency(sizes)
    print(
        "cold parse stage, all sentences different: "
        + ", ".join(f"{k}: {v:.0f} ms" for k, v in res["parse_ms"].items()),
        flush=True,
    )
    if not args.no_animate:
        stories = [(2, 1)] if args.quick else [(2, 1), (8, 2), (8, 1), (8, 4)]
        res["animate"] = []
        for actions, characters in stories:
            run = animate_run(actions, characters, startup_only=args.quick)
            res["animate"].append(run)
            if args.quick:  # the child stopped at the pipeline's first step: there is no animation to time
                print(
                    f"animate {actions} actions / {characters} characters: start-up {run['startup_s']:.2f}s "
                    "(--quick stops at the first step: no compute, export or animation)",
                    flush=True,
                )
                continue
            print(
                f"animate {actions} actions / {characters} characters: start-up {run['startup_s']:.2f}s, compute "
                f"{run['compute_s']:.2f}s, export {run['export_s']:.2f}s, wall {run['wall_s']:.2f}s, "
                f"{run['animation_s']:.1f}s of animation ({run['realtime_factor']:.2f}x real time), "
                f"{run['cpu_s']:.1f}s CPU, load {run['load_average'][0]:.1f}",
                flush=True,
            )
        res["startup_s"] = min(r["startup_s"] for r in res["animate"])
        res.update(serve_first_edit())
        print(
            f"wana serve: answers HTTP {res['serve_ready_s']:.2f}s after launch, acknowledges the first edit "
            f"{res['serve_first_ack_s']:.2f}s, its animation {res['serve_first_edit_s']:.2f}s",
            flush=True,
        )
        eight = [r for r in res["animate"] if r["actions"] == 8]
        if eight:
            res["animate_realtime_factor"] = eight[0]["realtime_factor"]
    if not args.no_render:
        frames = 8 if args.quick else 60
        fps_640, cpu_640 = render_fps(640, 480, frames)
        fps_1280, cpu_1280 = render_fps(1280, 720, frames // 2)
        res["render_fps_640"], res["render_cpu_ms_per_frame_640"] = round(fps_640, 2), round(cpu_640, 2)
        res["render_fps_1280"], res["render_cpu_ms_per_frame_1280"] = round(fps_1280, 2), round(cpu_1280, 2)
        res["encode_overlap"] = encode_overlap(frames)
        print(
            f"render: {res['render_fps_640']:.1f} fps at 640x480 ({res['render_cpu_ms_per_frame_640']:.1f} ms CPU a "
            f"frame), {res['render_fps_1280']:.1f} fps at 1280x720 ({res['render_cpu_ms_per_frame_1280']:.1f} ms); "
            f"{frames} frames rendered {res['encode_overlap']['render_only_s']:.2f}s, rendered and encoded "
            f"{res['encode_overlap']['render_and_encode_s']:.2f}s",
            flush=True,
        )
    if args.json:
        Path(args.json).write_text(json.dumps(res, indent=2))
    return res


if __name__ == "__main__":
    main()
