"""Frame I/O shared by broker, worker and client, tuned for the hot path.

Measured on the project's shared 2-core machine (``bench/bus.py`` and micro-benchmarks, pyzmq 27):
every pyzmq call costs microseconds, so the hot path makes as few as it can.

- pyzmq's convenience layer (``send_multipart``, ``recv_multipart``, ``Socket.poll``) builds flag
  enums and a fresh Poller per call; these helpers call the Cython socket methods directly with
  integer flags.
- ``recv(copy=True)`` of a 1 kB frame is about 3 times cheaper than ``copy=False``: a ``zmq.Frame``
  is a heavy object. But ``getsockopt(RCVMORE)`` costs more than a Frame (pyzmq maps the option
  through an enum), and ``Frame.more`` is free. So the broker, which faces peers it cannot trust to
  frame their messages right, takes the routing id as bytes (a ROUTER socket always puts at least
  one frame after it) and the rest as Frames (their ``more`` flag counts the parts; a payload is
  forwarded without copying it); workers and clients, which hear only from the broker, take whole
  frames as bytes and know from the envelope whether a body frame follows.
- A non-blocking receive that finds nothing raises ``zmq.Again``; the exception costs three to four
  times a ``zmq_poll`` with timeout 0 (about 6 against 1.5 us of CPU), while a receive of a waiting
  message needs no poll at all. So the loops poll (level-triggered: it returns at once while a
  message is waiting) and, when the poll found a message already waiting (it returned within
  ``BACKLOG_S``: a backlog, as under load), drain with plain receives until EAGAIN; in a closed loop
  of one request at a time they keep to one poll per message and never pay the exception.
"""

from __future__ import annotations

import contextlib
from collections.abc import Sequence
from typing import Any

import msgspec
import zmq

from proto.bus import MAX_BATCH, BatchFrame, Envelope, ErrorFrame, JobFrame, ReplyFrame, StatsFrame

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

_zmq_poll = zmq.zmq_poll
NOBLOCK = int(zmq.NOBLOCK)
SNDMORE = int(zmq.SNDMORE)
_MORE_NOBLOCK = NOBLOCK | SNDMORE
_POLLIN = int(zmq.POLLIN)
_RCVMORE = int(zmq.RCVMORE)
_MAX_PARTS = 2 + 2 * MAX_BATCH  # no bus message has more; the rest of a longer one is read and dropped
BACKLOG_S = 20e-6  # a poll answering faster than this found a message already waiting

encoder = msgspec.msgpack.Encoder()
# Every way decoding a frame can fail: msgspec's errors, and UnicodeDecodeError (a ValueError),
# which msgspec raises as itself for a msgpack string that is not UTF-8 (b"\x91\xa1\xff" once
# killed the broker). Every decode on the bus catches exactly this tuple.
# Messages ZeroMQ queues per peer on a receiving socket before it stops reading that connection: the
# sender then waits (TCP back-pressure; nothing is dropped on ROUTER or DEALER), so a peer flooding faster
# than the loop handles its messages holds at most this many in the receiver's memory, not all of them.
# (256 cost the broker ~10 us and a client ~5 us per request in bench/bus.py: flow control that often.)
RCVHWM = 4096


def watch_disconnects(sock: zmq.Socket) -> zmq.Socket | None:
    """A monitor of ``sock``'s connection drops (tcp:// and ipc://; None for inproc://, which never drops).

    ZeroMQ reconnects by itself, but what was in flight on the dropped connection is gone: a peer that
    learns of the drop re-sends (a client its pending jobs, a worker its READY, so the broker re-queues
    what it held).
    """
    endpoint = sock.getsockopt_string(zmq.LAST_ENDPOINT)
    if endpoint.startswith("inproc://"):
        return None
    return sock.get_monitor_socket(zmq.EVENT_DISCONNECTED)


def dropped(monitor: zmq.Socket | None) -> bool:
    """True when the monitored connection dropped since the last call (reads every pending event)."""
    seen = False
    # ZMQ_EVENTS rather than poll(): no Poller is built for the check
    while monitor is not None and int(monitor.getsockopt(zmq.EVENTS)) & _POLLIN:
        monitor.recv_multipart(zmq.NOBLOCK)
        seen = True
    return seen


def close_monitor(sock: zmq.Socket, monitor: zmq.Socket | None) -> None:
    if monitor is not None:
        with contextlib.suppress(zmq.ZMQError):
            sock.disable_monitor()
        monitor.close(0)


DECODE_ERRORS = (msgspec.DecodeError, msgspec.ValidationError, ValueError)
# Typed as Any because zmq.Frame (buffer protocol) is not declared a Buffer in pyzmq's stubs.
envelope_decoder: Any = msgspec.msgpack.Decoder(Envelope)

# Envelopes the broker sends with one body frame (STATS only in that direction).
_FROM_BROKER_WITH_BODY = frozenset((JobFrame, ReplyFrame, ErrorFrame, StatsFrame))
# The BATCH envelope for each count, encoded once.
BATCH_HEADS = [encoder.encode(BatchFrame(n)) for n in range(MAX_BATCH + 1)]


