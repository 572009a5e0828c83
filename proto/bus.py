"""Bus-level messages: the envelope of every bus frame, broker statistics, and the echo service.

proto/PROTOCOL.md is the authoritative description of frames, commands and messages. Everything
here is plain msgpack on the wire, readable by any msgpack library.
"""

from __future__ import annotations

from typing import Annotated, Union

import msgspec

from proto.common import Header, Request, Status

PROTOCOL_VERSION = 2  # 2: BATCH messages
MAX_BATCH = 64  # pairs one BATCH message may carry
MAX_DEADLINE_MS = 24 * 3600 * 1000  # the broker clamps longer deadlines to a day

# Range checks applied at decode: a value outside them is a malformed frame (E001), never an
# overflow deep inside the broker (a deadline of 2**64-1 ms once crashed it while encoding the JOB).
ServiceName = Annotated[str, msgspec.Meta(min_length=1, max_length=64)]
JobId = Annotated[str, msgspec.Meta(max_length=128)]  # "" only in an ERROR for an unnamed job
Key = Annotated[str, msgspec.Meta(max_length=128)]
Attempt = Annotated[int, msgspec.Meta(ge=0, le=255)]
DeadlineMs = Annotated[int, msgspec.Meta(ge=-(2**53), le=2**53)]  # clamped to MAX_DEADLINE_MS
Revision = Annotated[int, msgspec.Meta(ge=0, le=2**53)]
DocId = Annotated[str, msgspec.Meta(max_length=256)]
Count = Annotated[int, msgspec.Meta(ge=0, le=2**53)]
Short = Annotated[str, msgspec.Meta(max_length=256)]

# Every bus message is one envelope frame (a msgpack array whose first element is the command name)
# followed, for REQUEST, JOB, REPLY, ERROR and STATS-from-the-broker, by one body frame. The broker's
# ROUTER socket adds the peer's routing id in front. Array-like structs keep the envelope small and
# its decoding cheap; any msgpack library reads it as a plain array.


class ReadyFrame(msgspec.Struct, frozen=True, array_like=True, tag="READY"):
    """worker -> broker: register for ``service``. No body frame."""

    service: ServiceName
    protocol: Count = PROTOCOL_VERSION  # a different major version is refused with E012
    pid: Count = 0
    host: Short = ""
    max_frame: Count = 0  # bytes the worker accepts; 0 = unknown
    # jobs the broker may hand it at once (it runs them one after another)
    capacity: Annotated[int, msgspec.Meta(ge=1, le=1024)] = 1


class RequestFrame(msgspec.Struct, frozen=True, array_like=True, tag="REQUEST"):
    """client -> broker: one job for ``service``; the body frame is the request payload."""

    service: ServiceName
    job_id: JobId  # unique per job, chosen by the client; requests and replies are deduplicated by it
    key: Key  # idempotency key: hash of the inputs and the code/model version
    attempt: Attempt  # 0 from a client
    deadline_ms: DeadlineMs  # milliseconds left when sent (relative, so clocks need not agree)
    doc_id: DocId = ""  # document the job belongs to ("" for stateless calls)
    revision: Revision = 0  # document revision the job is computed for


class JobFrame(msgspec.Struct, frozen=True, array_like=True, tag="JOB"):
    """broker -> worker: a job to run; the body frame is the request payload."""

    job_id: JobId
    key: Key
    attempt: Attempt  # dispatches so far, this one included: 1, 2, 3
    deadline_ms: DeadlineMs  # milliseconds left when the broker dispatched the job
    doc_id: DocId = ""
    revision: Revision = 0


class ReplyFrame(msgspec.Struct, frozen=True, array_like=True, tag="REPLY"):
    """worker -> broker, then forwarded unchanged broker -> client; the body frame is the reply payload."""

    job_id: JobId


class ErrorFrame(msgspec.Struct, frozen=True, array_like=True, tag="ERROR"):
    """broker -> client: a bus-level failure of a job; the body frame is a proto.common.ErrorReply."""

    job_id: JobId  # "" when the request was too malformed to name its job


class BatchFrame(msgspec.Struct, frozen=True, array_like=True, tag="BATCH"):
    """Several jobs in one message: followed by ``count`` (envelope, body) frame pairs.

    Each pair is a REQUEST (client -> broker), JOB (broker -> worker), REPLY (worker -> broker ->
    client) or ERROR (broker -> client) exactly as it would travel alone. A backlog of short jobs
    then costs one message, not one per job (see PROTOCOL.md, section 2).
    """

    count: Annotated[int, msgspec.Meta(ge=1, le=MAX_BATCH)]  # (envelope, body) pairs that follow


