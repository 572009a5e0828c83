"""MP4 chunks joined into one video without re-encoding (the render service's frame ranges, the gateway's
export jobs): each chunk's packets are copied, their time stamps moved past the frames before it."""

from __future__ import annotations

import io
from collections.abc import Iterable
from fractions import Fraction
from pathlib import Path

from wana.domain.units import FPS


def join_chunks(chunks: Iterable[bytes | str | Path], out: str | Path | io.BytesIO, fps: int = FPS) -> int:
    """Concatenate MP4 chunks from ``encode_mp4`` into one MP4 without re-encoding.

    Args:
        chunks: MP4 files (paths or bytes) in frame order.
        out: output path or BytesIO.

    Returns:
        Total number of frames.
    """
    import av  # here: the gateway imports this module and need not load the codecs at start-up

    target = str(out) if isinstance(out, (str, Path)) else out
    dst = av.open(target, mode="w", format="mp4")
    ostream = None
    frames_done = 0
    try:
        for chunk in chunks:
            src_file = io.BytesIO(chunk) if isinstance(chunk, (bytes, bytearray)) else str(chunk)
            with av.open(src_file, mode="r") as src:
                istream = src.streams.video[0]
                if ostream is None:
                    ostream = dst.add_stream_from_template(istream)
                    ostream.time_base = istream.time_base
                tb = istream.time_base
                if tb is None:
                    raise ValueError("an MP4 chunk's video stream has no time base")
                offset = int(round(Fraction(frames_done, fps) / tb))
                count = 0
                for packet in src.demux(istream):
                    if packet.dts is None and packet.pts is None:
                        continue  # the demuxer's end-of-stream marker
                    if packet.pts is not None:
                        packet.pts += offset
                    if packet.dts is not None:
                        packet.dts += offset
                    packet.stream = ostream
                    dst.mux(packet)
                    count += 1
                frames_done += count
        if ostream is None:
            raise ValueError("no chunks to join")
    finally:
        dst.close()
    return frames_done
