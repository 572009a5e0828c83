"""The broker: one ROUTER socket that routes jobs by service name to registered workers (Majordomo).

Rules (proto/PROTOCOL.md is the authoritative description):

- Workers send READY with their service name; idle workers are kept per service in least-recently-used
  order, and a job goes to the worker that has waited longest. A worker announcing ``capacity`` > 1
  may be handed further jobs, but only when no worker of its service is idle and only while its jobs
  are short (its last one took, and its current one has run, less than 50 ms, and those it holds
  would take less than 50 ms at that pace).
- JOB, REPLY and ERROR messages go to an outbox per peer while a backlog is handled and are sent
  before the loop waits again (or after ``_FLUSH_EVERY`` messages): several for one peer travel as
  one BATCH. A BATCH that arrives is handled pair by pair, as if each had come alone.
- Heartbeats both ways every ``heartbeat_s``; a worker silent for ``liveness`` intervals is dead. Its
  jobs are re-queued at the front of their service queue with the attempt count raised; a job dispatched
  ``max_attempts`` times whose worker died each time gets an E007 error reply.
- Requests and replies are deduplicated by job id: a request whose job is already queued or in flight
  is ignored, the first reply to a job wins and later ones are dropped. Recent answers are kept, so a
  client that re-sends a job after its connection dropped (the answer may have been lost in flight)
  gets the answer again.
- Each service queue holds at most ``queue_limit`` waiting jobs; beyond that the client gets E005 busy.
- A payload over ``max_frame`` bytes gets E002; frames over twice that are refused by ZeroMQ itself
  (the connection is dropped) so that no peer can exhaust the broker's memory.
- Every job has a deadline (clamped to ``MAX_DEADLINE_MS``, a day); when it passes the client gets
  E006, or E003 when no worker for the service is registered at all (a request for an unknown
  service waits for a worker until then).
- No frame crashes the loop: each message is handled inside a guard; one that does not decode or
  validate gets E001 with the reason, any other failure is logged (once per kind) and answered
  E009, and the loop goes on. A READY of another protocol major version gets E012.
- Memory is bounded by bytes, not only by job count: the payloads the broker holds share one
  budget (``max_queued_bytes``; over it E005), each client may hold ``max_client_jobs`` jobs,
  service names are at most 64 characters, at most ``max_unserved`` services without a worker
  exist at once, and a service with neither workers nor jobs is forgotten.
- A REPLY is accepted only from a worker the job was dispatched to; a REQUEST whose job id another
  peer holds gets E010 and never re-points the job; STATS shows no job ids (only digests).

The broker keeps everything in memory: after a restart, workers re-register and clients re-send
their pending jobs (see wana/bus/client.py), so pending work completes.

This module runs to about 500 lines because every rule above acts on the same state from one
event loop; splitting the rules apart would hide how they interact. The plain bookkeeping classes
live in wana/bus/broker_state.py.
"""

from __future__ import annotations

import collections
import hashlib
import logging
import threading
import time
import uuid
from collections.abc import Iterable
from pathlib import Path

import msgspec
import zmq

from proto.bus import (
    MAX_BATCH,
    MAX_DEADLINE_MS,
    PROTOCOL_VERSION,
    BatchFrame,
    BrokerStats,
    DisconnectFrame,
    ErrorFrame,
    HeartbeatFrame,
    JobFrame,
    PingFrame,
    PongFrame,
    ReadyFrame,
    ReplyFrame,
    RequestFrame,
    StatsFrame,
)
from proto.common import ERROR_CODES, ErrorCode, ErrorReply, Header
from wana.bus import curve, wire
from wana.bus.broker_state import Job, Service, WorkerEntry, broker_stats

log = logging.getLogger(__name__)

_TICK_S = 0.05  # longest sleep of the event loop: bounds deadline precision and stop latency
_DONE_MEMORY = 65536  # job ids remembered after their reply, to drop duplicates
# Replies kept after they were sent, for a client that asks again: a reply ZeroMQ accepted can still be lost
# with its connection (a reset drops what was in flight), and the client then re-sends its pending jobs.
_UNDELIVERED_MEMORY = 4096
_MAX_SERVICES = 1024  # distinct service names the broker will track
_PREFETCH_MAX_JOB_S = 0.05  # prefetch only while a worker's jobs take less than this (see _next_worker)
_HEARTBEAT = wire.encoder.encode(HeartbeatFrame())
_DISCONNECT = wire.encoder.encode(DisconnectFrame())
_STATS = wire.encoder.encode(StatsFrame())
_FLUSH_EVERY = 8  # messages handled in a backlog before the outbox is sent (bounds the added latency)
_UNDELIVERED_BYTES = 64 * 1024 * 1024  # reply bytes kept for unreachable clients
_SERVICE_TTL_S = 30.0  # a service with neither workers nor jobs is forgotten after this


