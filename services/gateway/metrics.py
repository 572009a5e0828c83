"""The gateway's Prometheus metrics: how long an edit takes to be acknowledged, and a compute to finish.

Served on ``GET /metrics`` (text exposition format) beside the bus metrics of ``wana metrics``; one
registry per process, so several apps in one process (tests) add to the same series.
"""

from __future__ import annotations

from prometheus_client import CollectorRegistry, Counter, Histogram

REGISTRY = CollectorRegistry(auto_describe=True)

EDIT_ACK_SECONDS = Histogram(
    "wana_gateway_edit_ack_seconds",
    "seconds from an edit's arrival to its acknowledgement (persisted in the session database)",
    buckets=(0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1.0, 2.5),
    registry=REGISTRY,
)
COMPUTE_SECONDS = Histogram(
    "wana_gateway_compute_seconds",
    "seconds one compute of a document took (the whole pipeline, incremental)",
    buckets=(0.05, 0.1, 0.25, 0.5, 1.0, 2.5, 5.0, 10.0, 30.0, 60.0, 120.0, 300.0),
    registry=REGISTRY,
)
COMPUTE_FAILURES = Counter(
    "wana_gateway_compute_failures", "computes that raised instead of producing a result", registry=REGISTRY
)
