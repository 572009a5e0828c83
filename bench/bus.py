#!/usr/bin/env python
"""Round-trip latency and throughput through the wana broker, on ipc and tcp loopback.

For each transport: a broker process, two echo worker processes, and a client in this process sending
1 kB payloads. Latency: one request at a time (p50/p99 of the round trip). Throughput: a window of
requests kept in flight (pipelining), requests answered per second.

    .venv/bin/python bench/bus.py --quick --json out/bench_bus.json

Writes exactly ``{"tcp": {"p50_us", "p99_us", "req_per_s"}, "ipc": {...}}``; the table also shows
the machine's load and a pure-Python calibration loop, since on shared CPUs every number scales with it.
Targets (issue 2): p50 <= 200 us and >= 20,000 req/s.
"""

from __future__ import annotations

import argparse
import json
import multiprocessing as mp
import os
import platform
import shutil
import statistics
import sys
import tempfile
import time
from pathlib import Path

from tqdm import tqdm

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

SEED = 0  # the payload bytes come from this seed
PAYLOAD_BYTES = 1024


def _broker_main(url: str, ready: mp.Event, stop: mp.Event) -> None:
    from wana.bus.broker import Broker

    broker = Broker(url, queue_limit=100_000)
    ready.set()
    try:
        broker.run(_EventAdapter(stop))
    finally:
        broker.close()


class _EventAdapter:
    """multiprocessing.Event has is_set(); the broker only needs that."""

    def __init__(self, event: mp.Event):
        self._event = event

    def is_set(self) -> bool:
        return self._event.is_set()


def _worker_main(url: str, stop: mp.Event, capacity: int) -> None:
    import threading

    from wana.bus.worker import Worker

    local_stop = threading.Event()

    def watch() -> None:
        stop.wait()
        local_stop.set()

    threading.Thread(target=watch, daemon=True).start()
    Worker("echo", lambda payload: payload, url, capacity=capacity).run(local_stop)


def _percentile(sorted_values: list[float], q: float) -> float:
    i = min(len(sorted_values) - 1, max(0, round(q * (len(sorted_values) - 1))))
    return sorted_values[i]


def _cpu_s(pid: int) -> float:
    """CPU seconds (user + system) a process has used so far; NaN where /proc is missing."""
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except OSError:
        return float("nan")
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def measure(
    transport: str, n_latency: int, n_throughput: int, window: int, workers: int, capacity: int = 1
) -> tuple[dict[str, float], dict[str, float]]:
    """Run broker + workers for one transport; measure latency and throughput from this process.

    Returns:
        The JSON entry (p50_us, p99_us, req_per_s) and the CPU microseconds per request that the
        broker, the workers together and the client used during the throughput run.
    """
    from wana.bus.client import BusError, Client

    tmp = tempfile.mkdtemp(prefix="wana-bench-")
    if transport == "ipc":
        url = f"ipc://{tmp}/bus.sock"
    else:
        import socket

        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            url = f"tcp://127.0.0.1:{s.getsockname()[1]}"
    ctx = mp.get_context("spawn")
    stop, ready = ctx.Event(), ctx.Event()
    procs = [ctx.Process(target=_broker_main, args=(url, ready, stop), daemon=True)]
    procs[0].start()
    ready.wait(30)
    procs += [
        ctx.Process(target=_worker_main, args=(url, stop, capacity), daemon=True) for _ in range(workers)
    ]
    for p in procs[1:]:
        p.start()
    rng = __import__("random").Random(SEED)
    payload = bytes(rng.getrandbits(8) for _ in range(PAYLOAD_BYTES))
    client = Client(url)
    try:
        end = time.monotonic() + 60
        while True:
            svc = client.stats().services.get("echo")
            if svc is not None and svc.workers >= workers:
                break
            if time.monotonic() > end:
                raise RuntimeError("workers did not register")
            time.sleep(0.05)
        for _ in range(200):  # warm-up
            client.request("echo", payload)
        samples = []
        perf = time.perf_counter_ns
        for _ in range(n_latency):
            t0 = perf()
            reply = client.request("echo", payload)
            samples.append((perf() - t0) / 1000.0)
            if len(reply) != PAYLOAD_BYTES:
                raise RuntimeError("wrong echo")
        samples.sort()
        sent = done = 0
        cpu0 = [_cpu_s(procs[0].pid), sum(_cpu_s(p.pid) for p in procs[1:]), time.process_time()]
        t0 = time.perf_counter()
        while sent < min(window, n_throughput):
            client.submit("echo", payload)
            sent += 1
        while done < n_throughput:
            got = client.collect(timeout=5.0)
            if not got:
                raise RuntimeError("no reply within 5 s during the throughput run")
            for value in got.values():
                if isinstance(value, BusError):
                    raise value
            done += len(got)
            while sent < n_throughput and sent - done < window:
                client.submit("echo", payload)
                sent += 1
        elapsed = time.perf_counter() - t0
        cpu1 = [_cpu_s(procs[0].pid), sum(_cpu_s(p.pid) for p in procs[1:]), time.process_time()]
        cpu = {
            name: round((b - a) / n_throughput * 1e6, 1)
            for name, a, b in zip(("broker", "workers", "client"), cpu0, cpu1, strict=True)
        }
        result = {
            "p50_us": round(statistics.median(samples), 1),
            "p99_us": round(_percentile(samples, 0.99), 1),
            "req_per_s": round(n_throughput / elapsed, 1),
        }
        return result, cpu
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
        client.close()
        stop.set()
        for p in procs:
            p.join(timeout=5)
            if p.is_alive():
                p.kill()


