"""The worker runtime: register a bytes -> bytes handler for a service and serve jobs from the broker.

The handler is usually ``wana.bus.service.make_frame_handler(CONTRACT)``: it decodes the request,
calls the pure handler and encodes the reply, turning any failure into an ErrorReply. This module
adds the socket side: READY, heartbeats (also while a long handler runs), oversize and expired jobs
answered with an ErrorReply without calling the handler, and reconnection with exponential back-off
when the broker goes silent (for instance because it restarted).
"""

from __future__ import annotations

import logging
import os
import signal
import socket
import threading
import time
import uuid
from collections.abc import Callable
from typing import cast

import msgspec
import zmq

from proto.bus import BatchFrame, DisconnectFrame, ErrorFrame, HeartbeatFrame, JobFrame, ReadyFrame
from proto.common import ErrorCode, ErrorReply, Header
from wana.bus import curve, wire

log = logging.getLogger(__name__)

Handler = Callable[[bytes], bytes]

_TICK_S = 0.05  # longest sleep of the loop: bounds stop latency
_HEARTBEAT = wire.encoder.encode(HeartbeatFrame())
_DISCONNECT = wire.encoder.encode(DisconnectFrame())
_REPLY_HEAD = b"\x92" + wire.encoder.encode("REPLY")  # ["REPLY", job_id]: a 2-array, then the tag
DEFAULT_CAPACITY = 16  # jobs the broker may hand a worker at once (see Worker)
# Replies to a BATCH of jobs go back as one BATCH while the jobs are this quick; a reply never waits
# for a slower job (see Worker._on_jobs).
_HOLD_JOB_S = 0.001
_HOLD_MAX_S = 0.002


def reply_envelope(job_id: str) -> bytes:
    """The REPLY envelope for ``job_id``, byte for byte ``encode(ReplyFrame(job_id))``, built cheaper."""
    return _REPLY_HEAD + wire.encoder.encode(job_id)


