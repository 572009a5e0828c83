"""Frame I/O shared by broker, worker and client, tuned for the hot path.

pyzmq's convenience layer (``send_multipart``, ``recv_multipart``, ``Socket.poll``) costs several
microseconds per call in flag enums and a fresh Poller; on a busy machine that was most of a round
trip. These helpers call the Cython socket methods directly with integer flags, receive frames
without copying (``zmq.Frame`` supports the buffer protocol, so msgspec decodes it in place and the
broker forwards payloads untouched), and poll only when a non-blocking receive found nothing.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import msgspec
import zmq

from proto.bus import Envelope

_send: Any
_recv: Any
_get: Any
try:  # pyzmq's Cython backend (CPython)
    from zmq.backend.cython._zmq import Socket as _BaseSocket

    _send = _BaseSocket.send
    _recv = _BaseSocket.recv
    _get = _BaseSocket.get
except ImportError:  # pragma: no cover - the CFFI backend (PyPy): plain methods
    _send = zmq.Socket.send
    _recv = zmq.Socket.recv
    _get = zmq.Socket.getsockopt

NOBLOCK = int(zmq.NOBLOCK)
SNDMORE = int(zmq.SNDMORE)
_MORE_NOBLOCK = NOBLOCK | SNDMORE
_EVENTS = int(zmq.EVENTS)
_POLLIN = int(zmq.POLLIN)
_MAX_PARTS = 16  # no bus message has more; the rest of a longer one is read and dropped

encoder = msgspec.msgpack.Encoder()
# Typed as Any because zmq.Frame (buffer protocol) is not declared a Buffer in pyzmq's stubs.
envelope_decoder: Any = msgspec.msgpack.Decoder(Envelope)


def send(sock: zmq.Socket, frames: Sequence[object]) -> None:
    """Send one multipart message without blocking (raises zmq.ZMQError, e.g. EHOSTUNREACH)."""
    n = len(frames)
    if n == 3:  # the common shapes, unrolled: this runs for every message
        _send(sock, frames[0], _MORE_NOBLOCK)
        _send(sock, frames[1], _MORE_NOBLOCK)
        _send(sock, frames[2], NOBLOCK)
    elif n == 2:
        _send(sock, frames[0], _MORE_NOBLOCK)
        _send(sock, frames[1], NOBLOCK)
    else:
        for frame in frames[:-1]:
            _send(sock, frame, _MORE_NOBLOCK)
        _send(sock, frames[-1], NOBLOCK)


def readable(sock: zmq.Socket) -> bool:
    """True when a message is waiting (cheaper than a poll)."""
    return bool(_get(sock, _EVENTS) & _POLLIN)


def recv(sock: zmq.Socket) -> list[zmq.Frame] | None:
    """Receive one whole multipart message as zero-copy frames, or None when nothing is waiting."""
    try:  # cheaper than asking getsockopt(EVENTS) first when messages are flowing
        frame = _recv(sock, NOBLOCK, False)
    except zmq.Again:
        return None
    frames = [frame]
    while frame.more:
        frame = _recv(sock, NOBLOCK, False)
        if len(frames) < _MAX_PARTS:
            frames.append(frame)
    return frames


def wait(sock: zmq.Socket, timeout_s: float) -> bool:
    """Block until a message is waiting or ``timeout_s`` passed; True when readable."""
    if timeout_s <= 0:
        return readable(sock)
    return bool(zmq.zmq_poll([(sock, _POLLIN)], int(timeout_s * 1000) + 1))
