"""The failure gallery: a contact sheet of a few story frames, the failing ones marked, for a person to judge.

A check that fires on a correct animation is a bug in the check; the way to find one is to look at the
frames it names. ``contact_sheet`` renders only the listed frames with the real FrameRenderer (the same
camera and scene as the MP4), tiles them in a grid with the frame number and time under each, puts a red
border and a "FAIL" label on the marked ones, and writes a PNG with the title (the sentence and the
failed reasons) at the top.

    contact_sheet(scene, motions, commands, sentences, frames=[100, 130, 160], marked={130},
                  title="'Tom waves at Eve': Tom is out of frame for 2.1 s", path="out/s8.png")
"""

from __future__ import annotations

import math
import textwrap
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from proto.motion_data import Motion
from proto.scene import Scene
from services.render.renderer import FrameRenderer
from services.render.timeline import as_motion_list, place_commands
from services.render.video import FPS

TILE_W, TILE_H = 320, 240  # pixels of one rendered frame
LABEL_H = 18  # pixels of the frame/time line under a tile
PAD = 6  # pixels between tiles and around the sheet
COLUMNS = 4
MAX_TILES = 8  # more listed frames are thinned evenly (first and last kept)
BORDER = 4  # pixels of the red border of a failing tile
FAIL_RED = (230, 0, 0)
TITLE_SIZE = 14  # font pixels
TITLE_LINES = 6  # at most; a longer title is cut with an ellipsis


def _font(size: int) -> ImageFont.FreeTypeFont | ImageFont.ImageFont:
    try:
        return ImageFont.load_default(size=size)
    except TypeError:  # Pillow without FreeType
        return ImageFont.load_default()


def thin(frames: Iterable[int], n_frames: int, most: int = MAX_TILES) -> list[int]:
    """The listed frames inside the video, sorted, unique, thinned evenly to at most ``most``."""
    kept = sorted({min(max(int(f), 0), n_frames - 1) for f in frames})
    if len(kept) <= most:
        return kept
    picks = np.linspace(0, len(kept) - 1, most).round().astype(int)
    return [kept[i] for i in sorted(set(picks.tolist()))]


def title_lines(title: str, width: int) -> list[str]:
    """The title wrapped to the sheet's width (each line of the title wrapped on its own)."""
    chars = max(20, int((width - 2 * PAD) / (TITLE_SIZE * 0.55)))
    lines = [w for part in title.splitlines() or [""] for w in (textwrap.wrap(part, chars) or [""])]
    if len(lines) > TITLE_LINES:
        lines = lines[: TITLE_LINES - 1] + [lines[TITLE_LINES - 1][: chars - 1] + "…"]
    return lines


def sheet_layout(n_tiles: int, n_title_lines: int) -> tuple[int, int, int, int]:
    """(width, height, columns, title height) of a sheet in pixels."""
    cols = max(1, min(COLUMNS, n_tiles))
    rows = max(1, math.ceil(n_tiles / cols))
    title_h = PAD + n_title_lines * int(TITLE_SIZE * 1.3) + PAD
    return PAD + cols * (TILE_W + PAD), title_h + rows * (TILE_H + LABEL_H + PAD), cols, title_h


def tile_origin(i: int, cols: int, title_h: int) -> tuple[int, int]:
    """Top-left pixel (x, y) of tile i."""
    return PAD + (i % cols) * (TILE_W + PAD), title_h + (i // cols) * (TILE_H + LABEL_H + PAD)


def contact_sheet(
    scene: Scene,
    motions: Iterable[Motion] | Mapping[str, Motion],
    commands: Iterable[Any] | None,
    sentences: Iterable[Any] | None,
    frames: list[int],
    marked: set[int],
    title: str,
    path: str | Path,
) -> Path:
    """Render story frames into one PNG contact sheet.

    Args:
        scene, motions, commands, sentences: as ``write_outputs`` takes them (the same video).
        frames: story frames to show (30 fps); clipped to the video, thinned to MAX_TILES.
        marked: the failing frames among them (red border, "FAIL").
        title: the sentence and the failed reasons, drawn at the top (newlines start new lines).
        path: the PNG to write (folders are created).

    Returns:
        The path written.
    """
    mlist = as_motion_list(motions)
    sents = list(sentences or [])
    timed = place_commands(commands, sents, mlist)
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    with FrameRenderer(scene, mlist, timed, [], width=TILE_W, height=TILE_H) as renderer:
        shown = thin(frames, renderer.n_frames)
        tiles = [renderer.render(f) for f in shown]
    width = sheet_layout(len(shown), 1)[0]
    lines = title_lines(title, width)
    width, height, cols, title_h = sheet_layout(len(shown), len(lines))
    sheet = Image.new("RGB", (width, height), (255, 255, 255))
    draw = ImageDraw.Draw(sheet)
    font, small = _font(TITLE_SIZE), _font(12)
    for n, line in enumerate(lines):
        draw.text((PAD, PAD + n * int(TITLE_SIZE * 1.3)), line, fill=(20, 20, 20), font=font)
    for i, (f, tile) in enumerate(zip(shown, tiles, strict=True)):
        x, y = tile_origin(i, cols, title_h)
        sheet.paste(Image.fromarray(tile), (x, y))
        failing = f in marked
        if failing:
            for b in range(BORDER):
                draw.rectangle([x + b, y + b, x + TILE_W - 1 - b, y + TILE_H - 1 - b], outline=FAIL_RED)
            draw.rectangle([x + BORDER, y + BORDER, x + BORDER + 38, y + BORDER + 17], fill=FAIL_RED)
            draw.text((x + BORDER + 4, y + BORDER + 2), "FAIL", fill=(255, 255, 255), font=small)
        label = f"frame {f}  {f / FPS:.2f} s" + ("  FAIL" if failing else "")
        draw.text((x, y + TILE_H + 2), label, fill=FAIL_RED if failing else (60, 60, 60), font=small)
    sheet.save(out, format="PNG")
    return out