class Worker:
    """Serve one service's jobs with a bytes -> bytes handler.

    Args:
        service: service name clients address, e.g. ``"nlp"``.
        handler: pure function from request payload to reply payload; it should not raise (exceptions
            are turned into an E009 ErrorReply anyway).
        connect: broker URL.
        heartbeat_s: heartbeat interval in seconds; the broker must use the same one.
        liveness: broker heartbeats that may be missed before the worker reconnects.
        max_frame: largest request payload handled and reply payload sent (E002 otherwise).
        reconnect_max_s: ceiling of the exponential reconnect back-off (which starts at heartbeat_s).
        capacity: jobs the broker may hand this worker at once (default ``DEFAULT_CAPACITY``, 16).
            1 is classic Majordomo; more lets the next jobs travel while the current one runs, so
            short jobs arrive in batches and the broker round trip between them disappears (the
            bus's throughput target needs it). The broker still gives a job to an idle worker
            first, and prefetches only while this worker's jobs are short (its last one took, and
            its current one has run, under 50 ms, and the jobs it holds would take under 50 ms at
            that pace), so no job is parked behind long ones.
        keys: key directory (see wana/bus/curve.py) for a ``tcp://`` broker; default
            ``$WANA_BUS_KEYS``. The worker then talks CURVE with its ``worker`` pair.
        context: ZeroMQ context; pass the broker's to use ``inproc://``.

    ``run`` blocks; it may be called from any one thread. ``stop`` (an Event) ends it after the
    current job; the worker then sends DISCONNECT.
    """

    def __init__(
        self,
        service: str,
        handler: Handler,
        connect: str,
        *,
        heartbeat_s: float = 1.0,
        liveness: int = 3,
        max_frame: int = 32 * 1024 * 1024,
        reconnect_max_s: float = 30.0,
        capacity: int = DEFAULT_CAPACITY,
        keys: str | os.PathLike[str] | None = None,
        context: zmq.Context | None = None,
    ):
        if not service:
            raise ValueError("a worker needs a service name")
        if capacity < 1:
            raise ValueError("capacity must be at least 1")
        self.service = service
        self.handler = handler
        self.connect = connect
        self.heartbeat_s = float(heartbeat_s)
        self.liveness = int(liveness)
        self.max_frame = int(max_frame)
        self.capacity = int(capacity)
        self.reconnect_max_s = float(reconnect_max_s)
        self._context = context or zmq.Context.instance()
        self._keys = curve.keys_dir(keys) if connect.startswith("tcp://") else None
        self._socket: zmq.Socket | None = None
        self._monitor: zmq.Socket | None = None  # connection drops of _socket (wire.watch_disconnects)
        self._lock = threading.Lock()  # owns the socket: the loop, or the heartbeat thread during a job
        self._in_handler = False
        self._last_sent = 0.0
        self._broker_expiry = 0.0
        self._backoff = self.heartbeat_s
        self._broker_ttl = self.heartbeat_s * self.liveness
        self._draining = False  # receive without polling first: jobs were waiting (wire.py)
        self._stop = threading.Event()
        self._ready = wire.encoder.encode(
            ReadyFrame(
                service,
                pid=os.getpid(),
                host=socket.gethostname(),
                max_frame=self.max_frame,
                capacity=capacity,
            )
        )
        self.jobs_done = 0
        self.reconnects = 0
        self._failures: dict[str, int] = {}

    @property
    def backoff_s(self) -> float:
        """Seconds the next reconnection will wait (doubles while the broker stays away)."""
        return self._backoff

    # ----------------------------------------------------------------------------------- sockets

    def _open(self) -> None:
        sock = self._context.socket(zmq.DEALER)
        sock.setsockopt(zmq.LINGER, 0)
        sock.setsockopt(zmq.ROUTING_ID, b"W" + uuid.uuid4().hex.encode())
        sock.setsockopt(zmq.MAXMSGSIZE, 2 * self.max_frame + 4096)
        sock.setsockopt(zmq.RCVHWM, wire.RCVHWM)
        if self._keys is not None:
            curve.connect_curve(sock, self._keys, "worker")
        sock.connect(self.connect)
        self._socket = sock
        self._monitor = wire.watch_disconnects(sock)  # a dropped connection: READY again (_serve_once)
        now = time.monotonic()
        self._broker_expiry = now + self.heartbeat_s * self.liveness
        self._send(self._ready)

    def _close(self) -> None:
        if self._socket is not None:
            wire.close_monitor(self._socket, self._monitor)
            self._monitor = None
            self._socket.close(0)
            self._socket = None

    def _send(self, *frames: object) -> None:
        assert self._socket is not None
        try:
            wire.send(self._socket, frames)
        except zmq.Again:  # no broker connected (e.g. inproc after it closed): liveness will notice
            log.debug("%s worker: could not send, no broker connected", self.service)
        self._last_sent = time.monotonic()

    def _reconnect(self, stop: threading.Event) -> None:
        self._close()
        log.warning(
            "%s worker: broker silent or asked us to re-register; reconnecting in %.2fs",
            self.service,
            self._backoff,
        )
        stop.wait(self._backoff)
        self._backoff = min(self._backoff * 2, self.reconnect_max_s)
        self.reconnects += 1
        if not stop.is_set():
            self._open()

    # --------------------------------------------------------------------------------------- loop

    def run(self, stop: threading.Event | None = None) -> None:
        """Serve until ``stop`` is set; always sends DISCONNECT and closes the socket on the way out."""
        stop = stop or self._stop
        beat_stop = threading.Event()
        beat = threading.Thread(
            target=self._beat_during_jobs, args=(beat_stop,), name="wana-worker-beat", daemon=True
        )
        self._lock.acquire()
        try:
            self._open()
            beat.start()
            while not stop.is_set():
                try:
                    self._serve_once(stop)
                except zmq.ContextTerminated:
                    break
                except zmq.ZMQError as exc:  # a socket-level failure: start over with a fresh socket
                    log.warning("%s worker: socket error %s; reconnecting", self.service, exc)
                    self._reconnect(stop)
                except Exception as exc:  # the per-message guard: log once per kind, keep serving
                    self._log_failure(exc)
        finally:
            try:
                if self._socket is not None:
                    self._send(_DISCONNECT)
            except zmq.ZMQError:
                pass
            self._close()
            self._lock.release()
            beat_stop.set()
            if beat.is_alive():
                beat.join(timeout=2.0)

    def _serve_once(self, stop: threading.Event) -> None:
        """Send a heartbeat or reconnect when due, then handle at most one message."""
        sock = self._socket
        assert sock is not None
        now = time.monotonic()
        if now >= self._broker_expiry:
            self._reconnect(stop)
            return
        if now >= self._last_sent + self.heartbeat_s:
            if wire.dropped(self._monitor):
                # A reply or a JOB in flight may have gone with the connection: registering again makes
                # the broker re-queue whatever it thinks this worker holds (the READY travels on the
                # connection ZeroMQ re-opens, after anything queued before it).
                log.warning(
                    "%s worker: the connection to the broker dropped; registering again", self.service
                )
                self._send(self._ready)
            self._send(_HEARTBEAT)
        got = wire.recv_from_broker(sock) if self._draining else None
        if got is None:  # nothing waiting, or not draining (see wire.py): poll first
            self._draining = False
            if not wire.poll(
                sock, min(self._last_sent + self.heartbeat_s, self._broker_expiry, now + _TICK_S) - now
            ):
                return
            got = wire.recv_from_broker(sock)
            if got is None:
                return
            self._draining = time.monotonic() - now < wire.BACKLOG_S
        self._broker_expiry = time.monotonic() + self._broker_ttl
        msg, body = got
        kind = type(msg)
        if kind is JobFrame:
            self._backoff = self.heartbeat_s  # the broker knows us: the next outage starts over
            self._on_job(msg, cast(bytes, body))  # a JOB always carries its body (wire.py)
        elif kind is BatchFrame:
            self._backoff = self.heartbeat_s
            self._on_jobs(cast(list, body))
        elif kind is HeartbeatFrame:
            self._backoff = self.heartbeat_s
        elif kind is DisconnectFrame:
            self._reconnect(stop)  # the broker does not know us (it restarted): register again
        elif kind is ErrorFrame:  # e.g. E012: the broker refused our READY
            log.error("%s worker: the broker answered an error: %s", self.service, _error_text(body))
        elif kind is wire.Undecodable:
            log.warning(
                "%s worker: dropped a message with an undecodable envelope: %s", self.service, msg.reason
            )
        else:
            self._backoff = self.heartbeat_s
            log.warning("%s worker: dropped a %s envelope", self.service, kind.__name__)

    def _log_failure(self, exc: Exception) -> None:
        kind = type(exc).__name__
        self._failures[kind] = self._failures.get(kind, 0) + 1
        if self._failures[kind] == 1:
            log.error("%s worker: a message failed (logged once per kind)", self.service, exc_info=exc)

    def _on_job(self, job: JobFrame, payload: bytes) -> None:
        reply = self._run(job, payload)
        if self._socket is not None:
            self._send(reply_envelope(job.job_id), reply)
            self.jobs_done += 1

    def _on_jobs(self, pairs: list[tuple[object, bytes]]) -> None:
        """Run a BATCH of jobs in order; their replies go back together while the jobs are quick.

        A reply is held for the next job only while the job just run took under ``_HOLD_JOB_S``
        and the oldest held reply is younger than ``_HOLD_MAX_S``: a backlog of tiny jobs costs one
        message back, and no reply waits behind a slower job.
        """
        out: list[bytes] = []
        held_since = 0.0
        last = len(pairs) - 1
        monotonic = time.monotonic
        for i, (job, payload) in enumerate(pairs):
            if type(job) is not JobFrame:
                log.warning("%s worker: dropped a %s in a BATCH", self.service, type(job).__name__)
                continue
            started = monotonic()
            reply = self._run(job, payload)
            if self._socket is None:
                return
            out.append(reply_envelope(job.job_id))
            out.append(reply)
            now = monotonic()
            if len(out) == 2:
                held_since = now
            if i == last or now - started >= _HOLD_JOB_S or now - held_since >= _HOLD_MAX_S:
                self._send_pairs(out)
                out = []
        if out:
            self._send_pairs(out)

    def _send_pairs(self, pairs: list[bytes]) -> None:
        assert self._socket is not None
        try:
            wire.send_pairs(self._socket, (), pairs)
        except zmq.Again:  # no broker connected: its liveness check will notice
            log.debug("%s worker: could not send, no broker connected", self.service)
        self._last_sent = time.monotonic()
        self.jobs_done += len(pairs) // 2

    def _run(self, job: JobFrame, payload: bytes) -> bytes:
        """The reply payload for one job: the handler's, or an ErrorReply (size, deadline, failure)."""
        if len(payload) > self.max_frame:
            reply = self._error(
                job,
                ErrorCode.TOO_LARGE,
                f"request of {len(payload)} bytes exceeds the {self.max_frame}-byte cap",
            )
        elif job.deadline_ms <= 0:
            reply = self._error(job, ErrorCode.DEADLINE, "the job reached the worker after its deadline")
        else:
            self._in_handler = True
            self._lock.release()  # the heartbeat thread may use the socket while the handler runs
            try:
                reply = self.handler(payload)
            except Exception as exc:  # the frame handler already catches; a raw handler might not
                log.exception("%s worker: handler raised", self.service)
                reply = self._error(job, ErrorCode.HANDLER_FAILED, f"{type(exc).__name__}: {exc}")
            finally:
                self._lock.acquire()
                self._in_handler = False
                # The broker's heartbeats of the job's duration wait unread in the socket: silence is
                # counted from now, or a job longer than the liveness window reconnects (and, with
                # LINGER 0, may drop the reply it just queued).
                self._broker_expiry = max(self._broker_expiry, time.monotonic() + self._broker_ttl)
            if not isinstance(reply, (bytes, bytearray, memoryview)):
                reply = self._error(
                    job, ErrorCode.HANDLER_FAILED, f"handler returned {type(reply).__name__}, not bytes"
                )
            elif len(reply) > self.max_frame:
                reply = self._error(
                    job,
                    ErrorCode.TOO_LARGE,
                    f"reply of {len(reply)} bytes exceeds the {self.max_frame}-byte cap",
                )
        return reply

    @staticmethod
    def _error(job: JobFrame, code: str, message: str) -> bytes:
        header = Header(doc_id=job.doc_id, revision=job.revision)
        return wire.encoder.encode(ErrorReply(header=header, code=code, message=message))

    def _beat_during_jobs(self, stop: threading.Event) -> None:
        """Keep heartbeating while the loop is inside a long handler (the loop beats otherwise)."""
        while not stop.wait(self.heartbeat_s / 2):
            if not self._in_handler or time.monotonic() < self._last_sent + self.heartbeat_s:
                continue
            if self._lock.acquire(timeout=self.heartbeat_s / 4):
                try:
                    if self._in_handler and self._socket is not None:
                        self._send(_HEARTBEAT)
                finally:
                    self._lock.release()


