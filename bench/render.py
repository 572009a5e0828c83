"""Render throughput: frames per second of one render worker at 640x480, and the speed-up with 2 workers.

    .venv/bin/python bench/render.py [--quick] [--json PATH] [--frames N] [--width W --height H]

fps: one FrameRenderer in this process renders the demo office (4 objects, room, 2 skinned
characters walking, projected shadows) frame by frame after one warm-up frame; skinning, shading,
read-back and colour grading are all counted, encoding is not.

speedup_2_workers: a real broker and two render worker processes (ipc socket); the whole video is
asked for as two MP4 chunks (``RenderRequest(encoding="mp4")``) and joined, first one chunk after the
other (one worker busy at a time), then both at once (one per worker); speed-up = time(one at a
time) / time(both at once). Worker start-up and the first scene build are not timed. The machine's CPU count and load are printed: on a shared 2-core machine the speed-up is
bounded by the cores other processes leave free.

speedup_2_processes: the same video through ``renderer.render_mp4`` in this process (1) and in two
fork-server render processes on this machine (2), as ``wana animate`` renders; speed-up = time(1) / time(2),
the processes' start included (``--processes`` to measure it).

plan_seconds: building the staging of that video (rigs, tracks and the director's shot plan, which
measures what each candidate camera shows), with the director and without it (``--no-director``
renders with the commands' cameras alone, for comparing fps).

cycles_seconds_per_frame: the final-quality renderer (``--renderer blender``: Blender's Cycles on the CPU in a
subprocess, services.render.cycles_render) on the same demo video and size, ``--cycles-samples`` samples
(default 16, quick 4) and OpenImageDenoise, one Blender process on all cores; seconds per rendered frame with
Blender's start and the scene's import excluded (``cycles_setup_seconds`` has them). Skipped (null) when no
Python with bpy is found, or with ``--no-cycles``. ``--cycles-frames`` (default 8, quick 3) frames.

cycles_silhouette: does Cycles show the character where open3d does? The demo video's frames 0 and 20 at 96x72
(2 samples, no denoiser) rendered with and without the bodies (their shadows kept) by both renderers; the
silhouette is where the body changes the picture; reported: the largest centroid offset (pixels) and the
smallest share of open3d's silhouette that Cycles' covers.

JSON keys: fps, cpu_ms_per_frame (this process's CPU time per frame, all threads: what load does not
distort), cycles_seconds_per_frame, cycles_silhouette_offset_px, cycles_silhouette_overlap, cycles_setup_seconds, cycles_samples, speedup_2_workers, plan_seconds, plan_seconds_no_director (plus context: frames, width, height, seconds_1_worker,
seconds_2_workers, cpu_count, load_average).
"""

from __future__ import annotations

import argparse
import io
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

import msgspec  # noqa: E402
from tqdm import tqdm  # noqa: E402

from proto.common import Header  # noqa: E402
from proto.render import RenderReply, RenderRequest  # noqa: E402
from services.render.demo import demo_scene, walk_motion  # noqa: E402


def demo_motions(frames: int) -> list:
    return [
        walk_motion("Eve", (-2.0, 1.5), (1.0, -0.5), frames, sentence_id="s1"),
        walk_motion("Tom", (1.5, 1.8), (-0.5, 1.2), frames, expression="frown", sentence_id="s1"),
    ]


def plan_seconds(frames: int, director: bool) -> float:
    """Seconds to stage the demo video (the director's planning included when on)."""
    from services.render.staging import Staging

    t0 = time.perf_counter()
    Staging.build(demo_scene(), demo_motions(frames + 1), director=director)
    return time.perf_counter() - t0


