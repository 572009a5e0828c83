"""`wana metrics` over a real broker and worker: queue depth, in-flight jobs, counters and latencies on /metrics."""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import httpx
import pytest
from prometheus_client.parser import text_string_to_metric_families

from proto.bus import LATENCY_BUCKETS_S
from wana.bus.broker import Broker
from wana.bus.client import Client
from wana.metrics import latency_buckets, serve

ECHO_WORKER = Path(__file__).resolve().parents[1] / "bus" / "echo_worker.py"
HEARTBEAT_S = 0.1


def samples(url: str) -> dict[tuple[str, tuple[tuple[str, str], ...]], float]:
    text = httpx.get(url, timeout=10).text
    return {
        (s.name, tuple(sorted(s.labels.items()))): s.value
        for family in text_string_to_metric_families(text)
        for s in family.samples
    }


def value(got: dict[Any, float], name: str, **labels: str) -> float | None:
    return got.get((name, tuple(sorted(labels.items()))))


@pytest.fixture
def bus() -> Iterator[str]:
    tmp = tempfile.mkdtemp(prefix="wana-metrics-")
    url = f"ipc://{tmp}/bus.sock"
    broker = Broker(url, heartbeat_s=HEARTBEAT_S)
    broker.start_thread()
    worker = subprocess.Popen(
        [sys.executable, str(ECHO_WORKER), url, "--heartbeat", str(HEARTBEAT_S)], stderr=subprocess.DEVNULL
    )
    try:
        yield url
    finally:
        worker.kill()
        worker.wait(timeout=10)
        broker.close()
        shutil.rmtree(tmp, ignore_errors=True)


@pytest.fixture
def exporter(bus: str) -> Iterator[str]:
    server, collector = serve(bus, host="127.0.0.1", port=0)
    try:
        yield f"http://127.0.0.1:{server.server_port}/metrics"
    finally:
        server.shutdown()
        collector.close()


def test_latency_buckets_are_cumulative_and_end_at_inf():
    counts = [0] * (len(LATENCY_BUCKETS_S) + 1)
    counts[0], counts[3], counts[-1] = 2, 1, 4
    buckets = latency_buckets(counts)
    assert buckets[0] == ("0.01", 2.0)
    assert buckets[3] == (repr(LATENCY_BUCKETS_S[3]), 3.0)
    assert buckets[-2][1] == 3.0 and buckets[-1] == ("+Inf", 7.0)


def test_queued_jobs_show_as_depth_then_as_completed_jobs_with_their_latencies(bus, exporter):
    deadline = time.monotonic() + 30
    while value(samples(exporter), "wana_workers", service="echo") != 1:
        assert time.monotonic() < deadline, "the echo worker never registered"
        time.sleep(0.05)
    with Client(bus, heartbeat_s=HEARTBEAT_S) as client:
        jobs = [client.submit("echo", f"sleep:0.5:{i}".encode(), deadline_s=30) for i in range(5)]
        deadline = time.monotonic() + 10
        while True:  # the jobs reach the broker asynchronously
            loaded = samples(exporter)
            if (value(loaded, "wana_queue_depth", service="echo") or 0) > 0:
                break
            assert time.monotonic() < deadline, loaded
            time.sleep(0.02)
        # one STATS answer: every job is queued, on the one worker, or done
        depth = value(loaded, "wana_queue_depth", service="echo")
        assert value(loaded, "wana_in_flight_jobs", service="echo") == 1
        assert value(loaded, "wana_idle_workers", service="echo") == 0
        assert depth + 1 + value(loaded, "wana_jobs_completed_total", service="echo") == 5
        assert len(client.wait(jobs, timeout=30)) == 5
    done = samples(exporter)
    assert value(done, "wana_queue_depth", service="echo") == 0
    assert value(done, "wana_in_flight_jobs", service="echo") == 0
    assert value(done, "wana_jobs_completed_total", service="echo") == 5
    assert value(done, "wana_broker_completed_total") == 5
    assert value(done, "wana_job_latency_seconds_count", service="echo") == 5
    assert value(done, "wana_job_latency_seconds_bucket", service="echo", le="0.25") == 0  # each slept 0.5 s
    assert value(done, "wana_job_latency_seconds_bucket", service="echo", le="+Inf") == 5
    # one worker, one at a time: the k-th job waited for the k-1 before it
    assert value(done, "wana_job_latency_seconds_sum", service="echo") >= 0.5 * (1 + 2 + 3 + 4 + 5) * 0.95
    assert value(done, "wana_broker_up") == 1


def test_bus_errors_are_counted_by_code(bus, exporter):
    with Client(bus, heartbeat_s=HEARTBEAT_S) as client:
        job = client.submit("no-such-service", b"x", deadline_s=0.5)
        client.wait([job], timeout=10)
    got = samples(exporter)
    codes = {dict(labels)["code"]: v for (name, labels), v in got.items() if name == "wana_bus_errors_total"}
    assert sum(codes.values()) >= 1, got


def test_a_broker_that_does_not_answer_reads_as_down_with_no_depths():
    tmp = tempfile.mkdtemp(prefix="wana-metrics-")
    server, collector = serve(f"ipc://{tmp}/nobody.sock", host="127.0.0.1", port=0)
    try:
        got = samples(f"http://127.0.0.1:{server.server_port}/metrics")
    finally:
        server.shutdown()
        collector.close()
        shutil.rmtree(tmp, ignore_errors=True)
    assert value(got, "wana_broker_up") == 0
    assert not any(name == "wana_queue_depth" for name, _ in got)


def test_wana_metrics_serves_until_sigterm_and_then_exits_cleanly(bus):
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    proc = subprocess.Popen(
        [sys.executable, "-m", "wana.cli", "metrics", "--broker", bus, "--port", str(port)],
        stderr=subprocess.PIPE,
    )
    try:
        deadline = time.monotonic() + 30
        while True:
            try:
                got = samples(f"http://127.0.0.1:{port}/metrics")
                if value(got, "wana_workers", service="echo") == 1:
                    break
            except httpx.HTTPError:
                pass
            assert time.monotonic() < deadline and proc.poll() is None, "wana metrics did not serve"
            time.sleep(0.1)
        proc.terminate()
        assert proc.wait(timeout=15) == 0
    finally:
        if proc.poll() is None:
            proc.kill()


def test_wana_metrics_with_a_malformed_broker_url_says_so_and_exits_2():
    import subprocess
    import sys

    proc = subprocess.run(
        [sys.executable, "-m", "wana.metrics", "--broker", "notaurl", "--port", "0"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert proc.returncode == 2
    assert "cannot start with --broker 'notaurl'" in proc.stderr and "Traceback" not in proc.stderr
