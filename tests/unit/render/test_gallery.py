"""The failure gallery renders the listed frames into one PNG, with the failing tiles framed in red."""

from __future__ import annotations

import numpy as np
import pytest
from PIL import Image

from proto.ssg import Command
from services.render.demo import demo_scene, walk_motion
from services.render.gallery import (
    BORDER,
    COLUMNS,
    LABEL_H,
    MAX_TILES,
    PAD,
    TILE_H,
    TILE_W,
    contact_sheet,
    thin,
    title_lines,
)
from services.render.renderer import FrameRenderer
from services.render.timeline import place_commands

N = 40


def _is_red(px: np.ndarray) -> bool:
    r, g, b = (int(v) for v in px)
    return r > 200 and g < 40 and b < 40


@pytest.fixture(scope="module")
def sheet(tmp_path_factory):  # noqa: ANN201
    eve = walk_motion("Eve", (-1.5, 1.0), (1.0, -0.5), N, sentence_id="s1")
    sentences = [("s1", "Eve walks to the sofa."), ("s2", "camera left")]
    commands = [("s2", Command(kind="camera", value="left"))]
    path = tmp_path_factory.mktemp("gallery") / "s1.png"
    frames, marked = [0, 10, 20, 30, 39], {10, 30}
    title = "Eve walks to the sofa.\nEve is out of frame for 0.7 s of 'Eve walks to the sofa'"
    out = contact_sheet(demo_scene(), [eve], commands, sentences, frames, marked, title, path)
    with FrameRenderer(
        demo_scene(), [eve], place_commands(commands, sentences, [eve]), width=TILE_W, height=TILE_H
    ) as r:
        tile20 = r.render(20)
    return out, np.asarray(Image.open(out).convert("RGB")), frames, marked, title, tile20


@pytest.mark.slow
def test_the_sheet_is_a_png_of_the_grid_size(sheet):
    out, img, frames, _, title, _ = sheet
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    cols = min(COLUMNS, len(frames))
    assert img.shape[1] == PAD + cols * (TILE_W + PAD)
    rows = -(-len(frames) // cols)
    lines = title_lines(title, img.shape[1])
    assert len(lines) == 2
    title_h = img.shape[0] - rows * (TILE_H + LABEL_H + PAD)
    assert 2 * 14 <= title_h <= 80  # room for the two title lines, no more


@pytest.mark.slow
def test_failing_tiles_have_a_red_border_and_the_others_show_the_rendered_frame(sheet):
    _, img, frames, marked, _, tile20 = sheet
    cols = min(COLUMNS, len(frames))
    rows = -(-len(frames) // cols)
    top = img.shape[0] - rows * (TILE_H + LABEL_H + PAD)
    for i, f in enumerate(frames):
        x, y = PAD + (i % cols) * (TILE_W + PAD), top + (i // cols) * (TILE_H + LABEL_H + PAD)
        border = [
            img[y + 1, x + TILE_W // 2],
            img[y + TILE_H - 2, x + 1],
            img[y + TILE_H // 2, x + TILE_W - 2],
        ]
        if f in marked:
            assert all(_is_red(px) for px in border), f"frame {f}: no red border"
        else:
            assert not any(_is_red(px) for px in border), f"frame {f}: red border on a passing tile"
        if f == 20:  # an unmarked tile is the renderer's picture of that frame, pixel for pixel
            inner = img[y + BORDER : y + TILE_H - BORDER, x + BORDER : x + TILE_W - BORDER].astype(int)
            ref = tile20[BORDER:-BORDER, BORDER:-BORDER].astype(int)
            assert np.abs(inner - ref).max() <= 1


def test_frames_are_clipped_to_the_video_and_thinned_to_a_sheet():
    assert thin([5, 5, -3, 400], n_frames=100) == [0, 5, 99]
    many = thin(range(0, 300, 3), n_frames=300)
    assert len(many) == MAX_TILES and many[0] == 0 and many[-1] == 297