def measure_frames(frames: int, width: int, height: int, director: bool = True) -> tuple[float, float]:
    """(frames per second, CPU milliseconds per frame) of one FrameRenderer on the demo office.

    The CPU time is this process's, all its threads (llvmpipe's rasteriser threads included): what a
    frame costs whatever else the machine runs, where the frames per second follow the load."""
    from services.render.renderer import FrameRenderer

    with FrameRenderer(demo_scene(), demo_motions(frames + 1), [], width=width, height=height) as r:
        if not director:  # the commands' own cameras (here none: the establishing overview)
            from services.render.staging import Staging

            r.staging = Staging.build(r.scene, demo_motions(frames + 1), director=False)
        r.render(0)  # warm-up: GL context, buffers
        t0, c0 = time.perf_counter(), time.process_time()
        for _ in tqdm(r.frames(1, frames + 1), total=frames, desc="fps", unit="frame", leave=False):
            pass
        return frames / (time.perf_counter() - t0), 1000.0 * (time.process_time() - c0) / frames


def measure_fps(frames: int, width: int, height: int, director: bool = True) -> float:
    return measure_frames(frames, width, height, director)[0]


def time_processes(frames: int, width: int, height: int) -> tuple[float, float]:
    """Seconds for the demo video as one MP4 via render_mp4: (rendered here, in 2 render processes)."""
    from services.render.renderer import FrameRenderer, render_mp4

    out = []
    with FrameRenderer(demo_scene(), demo_motions(frames), [], width=width, height=height) as r:
        for k in (1, 2):
            t0 = time.perf_counter()
            render_mp4(r, io.BytesIO(), processes=k)
            out.append(time.perf_counter() - t0)
    return out[0], out[1]


def measure_cycles(frames: int, width: int, height: int, samples: int) -> dict | None:
    """Cycles on the demo video's frames [1, 1 + frames): seconds per frame and the process's set-up; None
    without bpy."""
    from services.render.cycles_render import CyclesJob, cycles_frames

    job = CyclesJob.build(demo_scene(), demo_motions(frames + 1), width=width, height=height, samples=samples)
    stats: list[dict] = []
    try:
        for _ in tqdm(cycles_frames(job, 1, frames + 1, workers=1, stats=stats), total=frames, leave=False):
            pass
    except ModuleNotFoundError as exc:
        print(f"cycles: skipped ({exc})", file=sys.stderr)
        return None
    return {
        "seconds_per_frame": stats[0]["render_s"] / stats[0]["frames"],
        "setup_seconds": stats[0]["setup_s"],
        "denoise": stats[0]["denoise"],
    }


