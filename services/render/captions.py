"""Burn the current sentence into a frame: a dark band at the bottom with wrapped white text."""

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


def draw_caption(frame: np.ndarray, text: str, max_lines: int = 2) -> np.ndarray:
    """Return a copy of ``frame`` (H, W, 3) uint8 with ``text`` in a band at the bottom."""
    h, w = frame.shape[:2]
    size = max(10, h // 26)
    font = _font(size)
    chars = max(10, int(w / (size * 0.55)))
    lines = textwrap.wrap(text, chars)[:max_lines]
    if not lines:
        return frame
    band = int(len(lines) * size * 1.3 + size * 0.6)
    out = frame.copy()
    out[h - band :] = (out[h - band :].astype(np.uint16) * 2 // 5).astype(np.uint8)
    img = Image.fromarray(out)
    draw = ImageDraw.Draw(img)
    y = h - band + int(size * 0.3)
    for line in lines:
        tw = draw.textlength(line, font=font)
        draw.text(((w - tw) / 2, y), line, fill=(255, 255, 255), font=font)
        y += int(size * 1.3)
    return np.asarray(img)