class HeartbeatFrame(msgspec.Struct, frozen=True, array_like=True, tag="HEARTBEAT"):
    """worker <-> broker, every heartbeat interval. No body frame."""


class DisconnectFrame(msgspec.Struct, frozen=True, array_like=True, tag="DISCONNECT"):
    """worker -> broker: I am leaving; broker -> worker: I do not know you, register again."""


class PingFrame(msgspec.Struct, frozen=True, array_like=True, tag="PING"):
    """client -> broker: liveness probe, sent every heartbeat interval while jobs are pending."""

    seq: Count = 0


class PongFrame(msgspec.Struct, frozen=True, array_like=True, tag="PONG"):
    """broker -> client: answer to PING with the broker's instance id (a new id means a restart)."""

    instance: Short
    seq: Count = 0
    max_frame: Count = 0  # largest payload the broker accepts (0: unknown); clients check before sending


class StatsFrame(msgspec.Struct, frozen=True, array_like=True, tag="STATS"):
    """client -> broker (no body); broker -> client with a BrokerStats body frame."""


Envelope = Union[  # noqa: UP007 - a runtime union for msgspec decoders
    ReadyFrame,
    RequestFrame,
    JobFrame,
    ReplyFrame,
    ErrorFrame,
    BatchFrame,
    HeartbeatFrame,
    DisconnectFrame,
    PingFrame,
    PongFrame,
    StatsFrame,
]

# Envelopes followed by exactly one body frame (STATS only in the broker -> client direction).
WITH_BODY = (RequestFrame, JobFrame, ReplyFrame, ErrorFrame)


# Upper bounds (seconds) of the job-latency buckets in ServiceStats.latency_counts; one more count
# follows for the jobs slower than the last bound (Prometheus' +Inf bucket).
LATENCY_BUCKETS_S: tuple[float, ...] = (0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1.0, 2.5, 5.0, 10.0, 30.0, 60.0)


class ServiceStats(msgspec.Struct, frozen=True, kw_only=True):
    workers: int  # registered workers
    idle: int  # workers waiting for a job
    queued: int  # jobs waiting for a worker
    in_flight: int  # jobs a worker is handling
    completed: int = 0  # replies forwarded for this service
    # seconds from a request's arrival at the broker to its reply, per bucket of LATENCY_BUCKETS_S
    # (not cumulative; len(LATENCY_BUCKETS_S) + 1 counts, or empty before the first reply)
    latency_counts: list[int] = []
    latency_sum_s: float = 0.0  # seconds, sum over the completed jobs


class WorkerStats(msgspec.Struct, frozen=True, kw_only=True):
    service: str
    pid: int
    host: str
    job_id: str  # "" when idle
    attempt: int  # attempt number of the job it holds, 0 when idle
    jobs: int = 0  # jobs it holds (at most its capacity)
    capacity: int = 1


class BrokerStats(msgspec.Struct, frozen=True, kw_only=True, tag="broker_stats"):
    """Answer to STATS: queue depths per service (what an autoscaler reads) and counters."""

    instance: str  # random id of this broker process run; changes on restart
    services: dict[str, ServiceStats] = {}
    workers: list[WorkerStats] = []
    completed: int = 0  # replies forwarded to clients
    requeued: int = 0  # jobs re-queued after their worker died
    duplicate_replies: int = 0  # replies dropped because the job was already answered or unknown
    duplicate_requests: int = 0  # requests ignored because the job id was already queued or in flight
    errors: dict[str, int] = {}  # bus-level error replies sent, by code
    refused_replies: int = 0  # replies dropped because the sender never held the job (forged)


# A tiny built-in service (wana/bus/echo.py): a health check for a deployment and the example
# service of the contract-test harness.


class EchoRequest(Request["EchoReply"], frozen=True, kw_only=True, tag="echo_request"):
    header: Header
    text: Annotated[str, msgspec.Meta(max_length=1 << 20)]
    sleep_s: float = 0.0  # seconds to wait before answering, 0..60 (for tests of slow jobs)


class EchoReply(msgspec.Struct, frozen=True, kw_only=True, tag="echo_reply"):
    header: Header
    status: Status = "ok"
    text: str
    worker_pid: int = 0
