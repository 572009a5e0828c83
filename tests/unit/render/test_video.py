"""H.264 encoding and joining chunks encoded separately."""

from __future__ import annotations

import io

import numpy as np
import pytest

from services.render.video import decode_frames, encode_mp4, join_chunks, probe


def _frames(n: int, h: int = 96, w: int = 128) -> list[np.ndarray]:
    out = []
    for i in range(n):
        f = np.full((h, w, 3), 40, np.uint8)
        f[20:60, 4 * i : 4 * i + 24] = (250, 80, 40)  # a box moving right
        out.append(f)
    return out


def test_chunks_encoded_apart_join_into_one_video_with_every_frame_in_order():
    frames = _frames(24)
    chunks = []
    for a, b in [(0, 7), (7, 16), (16, 24)]:
        buf = io.BytesIO()
        assert encode_mp4(frames[a:b], buf) == b - a
        chunks.append(buf.getvalue())
    out = io.BytesIO()
    assert join_chunks(chunks, out) == 24
    info = probe(out.getvalue())
    assert info["codec"] == "h264" and info["frames"] == 24 and info["width"] == 128
    assert abs(info["duration_s"] - 0.8) < 0.05
    decoded = decode_frames(out.getvalue())
    for i, (d, f) in enumerate(zip(decoded, frames, strict=True)):
        assert np.abs(d.astype(int) - f).mean() < 4, f"frame {i} differs from its source"
        cols = np.where((d[40, :, 0] > 180) & (d[40, :, 2] < 120))[0]
        assert abs(cols.min() - 4 * i) <= 2  # the moving box is where frame i put it: no reordering


def test_odd_sizes_are_padded_and_mixed_sizes_refused():
    buf = io.BytesIO()
    encode_mp4([np.zeros((31, 45, 3), np.uint8)] * 2, buf)
    assert probe(buf.getvalue())["width"] == 46
    with pytest.raises(ValueError, match="frame 1"):
        encode_mp4([np.zeros((32, 32, 3), np.uint8), np.zeros((16, 16, 3), np.uint8)], io.BytesIO())
    with pytest.raises(ValueError, match="no frames"):
        encode_mp4([], io.BytesIO())
