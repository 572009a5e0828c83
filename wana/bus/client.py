"""The client API the orchestrator (and tests) use to send jobs through the broker.

One DEALER socket with a fixed routing id, so the broker can answer across reconnects. Several jobs
may be in flight at once (``submit`` + ``wait``); ``request`` is the one-job shortcut.

While jobs are pending the client pings the broker every ``heartbeat_s``; the PONG carries the
broker's instance id. When that id changes (the broker restarted and lost its memory) or the broker
answers again after a silence, every pending job is sent again with the same job id, and the broker
ignores a job id it already holds, so pending work completes exactly once.

Not thread-safe: use one Client per thread (ZeroMQ sockets must not be shared between threads).
"""

from __future__ import annotations

import hashlib
import logging
import os
import time
import uuid
from collections.abc import Iterable, Sequence
from typing import Any, Literal

import msgspec
import zmq

import wana
from proto.bus import (
    MAX_BATCH,
    BatchFrame,
    BrokerStats,
    ErrorFrame,
    PingFrame,
    PongFrame,
    ReplyFrame,
    RequestFrame,
    StatsFrame,
)
from proto.common import ERROR_CODES, ErrorCode, ErrorReply
from wana.bus import curve, wire

log = logging.getLogger(__name__)

_TICK_S = 0.05
_STATS = wire.encoder.encode(StatsFrame())


class BusError(Exception):
    """A bus-level failure of one job: busy, deadline, attempts exhausted, oversize, unknown service.

    Attributes:
        code: key of proto.common.ERROR_CODES, e.g. "E005".
        message: human-readable detail.
        retryable: True when sending the same job later may succeed (busy).
    """

    def __init__(self, code: str, message: str, retryable: bool = False):
        super().__init__(f"{code} {ERROR_CODES.get(code, 'error')}: {message}")
        self.code = code
        self.message = message
        self.retryable = retryable


class _Pending:
    __slots__ = ("request", "payload", "local_deadline", "sent_to", "ping_before")

    def __init__(
        self,
        request: RequestFrame,
        payload: bytes,
        local_deadline: float,
        sent_to: str | None,
        ping_before: int,
    ):
        self.request = request
        self.payload = payload
        self.local_deadline = local_deadline
        self.sent_to = sent_to  # broker instance id when last sent (None: not known yet)
        self.ping_before = ping_before  # sequence number of the last PING sent before the job


_KEY_PREFIXES: dict[tuple[str, str], Any] = {}  # (service, version) -> hasher fed with both


def idempotency_key(service: str, payload: bytes, version: str = wana.__version__) -> str:
    """Default idempotency key: a hash of the service, the code version and the payload (32 hex chars).

    SHA-256 (hardware-accelerated on current CPUs, faster than BLAKE2b here) over
    ``service NUL version NUL payload``, truncated to 128 bits.
    """
    prefix = _KEY_PREFIXES.get((service, version))
    if prefix is None:
        if len(_KEY_PREFIXES) > 1024:
            _KEY_PREFIXES.clear()
        prefix = _KEY_PREFIXES[service, version] = hashlib.sha256(
            service.encode() + b"\0" + version.encode() + b"\0"
        )
    h = prefix.copy()
    h.update(payload)
    return h.hexdigest()[:32]


_default_key = idempotency_key  # submit's parameter of the same name hides the function there


