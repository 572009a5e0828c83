"""Scale-out throughput: motion jobs/s and render frames/s with 1, 2 and 4 worker processes; peak RSS.

    .venv/bin/python bench/scale_out.py [--quick] [--json PATH] [--workers 1,2,4]

Each worker is a `wana worker SERVICE --connect URL` process on a real broker (ipc socket), exactly
what a Deployment replica runs. Start-up and one warm-up job per worker are not timed.

motion_jobs_per_s {workers: value}: N furnished-office SynthesizeRequests (walk to the chair, the
editor's most common segment, each with its own idempotency key) submitted at once; jobs / seconds
until the last reply.

render_fps {workers: value}: one video of F frames (600; --quick 120) at 640x480 asked for as 4 MP4
ranges at once (so 1 worker renders 4 ranges in turn, 2 workers 2 each, 4 workers 1 each); F / seconds
until the last range is back.

gateway_rss_mb_peak and worker_rss_mb_peak {service: MB}: the peak resident set (VmHWM) of
`wana serve --broker URL` after editing a document through it until its compute finished, and of one
worker of each service after that compute (the motion and render ones after their runs above):
what the manifests' memory requests and limits are chosen from (deploy/README.md, "Sizing").

cpu_count and load_average are printed and kept: on a machine whose cores are shared, throughput
stops growing at the cores other processes leave free, so read the table against them.
"""

from __future__ import annotations

import argparse
import json
import os
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

import httpx  # noqa: E402
import msgspec  # noqa: E402

from proto.common import Header  # noqa: E402
from services.orchestrator.registry import SERVICES  # noqa: E402
from wana.bus.broker import Broker  # noqa: E402
from wana.bus.client import Client  # noqa: E402


def peak_rss_mb(pid: int) -> float:
    """VmHWM of a process, in MiB (Linux)."""
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmHWM:"):
            return int(line.split()[1]) / 1024.0
    raise RuntimeError(f"no VmHWM for pid {pid}")


class Bus:
    """A broker in this process and `wana worker` processes connected to it over ipc."""

    def __init__(self) -> None:
        self.tmp = Path(tempfile.mkdtemp(prefix="wana-scale-"))
        self.url = f"ipc://{self.tmp}/bus.sock"
        self.broker = Broker(self.url, queue_limit=1024)
        self.broker.start_thread()
        self.client = Client(self.url)
        self.procs: dict[str, list[subprocess.Popen[bytes]]] = {}
        self.env = dict(os.environ, PYTHONPATH=str(REPO), OMP_NUM_THREADS="1")

    def spawn(self, *args: str, log: str) -> subprocess.Popen[bytes]:
        with open(self.tmp / f"{log}.log", "wb") as err:
            return subprocess.Popen(
                [sys.executable, "-m", "wana.cli", *args],
                cwd=REPO,
                env=self.env,
                stdout=subprocess.DEVNULL,
                stderr=err,
            )

    def workers(self, service: str, n: int, timeout_s: float = 300) -> list[subprocess.Popen[bytes]]:
        procs = self.procs.setdefault(service, [])
        while len(procs) < n:
            procs.append(self.spawn("worker", service, "--connect", self.url, log=f"{service}-{len(procs)}"))
        end = time.monotonic() + timeout_s
        while True:
            svc = self.client.stats().services.get(service)
            if svc is not None and svc.workers >= n:
                return procs
            if time.monotonic() > end or any(p.poll() is not None for p in procs):
                raise RuntimeError(f"{service} workers did not start; see {self.tmp}")
            time.sleep(0.1)

    def stop_workers(self, service: str) -> None:
        procs = self.procs.pop(service, [])
        for p in procs:
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=15)
            except subprocess.TimeoutExpired:
                p.kill()
        end = time.monotonic() + 30  # the broker forgets them (DISCONNECT) before the next run counts workers
        while time.monotonic() < end:
            svc = self.client.stats().services.get(service)
            if svc is None or svc.workers == 0:
                return
            time.sleep(0.1)

    def run_all(self, service: str, payloads: list[bytes], tag: str, timeout_s: float = 1800) -> float:
        """Seconds from submitting every payload at once until the last reply."""
        t0 = time.perf_counter()
        jobs = [
            self.client.submit(service, p, deadline_s=timeout_s, idempotency_key=f"{tag}-{i}")
            for i, p in enumerate(payloads)
        ]
        done = self.client.wait(jobs, timeout=timeout_s)
        seconds = time.perf_counter() - t0
        if len(done) != len(jobs):
            raise RuntimeError(f"{len(jobs) - len(done)} {service} jobs unanswered")
        bad = [r for r in done.values() if not isinstance(r, bytes)]
        if bad:
            raise RuntimeError(f"{service} jobs failed: {bad[0]}")
        return seconds

    def close(self) -> None:
        for service in list(self.procs):
            self.stop_workers(service)
        self.client.close()
        self.broker.close()


def motion_payloads(n: int) -> list[bytes]:
    from proto.motion import SegmentEndState, SynthesizeRequest
    from proto.ssg import ActionNode, CharacterNode
    from wana.assets.scenedb import load_scenedb

    scene = next(r.scene for r in load_scenedb() if r.room_type == "office")
    names = {o.category: o.id for o in scene.objects}
    seat = names.get("office_chair") or names.get("chair") or ""
    out = []
    for i in range(n):
        state = SegmentEndState(x=-0.5 + 0.1 * (i % 10), z=-scene.room.depth / 2 + 0.6, yaw=0.0)
        req = SynthesizeRequest(
            header=Header(),
            character=CharacterNode(
                name=f"bench{i}", actions=[ActionNode(verb="walk", action="walk", destination=seat)]
            ),
            scene=scene,
            start=(state.x, state.z, state.yaw),
            start_state=state,
        )
        out.append(msgspec.msgpack.encode(req))
    return out


