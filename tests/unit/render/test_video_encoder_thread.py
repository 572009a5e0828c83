"""The MP4 encoder runs on its own thread: frames arrive intact and in order, errors on either side reach
the caller, and no encoder thread outlives the call."""

from __future__ import annotations

import io
import threading
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from services.render.video import QUEUE_FRAMES, decode_frames, encode_mp4


def _frames(n: int, reuse: bool = False) -> Iterator[np.ndarray]:
    buf = np.zeros((48, 64, 3), dtype=np.uint8)
    for i in range(n):
        img = buf if reuse else np.zeros_like(buf)
        img[:] = 0
        img[:, : 4 * (i + 1) % 64] = (255, 120, 10)  # a bar that grows by frame: order is visible
        yield img


def _encoder_threads() -> int:
    return sum(1 for t in threading.enumerate() if t.name == "mp4-encoder")


def test_more_frames_than_the_queue_holds_come_out_in_order_even_when_the_caller_reuses_its_buffer() -> None:
    n = 3 * QUEUE_FRAMES
    buf = io.BytesIO()
    assert encode_mp4(_frames(n, reuse=True), buf) == n
    got = decode_frames(buf.getvalue())
    want = list(_frames(n))
    assert len(got) == n
    for g, w in zip(got, want, strict=True):
        assert np.abs(g.astype(int) - w.astype(int)).mean() < 6  # H.264 at CRF 20 on hard edges
    assert _encoder_threads() == 0


def test_an_error_while_rendering_reaches_the_caller_and_stops_the_encoder() -> None:
    def failing() -> Iterator[np.ndarray]:
        yield from _frames(QUEUE_FRAMES + 3)
        raise RuntimeError("renderer died")

    with pytest.raises(RuntimeError, match="renderer died"):
        encode_mp4(failing(), io.BytesIO())
    assert _encoder_threads() == 0


def test_an_encoder_failure_reaches_the_caller(tmp_path: Path) -> None:
    with pytest.raises(Exception):  # noqa: B017 - PyAV's own error type for a path it cannot open
        encode_mp4(_frames(2 * QUEUE_FRAMES), tmp_path / "no-such-dir" / "out.mp4")
    assert _encoder_threads() == 0


def test_no_frames_is_refused() -> None:
    with pytest.raises(ValueError, match="no frames"):
        encode_mp4(iter([]), io.BytesIO())
