#!/usr/bin/env python
"""Broker memory under the flooding attacks of issue 18, and whether a real service still gets served.

A broker process with default settings on ipc; a client in this process plays the attacker:

1. 768 requests of 1 MiB each, spread over 16 services nobody serves, with hour-long deadlines
   (before the byte budget this took the broker from 27 to 628 MB for the whole hour);
2. 1,024 small requests to made-up service names (before, they filled the service table for good).

Then a real worker registers for a service the broker has never seen (while the table holds the
made-up names) and, once registered, must be served. The
broker's RSS is sampled from /proc every 20 ms throughout.

    .venv/bin/python bench/bus_memory.py --quick --json out/bench_bus_memory.json

Keys: ``broker_rss_mb_max`` (target <= 300), ``broker_rss_mb_idle``, ``flood_answered`` (requests
of attack 1 answered at once, E005), ``flood_held`` (accepted and held until their deadline),
``names_answered`` (attack 2 answered at once, E003), ``names_held``, ``real_service_served``.
``--quick`` waits less between the phases; the attack itself is the same.
"""

from __future__ import annotations

import argparse
import json
import multiprocessing as mp
import shutil
import sys
import tempfile
import threading
import time
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

MIB = 1024 * 1024


def _broker_main(url: str, ready, stop) -> None:
    from wana.bus.broker import Broker

    broker = Broker(url)
    ready.set()
    try:
        broker.run(_EventAdapter(stop))
    finally:
        broker.close()


class _EventAdapter:
    def __init__(self, event) -> None:
        self._event = event

    def is_set(self) -> bool:
        return self._event.is_set()


def _rss_mb(pid: int) -> float:
    with open(f"/proc/{pid}/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    return 0.0


class RssSampler(threading.Thread):
    def __init__(self, pid: int) -> None:
        super().__init__(daemon=True)
        self.pid = pid
        self.max_mb = 0.0
        self._stop_event = threading.Event()

    def run(self) -> None:
        while not self._stop_event.wait(0.02):
            self.max_mb = max(self.max_mb, _rss_mb(self.pid))

    def stop(self) -> None:
        self._stop_event.set()
        self.join()


def _answers(client, job_ids: list[str], seconds: float) -> Counter[str]:
    """Codes of the jobs answered within ``seconds`` ("ok" for a reply)."""
    from wana.bus.client import BusError

    got = client.wait(job_ids, timeout=seconds)
    return Counter(v.code if isinstance(v, BusError) else "ok" for v in got.values())


def measure(settle_s: float) -> dict[str, object]:
    from wana.bus.client import Client
    from wana.bus.worker import Worker

    tmp = tempfile.mkdtemp(prefix="wana-mem-")
    url = f"ipc://{tmp}/bus.sock"
    ctx = mp.get_context("spawn")
    ready, stop = ctx.Event(), ctx.Event()
    proc = ctx.Process(target=_broker_main, args=(url, ready, stop), daemon=True)
    proc.start()
    ready.wait(30)
    time.sleep(0.3)
    idle_mb = _rss_mb(proc.pid)
    sampler = RssSampler(proc.pid)
    sampler.start()
    result: dict[str, object] = {"broker_rss_mb_idle": round(idle_mb, 1)}
    try:
        with Client(url) as attacker:
            payload = bytes(MIB)
            flood = [attacker.submit(f"unserved-{i % 16}", payload, deadline_s=3600) for i in range(768)]
            answered = _answers(attacker, flood, settle_s)
            result["flood_answered"] = sum(answered.values())
            result["flood_codes"] = dict(answered)
            result["flood_held"] = len(flood) - sum(answered.values())
            names = [attacker.submit(f"made-up-{i}", b"x", deadline_s=3600) for i in range(1024)]
            answered = _answers(attacker, names, settle_s)
            result["names_answered"] = sum(answered.values())
            result["names_codes"] = dict(answered)
            result["names_held"] = len(names) - sum(answered.values())

            worker = Worker("real", lambda p: b"served:" + p, url)
            worker_stop = threading.Event()
            thread = threading.Thread(target=worker.run, args=(worker_stop,), daemon=True)
            thread.start()
            with Client(url) as user:
                end = time.monotonic() + 10
                while "real" not in user.stats().services and time.monotonic() < end:
                    time.sleep(0.02)  # the worker's READY must be in before its first request
                try:
                    result["real_service_served"] = (
                        user.request("real", b"hello", deadline_s=10) == b"served:hello"
                    )
                except Exception as exc:  # what the user would see
                    result["real_service_served"] = False
                    result["real_service_error"] = str(exc)
            worker_stop.set()
            thread.join(timeout=5)
            time.sleep(settle_s)
    finally:
        sampler.stop()
        stop.set()
        proc.join(timeout=10)
        if proc.is_alive():
            proc.kill()
        shutil.rmtree(tmp, ignore_errors=True)
    result["broker_rss_mb_max"] = round(sampler.max_mb, 1)
    return result


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="Broker RSS under the issue 18 flooding attacks.")
    parser.add_argument("--quick", action="store_true", help="shorter waits between the phases")
    parser.add_argument("--json", metavar="PATH", help="write the results as JSON to PATH")
    args = parser.parse_args(argv)
    result = measure(settle_s=1.0 if args.quick else 3.0)
    for key, value in result.items():
        print(f"{key:<24}{value}")
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps(result, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