def render_payloads(frames: int, ranges: int, width: int, height: int) -> list[bytes]:
    from proto.render import RenderRequest
    from services.render.demo import demo_scene, walk_motion
    from services.render.timeline import chunk_ranges

    scene = demo_scene()
    motions = [
        walk_motion("Eve", (-2.0, 1.5), (1.0, -0.5), frames, sentence_id="s1"),
        walk_motion("Tom", (1.5, 1.8), (-0.5, 1.2), frames, expression="frown", sentence_id="s1"),
    ]
    return [
        msgspec.msgpack.encode(
            RenderRequest(
                header=Header(),
                scene=scene,
                motions=motions,
                start_frame=a,
                end_frame=b,
                width=width,
                height=height,
                encoding="mp4",
            )
        )
        for a, b in chunk_ranges(frames, ranges)
    ]


def warm(bus: Bus, service: str, payload: bytes, n: int, tag: str) -> None:
    bus.run_all(service, [payload] * n, f"warm-{tag}")


def gateway_peak(bus: Bus) -> float:
    """Peak RSS (MiB) of `wana serve --broker` editing a small office story until its compute is done."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    db = bus.tmp / "sessions.sqlite"
    gw = bus.spawn("serve", "--port", str(port), "--broker", bus.url, "--db", str(db), log="gateway")
    base = f"http://127.0.0.1:{port}"
    try:
        end = time.monotonic() + 120
        while True:
            try:
                if httpx.get(f"{base}/healthz").is_success:
                    break
            except httpx.HTTPError:
                pass
            if time.monotonic() > end or gw.poll() is not None:
                raise RuntimeError(f"the gateway did not start; see {bus.tmp}")
            time.sleep(0.2)
        story = (REPO / "examples" / "office.txt").read_text()
        httpx.post(f"{base}/api/documents", json={"text": "", "doc_id": "bench"}).raise_for_status()
        httpx.put(f"{base}/api/documents/bench/text", json={"text": story}, timeout=60).raise_for_status()
        end = time.monotonic() + 900
        while "wana_gateway_compute_seconds_count 1.0" not in httpx.get(f"{base}/metrics").text:
            if time.monotonic() > end:
                raise RuntimeError("the gateway's compute did not finish")
            time.sleep(0.5)
        return peak_rss_mb(gw.pid)
    finally:
        gw.terminate()
        try:
            gw.wait(timeout=15)
        except subprocess.TimeoutExpired:
            gw.kill()


def main(argv: list[str] | None = None) -> dict:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--quick", action="store_true", help="fewer jobs and a 120-frame video")
    p.add_argument("--json", type=Path, help="write the result here")
    p.add_argument("--workers", default="1,2,4", help="worker counts to measure (comma separated)")
    args = p.parse_args(argv)
    counts = [int(n) for n in args.workers.split(",")]
    motion_jobs = 24 if args.quick else 200
    frames = 120 if args.quick else 600
    result: dict = {
        "motion_jobs_per_s": {},
        "render_fps": {},
        "motion_jobs": motion_jobs,
        "render_frames": frames,
        "render_ranges": 4,
        "cpu_count": os.cpu_count(),
        "load_average": [round(x, 2) for x in os.getloadavg()],
    }
    bus = Bus()
    try:
        motion = motion_payloads(motion_jobs)
        render = render_payloads(frames, 4, 640, 480)
        render_warm = render_payloads(4, 1, 640, 480)[0]
        for n in counts:
            bus.workers("motion", n)
            warm(bus, "motion", motion[0], n, f"motion{n}")
            seconds = bus.run_all("motion", motion, f"motion{n}")
            result["motion_jobs_per_s"][str(n)] = round(motion_jobs / seconds, 3)
            print(f"motion  {n} workers: {motion_jobs / seconds:8.2f} jobs/s", file=sys.stderr, flush=True)
            if n != counts[-1]:
                bus.stop_workers("motion")
        for n in counts:
            bus.workers("render", n)
            warm(bus, "render", render_warm, n, f"render{n}")
            seconds = bus.run_all("render", render, f"render{n}")
            result["render_fps"][str(n)] = round(frames / seconds, 2)
            print(f"render  {n} workers: {frames / seconds:8.2f} frames/s", file=sys.stderr, flush=True)
            if n != counts[-1]:
                bus.stop_workers("render")
        for service in SERVICES:  # one of each for the gateway's compute (motion and render stay as they are)
            if service not in bus.procs:
                bus.workers(service, 1)
        result["gateway_rss_mb_peak"] = round(gateway_peak(bus), 1)
        result["worker_rss_mb_peak"] = {
            s: round(max(peak_rss_mb(p.pid) for p in bus.procs[s]), 1) for s in SERVICES
        }
    finally:
        bus.close()
    result["load_average_after"] = [round(x, 2) for x in os.getloadavg()]
    print(json.dumps(result, indent=2))
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(result, indent=2) + "\n")
    return result


if __name__ == "__main__":
    main()
