"""Frames -> H.264 MP4 through PyAV, and chunks rendered by several workers joined into one video.

Every chunk is a complete MP4 that starts on a key frame and has no B-frames, with the same encoder
settings, so its packets can be copied one after another into one file (no re-encoding): the
joined video has exactly the frames of the chunks, in order, and plays without a seam.
"""

from __future__ import annotations

import io
import queue
import threading
from collections.abc import Iterable
from fractions import Fraction
from pathlib import Path

import av
import numpy as np

from wana.domain.units import FPS
from wana.mp4 import join_chunks  # noqa: F401  (the render service joins its chunks with it)

CRF = 20  # x264 constant rate factor: visually lossless-ish for flat-shaded renders
ENCODER_OPTIONS = {"crf": str(CRF), "preset": "veryfast", "tune": "zerolatency", "bf": "0"}


def _even(frame: np.ndarray) -> np.ndarray:
    h, w = frame.shape[:2]
    if h % 2 or w % 2:  # yuv420p needs even sizes: repeat the last row/column
        frame = np.pad(frame, ((0, h % 2), (0, w % 2), (0, 0)), mode="edge")
    return frame


QUEUE_FRAMES = 8  # frames in flight between the renderer and the encoder thread (about 7 MB at 640x480)
_END = None  # the producer's last item


def encode_mp4(frames: Iterable[np.ndarray], out: str | Path | io.BytesIO, fps: int = FPS) -> int:
    """Encode RGB frames to an H.264 MP4, the encoding on a thread of its own.

    The caller's thread pulls the frames (rendering them, when ``frames`` is a renderer's generator)
    while the encoder thread converts and compresses the previous ones: PyAV and x264 release the GIL,
    so the two overlap instead of taking turns. A bounded queue keeps memory flat.

    Args:
        frames: (H, W, 3) uint8 arrays, all the same size.
        out: file path or a BytesIO.
        fps: frames per second.

    Returns:
        The number of frames written.

    Raises:
        ValueError: no frames, or frames of different sizes.
    """
    target = str(out) if isinstance(out, (str, Path)) else out
    pending: queue.Queue[np.ndarray | None] = queue.Queue(maxsize=QUEUE_FRAMES)
    failures: list[BaseException] = []

    def encoder() -> None:
        container = None
        try:
            stream = None
            n = 0
            while (frame := pending.get()) is not _END:
                if container is None:
                    container = av.open(target, mode="w", format="mp4")
                    stream = container.add_stream("libx264", rate=fps, options=dict(ENCODER_OPTIONS))
                    stream.width, stream.height = frame.shape[1], frame.shape[0]
                    stream.pix_fmt = "yuv420p"
                    stream.codec_context.time_base = Fraction(1, fps)
                assert stream is not None  # opened together with the container
                vf = av.VideoFrame.from_ndarray(frame, format="rgb24")
                vf.pts = n
                for packet in stream.encode(vf):
                    container.mux(packet)
                n += 1
            if container is not None and stream is not None and not failures:
                for packet in stream.encode():
                    container.mux(packet)
        except BaseException as exc:  # handed to the caller's thread, which raises it
            failures.append(exc)
            while pending.get() is not _END:  # let the producer finish putting
                pass
        finally:
            if container is not None:
                container.close()

    thread = threading.Thread(target=encoder, name="mp4-encoder", daemon=True)
    thread.start()
    n = 0
    size: tuple[int, int] | None = None
    try:
        for frame in frames:
            if failures:
                break
            frame = _even(
                np.array(frame, dtype=np.uint8, order="C")
            )  # a copy: the caller may reuse its buffer
            if frame.ndim != 3 or frame.shape[2] != 3:
                raise ValueError(f"frames must be (H, W, 3) uint8, got {frame.shape}")
            if size is None:
                size = frame.shape[:2]
            elif frame.shape[:2] != size:
                raise ValueError(f"frame {n} is {frame.shape[:2]}, the video is {size}")
            pending.put(frame)
            n += 1
    except BaseException as exc:
        failures.append(exc)  # the encoder stops at the end marker without finishing the file
        raise
    finally:
        pending.put(_END)
        thread.join()
    if failures:
        raise failures[0]
    if n == 0:
        raise ValueError("no frames to encode")
    return n


def decode_frames(video: bytes | str | Path) -> list[np.ndarray]:
    """All frames of a video as (H, W, 3) uint8 RGB arrays."""
    src = io.BytesIO(video) if isinstance(video, (bytes, bytearray)) else str(video)
    with av.open(src, mode="r") as container:
        return [f.to_ndarray(format="rgb24") for f in container.decode(video=0)]


def probe(video: bytes | str | Path) -> dict[str, object]:
    """Codec, size, frame count and duration (seconds) of a video."""
    src = io.BytesIO(video) if isinstance(video, (bytes, bytearray)) else str(video)
    with av.open(src, mode="r") as container:
        s = container.streams.video[0]
        n = sum(1 for _ in container.decode(video=0))
        return {
            "codec": s.codec_context.name,
            "width": s.codec_context.width,
            "height": s.codec_context.height,
            "frames": n,
            "fps": float(s.average_rate) if s.average_rate else float(FPS),
            "duration_s": float(container.duration / av.time_base) if container.duration else n / FPS,
        }