class Undecodable:
    """Marker returned by ``recv_from_broker`` for a message whose envelope does not decode."""

    def __init__(self, reason: str):
        self.reason = reason


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


def send_pairs(sock: zmq.Socket, head: tuple[object, ...], pairs: Sequence[object]) -> None:
    """Send ``pairs`` (envelope, body, envelope, body, ...: a flat sequence) as one message.

    ``head`` is what goes first (the routing id on the broker's ROUTER socket, else empty). One
    pair travels as a plain message; more travel as a BATCH (callers keep to ``MAX_BATCH`` pairs).
    """
    n = len(pairs) // 2
    if n == 1:
        send(sock, (*head, pairs[0], pairs[1]))
        return
    for frame in head:
        _send(sock, frame, _MORE_NOBLOCK)
    _send(sock, BATCH_HEADS[n], _MORE_NOBLOCK)
    last = len(pairs) - 1
    for i in range(last):
        _send(sock, pairs[i], _MORE_NOBLOCK)
    _send(sock, pairs[last], NOBLOCK)


def poll(sock: zmq.Socket, timeout_s: float) -> bool:
    """True when a message is waiting, blocking up to ``timeout_s`` seconds for one (0: do not block)."""
    ms = int(timeout_s * 1000) + 1 if timeout_s > 0 else 0
    return bool(_zmq_poll([(sock, _POLLIN)], ms))


def readable(sock: zmq.Socket) -> bool:
    """True when a message is waiting (does not block)."""
    return bool(_zmq_poll([(sock, _POLLIN)], 0))


def wait(sock: zmq.Socket, timeout_s: float) -> bool:
    """Block until a message is waiting or ``timeout_s`` passed; True when readable."""
    return poll(sock, timeout_s)


def recv(sock: zmq.Socket) -> list[Any] | None:
    """Receive one message from a ROUTER socket: ``[routing id (bytes), Frame, ...]``, or None.

    Frames after the routing id are ``zmq.Frame`` objects (buffer protocol, ``len``, ``.bytes``),
    at most ``_MAX_PARTS`` in all; the rest of a longer message is read and dropped.
    """
    try:
        identity = _recv(sock, NOBLOCK, True)
    except zmq.Again:
        return None
    frame = _recv(sock, NOBLOCK, False)  # a ROUTER always delivers a frame after the routing id
    frames = [identity, frame]
    while frame.more:
        frame = _recv(sock, NOBLOCK, False)
        if len(frames) < _MAX_PARTS:
            frames.append(frame)
    return frames


def recv_from_broker(sock: zmq.Socket) -> tuple[Any, bytes | None] | None:
    """Receive one message the broker sent to a worker or client: ``(envelope, body or None)``.

    The envelope decides whether a body frame follows (the broker frames its messages right). An
    envelope that does not decode comes back as ``(Undecodable, None)`` with the rest of its
    message read and dropped. None when nothing is waiting. A BATCH comes back as
    ``(BatchFrame, [(envelope, body), ...])``.
    """
    try:
        head = _recv(sock, NOBLOCK, True)
    except zmq.Again:
        return None
    try:
        msg = envelope_decoder.decode(head)
    except DECODE_ERRORS as exc:
        _drop_rest(sock)
        return Undecodable(str(exc)), None
    if type(msg) is BatchFrame:
        return _recv_batch(sock, msg)
    # Frame counts are checked against RCVMORE, never by trying a receive: that would take the
    # first frame of the next message as this one's body.
    body = None
    if type(msg) in _FROM_BROKER_WITH_BODY:
        if not _get(sock, _RCVMORE):  # a body-less message where a body belongs: not from a wana broker
            return Undecodable(f"{type(msg).__name__} without its body frame"), None
        body = _recv(sock, NOBLOCK, True)
    if _get(sock, _RCVMORE):  # more frames than the command has: never read them as the next message
        _drop_rest(sock)
        return Undecodable(f"{type(msg).__name__} with more frames than it carries"), None
    return msg, body


def _recv_batch(sock: zmq.Socket, batch: BatchFrame) -> tuple[Any, Any]:
    """The ``(envelope, body)`` pairs after a BATCH envelope (see ``recv_from_broker``)."""
    pairs: list[tuple[Any, bytes]] = []
    decode = envelope_decoder.decode
    try:
        for _ in range(batch.count):
            if not _get(sock, _RCVMORE):
                return Undecodable(f"a BATCH of {batch.count} ended after {len(pairs)} pairs"), None
            msg = decode(_recv(sock, NOBLOCK, True))
            if not _get(sock, _RCVMORE):
                return Undecodable(f"a BATCH of {batch.count} ended inside pair {len(pairs) + 1}"), None
            pairs.append((msg, _recv(sock, NOBLOCK, True)))
    except DECODE_ERRORS as exc:
        _drop_rest(sock)
        return Undecodable(f"in a BATCH: {exc}"), None
    if _get(sock, _RCVMORE):
        _drop_rest(sock)
        return Undecodable(f"a BATCH of {batch.count} has more frames"), None
    return batch, pairs


def _drop_rest(sock: zmq.Socket) -> None:
    while _get(sock, _RCVMORE):
        _recv(sock, NOBLOCK, True)
