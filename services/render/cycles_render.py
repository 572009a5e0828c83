"""The final-quality render: the same shots as the open3d preview, path traced by Blender's Cycles on the CPU.

The GLB that the pipeline writes already holds everything a frame needs (room, skinned characters or the
user's own cast, held props, doors and lamps, the director's camera keyed on every frame), so a Cycles frame
is that GLB imported by Blender and rendered at the frame's time. Blender runs in subprocesses
(``bpy_cycles.py``, by the interpreter services.render.fbx_export picks), one per frame range: the ranges are
``timeline.chunk_ranges`` of the video, as the open3d render splits them over render processes and
workers, so a range is one ``RenderRequest(renderer="blender", start_frame, end_frame)`` on any worker and
several at once on one machine. The captions are drawn on the frames here, as the open3d renderer draws
them; weather is the first frame's sun (no rain, snow or fog particles).

    job = CyclesJob.build(scene, motions, commands, captions, width=320, height=240, samples=16)
    render_mp4_cycles(job, "animation.mp4", workers=2)

Not named ``cycles.py``: Blender runs ``bpy_cycles.py`` from this folder, and a ``cycles`` module here would
shadow Blender's own Cycles add-on (the engine would then be missing).
"""

from __future__ import annotations

import io
import json
import os
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from PIL import Image

from proto.motion_data import Motion
from proto.render import Caption, TimedCommand
from proto.scene import Scene
from services.render import captions as captions_mod
from services.render.cast_gltf import CastCharacter
from services.render.fbx_export import TIMEOUT_S, blender_python, missing_message
from services.render.gltf_export import scene_glb
from services.render.staging import Staging
from services.render.timeline import caption_at, chunk_ranges
from services.render.weather import look_at

SCRIPT = Path(__file__).with_name("bpy_cycles.py")
DEFAULT_SAMPLES = 16
MAX_SAMPLES = 4096
MISSING = missing_message("a Cycles render (--renderer blender)")


def workers_default() -> int:
    """Blender processes at once when none are asked for: the CPUs this process may use (at most 4).

    Cycles threads across cores itself, so more processes only help by overlapping Blender's start-up
    (about 2 s each) with other ranges' rendering."""
    cpus = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1
    return max(1, min(4, cpus))


@dataclass
class CyclesJob:
    """What every range of one Cycles video shares: the GLB, the per-frame field of view, the light.

    Attributes:
        glb: ``scene_glb`` bytes with the director's camera for this picture size.
        n_frames: the video's length (the open3d render's, same staging).
        yfov: (n_frames,) vertical field of view per frame, radians (glTF keys only the first).
        sun: unit direction towards the sun (Y up), from the first frame's weather.
        captions: drawn on the frames as the open3d renderer draws them.
        shots: the staging's shot plan (for the reply).
    """

    glb: bytes
    n_frames: int
    width: int
    height: int
    samples: int = DEFAULT_SAMPLES
    yfov: list[float] = field(default_factory=list)
    sun: tuple[float, float, float] = (0.0, 1.0, 0.0)
    background: tuple[float, float, float] = (0.62, 0.68, 0.78)
    captions: list[Caption] = field(default_factory=list)
    staging: Staging | None = None
    denoise: bool = True
    hide_characters: bool = False  # bodies left out of the picture, their shadows kept (tests, silhouettes)

    @classmethod
    def build(
        cls,
        scene: Scene,
        motions: list[Motion],
        commands: list[TimedCommand] | None = None,
        captions: list[Caption] | None = None,
        *,
        n_frames: int = 0,
        width: int = 640,
        height: int = 480,
        samples: int = DEFAULT_SAMPLES,
        cast: Mapping[str, CastCharacter] | None = None,
    ) -> CyclesJob:
        """Stage the video as the open3d renderer does and write its GLB (the user's cast wears its mesh).

        Raises:
            ValueError: samples outside 1..MAX_SAMPLES, or what Staging.build raises.
        """
        if not 1 <= samples <= MAX_SAMPLES:
            raise ValueError(f"samples must be 1..{MAX_SAMPLES}, got {samples}")
        stage = Staging.build(scene, motions, commands, n_frames)
        track = stage.camera_track(width, height)
        look = look_at(0, stage.weather_keys)
        towards = -np.asarray(look.sun, dtype=np.float64)
        return cls(
            glb=scene_glb(scene, motions, camera=track, armature_nodes=True, cast=cast),
            n_frames=stage.n_frames,
            width=int(width),
            height=int(height),
            samples=int(samples),
            yfov=[float(x) for x in np.radians(track.fov_deg)],
            sun=(float(towards[0]), float(towards[1]), float(towards[2])),
            background=(float(look.background[0]), float(look.background[1]), float(look.background[2])),
            captions=list(captions or []),
            staging=stage,
        )

    def _spec(self, start: int, end: int, threads: int) -> dict:
        return {
            "start": start,
            "end": end,
            "width": self.width,
            "height": self.height,
            "samples": self.samples,
            "threads": threads,
            "sun": list(self.sun),
            "background": list(self.background),
            "yfov": self.yfov,
            "denoise": self.denoise,
            "hide_characters": self.hide_characters,
        }