def cycles_silhouette() -> dict | None:
    """Largest centroid offset (px) and smallest overlap of the body's silhouette, Cycles against open3d."""
    import dataclasses

    import numpy as np

    from services.render.cycles_render import CyclesJob, cycles_frames
    from services.render.renderer import FrameRenderer

    w, h = 96, 72
    motions = [walk_motion("Eve", (-2.0, 1.5), (1.0, -0.5), 40, sentence_id="s1")]
    job = CyclesJob.build(demo_scene(), motions, width=w, height=h, samples=2)
    job.denoise = False

    def mask(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return np.abs(a.astype(float) - b.astype(float)).sum(axis=2) > 40.0

    offsets, overlaps = [], []
    try:
        with FrameRenderer(demo_scene(), motions, width=w, height=h) as r:
            for f in (0, 20):
                ours = mask(
                    next(cycles_frames(job, f, f + 1)),
                    next(cycles_frames(dataclasses.replace(job, hide_characters=True), f, f + 1)),
                )
                theirs = mask(r.render(f), r.render(f, hide_characters=True))
                cy = [np.array(np.nonzero(m)[::-1]).mean(axis=1) for m in (ours, theirs)]
                offsets.append(float(np.abs(cy[0] - cy[1]).max()))
                overlaps.append(float((ours & theirs).sum() / max(theirs.sum(), 1)))
    except ModuleNotFoundError:
        return None
    return {"offset_px": max(offsets), "overlap": min(overlaps)}


def _start_workers(url: str, n: int, logs: Path) -> list[subprocess.Popen]:
    env = dict(os.environ, PYTHONPATH=str(REPO), OMP_NUM_THREADS="1")
    code = "import sys; from services.render.worker import main; main(sys.argv[1])"
    procs = []
    for i in range(n):
        with open(logs / f"worker-{i}.log", "wb") as err:
            procs.append(subprocess.Popen([sys.executable, "-c", code, url], cwd=REPO, env=env, stderr=err))
    return procs


def time_chunked(frames: int, width: int, height: int, chunks: int = 2) -> tuple[float, float]:
    """Seconds to render the whole video as MP4 chunks, joined: (one chunk at a time, all at once on 2 workers).

    Two warmed-up workers serve both runs. Chunks sent one after another are what one worker can
    do; sent together, the broker hands one to each worker.
    """
    from services.render.timeline import chunk_ranges
    from services.render.video import join_chunks
    from wana.bus.broker import Broker
    from wana.bus.client import Client

    n_workers = 2
    tmp = Path(tempfile.mkdtemp(prefix="wana-bench-"))
    url = f"ipc://{tmp}/bus.sock"
    broker = Broker(url)
    broker.start_thread()
    procs = _start_workers(url, n_workers, tmp)
    client = Client(url)
    try:
        end = time.monotonic() + 180
        while True:
            svc = client.stats().services.get("render")
            if svc is not None and svc.workers >= n_workers:
                break
            if time.monotonic() > end or any(p.poll() is not None for p in procs):
                raise RuntimeError(f"render workers did not start; see {tmp}")
            time.sleep(0.05)
        scene, motions = demo_scene(), demo_motions(frames)
        warm = RenderRequest(
            header=Header(),
            scene=scene,
            motions=motions,
            start_frame=0,
            end_frame=1,
            width=width,
            height=height,
        )
        warm_jobs = [
            client.submit("render", msgspec.msgpack.encode(warm), deadline_s=300, idempotency_key=f"warm-{i}")
            for i in range(n_workers)
        ]
        client.wait(warm_jobs, timeout=300)  # both workers have imported and built the scene once

        def run(parallel: bool, tag: str) -> float:
            t0 = time.perf_counter()
            jobs, videos = [], []
            for a, b in chunk_ranges(frames, chunks):
                req = RenderRequest(
                    header=Header(),
                    scene=scene,
                    motions=motions,
                    start_frame=a,
                    end_frame=b,
                    width=width,
                    height=height,
                    encoding="mp4",
                )
                jobs.append(
                    client.submit(
                        "render", msgspec.msgpack.encode(req), deadline_s=600, idempotency_key=f"{tag}-{a}"
                    )
                )
                if not parallel:
                    videos.append(
                        msgspec.msgpack.decode(client.result(jobs[-1], timeout=600), type=RenderReply).video
                    )
            if parallel:
                videos = [
                    msgspec.msgpack.decode(client.result(j, timeout=600), type=RenderReply).video
                    for j in jobs
                ]
            n = join_chunks(videos, io.BytesIO())
            if n != frames:
                raise RuntimeError(f"joined video has {n} frames, expected {frames}")
            return time.perf_counter() - t0

        return run(False, "one"), run(True, "two")
    finally:
        client.close()
        for p in procs:
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                p.kill()
        broker.close()


def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0],
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=__doc__,
    )
    ap.add_argument("--quick", action="store_true", help="fewer frames (finishes in under 30 s)")
    ap.add_argument("--json", metavar="PATH", help="write the results as JSON")
    ap.add_argument("--frames", type=int, default=0, help="frames to render (default 120, quick 10)")
    ap.add_argument("--width", type=int, default=640)
    ap.add_argument("--height", type=int, default=480)
    ap.add_argument("--no-director", action="store_true", help="render with the commands' cameras alone")
    ap.add_argument("--fps-only", action="store_true", help="skip the 2-worker speed-up")
    ap.add_argument("--processes", action="store_true", help="also time 2 local render processes")
    ap.add_argument("--no-cycles", action="store_true", help="skip the Blender Cycles render")
    ap.add_argument("--cycles-frames", type=int, default=0, help="Cycles frames (default 8, quick 3)")
    ap.add_argument("--cycles-samples", type=int, default=0, help="Cycles samples (default 16, quick 4)")
    args = ap.parse_args(argv)
    frames = args.frames or (10 if args.quick else 120)
    fps, cpu_ms = measure_frames(frames, args.width, args.height, director=not args.no_director)
    samples = args.cycles_samples or (4 if args.quick else 16)
    cycles = silhouette = None
    if not args.no_cycles:
        cycles = measure_cycles(
            args.cycles_frames or (3 if args.quick else 8), args.width, args.height, samples
        )
        silhouette = cycles_silhouette() if cycles else None
    plan = plan_seconds(frames, True)
    plan_off = plan_seconds(frames, False)
    if args.fps_only:
        t1 = t2 = float("nan")
    else:
        t1, t2 = time_chunked(frames, args.width, args.height)
    p1 = p2 = float("nan")
    if args.processes:
        p1, p2 = time_processes(max(frames, 96), args.width, args.height)
    result = {
        "fps": round(fps, 2),
        "cpu_ms_per_frame": round(cpu_ms, 2),
        "cycles_seconds_per_frame": round(cycles["seconds_per_frame"], 3) if cycles else None,
        "cycles_setup_seconds": round(cycles["setup_seconds"], 2) if cycles else None,
        "cycles_samples": samples,
        "cycles_denoise": cycles["denoise"] if cycles else None,
        "cycles_silhouette_offset_px": round(silhouette["offset_px"], 2) if silhouette else None,
        "cycles_silhouette_overlap": round(silhouette["overlap"], 3) if silhouette else None,
        "speedup_2_processes": round(p1 / p2, 2),
        "seconds_1_2_processes": [round(p1, 2), round(p2, 2)],
        "speedup_2_workers": round(t1 / t2, 2),
        "plan_seconds": round(plan, 3),
        "plan_seconds_no_director": round(plan_off, 3),
        "director": not args.no_director,
        "frames": frames,
        "width": args.width,
        "height": args.height,
        "seconds_1_worker": round(t1, 2),
        "seconds_2_workers": round(t2, 2),
        "cpu_count": os.cpu_count(),
        "load_average": [round(x, 2) for x in os.getloadavg()],
    }
    print(f"{'metric':<22}{'value':>10}")
    print(f"{'fps (1 worker)':<22}{result['fps']:>10}")
    print(f"{'CPU ms per frame':<22}{result['cpu_ms_per_frame']:>10}")
    spf = result["cycles_seconds_per_frame"]
    print(f"{'cycles s/frame':<22}{'skipped' if spf is None else spf:>10}  ({samples} samples, 1 process)")
    if silhouette:
        print(
            f"{'cycles silhouette':<22}{silhouette['offset_px']:>10.2f}  px off, {silhouette['overlap']:.0%} overlap"
        )
    print(f"{'speedup_2_workers':<22}{result['speedup_2_workers']:>10}")
    print(f"{'speedup_2_processes':<22}{result['speedup_2_processes']:>10}")
    print(f"{'plan s, no director':<22}{result['plan_seconds']:>5} / {result['plan_seconds_no_director']}")
    print(f"{'seconds 1 / 2 workers':<22}{result['seconds_1_worker']:>5} / {result['seconds_2_workers']}")
    print(f"{'frames, size':<22}{frames:>5}, {args.width}x{args.height}")
    print(f"{'cpus, load average':<22}{os.cpu_count():>5}, {result['load_average']}")
    if args.json:
        Path(args.json).write_text(json.dumps(result, indent=2))
    return result


if __name__ == "__main__":
    main()
