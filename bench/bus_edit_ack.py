#!/usr/bin/env python
"""Edit-acknowledgement latency over the gateway's WebSocket while a long compute runs (issue 18).

A real gateway (uvicorn in a thread, real SQLite) whose pipeline backend holds its first stage for
``--compute-s`` seconds (10 s; 3 s with ``--quick``), so one compute runs that long; meanwhile a
client sends edits one after another and times each ack, and a REST GET of the document is timed
too. Before the compute left the document lock, every edit and read waited for the whole compute.

    .venv/bin/python bench/bus_edit_ack.py --quick --json out/bench_edit_ack.json

Keys: ``ack_ms_p50``, ``ack_ms_p95`` (target <= 50), ``ack_ms_max``, ``edits``, ``get_ms_max``,
``compute_s`` (how long the compute was held), ``edits_during_compute`` (acks that arrived before it ended).
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))


def measure(compute_s: float, edits: int) -> dict[str, Any]:
    import httpx
    from websockets.sync.client import connect

    from services.gateway.app import ServiceSubset
    from services.gateway.server import GatewayThread
    from services.gateway.settings import SERVICES, Settings
    from services.orchestrator.backend import InProcessBackend
    from services.orchestrator.session import Orchestrator

    class HeldBackend(ServiceSubset):
        """No service enabled; the first call of a compute is held ``compute_s`` seconds."""

        def __init__(self) -> None:
            super().__init__(InProcessBackend(), {s: "disabled in this benchmark" for s in SERVICES})
            self.held_until = 0.0
            self.first = threading.Event()

        def call(self, request: Any) -> Any:
            if not self.first.is_set():
                self.first.set()
                self.held_until = time.monotonic() + compute_s
                time.sleep(compute_s)
            return super().call(request)

    with tempfile.TemporaryDirectory(prefix="wana-ack-") as tmp:
        backend = HeldBackend()
        orch = Orchestrator(Path(tmp) / "s.sqlite", backend)
        settings = Settings(db=Path(tmp) / "unused.sqlite", backend="inprocess", services=())
        doc_id = orch.create("Eve walks.").doc_id
        with GatewayThread(settings, orch) as gw, httpx.Client(base_url=gw.base_url, timeout=60) as http:
            with connect(f"{gw.ws_url}/api/documents/{doc_id}/live", max_size=None) as ws:
                backend.first.wait(30)
                acks, gets, during = [], [], 0
                for version in range(edits):
                    t0 = time.perf_counter()
                    ws.send(
                        json.dumps(
                            {
                                "type": "edit",
                                "base_version": version,
                                "changes": [{"start": 10 + version, "end": 10 + version, "text": "!"}],
                                "client_seq": version,
                            }
                        )
                    )
                    while json.loads(ws.recv(timeout=60))["type"] != "ack":
                        pass
                    acks.append((time.perf_counter() - t0) * 1000.0)
                    during += time.monotonic() < backend.held_until
                    if version % 10 == 0:
                        t0 = time.perf_counter()
                        http.get(f"/api/documents/{doc_id}").raise_for_status()
                        gets.append((time.perf_counter() - t0) * 1000.0)
                    time.sleep(compute_s / edits / 2)  # spread the edits over the first half of the compute
        orch.close()
    acks.sort()
    return {
        "edits": len(acks),
        "edits_during_compute": during,
        "compute_s": compute_s,
        "ack_ms_p50": round(statistics.median(acks), 2),
        "ack_ms_p95": round(acks[int(0.95 * (len(acks) - 1))], 2),
        "ack_ms_max": round(acks[-1], 2),
        "get_ms_max": round(max(gets), 2),
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="Edit-ack latency during a long compute (issue 18).")
    parser.add_argument("--quick", action="store_true", help="a 3 s compute instead of 10 s")
    parser.add_argument("--json", metavar="PATH", help="write the results as JSON to PATH")
    parser.add_argument("--edits", type=int, default=100)
    args = parser.parse_args(argv)
    result = measure(3.0 if args.quick else 10.0, args.edits)
    for key, value in result.items():
        print(f"{key:<22}{value}")
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps(result, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
