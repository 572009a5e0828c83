"""`wana metrics`: the broker's STATS as Prometheus metrics, for dashboards and the autoscaler.

The HorizontalPodAutoscalers of deploy/k8s/ scale each worker Deployment on the external metric
``wana_queue_depth{service}``; Prometheus scrapes this exporter and prometheus-adapter (rules in
deploy/k8s/metrics.yaml) serves the series to the HPAs. Every scrape asks the broker for STATS once
(a few hundred bytes over the bus), so the numbers are never older than the scrape itself; when the
broker does not answer, ``wana_broker_up`` is 0 and no per-service series are given (an HPA then holds
its replica count instead of scaling on a stale depth).
"""

from __future__ import annotations

import argparse
import logging
import signal
import sys
import threading
from collections.abc import Iterator
from typing import Any

import zmq
from prometheus_client import CollectorRegistry, start_http_server
from prometheus_client.core import CounterMetricFamily, GaugeMetricFamily, HistogramMetricFamily
from prometheus_client.registry import Collector

from proto.bus import LATENCY_BUCKETS_S, BrokerStats

log = logging.getLogger(__name__)

# BrokerStats counters exported as <name>_total: what each counts is documented on BrokerStats.
_BROKER_COUNTERS = ("completed", "requeued", "duplicate_replies", "duplicate_requests", "refused_replies")


def latency_buckets(counts: list[int]) -> list[tuple[str, float]]:
    """Per-bucket job counts (ServiceStats.latency_counts) as Prometheus' cumulative (le, count) pairs."""
    bounds = [repr(b) for b in LATENCY_BUCKETS_S] + ["+Inf"]
    cumulative, total = [], 0
    for bound, count in zip(bounds, counts, strict=True):
        total += count
        cumulative.append((bound, float(total)))
    return cumulative


def metric_families(stats: BrokerStats | None) -> list[Any]:
    """The metric families of one STATS answer (None: the broker did not answer)."""
    up = GaugeMetricFamily("wana_broker_up", "1 when the broker answered STATS for this scrape")
    up.add_metric([], 0.0 if stats is None else 1.0)
    if stats is None:
        return [up]
    label = ["service"]
    depth = GaugeMetricFamily("wana_queue_depth", "jobs waiting for a worker, per service", labels=label)
    workers = GaugeMetricFamily("wana_workers", "workers registered, per service", labels=label)
    idle = GaugeMetricFamily("wana_idle_workers", "registered workers holding no job", labels=label)
    in_flight = GaugeMetricFamily("wana_in_flight_jobs", "jobs a worker is handling", labels=label)
    jobs = CounterMetricFamily("wana_jobs_completed", "replies forwarded, per service", labels=label)
    latency = HistogramMetricFamily(
        "wana_job_latency_seconds",
        "seconds from a request's arrival at the broker to its reply, per service",
        labels=label,
    )
    for name, svc in sorted(stats.services.items()):
        depth.add_metric([name], svc.queued)
        workers.add_metric([name], svc.workers)
        idle.add_metric([name], svc.idle)
        in_flight.add_metric([name], svc.in_flight)
        jobs.add_metric([name], svc.completed)
        if svc.latency_counts:
            latency.add_metric([name], latency_buckets(svc.latency_counts), svc.latency_sum_s)
    errors = CounterMetricFamily("wana_bus_errors", "bus-level error replies sent, by code", labels=["code"])
    for code, count in sorted(stats.errors.items()):
        errors.add_metric([code], count)
    counters = []
    for field in _BROKER_COUNTERS:
        family = CounterMetricFamily(f"wana_broker_{field}", f"BrokerStats.{field} of the broker")
        family.add_metric([], getattr(stats, field))
        counters.append(family)
    return [up, depth, workers, idle, in_flight, jobs, latency, errors, *counters]


class BrokerCollector(Collector):
    """Asks the broker for STATS on every scrape (one scrape at a time: the bus client is one socket)."""

    def __init__(self, broker: str, *, keys: str | None = None, timeout_s: float = 2.0) -> None:
        from wana.bus.client import Client

        self._client = Client(broker, keys=keys)
        self._timeout_s = timeout_s
        self._lock = threading.Lock()

    def collect(self) -> Iterator[Any]:
        with self._lock:
            try:
                stats: BrokerStats | None = self._client.stats(timeout=self._timeout_s)
            except TimeoutError as exc:
                log.warning("%s", exc)
                stats = None
        yield from metric_families(stats)

    def close(self) -> None:
        self._client.close()


def serve(broker: str, *, host: str, port: int, keys: str | None = None) -> tuple[Any, BrokerCollector]:
    """Start the exporter's HTTP server on a thread; returns (server, collector) for the caller to close."""
    registry = CollectorRegistry(auto_describe=False)
    collector = BrokerCollector(broker, keys=keys)
    registry.register(collector)
    server, _thread = start_http_server(port, addr=host, registry=registry)
    return server, collector


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="wana metrics",
        description="Export the broker's queue depths, workers, jobs, errors and job latencies as "
        "Prometheus metrics on http://HOST:PORT/metrics (what the worker HPAs scale on).",
    )
    p.add_argument("--broker", required=True, metavar="URL", help="broker endpoint, e.g. tcp://HOST:5555")
    p.add_argument("--port", type=int, default=9108, help="HTTP port of /metrics (default 9108)")
    p.add_argument("--host", default="127.0.0.1", help="address to bind (default 127.0.0.1)")
    p.add_argument(
        "--keys", metavar="DIR", help="CURVE key directory with the client pair (default: $WANA_BUS_KEYS)"
    )
    return p


def main(argv: list[str] | None = None) -> int:
    """`wana metrics`: serve /metrics until SIGTERM or Ctrl-C. Returns the exit status."""
    args = build_parser().parse_args(argv)
    stop = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: stop.set())
    try:
        server, collector = serve(args.broker, host=args.host, port=args.port, keys=args.keys)
    except (zmq.ZMQError, OSError) as exc:  # a malformed broker URL, a port in use, unreadable keys
        print(f"wana metrics: cannot start with --broker {args.broker!r}: {exc}", file=sys.stderr)
        return 2
    print(
        f"wana metrics: http://{args.host}:{server.server_port}/metrics (broker {args.broker})",
        file=sys.stderr,
        flush=True,
    )
    try:
        stop.wait()
    except KeyboardInterrupt:
        pass
    finally:
        server.shutdown()
        collector.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
