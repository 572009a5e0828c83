"""The broker's bookkeeping: jobs, registered workers, per-service queues, and their statistics.

Plain data with no sockets, kept apart from wana/bus/broker.py so that the routing rules there read
on their own.
"""

from __future__ import annotations

import bisect
import collections
from collections.abc import Callable

import zmq

from proto.bus import LATENCY_BUCKETS_S, BrokerStats, ReadyFrame, RequestFrame, ServiceStats, WorkerStats


class Job:
    __slots__ = (
        "job_id",
        "client",
        "service",
        "request",
        "attempt",
        "deadline",
        "payload",
        "worker",
        "holders",
        "arrived",
    )

    def __init__(self, client: bytes, request: RequestFrame, payload: zmq.Frame, now: float):
        self.job_id = request.job_id
        self.client = client
        self.service = request.service
        self.request = request
        self.attempt = request.attempt
        self.deadline = now + request.deadline_ms / 1000.0
        self.payload = payload
        self.worker: bytes | None = None
        self.holders: set[bytes] = set()  # workers it was dispatched to: only they may answer it
        self.arrived = now  # when the broker took it in (its latency runs from here to the reply)


class WorkerEntry:
    __slots__ = ("identity", "service", "expiry", "jobs", "capacity", "ready", "started", "job_s")

    def __init__(self, identity: bytes, ready: ReadyFrame, expiry: float):
        self.identity = identity
        self.service = ready.service
        self.expiry = expiry
        self.jobs: dict[str, None] = {}  # job ids it holds, in dispatch order
        self.capacity = max(1, ready.capacity)
        self.ready = ready
        # Prefetch guard (see Broker._next_worker): when the job it runs now started (its dispatch
        # to the idle worker, or the reply to the job before), and how long its last job took.
        self.started = 0.0
        self.job_s = float("inf")  # none finished yet


class Service:
    __slots__ = (
        "name",
        "idle",
        "queue",
        "workers",
        "prefetching",
        "empty_since",
        "held_bytes",
        "completed",
        "latency_counts",
        "latency_sum_s",
    )

    def __init__(self, name: str):
        self.name = name
        self.idle: collections.deque[bytes] = (
            collections.deque()
        )  # workers holding no job, least recently used first
        self.queue: collections.deque[str] = collections.deque()  # job ids waiting for a worker
        self.workers: set[bytes] = set()
        self.prefetching = 0  # registered workers with capacity > 1
        self.empty_since: float | None = None  # when it last had neither workers nor jobs
        self.held_bytes = 0  # payload bytes of its jobs, queued or in flight
        self.completed = 0  # replies forwarded
        self.latency_counts = [0] * (len(LATENCY_BUCKETS_S) + 1)  # per bucket, see ServiceStats
        self.latency_sum_s = 0.0

    def record_reply(self, latency_s: float) -> None:
        """Count one forwarded reply that took ``latency_s`` seconds since its request arrived."""
        self.completed += 1
        self.latency_counts[bisect.bisect_left(LATENCY_BUCKETS_S, latency_s)] += 1
        self.latency_sum_s += latency_s


def broker_stats(
    instance: str,
    services: dict[str, Service],
    workers: dict[bytes, WorkerEntry],
    jobs: dict[str, Job],
    counters: dict[str, int],
    errors: dict[str, int],
    show_job: Callable[[str], str] | None = None,
) -> BrokerStats:
    """Queue depths per service, registered workers and counters, as answered to STATS.

    ``show_job`` maps a held job id to what the statistics show (None: the id itself).
    """
    service_stats = {}
    for name, svc in services.items():
        in_flight = sum(len(workers[wid].jobs) for wid in svc.workers)
        idle = sum(1 for wid in svc.workers if not workers[wid].jobs)
        service_stats[name] = ServiceStats(
            workers=len(svc.workers),
            idle=idle,
            queued=len(svc.queue),
            in_flight=in_flight,
            completed=svc.completed,
            latency_counts=list(svc.latency_counts) if svc.completed else [],
            latency_sum_s=svc.latency_sum_s,
        )
    worker_stats = []
    for w in workers.values():
        first = next(iter(w.jobs), "")
        job = jobs.get(first)
        worker_stats.append(
            WorkerStats(
                service=w.service,
                pid=w.ready.pid,
                host=w.ready.host,
                job_id=first if show_job is None or not first else show_job(first),
                attempt=job.attempt if job is not None else 0,
                jobs=len(w.jobs),
                capacity=w.capacity,
            )
        )
    return BrokerStats(
        instance=instance, services=service_stats, workers=worker_stats, errors=dict(errors), **counters
    )
