"""Fast video: captions blended through a cached mask give Pillow's own pixels, the light's gain graded in
the read-back equals the look-up-table grade, and frame ranges rendered in separate processes join into the
one-process video."""

from __future__ import annotations

import io
import textwrap

import numpy as np
import pytest
from PIL import Image, ImageDraw

from services.render.canvas import to_uint8
from services.render.captions import _font, draw_caption
from services.render.weather import LOOKS, grade


def _pillow_caption(frame: np.ndarray, text: str, max_lines: int = 2) -> np.ndarray:
    """The caption drawn the direct way (text laid out and rasterised into the frame by Pillow)."""
    h, w = frame.shape[:2]
    size = max(10, h // 26)
    font = _font(size)
    lines = textwrap.wrap(text, max(10, int(w / (size * 0.55))))[:max_lines]
    band = int(len(lines) * size * 1.3 + size * 0.6)
    out = frame.copy()
    out[h - band :] = (out[h - band :].astype(np.uint16) * 2 // 5).astype(np.uint8)
    img = Image.fromarray(out)
    draw = ImageDraw.Draw(img)
    y = h - band + int(size * 0.3)
    for line in lines:
        draw.text(((w - draw.textlength(line, font=font)) / 2, y), line, fill=(255, 255, 255), font=font)
        y += int(size * 1.3)
    return np.asarray(img)


@pytest.mark.parametrize("size", [(240, 320), (480, 640), (720, 1280)])
def test_a_cached_caption_has_the_pixels_pillow_draws(size: tuple[int, int]) -> None:
    frame = np.random.default_rng(1).integers(0, 256, (*size, 3), dtype=np.uint8)
    for text in ["Eve walks to the chair and sits down while Tom waves at her from the far window.", "Hi."]:
        got = draw_caption(frame, text)
        assert np.array_equal(got, _pillow_caption(frame, text))
        assert not np.array_equal(got, frame)  # something was drawn
    assert draw_caption(frame, "") is frame


def test_the_gain_graded_in_the_read_back_equals_the_lookup_grade() -> None:
    # the GL read-back is 8-bit colour as floats: k / 255
    levels = np.random.default_rng(2).integers(0, 256, (60, 80, 3)).astype(np.float32) / 255.0
    for name in ["sunny", "night", "snowy"]:
        look = LOOKS[name]
        assert np.array_equal(to_uint8(levels, look.gain), grade(to_uint8(levels), None, look)), name


@pytest.mark.slow
def test_frame_ranges_rendered_in_two_processes_join_into_the_video_of_one() -> None:
    from services.render.demo import demo_scene, walk_motion
    from services.render.renderer import MIN_CHUNK_FRAMES, FrameRenderer, render_mp4
    from services.render.video import decode_frames

    n = 2 * MIN_CHUNK_FRAMES
    motions = [walk_motion("Eve", (-2.0, 1.5), (1.0, -0.5), n, sentence_id="s1")]
    with FrameRenderer(demo_scene(), motions, [], width=96, height=64, n_frames=n) as r:
        raw = list(r.frames(0, n))  # this process holds a GL context when the render processes start
        done: list[int] = []
        two, one = io.BytesIO(), io.BytesIO()
        assert render_mp4(r, two, processes=2, progress=done.append) == n
        assert sum(done) == n and len(done) >= 2  # progress per chunk, from the processes
        assert render_mp4(r, one, processes=1) == n
    a, b = decode_frames(two.getvalue()), decode_frames(one.getvalue())
    assert len(a) == len(b) == n
    for i in (0, n // 2 - 1, n // 2, n - 1):  # both sides of the seam: as close to the render as one video
        err_two, err_one = (float(np.abs(v[i].astype(int) - raw[i]).mean()) for v in (a, b))
        assert err_two < 8.0 and err_two <= err_one + 1.0, (i, err_two, err_one)
    assert np.abs(a[n // 2].astype(int) - raw[0]).mean() > np.abs(a[n // 2].astype(int) - raw[n // 2]).mean()


def test_the_byte_graded_read_back_equals_the_float_one() -> None:
    from services.render.canvas import graded

    rgb = np.random.default_rng(3).integers(0, 256, (48, 64, 3), dtype=np.uint8)
    for name in ["sunny", "night", "snowy", "rainy"]:
        gain = LOOKS[name].gain
        assert np.array_equal(graded(rgb, gain), to_uint8(rgb.astype(np.float32) / np.float32(255.0), gain))
    assert graded(rgb, None) is rgb


@pytest.mark.slow
def test_frames_read_back_as_bytes_have_the_pixels_of_the_float_capture() -> None:
    from proto.render import TimedCommand
    from proto.ssg import Command
    from services.render.demo import demo_scene, walk_motion
    from services.render.renderer import FrameRenderer

    motions = [walk_motion("Eve", (-2.0, 1.5), (1.0, -0.5), 30, sentence_id="s1")]
    night = [TimedCommand(frame=10, command=Command(kind="weather", value="night"))]
    with FrameRenderer(demo_scene(), motions, night, width=96, height=72) as r:
        r.render(0)
        canvas = r._canvas
        assert canvas is not None and canvas._bytes is not None  # the byte read-back is what renders here
        fast = [r.render(f) for f in (0, 15, 29)]
        canvas._bytes = None  # the visualiser's own float capture
        slow = [r.render(f) for f in (0, 15, 29)]
    for a, b in zip(fast, slow, strict=True):
        assert a.dtype == np.uint8 and a.flags.writeable and a.flags.c_contiguous
        assert np.array_equal(a, b)
    assert not np.array_equal(fast[0], fast[1])  # the walk and the night are in the pictures


@pytest.mark.slow
def test_fog_reads_the_depth_of_the_frame_it_greys() -> None:
    from services.render.demo import demo_scene, walk_motion
    from services.render.renderer import FrameRenderer

    motions = [walk_motion("Eve", (-2.0, 1.5), (1.0, -0.5), 10, sentence_id="s1")]
    with FrameRenderer(demo_scene(), motions, width=96, height=72) as r:
        r.render(0)
        canvas = r._canvas
        assert canvas is not None
        _, depth = canvas.draw(r.camera(3), with_depth=True)
    assert depth is not None and depth.shape == (72, 96) and depth.dtype == np.float32
    drawn = depth > 0
    assert 0.2 < drawn.mean() < 1.0  # the room is drawn, the sky around it is not (0)
    near, far = np.percentile(depth[drawn], [5, 95])
    assert 0.5 < near < far - 1.0 and far < 30.0  # metres to the floor in front and the far walls