class Client:
    """Send jobs to services through the broker at ``connect``.

    Args:
        connect: broker URL (``inproc://`` needs the broker's context, passed as ``context``).
        heartbeat_s: ping interval while jobs are pending; should match the broker's heartbeat.
        liveness: missed pongs after which the broker is presumed gone (jobs re-sent when it answers).
        keys: key directory (see wana/bus/curve.py) for a ``tcp://`` broker; default
            ``$WANA_BUS_KEYS``. The client then talks CURVE with its ``client`` pair.
        context: ZeroMQ context; defaults to the process-wide one.
    """

    def __init__(
        self,
        connect: str,
        *,
        heartbeat_s: float = 1.0,
        liveness: int = 3,
        keys: str | os.PathLike[str] | None = None,
        context: zmq.Context | None = None,
    ):
        self.connect = connect
        self.heartbeat_s = float(heartbeat_s)
        self.liveness = int(liveness)
        self._context = context or zmq.Context.instance()
        self._socket = self._context.socket(zmq.DEALER)
        self._socket.setsockopt(zmq.LINGER, 0)
        self._socket.setsockopt(zmq.ROUTING_ID, b"C" + uuid.uuid4().hex.encode())
        self._socket.setsockopt(zmq.SNDHWM, 0)
        self._socket.setsockopt(zmq.RCVHWM, wire.RCVHWM)
        root = curve.keys_dir(keys) if connect.startswith("tcp://") else None
        if root is not None:
            curve.connect_curve(self._socket, root, "client")
        self._socket.connect(connect)
        self._monitor = wire.watch_disconnects(self._socket)  # a dropped connection: re-send (_pump)
        self._prefix = uuid.uuid4().hex[:12]
        self._counter = 0
        self._pending: dict[str, _Pending] = {}
        self._results: dict[str, bytes | BusError] = {}
        self._stats: BrokerStats | None = None
        # Any: they decode zmq.Frame objects, which pyzmq's stubs do not declare as buffers.
        self._error_decoder: Any = msgspec.msgpack.Decoder(ErrorReply)
        self._stats_decoder: Any = msgspec.msgpack.Decoder(BrokerStats)
        self.broker_instance: str | None = None
        self.broker_max_frame = 0  # the broker's payload cap, from its PONG (0: not known yet)
        self._unanswered_since: float | None = None  # first PING sent since the last PONG
        self._last_ping = 0.0
        self._next_check = 0.0  # pings and local deadlines are checked at most every _TICK_S
        self._broker_lost = False
        self._ping_seq = 0
        self.resent = 0
        self._failures = 0
        self._ping()

    # -------------------------------------------------------------------------------- public API

    def submit(
        self,
        service: str,
        payload: bytes,
        *,
        idempotency_key: str | None = None,
        deadline_s: float = 30.0,
        doc_id: str = "",
        revision: int = 0,
    ) -> str:
        """Send one job and return its job id at once; collect the reply with ``wait`` or ``result``.

        Args:
            service: service name, e.g. "nlp".
            payload: request payload, normally a msgpack-encoded request struct.
            idempotency_key: hash of the inputs and the code/model version; computed from the
                payload and wana's version when None.
            deadline_s: seconds the job may take, queueing included; then it fails with E006.
            doc_id, revision: document and revision the job is computed for.
        """
        if deadline_s <= 0:
            raise ValueError("deadline_s must be positive")
        self._check_size(payload)
        pending = self._pending_job(service, payload, idempotency_key, deadline_s, doc_id, revision)
        if not self._send((wire.encoder.encode(pending.request), pending.payload)):
            pending.sent_to = ""  # not delivered: the next PONG from any broker re-sends it
        return pending.request.job_id

    def submit_many(
        self,
        service: str,
        payloads: Sequence[bytes],
        *,
        deadline_s: float = 30.0,
        doc_id: str = "",
        revision: int = 0,
    ) -> list[str]:
        """Send several jobs for one service in as few messages as possible; their job ids, in order.

        Each payload is its own job (own job id, default idempotency key, deadline, retries),
        exactly as ``submit`` sends it; up to ``proto.bus.MAX_BATCH`` of them travel in one BATCH
        message, which saves the broker and this client most of the per-message cost when many
        short jobs go out at once. Collect the replies with ``wait`` or ``collect``.
        """
        if deadline_s <= 0:
            raise ValueError("deadline_s must be positive")
        bad = [i for i, p in enumerate(payloads) if not isinstance(p, (bytes, bytearray, memoryview))]
        if bad:  # checked before any job is registered: nothing half-sent
            raise TypeError(f"payloads must be bytes; item {bad[0]} is {type(payloads[bad[0]]).__name__}")
        for p in payloads:
            self._check_size(p)
        jobs = [self._pending_job(service, p, None, deadline_s, doc_id, revision) for p in payloads]
        encode = wire.encoder.encode
        for start in range(0, len(jobs), MAX_BATCH):
            chunk = jobs[start : start + MAX_BATCH]
            pairs: list[object] = []
            for pending in chunk:
                pairs.append(encode(pending.request))
                pairs.append(pending.payload)
            try:
                wire.send_pairs(self._socket, (), pairs)
            except zmq.Again:  # no broker connected at all: the next PONG re-sends them
                for pending in chunk:
                    pending.sent_to = ""
        return [pending.request.job_id for pending in jobs]

    def _check_size(self, payload: object) -> None:
        """Refuse a payload over the broker's cap here: ZeroMQ would cut the connection, unanswered.

        Raises:
            BusError: E002 when the broker's PONG announced a cap and the payload exceeds it.
        """
        cap = self.broker_max_frame
        if cap and isinstance(payload, (bytes, bytearray, memoryview)) and len(payload) > cap:
            raise BusError(
                ErrorCode.TOO_LARGE, f"payload of {len(payload)} bytes exceeds the broker's {cap}-byte cap"
            )

    def _pending_job(
        self,
        service: str,
        payload: bytes,
        idempotency_key: str | None,
        deadline_s: float,
        doc_id: str,
        revision: int,
    ) -> _Pending:
        """Register one job as pending (not sent yet) and return it."""
        if not self._pending:  # a drop while idle concerns no job (while busy, _pump looks every tick)
            self._connection_dropped()
        if not isinstance(payload, (bytes, bytearray, memoryview)):
            raise TypeError(f"payload must be bytes, not {type(payload).__name__}")
        self._counter += 1
        job_id = f"{self._prefix}-{self._counter}"
        payload = bytes(payload)  # no copy when it is bytes already
        key = idempotency_key if idempotency_key is not None else _default_key(service, payload)
        request = RequestFrame(service, job_id, key, 0, int(deadline_s * 1000), doc_id, revision)
        local_deadline = time.monotonic() + deadline_s + self.heartbeat_s * self.liveness
        pending = _Pending(request, payload, local_deadline, self.broker_instance, self._ping_seq)
        self._pending[job_id] = pending
        return pending

    def wait(
        self,
        job_ids: Iterable[str],
        timeout: float | None = None,
        *,
        return_when: Literal["all", "any"] = "all",
    ) -> dict[str, bytes | BusError]:
        """Wait for jobs; return ``{job_id: reply payload or BusError}`` for those finished.

        Returns when all (or, with ``return_when="any"``, at least one) of ``job_ids`` finished or
        after ``timeout`` seconds (None: until each job's deadline). Finished results are handed
        over once: a later ``wait`` for the same id does not return it again.
        """
        wanted = list(dict.fromkeys(job_ids))
        unknown = [j for j in wanted if j not in self._pending and j not in self._results]
        if unknown:
            raise KeyError(f"unknown or already collected job ids: {unknown[:5]}")
        end = None if timeout is None else time.monotonic() + timeout
        need = len(wanted) if return_when == "all" else min(1, len(wanted))
        until = wanted[0] if len(wanted) == 1 else None
        results = self._results
        wanted_set = set(wanted)
        while not (
            results.keys() >= wanted_set
            if need == len(wanted)
            else sum(1 for j in wanted if j in results) >= need
        ):
            now = time.monotonic()
            if end is not None and now >= end:
                break
            step = _TICK_S if end is None else max(0.0, min(_TICK_S, end - now))
            self._pump(step, until)
        return {j: self._results.pop(j) for j in wanted if j in self._results}

    def collect(self, timeout: float = 0.0) -> dict[str, bytes | BusError]:
        """Every result that has arrived, waiting up to ``timeout`` seconds for at least one (as completed)."""
        if not self._results and self._pending:
            end = time.monotonic() + timeout
            while True:
                self._pump(max(0.0, min(_TICK_S, end - time.monotonic())))
                if self._results or not self._pending or time.monotonic() >= end:
                    break
        out, self._results = self._results, {}
        return out

    def result(self, job_id: str, timeout: float | None = None) -> bytes:
        """The reply payload of one job; raises BusError on a bus-level error, TimeoutError on timeout."""
        got = self.wait([job_id], timeout)
        if job_id not in got:
            raise TimeoutError(f"job {job_id} not finished after {timeout} s")
        out = got[job_id]
        if isinstance(out, BusError):
            raise out
        return out

    def request(
        self,
        service: str,
        payload: bytes,
        *,
        idempotency_key: str | None = None,
        deadline_s: float = 30.0,
        doc_id: str = "",
        revision: int = 0,
    ) -> bytes:
        """Send one job and return its reply payload (which may encode a service's ErrorReply).

        Raises:
            BusError: bus-level failure (E002 oversize, E003 unknown service, E005 busy, E006
                deadline, E007 attempts exhausted).
        """
        job_id = self.submit(
            service,
            payload,
            idempotency_key=idempotency_key,
            deadline_s=deadline_s,
            doc_id=doc_id,
            revision=revision,
        )
        return self.result(job_id)

    def cancel(self, job_ids: Iterable[str]) -> None:
        """Stop waiting for jobs (e.g. of a superseded revision); their replies will be dropped."""
        for j in job_ids:
            self._pending.pop(j, None)
            self._results.pop(j, None)

    @property
    def pending(self) -> int:
        """Jobs sent and not answered yet."""
        return len(self._pending)

    def stats(self, timeout: float = 5.0) -> BrokerStats:
        """Ask the broker for its queue depths, workers and counters."""
        self._stats = None
        self._send((_STATS,))
        end = time.monotonic() + timeout
        while self._stats is None:
            left = end - time.monotonic()
            if left <= 0:
                raise TimeoutError(f"broker at {self.connect} did not answer STATS within {timeout} s")
            self._pump(min(_TICK_S, left))
        return self._stats

    def close(self) -> None:
        """Close the socket; pending jobs are abandoned."""
        if not self._socket.closed:
            wire.close_monitor(self._socket, self._monitor)
            self._socket.close(0)

    def __enter__(self) -> Client:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # --------------------------------------------------------------------------------- internals

    def _send(self, frames: tuple[object, ...]) -> bool:
        try:
            wire.send(self._socket, frames)
            return True
        except zmq.Again:  # no broker connected at all (inproc after it closed): retried on PONG
            return False

    def _connection_dropped(self) -> bool:
        """Whether the connection dropped since the last look; if so, the jobs pending now (what was in
        flight may be lost with it) are re-sent at the next PONG. A job sent after the drop is not."""
        if not wire.dropped(self._monitor):
            return False
        for p in self._pending.values():
            p.sent_to = ""
        return True

    def _ping(self) -> None:
        self._ping_seq += 1
        if self._unanswered_since is None:
            self._unanswered_since = time.monotonic()
        self._send((wire.encoder.encode(PingFrame(self._ping_seq)),))
        self._last_ping = time.monotonic()

    def _pump(self, timeout_s: float, until: str | None = None) -> None:
        """Read what arrives within ``timeout_s`` (stop early once job ``until`` has its result).

        Whatever is already waiting is read without blocking (drained until EAGAIN when the poll
        found a backlog, see wire.py); then pings and local deadlines run.
        """
        sock = self._socket
        poll, recv, monotonic = wire.poll, wire.recv_from_broker, time.monotonic
        on_message = self._on_message
        results = self._results
        timeout = timeout_s
        while True:
            before = monotonic()
            if not poll(sock, timeout):
                break
            draining = monotonic() - before < wire.BACKLOG_S
            got = recv(sock)
            while got is not None:
                try:
                    on_message(got[0], got[1])
                except Exception as exc:  # the per-message guard: a bad message never breaks the client
                    self._failures += 1
                    if self._failures == 1:
                        log.error("bus client: a message from the broker failed (logged once)", exc_info=exc)
                if until is not None and until in results:
                    break
                got = recv(sock) if draining else None
            if got is not None or draining:
                break  # the awaited job is answered, or the backlog was drained until EAGAIN
            timeout = 0.0
        now = monotonic()
        if self._pending and now >= self._next_check:
            self._next_check = now + _TICK_S
            if self._connection_dropped():
                self._ping()
            elif now - self._last_ping >= self.heartbeat_s:
                self._ping()
            if (
                self._unanswered_since is not None
                and now - self._unanswered_since > self.heartbeat_s * self.liveness
            ):
                self._broker_lost = True
            expired = [j for j, p in self._pending.items() if p.local_deadline <= now]
            for j in expired:
                del self._pending[j]
                self._results[j] = BusError(
                    ErrorCode.DEADLINE, f"no answer from the broker at {self.connect} before the deadline"
                )

    def _on_message(self, msg: Any, body: Any) -> None:
        """Handle one message from the broker (``body``: bytes for the commands that carry one)."""
        kind = type(msg)
        if kind is ReplyFrame:
            if self._pending.pop(msg.job_id, None) is not None:  # else: a duplicate or a cancelled job
                self._results[msg.job_id] = body
        elif kind is ErrorFrame:
            if self._pending.pop(msg.job_id, None) is not None:
                try:
                    err = self._error_decoder.decode(body)
                    self._results[msg.job_id] = BusError(err.code, err.message, err.retryable)
                except wire.DECODE_ERRORS as exc:
                    self._results[msg.job_id] = BusError(
                        ErrorCode.MALFORMED, f"undecodable error reply from the broker: {exc}"
                    )
        elif kind is BatchFrame:
            for item, item_body in body:
                if type(item) is not BatchFrame:  # a BATCH holds single messages only
                    self._on_message(item, item_body)
        elif kind is PongFrame:
            self.broker_max_frame = msg.max_frame
            self._on_pong(msg.instance, msg.seq)
        elif kind is StatsFrame:
            self._stats = self._stats_decoder.decode(body)

    def _on_pong(self, instance: str, seq: int) -> None:
        """Re-send the pending jobs this broker instance may not hold (see the module docstring)."""
        self._unanswered_since = None
        resend_all, self._broker_lost = self._broker_lost, False
        self.broker_instance = instance
        for p in self._pending.values():
            if p.sent_to == instance and not resend_all:
                continue
            if p.sent_to is None and seq <= p.ping_before and not resend_all:
                p.sent_to = instance  # the broker answered a PING sent before the job: it has the job
                continue
            left_ms = int((p.local_deadline - self.heartbeat_s * self.liveness - time.monotonic()) * 1000)
            if left_ms <= 0:
                continue
            p.request = msgspec.structs.replace(p.request, deadline_ms=left_ms)
            p.sent_to = instance if self._send((wire.encoder.encode(p.request), p.payload)) else ""
            self.resent += 1
