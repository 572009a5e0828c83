"""Burn the current sentence into a frame: a dark band at the bottom with wrapped white text.

A caption stays on screen for many frames, so its text is drawn once into a coverage mask (cached by
text and frame size) and each frame only darkens the band and blends white in through the mask, with
Pillow's own rounding, instead of laying the text out and rasterising it again every frame.
"""

from __future__ import annotations

import textwrap
from functools import lru_cache

import numpy as np
from PIL import Image, ImageDraw, ImageFont


@lru_cache(maxsize=8)
def _font(size: int) -> ImageFont.FreeTypeFont | ImageFont.ImageFont:
    try:
        return ImageFont.load_default(size=size)
    except TypeError:  # Pillow without FreeType: fixed bitmap font
        return ImageFont.load_default()


@lru_cache(maxsize=32)
def _mask(text: str, w: int, h: int, max_lines: int) -> np.ndarray | None:
    """(band, w) uint16 text coverage in [0, 255] for the bottom band of a w x h frame; None: no text."""
    size = max(10, h // 26)
    font = _font(size)
    chars = max(10, int(w / (size * 0.55)))
    lines = textwrap.wrap(text, chars)[:max_lines]
    if not lines:
        return None
    band = int(len(lines) * size * 1.3 + size * 0.6)
    img = Image.new("L", (w, band), 0)
    draw = ImageDraw.Draw(img)
    y = int(size * 0.3)
    for line in lines:
        tw = draw.textlength(line, font=font)
        draw.text(((w - tw) / 2, y), line, fill=255, font=font)
        y += int(size * 1.3)
    return np.asarray(img, dtype=np.uint16)


def draw_caption(frame: np.ndarray, text: str, max_lines: int = 2) -> np.ndarray:
    """Return a copy of ``frame`` (H, W, 3) uint8 with ``text`` in a band at the bottom."""
    h, w = frame.shape[:2]
    mask = _mask(text, w, h, max_lines)
    if mask is None:
        return frame
    band = len(mask)
    out = frame.copy()
    dark = out[h - band :].astype(np.uint16) * 2 // 5
    tmp = (255 - dark) * mask[..., None] + 128  # Pillow's blend towards white, rounded as it rounds
    out[h - band :] = (dark + ((tmp + (tmp >> 8)) >> 8)).astype(np.uint8)
    return out