class Broker:
    """A Majordomo-style broker on one ROUTER socket bound to one or more URLs.

    Args:
        bind: URL or URLs to bind (``inproc://name``, ``ipc:///path``, ``tcp://127.0.0.1:5555``;
            ``tcp://127.0.0.1:*`` picks a free port, see ``endpoints``).
        heartbeat_s: heartbeat interval in seconds, both directions.
        liveness: heartbeats a worker may miss before it is declared dead.
        queue_limit: jobs that may wait per service before new ones get E005 busy.
        max_frame: largest request or reply payload in bytes; larger ones get E002.
        max_attempts: dispatches of one job before its worker's death turns into E007.
        max_queued_bytes: payload bytes of all jobs the broker holds (queued or in flight) before
            new ones get E005 busy; jobs for services without a worker may hold a quarter of it.
        max_client_jobs: jobs one client may have in the broker at once before new ones get E005.
        max_unserved: services without a registered worker that requests may create (more: E003).
        keys: key directory (``wana keys new DIR``, see wana/bus/curve.py): the socket becomes a
            CURVE server admitting only the allow lists' keys, and each command is checked against
            the sender's role. Without keys, binding a non-loopback TCP endpoint raises
            ``curve.InsecureBind``.
        insecure: bind a non-loopback endpoint without keys anyway (logs a warning).
        context: ZeroMQ context; pass the shared one to use ``inproc://``. With keys and no context
            the broker uses a context of its own (ZAP handlers are one per context).

    Not thread-safe: after ``start_thread()`` only ``close()`` (and ``endpoints``) may be used from
    other threads.
    """

    def __init__(
        self,
        bind: str | Iterable[str],
        *,
        heartbeat_s: float = 1.0,
        liveness: int = 3,
        queue_limit: int = 256,
        max_frame: int = 32 * 1024 * 1024,
        max_attempts: int = 3,
        max_queued_bytes: int = 128 * 1024 * 1024,
        max_client_jobs: int = 4096,
        max_unserved: int = 64,
        keys: str | Path | None = None,
        insecure: bool = False,
        context: zmq.Context | None = None,
    ):
        if heartbeat_s <= 0 or liveness < 1 or queue_limit < 1 or max_frame < 1 or max_attempts < 1:
            raise ValueError(
                "heartbeat_s, liveness, queue_limit, max_frame and max_attempts must be positive"
            )
        self.heartbeat_s = float(heartbeat_s)
        self.liveness = int(liveness)
        self.queue_limit = int(queue_limit)
        self.max_frame = int(max_frame)
        self.max_attempts = int(max_attempts)
        self.max_queued_bytes = int(max_queued_bytes)
        self.max_client_jobs = int(max_client_jobs)
        self.max_unserved = int(max_unserved)
        self.queued_bytes = 0  # payload bytes of the jobs in self._jobs
        self._client_jobs: collections.Counter[bytes] = collections.Counter()
        self._failures: collections.Counter[str] = collections.Counter()  # guard catches, by kind
        self._undelivered_bytes = 0
        self.instance = uuid.uuid4().hex[:16]
        root = None if keys is None else Path(keys)
        urls = [bind] if isinstance(bind, str) else list(bind)
        for url in urls:
            curve.check_bind(url, secure=root is not None, insecure=insecure)
        self._own_context = context is None and root is not None
        self._context = context or (zmq.Context() if root is not None else zmq.Context.instance())
        self._socket = self._context.socket(zmq.ROUTER)
        self._auth = None
        self._allow: curve.AllowList | None = None
        self._sender_key = ""  # the current message's sender public key (Z85), with keys
        self._peer_keys: collections.OrderedDict[bytes, str] = collections.OrderedDict()  # with keys
        if root is not None:
            self._auth, self._allow = curve.serve_curve(self._socket, self._context, root)
        self._socket.setsockopt(zmq.LINGER, 0)
        self._socket.setsockopt(zmq.ROUTER_MANDATORY, 1)  # learn at once when a peer is gone
        # A reconnecting client keeps its routing id. With keys, an id stays with the connection that
        # first used it instead: a second peer presenting it (to take over another's replies) is
        # refused by ZeroMQ, not handed over; a client that really reconnected gets its id back once
        # its old connection is gone, and re-sends its jobs (PONG).
        self._socket.setsockopt(zmq.ROUTER_HANDOVER, 0 if root is not None else 1)
        self._socket.setsockopt(zmq.SNDHWM, 0)  # queues are bounded by queue_limit, not by dropping
        self._socket.setsockopt(zmq.RCVHWM, wire.RCVHWM)  # a flooding peer waits (wire.RCVHWM)
        self._socket.setsockopt(zmq.MAXMSGSIZE, 2 * self.max_frame + 4096)
        self.endpoints: list[str] = []
        if not urls:
            raise ValueError("Broker needs at least one URL to bind")
        try:
            for url in urls:
                self._socket.bind(url)
                self.endpoints.append(self._socket.getsockopt_string(zmq.LAST_ENDPOINT))
        except zmq.ZMQError:
            self._socket.close(0)
            self._stop_auth()
            raise
        self._services: dict[str, Service] = {}
        self._workers: dict[bytes, WorkerEntry] = {}
        self._jobs: dict[str, Job] = {}
        self._done: dict[str, bytes] = {}  # answered job id -> the client that sent it
        self._undelivered: collections.OrderedDict[str, tuple[bytes, tuple]] = collections.OrderedDict()
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._closed = False
        self.completed = 0
        self.requeued = 0
        self.duplicate_replies = 0
        self.duplicate_requests = 0
        self.refused_replies = 0
        self.errors: collections.Counter[str] = collections.Counter()
        self._worker_ttl = self.heartbeat_s * self.liveness
        self._now = time.monotonic()  # read once per message by the loop (run)
        # Outbox: JOB, REPLY and ERROR pairs per peer, sent by _flush (one BATCH per peer when several
        # pile up while a backlog is handled); the job id of each pair, for when the peer is gone.
        self._out: dict[bytes, list] = {}
        self._out_jobs: dict[bytes, list[str]] = {}

    # ----------------------------------------------------------------------------------- lifetime

    def run(self, stop: threading.Event | None = None) -> None:
        """Serve until ``stop`` (or the broker's own stop event, set by ``close()``) is set."""
        stopped = self._stop.is_set if stop is None else (lambda: stop.is_set() or self._stop.is_set())
        sock = self._socket
        recv = wire.recv
        poll = wire.poll
        on_message = self._on_message
        monotonic = time.monotonic
        now = self._now = monotonic()
        next_heartbeat = now + self.heartbeat_s
        next_tick = now
        draining, backlog_s = False, wire.BACKLOG_S
        handled = 0
        while True:
            if now >= next_tick:
                if stopped():
                    self._flush()
                    return
                try:
                    if now >= next_heartbeat:
                        self._heartbeat(now)
                        next_heartbeat = now + self.heartbeat_s
                    self._expire_jobs(now)
                except Exception as exc:  # a bug in a timer must not stop the bus either
                    self._log_failure("timers", exc)
                next_tick = min(now + _TICK_S, next_heartbeat)
            # Drain with plain receives while a backlog lasts, else poll first (see wire.py).
            frames = recv(sock) if draining else None
            if frames is None:
                if self._out:
                    self._flush()
                handled = 0
                before = monotonic()
                readable = poll(sock, next_tick - before)
                now = self._now = monotonic()  # the one clock reading each message's handling uses
                draining = now - before < backlog_s
                if not readable:
                    continue
                frames = recv(sock)
                if frames is None:
                    continue
            else:
                now = self._now = monotonic()
            try:
                on_message(frames)
            except Exception as exc:  # the per-message guard: answer E009, keep serving
                self._on_failure(frames[0], exc)
            handled += 1
            if handled >= _FLUSH_EVERY and self._out:
                self._flush()
                handled = 0

    def start_thread(self) -> threading.Thread:
        """Run the broker in a daemon thread; ``close()`` stops it."""
        if self._thread is not None:
            raise RuntimeError("broker already started")
        self._thread = threading.Thread(target=self.run, name="wana-broker", daemon=True)
        self._thread.start()
        return self._thread

    def close(self) -> None:
        """Stop the loop (waiting for its thread if ``start_thread`` was used) and close the socket."""
        if self._closed:
            return
        self._stop.set()
        if self._thread is not None and self._thread is not threading.current_thread():
            self._thread.join(timeout=5.0)

        self._closed = True
        self._socket.close(0)
        self._stop_auth()

    def _stop_auth(self) -> None:
        if self._auth is not None:
            self._auth.stop()
            self._auth = None
        if self._own_context:
            self._context.term()
            self._own_context = False

    def __enter__(self) -> Broker:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # ------------------------------------------------------------------------------------ inbound

    def _log_failure(self, where: str, exc: Exception) -> None:
        """Log a failure with its traceback the first time its kind is seen, then only count it."""
        kind = f"{where}:{type(exc).__name__}"
        self._failures[kind] += 1
        if self._failures[kind] == 1:
            log.error("broker: %s failed (logged once per kind)", where, exc_info=exc)
        else:
            log.debug("broker: %s failed again: %s", where, exc)

    def _on_failure(self, sender: bytes, exc: Exception) -> None:
        self._log_failure("a message handler", exc)
        try:
            self._client_error(
                sender,
                "",
                ErrorCode.HANDLER_FAILED,
                f"the broker failed on this message: {type(exc).__name__}",
            )
        except Exception as again:  # pragma: no cover - even the answer failed: only log
            self._log_failure("an E009 answer", again)

    def _on_message(self, frames: list) -> None:
        """Handle one message: ``[routing id (bytes), envelope Frame, body Frames...]``."""
        sender = frames[0]  # wire.recv always returns the routing id and at least one frame
        try:
            msg = wire.envelope_decoder.decode(frames[1])
        except wire.DECODE_ERRORS as exc:
            self._client_error(
                sender, _job_id_of(frames[1]), ErrorCode.MALFORMED, f"undecodable envelope: {exc}"
            )
            return
        kind = type(msg)
        if self._allow is not None:  # ZAP put the sender's public key on each frame
            self._sender_key = frames[1].get("User-Id") or ""
            if not self._key_matches(sender, self._sender_key):
                self._client_error(
                    sender, "", ErrorCode.UNAUTHORISED, "this routing id belongs to another key"
                )
                return
        if kind is RequestFrame:
            if len(frames) != 3:
                self._client_error(
                    sender,
                    msg.job_id,
                    ErrorCode.MALFORMED,
                    f"REQUEST needs 1 body frame, got {len(frames) - 2}",
                )
                return
            self._on_request(sender, msg, frames[2])
            return
        if kind is BatchFrame:
            self._on_batch(sender, msg.count, frames)
            return
        worker = self._workers.get(sender)
        if worker is not None:
            worker.expiry = self._now + self._worker_ttl
        if kind is ReplyFrame:
            if len(frames) != 3:
                log.warning("dropped a REPLY with %d body frames from %r", len(frames) - 2, sender)
                return
            self._on_reply(sender, worker, msg.job_id, frames, 1)
        elif kind is HeartbeatFrame:
            if worker is None:
                self._send(sender, _DISCONNECT)
        elif kind is PingFrame:
            self._send(sender, wire.encoder.encode(PongFrame(self.instance, msg.seq, self.max_frame)))
        elif kind is ReadyFrame:
            self._on_ready(sender, worker, msg)
        elif kind is DisconnectFrame:
            if worker is not None:
                self._remove_worker(worker, "it disconnected")
        elif kind is StatsFrame:
            if self._allow is not None and not self._allow.is_client(self._sender_key):
                self._client_error(sender, "", ErrorCode.UNAUTHORISED, "STATS is for authorised clients only")
                return
            self._send(sender, _STATS, wire.encoder.encode(self.stats(job_ids=False)))
        else:
            why = f"{kind.__name__} is not a command the broker answers"
            self._client_error(sender, getattr(msg, "job_id", ""), ErrorCode.MALFORMED, why)

    def _key_matches(self, sender: bytes, key: str) -> bool:
        """With keys: a routing id is bound to the key that first used it (the last 65,536 ids)."""
        known = self._peer_keys.get(sender)
        if known is None:
            self._peer_keys[sender] = key
            if len(self._peer_keys) > _DONE_MEMORY:
                self._peer_keys.popitem(last=False)
            return True
        if known != key:
            log.warning("refused a message from %r: its routing id belongs to another key", sender)
            return False
        return True

    def _on_batch(self, sender: bytes, count: int, frames: list) -> None:
        """A BATCH of REQUESTs (from a client) or REPLYs (from a worker): each handled as if alone."""
        if not 1 <= count <= MAX_BATCH or len(frames) != 2 + 2 * count:
            why = f"BATCH of {count} needs {2 * count} frames after it (at most {2 * MAX_BATCH}), got {len(frames) - 2}"
            self._client_error(sender, "", ErrorCode.MALFORMED, why)
            return
        worker = self._workers.get(sender)
        if worker is not None:
            worker.expiry = self._now + self._worker_ttl
        decode = wire.envelope_decoder.decode
        for i in range(2, len(frames), 2):
            try:
                msg = decode(frames[i])
            except wire.DECODE_ERRORS as exc:
                why = f"undecodable envelope in a BATCH: {exc}"
                self._client_error(sender, _job_id_of(frames[i]), ErrorCode.MALFORMED, why)
                continue
            kind = type(msg)
            if kind is RequestFrame:
                self._on_request(sender, msg, frames[i + 1])
            elif kind is ReplyFrame:
                self._on_reply(sender, worker, msg.job_id, frames[i : i + 2], 0)
            else:  # a nested BATCH, or a command that never travels in one: answered, not dropped
                why = f"a {kind.__name__} in a BATCH: only REQUEST and REPLY may travel in one"
                self._client_error(sender, getattr(msg, "job_id", ""), ErrorCode.MALFORMED, why)

    def _on_request(self, client: bytes, request: RequestFrame, payload: zmq.Frame) -> None:
        job_id = request.job_id
        if self._allow is not None and not self._allow.is_client(self._sender_key):
            why = "this peer's key is not in the clients' allow list"
            self._client_error(client, job_id, ErrorCode.UNAUTHORISED, why, request.doc_id, request.revision)
            return
        job = self._jobs.get(job_id)
        owner = job.client if job is not None else self._done.get(job_id)
        if owner is not None and owner != client:  # never re-point a job to another peer
            why = f"job id {job_id!r} is already used by another peer"
            self._client_error(client, job_id, ErrorCode.UNAUTHORISED, why, request.doc_id, request.revision)
            return
        if job is not None:  # the same client again (e.g. after a broker silence): it gets the reply
            self.duplicate_requests += 1
            return
        if owner is not None:
            self.duplicate_requests += 1
            kept = self._undelivered.get(job_id)
            if kept is not None and kept[0] == client:  # kept until the bounds push it out
                self._send(client, *kept[1])
            else:
                why = f"job {job_id!r} was answered already"
                self._client_error(
                    client, job_id, ErrorCode.INVALID_INPUT, why, request.doc_id, request.revision
                )
            return
        if len(payload) > self.max_frame:
            why = f"payload of {len(payload)} bytes exceeds the {self.max_frame}-byte cap"
            self._client_error(client, job_id, ErrorCode.TOO_LARGE, why, request.doc_id, request.revision)
            return
        if request.deadline_ms <= 0:
            why = "the request arrived after its deadline"
            self._client_error(client, job_id, ErrorCode.DEADLINE, why, request.doc_id, request.revision)
            return
        if request.deadline_ms > MAX_DEADLINE_MS:
            request = msgspec.structs.replace(request, deadline_ms=MAX_DEADLINE_MS)
        svc = self._services.get(request.service)
        if svc is None:
            unserved = sum(1 for known in self._services.values() if not known.workers)
            if len(self._services) >= _MAX_SERVICES or unserved >= self.max_unserved:
                why = f"unknown service {request.service!r} (and {unserved} services have no worker)"
                self._client_error(
                    client, job_id, ErrorCode.UNKNOWN_SERVICE, why, request.doc_id, request.revision
                )
                return
            svc = self._services[request.service] = Service(request.service)
        busy = None
        if len(svc.queue) >= self.queue_limit:
            busy = f"service {request.service!r} has {len(svc.queue)} jobs waiting"
        elif self.queued_bytes + len(payload) > self.max_queued_bytes:
            busy = f"the broker holds {self.queued_bytes} payload bytes (budget {self.max_queued_bytes})"
        elif not svc.workers and (
            sum(known.held_bytes for known in self._services.values() if not known.workers) + len(payload)
            > self.max_queued_bytes // 4
        ):  # jobs nobody can run yet may not crowd out those of served services
            busy = f"jobs for services without a worker hold a quarter of the {self.max_queued_bytes}-byte budget"
        elif self._client_jobs[client] >= self.max_client_jobs:
            busy = f"this client has {self._client_jobs[client]} jobs in the broker (limit {self.max_client_jobs})"
        if busy is not None:
            self._client_error(
                client, job_id, ErrorCode.BUSY, busy, request.doc_id, request.revision, retryable=True
            )
            return
        self.queued_bytes += len(payload)
        svc.held_bytes += len(payload)
        self._client_jobs[client] += 1
        self._jobs[job_id] = Job(client, request, payload, self._now)
        svc.queue.append(job_id)
        if svc.idle or svc.prefetching:
            self._dispatch(svc)

    def _on_ready(self, sender: bytes, worker: WorkerEntry | None, ready: ReadyFrame) -> None:
        if ready.protocol != PROTOCOL_VERSION:
            why = f"bus protocol {ready.protocol} is not supported (this broker speaks {PROTOCOL_VERSION})"
            self._client_error(sender, "", ErrorCode.SCHEMA_VERSION, why)
            return
        if self._allow is not None and not self._allow.may_serve(self._sender_key, ready.service):
            log.warning("refused worker %r: its key may not serve %r", sender, ready.service)
            self._client_error(
                sender, "", ErrorCode.UNAUTHORISED, f"this peer's key may not serve {ready.service!r}"
            )
            return
        if worker is not None:  # re-registration: whatever it held is abandoned
            self._remove_worker(worker, "it registered again")
        svc = self._services.get(ready.service)
        if svc is None:
            if len(self._services) >= _MAX_SERVICES:
                log.warning("refused worker %r: too many services", sender)
                self._send(sender, _DISCONNECT)
                return
            svc = self._services[ready.service] = Service(ready.service)
        worker = WorkerEntry(sender, ready, self._now + self._worker_ttl)
        self._workers[sender] = worker
        svc.workers.add(sender)
        svc.idle.append(sender)
        if worker.capacity > 1:
            svc.prefetching += 1
        log.info("worker %r (pid %d) registered for %r", sender, ready.pid, ready.service)
        self._dispatch(svc)

    def _on_reply(
        self, sender: bytes, worker: WorkerEntry | None, job_id: str, frames: list, at: int
    ) -> None:
        """A worker's reply; ``frames[at]`` is its envelope, ``frames[at + 1]`` the body."""
        job = self._jobs.get(job_id)
        if job is None:
            self.duplicate_replies += 1
        elif sender not in job.holders:  # forged: only a worker the job was dispatched to answers it
            self.refused_replies += 1
            log.warning("refused a REPLY for job %r from %r, which never held it", job_id, sender)
            job = None
        else:
            # The first reply wins, even from a worker presumed dead whose job went to another worker;
            # that other worker finishes and its reply is dropped as a duplicate.
            del self._jobs[job_id]
            self._release(job)
            self._remember_done(job_id, job.client)
            body = frames[at + 1]
            if len(body) > self.max_frame:
                why = f"reply of {len(body)} bytes exceeds the {self.max_frame}-byte cap"
                self._client_error(
                    job.client, job_id, ErrorCode.TOO_LARGE, why, job.request.doc_id, job.request.revision
                )
            else:
                self.completed += 1
                served = self._services.get(job.service)
                if served is not None:
                    served.record_reply(self._now - job.arrived)
                self._post(job.client, job_id, frames[at], body)  # the envelope is forwarded as it came
        if worker is None:
            self._send(sender, _DISCONNECT)  # e.g. a worker of the broker before a restart
            return
        if worker.jobs.pop(job_id, 0) is None:  # it held this job (values are None)
            now = self._now
            worker.job_s = now - worker.started
            worker.started = now  # its next job (if it holds one) starts now
            svc = self._services[worker.service]
            if not worker.jobs:
                svc.idle.append(sender)
            if svc.queue:
                self._dispatch(svc)

    def _release(self, job: Job) -> None:
        """Give back the budget a job held (it has left ``self._jobs``)."""
        self.queued_bytes -= len(job.payload)
        svc = self._services.get(job.service)
        if svc is not None:
            svc.held_bytes -= len(job.payload)
        left = self._client_jobs[job.client] - 1
        if left > 0:
            self._client_jobs[job.client] = left
        else:
            del self._client_jobs[job.client]

    def _expire_services(self, now: float) -> None:
        """Forget services that had neither workers nor jobs for ``_SERVICE_TTL_S``.

        Made-up names then leave the table (a request for one still waits out its deadline), and
        a service whose workers left stays visible to STATS readers (autoscalers) for a while.
        """
        for name, svc in list(self._services.items()):
            if svc.workers or svc.queue:
                svc.empty_since = None
            elif svc.empty_since is None:
                svc.empty_since = now
            elif now - svc.empty_since > _SERVICE_TTL_S:
                del self._services[name]

    # ----------------------------------------------------------------------------------- dispatch

    def _next_worker(self, svc: Service) -> WorkerEntry | None:
        """The idle worker that waited longest, else (prefetch) the least loaded one with a free slot.

        A worker is prefetched to only while its jobs are short: the jobs it holds would take less
        than ``_PREFETCH_MAX_JOB_S`` at the pace of its last one, and the one it runs now started
        less than that long ago. Short jobs then travel in batches (throughput), while no job is
        parked behind long ones for more than about that; a worker that has not finished a job
        yet gets none.
        """
        while svc.idle:
            worker = self._workers.get(svc.idle.popleft())
            if worker is not None and not worker.jobs:
                worker.started = self._now
                return worker
        if not svc.prefetching:
            return None
        best = None
        fresh = self._now - _PREFETCH_MAX_JOB_S
        for wid in svc.workers:
            worker = self._workers[wid]
            held = len(worker.jobs)
            if (
                held < worker.capacity
                and max(held, 1) * worker.job_s < _PREFETCH_MAX_JOB_S
                and worker.started >= fresh
                and (best is None or held < len(best.jobs))
            ):
                best = worker
        return best

    def _dispatch(self, svc: Service) -> None:
        post, encode = self._post, wire.encoder.encode
        queue, idle, workers, jobs = svc.queue, svc.idle, self._workers, self._jobs
        while queue:
            if idle:  # the idle worker that waited longest (inlined _next_worker: this is hot)
                worker = workers.get(idle.popleft())
                if worker is None or worker.jobs:
                    continue
                worker.started = self._now
            else:
                worker = self._next_worker(svc)
                if worker is None:
                    return
            job = jobs.get(queue.popleft())
            if job is None:  # expired while queued
                if not worker.jobs:
                    svc.idle.appendleft(worker.identity)
                continue
            job.attempt += 1
            job.worker = worker.identity
            job.holders.add(worker.identity)
            worker.jobs[job.job_id] = None
            r = job.request
            left_ms = max(1, int((job.deadline - self._now) * 1000))
            envelope = encode(JobFrame(r.job_id, r.key, job.attempt, left_ms, r.doc_id, r.revision))
            post(worker.identity, r.job_id, envelope, job.payload)

    def _remove_worker(self, worker: WorkerEntry, why: str, *, undelivered: Iterable[str] = ()) -> None:
        """Forget a worker; re-queue its jobs, or fail those whose last allowed attempt it was.

        ``undelivered``: jobs that never reached the worker (their JOB failed to send); they, and
        the jobs still in the outbox for it, are re-queued without counting as an attempt.
        """
        unsent = set(undelivered)
        self._out.pop(worker.identity, None)
        unsent.update(self._out_jobs.pop(worker.identity, ()))
        self._workers.pop(worker.identity, None)
        svc = self._services.get(worker.service)
        if svc is not None:
            svc.workers.discard(worker.identity)
            try:
                svc.idle.remove(worker.identity)
            except ValueError:
                pass
        log.info("worker %r of %r removed: %s", worker.identity, worker.service, why)
        if worker.capacity > 1 and svc is not None:
            svc.prefetching -= 1
        held, worker.jobs = list(worker.jobs), {}
        requeue = []
        for job_id in held:
            job = self._jobs.get(job_id)
            if job is None or job.worker != worker.identity:
                continue  # already answered or expired
            job.worker = None
            delivered = job_id not in unsent
            if not delivered:
                job.attempt -= 1  # the job never reached it: not an attempt
            elif job.attempt >= self.max_attempts:
                del self._jobs[job_id]
                self._release(job)
                self._remember_done(job_id, job.client)
                message = f"the worker died during each of {job.attempt} attempts (last: {why})"
                self._client_error(
                    job.client,
                    job_id,
                    ErrorCode.WORKER_DIED,
                    message,
                    job.request.doc_id,
                    job.request.revision,
                )
                continue
            if delivered:
                self.requeued += 1
            requeue.append(job_id)
        if svc is not None and requeue:
            svc.queue.extendleft(reversed(requeue))  # they waited longest: they go first, in order
            self._dispatch(svc)

    # ------------------------------------------------------------------------------------- timers

    def _heartbeat(self, now: float) -> None:
        for worker in list(self._workers.values()):
            if worker.expiry < now:
                self._remove_worker(worker, f"no heartbeat for {self.liveness} intervals")
            elif not self._send(worker.identity, _HEARTBEAT):
                self._remove_worker(worker, "it is unreachable")
        self._expire_services(now)

    def _expire_jobs(self, now: float) -> None:
        expired = [job for job in self._jobs.values() if job.deadline <= now]
        for job in expired:
            del self._jobs[job.job_id]
            self._release(job)
            self._remember_done(job.job_id, job.client)
            svc = self._services.get(job.service)
            if job.worker is None and svc is not None:
                try:
                    svc.queue.remove(job.job_id)
                except ValueError:
                    pass
            if svc is None or not svc.workers:
                code, why = (
                    ErrorCode.UNKNOWN_SERVICE,
                    f"no worker for service {job.service!r} registered before the deadline",
                )
            else:
                where = "in the queue" if job.worker is None else f"on a worker (attempt {job.attempt})"
                code, why = ErrorCode.DEADLINE, f"deadline passed while the job was {where}"
            self._client_error(job.client, job.job_id, code, why, job.request.doc_id, job.request.revision)

    # ------------------------------------------------------------------------------------ outbound

    def _send(self, identity: bytes, *frames: object) -> bool:
        try:
            wire.send(self._socket, (identity, *frames))
            return True
        except zmq.ZMQError as exc:  # EHOSTUNREACH (ROUTER_MANDATORY): the peer is gone
            log.debug("could not send to %r: %s", identity, exc)
            return False

    def _post(self, peer: bytes, job_id: str, envelope: object, body: object) -> None:
        """Queue a JOB, REPLY or ERROR for ``peer``; ``_flush`` sends it (the loop flushes before it waits)."""
        out = self._out.get(peer)
        if out is None:
            self._out[peer] = [envelope, body]
            self._out_jobs[peer] = [job_id]
            return
        out.append(envelope)
        out.append(body)
        jobs = self._out_jobs[peer]
        jobs.append(job_id)
        if len(jobs) >= MAX_BATCH:
            self._send_out(peer, self._out.pop(peer), self._out_jobs.pop(peer))

    def _flush(self) -> None:
        """Send every peer's queued pairs: one message each, a BATCH where there are several."""
        while self._out:  # a peer found gone re-queues its jobs, which may go out to another one
            out, jobs = self._out, self._out_jobs
            self._out, self._out_jobs = {}, {}
            for peer, pairs in out.items():
                self._send_out(peer, pairs, jobs[peer])

    def _send_out(self, peer: bytes, pairs: list, job_ids: list[str]) -> None:
        worker = self._workers.get(peer)
        try:
            wire.send_pairs(self._socket, (peer,), pairs)
            if worker is None:  # a client's answers to its own jobs: kept a while, in case of loss
                done = self._done
                for i, job_id in enumerate(job_ids):
                    if done.get(job_id) == peer:
                        self._keep_undelivered(peer, job_id, pairs[2 * i], pairs[2 * i + 1])
            return
        except zmq.ZMQError as exc:  # EHOSTUNREACH (ROUTER_MANDATORY): the peer is gone
            log.debug("could not send to %r: %s", peer, exc)
        if worker is not None:  # JOBs: re-queue them, they never reached it
            self._remove_worker(worker, "it is unreachable", undelivered=job_ids)
            return
        for i, job_id in enumerate(job_ids):  # a client: keep its replies in case it asks again
            self._keep_undelivered(peer, job_id, pairs[2 * i], pairs[2 * i + 1])

    def _keep_undelivered(self, client: bytes, job_id: str, envelope: object, body: object) -> None:
        old = self._undelivered.pop(job_id, None)
        if old is not None:
            self._undelivered_bytes -= len(old[1][1])
        self._undelivered[job_id] = (client, (envelope, body))
        self._undelivered_bytes += len(body)  # type: ignore[arg-type]
        while self._undelivered and (
            len(self._undelivered) > _UNDELIVERED_MEMORY or self._undelivered_bytes > _UNDELIVERED_BYTES
        ):
            _, (_, dropped) = self._undelivered.popitem(last=False)
            self._undelivered_bytes -= len(dropped[1])

    def _client_error(
        self,
        client: bytes,
        job_id: str,
        code: str,
        message: str,
        doc_id: str = "",
        revision: int = 0,
        *,
        retryable: bool = False,
    ) -> None:
        assert code in ERROR_CODES, code
        self.errors[code] += 1
        reply = ErrorReply(
            header=Header(doc_id=doc_id, revision=revision), code=code, message=message, retryable=retryable
        )
        log.debug("job %r: %s %s", job_id, code, message)
        envelope = wire.encoder.encode(ErrorFrame(job_id))
        self._post(client, job_id, envelope, wire.encoder.encode(reply))

    def _remember_done(self, job_id: str, client: bytes) -> None:
        done = self._done
        done[job_id] = client
        if len(done) > _DONE_MEMORY:
            del done[next(iter(done))]

    # -------------------------------------------------------------------------------- statistics

    def stats(self, *, job_ids: bool = True) -> BrokerStats:
        """Queue depths per service, registered workers and counters (also answered to STATS).

        ``job_ids=False`` (what a STATS command gets) shows a digest of each held job id instead
        of the id itself, so that no peer can learn another's job ids to forge or hijack them.
        """
        counters = {
            "completed": self.completed,
            "requeued": self.requeued,
            "duplicate_replies": self.duplicate_replies,
            "duplicate_requests": self.duplicate_requests,
            "refused_replies": self.refused_replies,
        }
        shown = None if job_ids else _job_digest
        return broker_stats(
            self.instance, self._services, self._workers, self._jobs, counters, self.errors, shown
        )


def _job_id_of(envelope: object) -> str:
    """The job id of a REQUEST envelope that failed validation, so its sender can match the E001."""
    try:
        fields = msgspec.msgpack.decode(envelope)  # type: ignore[call-overload]
    except wire.DECODE_ERRORS:
        return ""
    if isinstance(fields, list) and len(fields) > 2 and fields[0] == "REQUEST":
        job_id = fields[2]
        if isinstance(job_id, str) and len(job_id) <= 128:
            return job_id
    return ""


def _job_digest(job_id: str) -> str:
    return "#" + hashlib.sha256(job_id.encode()).hexdigest()[:12]
