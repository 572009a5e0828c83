"""The final-quality render (Blender's Cycles through bpy in subprocesses) against the open3d render of the same
request: the same frame count, a picture that is not blank, the character where the open3d frame shows it,
and frame ranges rendered apart equal to the whole. Tiny pictures and 2 samples: Cycles runs on the CPU.

The tests skip when no Python with bpy is found (services.render.fbx_export.blender_python).
"""

from __future__ import annotations

import dataclasses
import io

import numpy as np
import pytest

from proto.common import Header
from proto.render import ExportRequest, RenderRequest
from services.render import fbx_export
from services.render.cycles_render import CyclesJob, cycles_frames, render_mp4_cycles
from services.render.demo import demo_scene, walk_motion
from services.render.handlers import handle_export, handle_render
from services.render.renderer import FrameRenderer
from services.render.video import decode_frames, probe

try:
    fbx_export.blender_python()
except ModuleNotFoundError as exc:
    pytest.skip(str(exc), allow_module_level=True)

pytestmark = pytest.mark.slow
W, H = 96, 72
SAMPLES = 2
FRAMES = [0, 20]


def _motions():
    return [walk_motion("Eve", (-2.0, 1.5), (1.0, -0.5), 40, sentence_id="s1")]


def _silhouette(with_body: np.ndarray, without: np.ndarray, threshold: float = 40.0) -> np.ndarray:
    """Pixels where the body changes the picture (the same shot rendered without the body, shadows kept)."""
    return np.abs(with_body.astype(np.float64) - without.astype(np.float64)).sum(axis=2) > threshold


def _centroid(mask: np.ndarray) -> np.ndarray:
    ys, xs = np.nonzero(mask)
    return np.array([xs.mean(), ys.mean()])


@pytest.fixture(scope="module")
def job() -> CyclesJob:
    j = CyclesJob.build(demo_scene(), _motions(), width=W, height=H, samples=SAMPLES)
    j.denoise = False  # 2 samples: the test compares shapes, not grain
    return j


@pytest.fixture(scope="module")
def preview():
    with FrameRenderer(demo_scene(), _motions(), width=W, height=H) as r:
        yield r


def test_same_video_length_as_open3d(preview) -> None:
    scene, motions = demo_scene(), _motions()
    base = {"header": Header(), "format": "mp4", "scene": scene, "motions": motions, "width": W, "height": H}
    cycles = handle_export(ExportRequest(**base, renderer="blender", samples=1, render_workers=2))
    fast = handle_export(ExportRequest(**base))
    assert cycles.n_frames == fast.n_frames == preview.n_frames
    info = probe(cycles.data)
    assert info["frames"] == probe(fast.data)["frames"] == preview.n_frames
    assert (info["width"], info["height"], info["fps"]) == (W, H, 30.0)
    assert [s.start_frame for s in cycles.shots] == [s.start_frame for s in fast.shots]
    frames = decode_frames(cycles.data)
    assert all(f.std() > 10.0 for f in frames[:: max(1, len(frames) // 4)])  # a room, not a flat colour


@pytest.mark.parametrize("frame", FRAMES)
def test_character_where_open3d_shows_it(job, preview, frame: int) -> None:
    cycles = next(cycles_frames(job, frame, frame + 1))
    plate = next(cycles_frames(dataclasses.replace(job, hide_characters=True), frame, frame + 1))
    assert cycles.shape == (H, W, 3)
    assert cycles.std() > 10.0, "a blank picture"
    assert np.abs(cycles.astype(int) - preview.render(frame).astype(int)).mean() < 80.0  # the same room
    ours = _silhouette(cycles, plate)
    theirs = _silhouette(preview.render(frame), preview.render(frame, hide_characters=True))
    assert theirs.sum() > 20, "the open3d frame shows the character"
    assert ours.sum() > 0.4 * theirs.sum(), "Cycles shows the character (its silhouette)"
    assert ours.sum() < 2.5 * theirs.sum()
    offset = np.abs(_centroid(ours) - _centroid(theirs))
    assert offset[0] < 0.06 * W and offset[1] < 0.06 * H, f"silhouette centroid {offset} px off"
    overlap = (ours & theirs).sum() / theirs.sum()
    assert overlap > 0.5


def test_ranges_apart_equal_the_whole(job) -> None:
    """Two Blender processes on halves of a range give the frames one process gives (fixed seed)."""
    one = list(cycles_frames(job, 4, 8, workers=1))
    two = list(cycles_frames(job, 4, 8, workers=2))
    assert len(one) == len(two) == 4
    for a, b in zip(one, two, strict=True):
        assert np.abs(a.astype(int) - b.astype(int)).max() <= 2


def test_render_request_chunks_join(job) -> None:
    """The worker protocol: a RenderRequest per frame range, each an MP4 chunk, joined like open3d's."""
    from services.render.video import join_chunks

    base = {"header": Header(), "scene": demo_scene(), "motions": _motions(), "width": W, "height": H}
    chunks = [
        handle_render(
            RenderRequest(**base, start_frame=a, end_frame=b, encoding="mp4", renderer="blender", samples=1)
        )
        for a, b in [(0, 3), (3, 5)]
    ]
    assert [c.n_frames for c in chunks] == [job.n_frames] * 2
    joined = io.BytesIO()
    assert join_chunks([c.video for c in chunks], joined) == 5
    assert probe(joined.getvalue())["frames"] == 5
    out = io.BytesIO()
    assert render_mp4_cycles(job, out, start=0, end=2, workers=1) == 2


def test_missing_blender_is_said(monkeypatch) -> None:
    from services.render.cycles_render import MISSING

    monkeypatch.setenv("WANA_BLENDER_PYTHON", "/nonexistent/python")
    with pytest.raises(ModuleNotFoundError, match="Cycles render"):
        next(cycles_frames(CyclesJob(glb=b"", n_frames=2, width=W, height=H), 0, 1))
    assert "pip install bpy" in MISSING
