"""Render a known scene and check pixels: the character is where its motion says, commands change the view.

Frames are compared with renders of the same scene without the character; the character's
position comes from the analytic walk (``hips_path``), projected with the frame's camera.
"""

from __future__ import annotations

import numpy as np
import pytest

from proto.render import TimedCommand
from proto.ssg import Command
from services.render.camera import project
from services.render.demo import demo_scene, hips_path, walk_motion
from services.render.renderer import FrameRenderer

W, H = 320, 240
START, END, N = (-2.0, 1.2), (1.2, -0.4), 60


@pytest.fixture(scope="module")
def renders():
    """Frames of Eve walking (overview camera) and the same frames of the empty scene."""
    scene = demo_scene()
    motion = walk_motion("Eve", START, END, N)
    out = {}
    with FrameRenderer(scene, [motion], [], width=W, height=H) as r:
        poses = {f: r.camera(f) for f in (0, 45)}
        out["eve"] = {f: r.render(f) for f in (0, 45)}
        out["eve_again"] = r.render(45)
        out["chunk"] = list(r.frames(44, 46))
    with FrameRenderer(scene, [], [], n_frames=N, width=W, height=H) as r:
        out["empty"] = {f: r.render(f, poses[f]) for f in (0, 45)}
    out["poses"] = poses
    return out


def _mask(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.abs(a.astype(int) - b.astype(int)).max(axis=2) > 25


@pytest.mark.slow
def test_the_character_is_drawn_where_the_motion_puts_its_hips(renders):
    hips = hips_path("Eve", START, END, N)
    centroids = {}
    for f in (0, 45):
        mask = _mask(renders["eve"][f], renders["empty"][f])
        assert mask.sum() > 150, f"frame {f}: the character covers almost no pixels"
        uv, depth = project(hips[f][None], renders["poses"][f], W, H)
        assert depth[0] > 0
        rows, cols = np.nonzero(mask)
        dist = np.hypot(cols - uv[0, 0], rows - uv[0, 1]).min()
        assert dist < 4, f"frame {f}: nearest character pixel is {dist:.1f} px from the projected hips"
        centroids[f] = (uv[0], np.array([cols.mean(), rows.mean()]))
    moved_hips = centroids[45][0] - centroids[0][0]
    moved_pixels = centroids[45][1] - centroids[0][1]
    assert np.linalg.norm(moved_hips) > 20
    cos = moved_hips @ moved_pixels / (np.linalg.norm(moved_hips) * np.linalg.norm(moved_pixels))
    assert cos > 0.9, "the drawn character moved in a different direction than its hips"


@pytest.mark.slow
def test_rendering_is_deterministic_and_a_chunk_equals_the_same_frames_of_a_longer_run(renders):
    assert np.array_equal(renders["eve"][45], renders["eve_again"])
    assert np.array_equal(renders["chunk"][1], renders["eve"][45])


@pytest.mark.slow
def test_a_camera_command_changes_the_view_to_the_characters_front():
    scene = demo_scene()
    motion = walk_motion("Eve", START, END, N)
    cmd = [TimedCommand(frame=10, command=Command(kind="camera", value="front", target="Eve"))]
    with FrameRenderer(scene, [motion], cmd, width=W, height=H) as r:
        before, after = r.render(5), r.render(50)
        pose = r.camera(50)
    with FrameRenderer(scene, [], [], n_frames=N, width=W, height=H) as r:
        empty = r.render(50, pose)
    assert np.abs(before.astype(int) - after.astype(int)).mean() > 20  # a different view
    mask = _mask(after, empty)
    uv, _ = project(hips_path("Eve", START, END, N)[50][None], pose, W, H)
    assert abs(uv[0, 0] - W / 2) < W * 0.1  # the front camera centres the character
    assert mask.mean() > 0.025  # and shows it large (about 5% of the picture; under 1% in the overview)
    assert mask[int(uv[0, 1]), int(uv[0, 0])]


@pytest.mark.slow
def test_night_is_darker_and_rain_adds_streaks():
    scene = demo_scene()
    cmds = [TimedCommand(frame=0, command=Command(kind="weather", value="night"))]
    with FrameRenderer(scene, [], [], n_frames=60, width=W, height=H) as r:
        day = r.render(50)
    with FrameRenderer(scene, [], cmds, n_frames=60, width=W, height=H) as r:
        night = r.render(50)
    assert night.mean() < 0.6 * day.mean()
    rain = [TimedCommand(frame=0, command=Command(kind="weather", value="rainy"))]
    with FrameRenderer(scene, [], rain, n_frames=60, width=W, height=H) as r:
        a, b = r.render(40), r.render(41)
    assert 0 < _mask(a, b).mean() < 0.2  # only the falling rain differs between two frames


@pytest.mark.slow
def test_two_renderers_in_one_process_take_turns_with_the_gl_context():
    scene = demo_scene()
    a = FrameRenderer(scene, [walk_motion("Eve", START, END, 10)], [], width=64, height=48)
    b = FrameRenderer(scene, [], [], n_frames=10, width=80, height=60)
    try:
        first = a.render(3)
        other = b.render(3)
        again = a.render(3)  # b's canvas closed a's; a reopens its own
        assert other.shape == (60, 80, 3) and np.array_equal(first, again)
    finally:
        a.close()
        b.close()