def python_loop_ms() -> float:
    """Milliseconds this machine takes for 10**6 additions in pure Python (about 30-60 on an idle core)."""
    start = time.perf_counter()
    total = 0
    for i in range(1_000_000):
        total += i
    return (time.perf_counter() - start) * 1000


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        description="Round-trip latency and throughput through the wana broker (ipc and tcp loopback, "
        "2 echo workers, 1 kB payload). Targets: p50 <= 200 us, >= 20,000 req/s."
    )
    parser.add_argument("--quick", action="store_true", help="fewer requests; finishes in under 30 s")
    parser.add_argument("--json", metavar="PATH", help="write the results as JSON to PATH")
    parser.add_argument("--transports", default="ipc,tcp", help="comma-separated subset of ipc,tcp")
    parser.add_argument("--window", type=int, default=64, help="requests in flight in the throughput run")
    parser.add_argument("--workers", type=int, default=2, help="echo worker processes")
    parser.add_argument(
        "--capacity",
        type=int,
        default=1,
        help="jobs the broker may hand each worker at once (1: classic Majordomo)",
    )
    args = parser.parse_args(argv)
    n_latency, n_throughput = (2000, 10000) if args.quick else (20000, 100000)
    calibration = python_loop_ms()
    results: dict[str, dict] = {}
    cpu: dict[str, dict] = {}
    for transport in tqdm(args.transports.split(","), desc="transports", leave=False):
        results[transport], cpu[transport] = measure(
            transport, n_latency, n_throughput, args.window, args.workers, args.capacity
        )
    print(
        f"{'transport':<10} {'p50 (us)':>10} {'p99 (us)':>10} {'req/s':>10}   CPU us/request: broker workers client"
    )
    for transport, r in results.items():
        c = cpu[transport]
        print(
            f"{transport:<10} {r['p50_us']:>10.1f} {r['p99_us']:>10.1f} {r['req_per_s']:>10.0f}"
            f"   {c['broker']:>21.1f} {c['workers']:>7.1f} {c['client']:>6.1f}"
        )
    print(f"targets:   {'<= 200':>10} {'':>10} {'>= 20000':>10}")
    print(
        f"config: {args.workers} workers (capacity {args.capacity}), {PAYLOAD_BYTES}-byte payload, "
        f"window {args.window}, "
        f"{n_latency} latency + {n_throughput} throughput requests per transport; {os.cpu_count()} CPUs, "
        f"load average {os.getloadavg()[0]:.1f}, pure-Python calibration loop {calibration:.0f} ms "
        f"(about 30-60 ms on an idle core; larger means the CPUs are shared), Python {platform.python_version()}"
    )
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps(results, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