def _error_text(body: object) -> str:
    try:
        err = msgspec.msgpack.decode(cast(bytes, body), type=ErrorReply)
    except wire.DECODE_ERRORS as exc:
        return f"(undecodable: {exc})"
    return f"{err.code} {err.message}"


def serve(
    service: str,
    handler: Handler,
    connect: str,
    *,
    heartbeat_s: float | None = None,
    capacity: int | None = None,
    context: zmq.Context | None = None,
) -> None:
    """Serve ``service`` until SIGTERM or SIGINT (then finish the current job, DISCONNECT and return).

    ``heartbeat_s`` defaults to the environment variable ``WANA_BUS_HEARTBEAT_S`` or 1.0 s; it must
    match the broker's. ``capacity`` (see Worker) defaults to ``WANA_BUS_CAPACITY`` or
    ``DEFAULT_CAPACITY``.
    """
    if heartbeat_s is None:
        heartbeat_s = float(os.environ.get("WANA_BUS_HEARTBEAT_S", "1.0"))
    if capacity is None:
        capacity = int(os.environ.get("WANA_BUS_CAPACITY", str(DEFAULT_CAPACITY)))
    stop = threading.Event()
    previous = {}
    if threading.current_thread() is threading.main_thread():
        for sig in (signal.SIGTERM, signal.SIGINT):
            previous[sig] = signal.signal(sig, lambda *_: stop.set())
    try:
        log.info("%s worker (pid %d) serving via %s", service, os.getpid(), connect)
        Worker(service, handler, connect, heartbeat_s=heartbeat_s, capacity=capacity, context=context).run(
            stop
        )
    finally:
        for sig, old in previous.items():
            signal.signal(sig, old)