@dataclass
class RangeRun:
    """One Blender process rendering frames [start, end) into its folder."""

    start: int
    end: int
    folder: Path
    process: subprocess.Popen
    log: Path


def _die_with_parent() -> None:
    """In the Blender child, before exec: on Linux, end with the render process (a killed worker leaves no
    Blender rendering on)."""
    try:
        import ctypes
        import signal

        ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):  # not Linux: the finally in cycles_frames still ends them
        pass


def _launch(job: CyclesJob, glb: Path, start: int, end: int, tmp: Path, threads: int) -> RangeRun:
    folder = tmp / f"frames_{start:05d}_{end:05d}"
    folder.mkdir()
    spec = folder / "job.json"
    spec.write_text(json.dumps(job._spec(start, end, threads)))
    log = folder / "blender.log"
    with open(log, "wb") as out:
        process = subprocess.Popen(
            [blender_python(MISSING), str(SCRIPT), str(glb), str(spec), str(folder)],
            stdout=out,
            stderr=subprocess.STDOUT,
            env={**os.environ, "PYTHONNOUSERSITE": "1"},
            preexec_fn=_die_with_parent if sys.platform.startswith("linux") else None,  # noqa: PLW1509
        )
    return RangeRun(start, end, folder, process, log)


def _finish(run: RangeRun, deadline: float) -> dict:
    """Wait for the range's Blender; what it reports.

    Raises:
        RuntimeError: Blender failed or ran past the deadline (its last output lines in the message).
    """
    try:
        code = run.process.wait(timeout=max(1.0, deadline - time.monotonic()))
    except subprocess.TimeoutExpired:
        run.process.kill()
        run.process.wait()
        code = -9
    text = run.log.read_text(errors="replace")
    line = next((x for x in text.splitlines() if x.startswith("WANA_CYCLES ")), "")
    if code != 0 or not line:
        tail = "\n".join(text.strip().splitlines()[-8:])
        raise RuntimeError(
            f"Blender's Cycles render of frames [{run.start}, {run.end}) failed ({code}): {tail}"
        )
    return json.loads(line[len("WANA_CYCLES ") :])


def cycles_frames(
    job: CyclesJob, start: int = 0, end: int = -1, *, workers: int = 1, stats: list[dict] | None = None
) -> Iterator[np.ndarray]:
    """Frames [start, end) as (H, W, 3) uint8, rendered by ``workers`` Blender processes at once.

    The range is split with ``chunk_ranges`` into one contiguous range per process; the frames come back
    in order, each with its caption drawn. ``stats`` (when given) receives each process's report (frames,
    setup and render seconds, whether the denoiser ran).

    Raises:
        ModuleNotFoundError: no Python with bpy (the message says how to get one).
        ValueError: a range outside the video.
        RuntimeError: a Blender process failed.
    """
    end = job.n_frames if end < 0 else int(end)
    if not 0 <= start <= end <= job.n_frames:
        raise ValueError(f"frame range [{start}, {end}) is outside the animation's [0, {job.n_frames})")
    if end == start:
        return
    blender_python(MISSING)  # the clear message before any work
    spans = chunk_ranges(end - start, max(1, min(int(workers), end - start)))
    cpus = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1
    threads = max(1, cpus // len(spans))
    with tempfile.TemporaryDirectory(prefix="wana-cycles-") as tmp_name:
        tmp = Path(tmp_name)
        glb = tmp / "scene.glb"
        glb.write_bytes(job.glb)
        runs = [_launch(job, glb, start + a, start + b, tmp, threads) for a, b in spans]
        deadline = time.monotonic() + TIMEOUT_S + 60.0 * (end - start) / len(spans)
        try:
            for run in runs:
                report = _finish(run, deadline)
                if stats is not None:
                    stats.append(report)
                for f in range(run.start, run.end):
                    png = run.folder / f"frame_{f:05d}.png"
                    if not png.is_file():
                        raise RuntimeError(f"Blender wrote no image for frame {f}")
                    img = np.asarray(Image.open(png).convert("RGB"), dtype=np.uint8)
                    text = caption_at(job.captions, f)
                    yield captions_mod.draw_caption(img, text) if text else img
        finally:
            for run in runs:
                if run.process.poll() is None:
                    run.process.kill()
                    run.process.wait()


def render_mp4_cycles(
    job: CyclesJob,
    out: str | Path | io.BytesIO,
    *,
    start: int = 0,
    end: int = -1,
    workers: int = 0,
    stats: list[dict] | None = None,
) -> int:
    """Frames [start, end) (default the whole video) as an H.264 MP4 encoded as the open3d frames are
    (``video.encode_mp4``); ``workers`` Blender processes at once (0 = ``workers_default()``). Returns the
    number of frames written."""
    from services.render.video import encode_mp4

    return encode_mp4(cycles_frames(job, start, end, workers=workers or workers_default(), stats=stats), out)
