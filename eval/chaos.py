"""Chaos run: the bus and the gateway across network namespaces, under delay, loss, kills and a partition.

    sudo .venv/bin/python eval/chaos.py --json out/eval/chaos.json [--quick]

The broker, one worker of every service and the gateway each run in a Linux network namespace of their
own (``ip netns``, one veth pair each to the root namespace), on a CURVE-keyed bus (``wana keys new``).
Nothing routes between the namespaces: every connection goes through a small asyncio TCP proxy in the root
namespace, one per namespace, which is where the network is made bad (this kernel has no ``tc netem`` and
no iptables, so impairments live in userspace, at the level of the byte stream):

- **delay**: each chunk read is delivered 20 ms +- 10 ms later (uniform), in order;
- **loss, 1 %**: TCP never loses bytes an application sees, so a lost segment is emulated as what the
  application does see, its retransmission: 1 % of chunks (and everything behind them) wait another
  200 ms (Linux's minimum RTO). Besides, 0.1 % of chunks close the connection (both ends, as a reset):
  the harsher case, which ZeroMQ and the WebSocket clients must reconnect from;
- **partition**: for 5 s a namespace's proxy forwards nothing either way, on open connections and on new
  ones (held, not refused), as a cable pulled for less than a TCP timeout.

Meanwhile several editor clients (WebSocket, through the gateway's proxy) make edits, each appending a
sentence with a unique marker; random workers are killed with SIGKILL (and restarted 1 s later, as a
supervisor would), the broker once, the gateway once, and one worker namespace is partitioned for 5 s. A
client that loses its connection mid-edit reconnects and looks for its marker in the text before sending
the edit again, as an editor must. After the run every document is read back over REST.

JSON keys: ``edits_acked``; ``edits_lost`` (acknowledged but missing from the text after recovery, must
be 0); ``replies_duplicated`` (must be 0: an acknowledgement received twice for one edit, a marker applied
twice, or a bus reply delivered twice to the probe client); ``jobs_failed_clearly`` (requests that ended
in an error with a code: WebSocket ``error`` messages and the probe's BusErrors, none hung); ``recovery_s_p95``
(per fault, the time from injecting it until every service has a worker, a parse probe through the broker
succeeds and the gateway acknowledges an edit); ``broker_rss_mb_max``. It needs root and ``ip netns`` and
says why it skips elsewhere. ``--quick`` is the 60 s version CI runs; everything is bounded by timeouts and
the namespaces and processes are removed in ``finally`` (and on SIGTERM).

This script runs to about 500 lines because the proxy, the topology, the processes, the clients and the
fault schedule must share one event loop and one clean-up; apart, each would be too small to name.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import json
import math
import os
import random
import secrets
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

PREFIX = "wch"  # namespace and veth names start with this (kept short: interface names are <= 15 bytes)
SUBNET = "10.213"  # namespace i: root side 10.213.i.1, inside 10.213.i.2
BUS_PORT = 5555
GATEWAY_PORT = 8765
DELAY_S, JITTER_S = 0.020, 0.010
LOSS_P, LOSS_STALL_S, RESET_P = 0.01, 0.200, 0.001
PARTITION_S = 5.0
RESTART_AFTER_S = 1.0
EDITS_PER_DOCUMENT = 100  # an editor moves to its next document then, so that no compute grows without end


def unavailable_reason() -> str:
    """Why this machine cannot run the chaos run ("" when it can)."""
    if not hasattr(os, "geteuid") or os.geteuid() != 0:
        return "needs root (network namespaces and veth pairs)"
    if shutil.which("ip") is None:
        return "needs the ip command (iproute2)"
    probe = subprocess.run(["ip", "netns", "list"], capture_output=True, text=True, check=False)
    if probe.returncode != 0:
        return f"ip netns is not available: {probe.stderr.strip()}"
    return ""


def sh(*args: str, check: bool = True) -> None:
    subprocess.run(list(args), check=check, capture_output=True, timeout=30)


# ------------------------------------------------------------------------------------------- network


class Namespace:
    """One network namespace with a veth pair to the root namespace (root side .1, inside .2)."""

    def __init__(self, name: str, index: int) -> None:
        self.name, self.index = f"{PREFIX}-{name}", index
        self.outer, self.inner = f"{SUBNET}.{index}.1", f"{SUBNET}.{index}.2"
        self.veth = f"{PREFIX}{index}"

    def create(self) -> None:
        sh("ip", "netns", "add", self.name)
        sh("ip", "link", "add", self.veth, "type", "veth", "peer", "name", f"{self.veth}p")
        sh("ip", "link", "set", f"{self.veth}p", "netns", self.name)
        sh("ip", "addr", "add", f"{self.outer}/24", "dev", self.veth)
        sh("ip", "link", "set", self.veth, "up")
        inside = ("ip", "netns", "exec", self.name)
        sh(*inside, "ip", "addr", "add", f"{self.inner}/24", "dev", f"{self.veth}p")
        sh(*inside, "ip", "link", "set", f"{self.veth}p", "up")
        sh(*inside, "ip", "link", "set", "lo", "up")

    def delete(self) -> None:
        sh("ip", "link", "del", self.veth, check=False)
        sh("ip", "netns", "del", self.name, check=False)


def remove_leftovers() -> None:
    """Namespaces and links of an earlier run of this script (our prefix only)."""
    listed = subprocess.run(["ip", "netns", "list"], capture_output=True, text=True, check=False).stdout
    for line in listed.splitlines():
        name = line.split()[0] if line.split() else ""
        if name.startswith(f"{PREFIX}-"):
            sh("ip", "netns", "del", name, check=False)


@dataclass
class Proxy:
    """A TCP proxy that delays, stalls ("loses") and resets chunks, and can partition its connections."""

    listen: tuple[str, int]
    target: tuple[str, int]
    rng: random.Random
    healed: asyncio.Event = field(default_factory=asyncio.Event)
    resets: int = 0
    stalls: int = 0
    _server: asyncio.AbstractServer | None = None
    _writers: set[asyncio.StreamWriter] = field(default_factory=set)

    async def start(self) -> None:
        self.healed.set()
        self._server = await asyncio.start_server(self._accept, *self.listen, reuse_address=True)

    async def close(self) -> None:
        if self._server is not None:
            self._server.close()
        for w in list(self._writers):
            w.transport.abort()

    async def partition(self, seconds: float) -> None:
        self.healed.clear()
        await asyncio.sleep(seconds)
        self.healed.set()

    async def _accept(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        with contextlib.suppress(asyncio.CancelledError):  # the run is over: nothing to report
            await self._serve(reader, writer)

    async def _serve(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        await self.healed.wait()  # a new connection during a partition is held, not refused
        try:
            up_reader, up_writer = await asyncio.wait_for(asyncio.open_connection(*self.target), 5)
        except (TimeoutError, OSError):
            writer.transport.abort()
            return
        self._writers |= {writer, up_writer}
        pair = (writer, up_writer)
        await asyncio.gather(
            self._pipe(reader, up_writer, pair), self._pipe(up_reader, writer, pair), return_exceptions=True
        )
        for w in pair:
            self._writers.discard(w)
            w.transport.abort()

    async def _pipe(
        self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter, pair: tuple[Any, Any]
    ) -> None:
        queue: asyncio.Queue[tuple[float, bytes]] = asyncio.Queue()
        deliver = asyncio.get_running_loop().create_task(self._deliver(queue, writer))
        last = 0.0
        try:
            while chunk := await reader.read(65536):
                if self.rng.random() < RESET_P:
                    self.resets += 1
                    for w in pair:
                        w.transport.abort()
                    return
                at = time.monotonic() + DELAY_S + self.rng.uniform(-JITTER_S, JITTER_S)
                if self.rng.random() < LOSS_P:
                    self.stalls += 1
                    at += LOSS_STALL_S
                last = max(last, at)  # in order: nothing overtakes a stalled chunk
                queue.put_nowait((last, chunk))
        finally:
            queue.put_nowait((0.0, b""))
            with contextlib.suppress(Exception, asyncio.CancelledError):
                await deliver

    async def _deliver(self, queue: asyncio.Queue[tuple[float, bytes]], writer: asyncio.StreamWriter) -> None:
        while True:
            at, chunk = await queue.get()
            if not chunk:
                writer.transport.abort()
                return
            await asyncio.sleep(max(0.0, at - time.monotonic()))
            await self.healed.wait()
            writer.write(chunk)
            await writer.drain()


async def _through_resets(send: Any, tries: int = 5) -> Any:
    """The set-up and read-back requests of the run itself, sent again when the faulty proxy resets them.

    The proxy resets one chunk in a thousand on purpose; that is the editors' weather, not the harness's: a
    seed document lost to a reset would end the run before it measured anything. (A reset POST may leave an
    unused document behind; the run only reads the ones it got an id for.)
    """
    import httpx

    for attempt in range(tries):
        try:
            return await send()
        except httpx.TransportError:
            if attempt == tries - 1:
                raise
            await asyncio.sleep(0.5)
    raise AssertionError("unreachable")


# ----------------------------------------------------------------------------------------- processes


@dataclass
class Component:
    """A process of the bus or the gateway, run in its namespace and restarted on demand."""

    name: str
    ns: Namespace
    argv: list[str]
    log: Path
    env: dict[str, str]
    proc: subprocess.Popen[bytes] | None = None

    def start(self) -> None:
        with open(self.log, "ab") as out:
            self.proc = subprocess.Popen(
                ["ip", "netns", "exec", self.ns.name, sys.executable, "-m", "wana.cli", *self.argv],
                cwd=REPO,
                env=self.env,
                stdout=out,
                stderr=subprocess.STDOUT,
            )

    def kill(self) -> None:
        if self.proc is not None and self.proc.poll() is None:
            os.kill(self.proc.pid, signal.SIGKILL)  # ip netns exec execs the command: this is its pid
            self.proc.wait(timeout=10)

    def rss_mb(self) -> float:
        if self.proc is None or self.proc.poll() is not None:
            return 0.0
        try:
            for line in Path(f"/proc/{self.proc.pid}/status").read_text().splitlines():
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) / 1024.0
        except OSError:
            pass
        return 0.0


# ---------------------------------------------------------------------------------------- the clients


@dataclass
class Tally:
    acked: dict[str, str] = field(default_factory=dict)  # marker -> document id
    ack_counts: dict[str, int] = field(default_factory=dict)  # marker -> acks received
    failed_clearly: int = 0
    probe_duplicates: int = 0
    recoveries: list[float] = field(default_factory=list)
    faults: list[str] = field(default_factory=list)
    rss_max: float = 0.0


class Editor:
    """One editor client: appends marked sentences to its document, one at a time, surviving outages, and
    moves to its next document after EDITS_PER_DOCUMENT."""

    def __init__(self, index: int, url: str, docs: list[str], token: str, tally: Tally, rng: random.Random):
        self.index, self.url, self.docs, self.token = index, url, docs, token
        self.doc_id, self.in_doc = docs[0], 0
        self.tally, self.rng = tally, rng
        self.sent = 0  # markers made so far (an edit re-sent after an outage keeps its marker)

    async def run(self, until: float) -> None:
        from websockets.asyncio.client import connect

        pending: str | None = None  # the marker of an edit sent but not acknowledged
        while time.monotonic() < until:
            try:
                async with connect(
                    f"{self.url}/api/documents/{self.doc_id}/live",
                    additional_headers={"Authorization": f"Bearer {self.token}"},
                    open_timeout=5,
                    max_size=None,
                ) as ws:
                    state = await self._next(ws, "state", 10)
                    version, text = state["version"], state["text"]
                    while time.monotonic() < until:
                        if pending is not None and f" {pending}." in text:
                            pending = None  # it was applied before the connection went: not sent again
                        marker = pending or f"m{self.index}x{self.sent}"
                        self.sent += 0 if pending else 1
                        pending = marker
                        sentence = f" Eve waves at {marker}."
                        await ws.send(
                            json.dumps(
                                {
                                    "type": "edit",
                                    "base_version": version,
                                    "client_seq": self.sent,
                                    "changes": [{"start": len(text), "end": len(text), "text": sentence}],
                                }
                            )
                        )
                        reply = await self._next(ws, ("ack", "stale"), 10)
                        if reply["type"] == "stale":
                            version, text = reply["current_version"], reply["text"]
                            continue
                        self.tally.ack_counts[marker] = self.tally.ack_counts.get(marker, 0) + 1
                        if self.tally.ack_counts[marker] == 1:
                            self.tally.acked[marker] = self.doc_id
                        pending = None
                        version, text = reply["version"], text + sentence
                        self.in_doc += 1
                        await asyncio.sleep(self.rng.uniform(0.3, 0.8))
                        if self.in_doc >= EDITS_PER_DOCUMENT and self.doc_id != self.docs[-1]:
                            self.doc_id, self.in_doc = self.docs[self.docs.index(self.doc_id) + 1], 0
                            break  # connect to the next document
            except Exception as exc:  # noqa: BLE001 - any outage: reconnect
                if not _is_outage(exc):
                    raise
                await asyncio.sleep(self.rng.uniform(0.2, 0.6))

    async def _next(self, ws: Any, kinds: Any, timeout: float) -> dict[str, Any]:
        kinds = (kinds,) if isinstance(kinds, str) else kinds
        deadline = time.monotonic() + timeout
        while True:
            msg = json.loads(await asyncio.wait_for(ws.recv(), max(deadline - time.monotonic(), 0.01)))
            if msg["type"] == "error":
                self.tally.failed_clearly += 1
            if msg["type"] in kinds:
                return msg


def _is_outage(exc: BaseException) -> bool:
    from websockets.exceptions import WebSocketException

    return isinstance(exc, (OSError, TimeoutError, WebSocketException, EOFError, KeyError))


def counting_client(url: str, keys: Path) -> Any:
    """A bus Client that counts replies the broker sent twice for one job it was asked once.

    A job the client re-sent (its connection dropped, or the broker went silent) may be answered again,
    by design: the client cannot tell a lost reply from one still on its way, and drops the second one.
    Those are counted apart (``redelivered``); a second reply to a job sent once is a duplicate.
    """
    from proto.bus import ErrorFrame, ReplyFrame
    from wana.bus.client import Client

    class CountingClient(Client):
        answered: set[str]
        resent_ids: set[str]
        duplicates = 0
        redelivered = 0

        def _on_pong(self, instance: str, seq: int) -> None:
            before = {j: p.request for j, p in self._pending.items()}
            super()._on_pong(instance, seq)
            self.resent_ids |= {j for j, p in self._pending.items() if p.request is not before.get(j)}

        def _on_message(self, msg: Any, body: Any) -> None:
            if type(msg) in (ReplyFrame, ErrorFrame):
                if msg.job_id in self.answered:
                    if msg.job_id in self.resent_ids:
                        self.redelivered += 1
                    else:
                        self.duplicates += 1
                        print(f"chaos: a second {type(msg).__name__} for job {msg.job_id}", file=sys.stderr)
                elif msg.job_id in self._pending:
                    self.answered.add(msg.job_id)
            super()._on_message(msg, body)

    client = CountingClient(url, keys=keys)
    client.answered, client.resent_ids = set(), set()
    return client


# -------------------------------------------------------------------------------------------- the run


class Chaos:
    def __init__(self, quick: bool, seed: int, workdir: Path) -> None:
        from services.orchestrator.registry import SERVICES

        self.quick, self.rng, self.dir = quick, random.Random(seed), workdir
        self.services = SERVICES
        self.token = secrets.token_hex(16)
        self.keys = workdir / "keys"
        self.spaces = {"broker": Namespace("broker", 1), "gateway": Namespace("gw", 2)}
        for i, service in enumerate(self.services):
            self.spaces[service] = Namespace(service[:8], 10 + i)
        self.proxies: dict[str, Proxy] = {}
        self.components: dict[str, Component] = {}
        self.tally = Tally()
        self.probe: Any = None  # the readiness checks' bus client
        self.load: Any = None  # a steady stream of parse requests through the broker, all run long
        self.load_results: dict[str, int] = {}
        self.computed = 0
        self.not_ready = ""
        self.plan_rng = random.Random(seed + 1)  # the fault schedule, apart from the proxies' draws

    # -- set-up ------------------------------------------------------------------------------------
    def _env(self) -> dict[str, str]:
        return dict(
            os.environ, PYTHONPATH=str(REPO), WANA_BUS_HEARTBEAT_S="1.0", WANA_BUS_KEYS=str(self.keys)
        )

    async def setup(self) -> None:
        from wana.bus.curve import new_keys

        new_keys(self.keys)
        remove_leftovers()
        for ns in self.spaces.values():
            ns.create()
        broker = self.spaces["broker"]
        for name, ns in self.spaces.items():  # each namespace reaches the broker through its own proxy
            if name != "broker":
                self.proxies[name] = Proxy((ns.outer, BUS_PORT), (broker.inner, BUS_PORT), self.rng)
        self.proxies["probe"] = Proxy(("127.0.0.1", 0), (broker.inner, BUS_PORT), self.rng)
        self.proxies["editors"] = Proxy(
            ("127.0.0.1", 0), (self.spaces["gateway"].inner, GATEWAY_PORT), self.rng
        )
        for p in self.proxies.values():
            await p.start()
        env, logs = self._env(), self.dir / "logs"
        logs.mkdir()
        self.components["broker"] = Component(
            "broker",
            broker,
            ["broker", "--bind", f"tcp://{broker.inner}:{BUS_PORT}", "--keys", str(self.keys)],
            logs / "broker.log",
            env,
        )
        for service in self.services:
            ns = self.spaces[service]
            self.components[service] = Component(
                service,
                ns,
                ["worker", service, "--connect", f"tcp://{ns.outer}:{BUS_PORT}"],
                logs / f"{service}.log",
                env,
            )
        gw = self.spaces["gateway"]
        self.components["gateway"] = Component(
            "gateway",
            gw,
            [
                "serve",
                "--host",
                gw.inner,
                "--port",
                str(GATEWAY_PORT),
                "--backend",
                "remote",
                "--broker",
                f"tcp://{gw.outer}:{BUS_PORT}",
                "--db",
                str(self.dir / "sessions.sqlite"),
                "--log-level",
                "warning",
            ],
            logs / "gateway.log",
            dict(env, WANA_TOKEN=self.token),
        )
        for c in self.components.values():
            c.start()
        port = self.proxies["probe"]._server.sockets[0].getsockname()[1]  # type: ignore[union-attr]
        self.probe = counting_client(f"tcp://127.0.0.1:{port}", self.keys)
        self.load = counting_client(f"tcp://127.0.0.1:{port}", self.keys)
        await self._until(self._ready, 240, "every service and the gateway to come up")

    def _editors_url(self) -> str:
        port = self.proxies["editors"]._server.sockets[0].getsockname()[1]  # type: ignore[union-attr]
        return f"ws://127.0.0.1:{port}"

    async def _until(self, check: Any, timeout: float, what: str) -> float:
        started = time.monotonic()
        while not await check():
            if time.monotonic() - started > timeout:
                raise TimeoutError(f"waited {timeout:.0f} s for {what}: {self.not_ready}")
            await asyncio.sleep(0.2)
        return time.monotonic() - started

    async def _ready(self) -> bool:
        """Every service has a worker, a parse goes through the broker and the gateway answers."""
        return await asyncio.to_thread(self._ready_sync)

    def _ready_sync(self) -> bool:
        import httpx
        import msgspec

        from proto.common import Header
        from proto.nlp import ParseReply, ParseRequest
        from wana.bus.client import BusError

        self.not_ready = "the broker's STATS did not come"
        try:
            services = self.probe.stats(timeout=2.0).services
            missing = [s for s in self.services if services.get(s) is None or services[s].workers < 1]
            if missing:
                self.not_ready = f"no worker registered for {', '.join(missing)}"
                return False
            self.not_ready = f"a parse through the broker failed (nlp: {services['nlp']})"
            request = ParseRequest(header=Header(), sentence_id="probe", text="Eve waves.")
            reply = self.probe.request("nlp", msgspec.msgpack.encode(request), deadline_s=5)
            msgspec.msgpack.decode(reply, type=ParseReply)
        except BusError as exc:
            self.not_ready += f" ({exc})"
            if exc.code not in ("E006",):  # a deadline while recovering is waiting, not a clear failure
                self.tally.failed_clearly += 1
            return False
        except Exception:  # noqa: BLE001 - stats timed out: not ready yet
            return False
        self.not_ready = "the gateway's /api/health did not answer 200"
        url = self._editors_url().replace("ws://", "http://")
        try:
            r = httpx.get(f"{url}/api/health", headers={"Authorization": f"Bearer {self.token}"}, timeout=3)
        except httpx.HTTPError:
            return False
        return r.status_code == 200

    # -- faults ------------------------------------------------------------------------------------
    async def _restart(self, name: str) -> None:
        self.components[name].kill()
        await asyncio.sleep(RESTART_AFTER_S)
        self.components[name].start()

    async def fault(self, kind: str, target: str) -> None:
        started = time.monotonic()
        self.tally.faults.append(f"{kind} {target}")
        if kind == "kill":
            await self._restart(target)
        elif kind == "partition":
            await self.proxies[target].partition(PARTITION_S)
        await self._until(self._ready, 180, f"recovery from {kind} {target}")
        self.tally.recoveries.append(time.monotonic() - started)
        print(f"chaos: {kind} {target}: recovered in {self.tally.recoveries[-1]:.1f} s", file=sys.stderr)

    def schedule(self, seconds: float) -> list[tuple[float, str, str]]:
        """(time, kind, target): worker kills spread over the run, the broker, the gateway and a partition once."""
        workers = list(self.services)
        plan = [
            (0.10, "kill", self.plan_rng.choice(workers)),
            (0.25, "kill", "broker"),
            (0.40, "partition", self.plan_rng.choice(workers)),
            (0.55, "kill", self.plan_rng.choice(workers)),
            (0.70, "kill", "gateway"),
            (0.85, "kill", self.plan_rng.choice(workers)),
        ]
        if not self.quick:
            plan += [(f + 0.05, "kill", self.plan_rng.choice(workers)) for f in (0.15, 0.3, 0.45, 0.6, 0.75)]
        return sorted((f * seconds, kind, target) for f, kind, target in plan)

    def _load_sync(self, until: float) -> None:
        """Parse requests one after another until ``until``: each gets a reply or an error with a code."""
        import msgspec

        from proto.common import Header
        from proto.nlp import ParseRequest
        from wana.bus.client import BusError

        i = 0
        while time.monotonic() < until:
            i += 1
            request = ParseRequest(header=Header(), sentence_id=f"load{i}", text=f"Tom sits on chair {i}.")
            try:
                self.load.request("nlp", msgspec.msgpack.encode(request), deadline_s=15)
                outcome = "ok"
            except BusError as exc:
                outcome = exc.code
                self.tally.failed_clearly += 1
            self.load_results[outcome] = self.load_results.get(outcome, 0) + 1
            time.sleep(0.1)

    async def _sample_rss(self, until: float) -> None:
        while time.monotonic() < until:
            self.tally.rss_max = max(self.tally.rss_max, self.components["broker"].rss_mb())
            await asyncio.sleep(0.5)

    # -- run ---------------------------------------------------------------------------------------
    async def run(self, seconds: float, n_editors: int) -> dict[str, Any]:
        import httpx

        await self.setup()
        base = self._editors_url().replace("ws://", "http://")
        headers = {"Authorization": f"Bearer {self.token}"}
        async with httpx.AsyncClient(base_url=base, headers=headers, timeout=20) as http:
            seed_text = "In the office there is a desk near a window$. A chair is in front of the desk$."
            per_editor = max(1, math.ceil(seconds / 60))  # at about 1.6 edits a second, <= 100 each
            docs = [
                [
                    (
                        await _through_resets(lambda: http.post("/api/documents", json={"text": seed_text}))
                    ).json()["doc_id"]
                    for _ in range(per_editor)
                ]
                for _ in range(n_editors)
            ]
        start = time.monotonic()
        until = start + seconds
        editors = [
            Editor(i, self._editors_url(), d, self.token, self.tally, random.Random(i))
            for i, d in enumerate(docs)
        ]
        tasks = [asyncio.create_task(e.run(until)) for e in editors]
        tasks.append(asyncio.create_task(asyncio.to_thread(self._load_sync, until)))
        tasks.append(asyncio.create_task(self._sample_rss(until + 30)))
        for at, kind, target in self.schedule(seconds):
            await asyncio.sleep(max(0.0, start + at - time.monotonic()))
            await self.fault(kind, target)
        await asyncio.gather(*tasks[:-1])
        await self._until(self._ready, 180, "the final recovery")
        tasks[-1].cancel()
        texts: dict[str, str] = {}
        async with httpx.AsyncClient(base_url=base, headers=headers, timeout=20) as http:
            for d in (d for mine in docs for d in mine):
                texts[d] = (await _through_resets(lambda d=d: http.get(f"/api/documents/{d}"))).json()["text"]
        # Every document's newest version must get its animation; after the gateway's restart each is a
        # cold compute, two at a time (WANA_COMPUTE_THREADS), so the wait grows with their number.
        wait_s = 120.0 + 30.0 * len(texts)
        self.computed = sum(await asyncio.gather(*(self._computes(d, wait_s) for d in texts)))
        return self.result(texts)

    async def _computes(self, doc_id: str, wait_s: float) -> bool:
        """True when the document's newest version gets its animation after the run (no compute hung)."""
        from websockets.asyncio.client import connect

        deadline = time.monotonic() + wait_s
        while time.monotonic() < deadline:  # a connection the proxy resets is opened again, not a failure
            with contextlib.suppress(Exception):
                async with connect(
                    f"{self._editors_url()}/api/documents/{doc_id}/live",
                    additional_headers={"Authorization": f"Bearer {self.token}"},
                    open_timeout=10,
                    max_size=None,
                ) as ws:
                    version = -1
                    while time.monotonic() < deadline:
                        msg = json.loads(await asyncio.wait_for(ws.recv(), deadline - time.monotonic()))
                        last = {
                            k: v
                            for k, v in msg.items()
                            if k in ("type", "version", "stage", "done", "total", "code", "message")
                        }
                        if msg["type"] == "state":
                            version = msg["version"]
                        elif msg["type"] == "animation" and msg["version"] == version:
                            return True
            await asyncio.sleep(0.5)
        stats = await asyncio.to_thread(lambda: self.probe.stats(timeout=5.0))
        busy = {n: (s.workers, s.queued, s.in_flight) for n, s in stats.services.items()}
        print(
            f"chaos: document {doc_id} not animated; last message {locals().get('last')}; broker "
            f"(workers, queued, in flight) {busy}",
            file=sys.stderr,
        )
        return False

    def result(self, texts: dict[str, str]) -> dict[str, Any]:
        t = self.tally
        lost = [m for m, doc in t.acked.items() if f" {m}." not in texts[doc]]
        applied_twice = sum(max(0, text.count(f" {m}.") - 1) for text in texts.values() for m in t.ack_counts)
        acked_twice = sum(n - 1 for n in t.ack_counts.values() if n > 1)
        recoveries = sorted(t.recoveries)
        p95 = (
            recoveries[min(len(recoveries) - 1, int(round(0.95 * (len(recoveries) - 1))))]
            if recoveries
            else 0.0
        )
        print(
            f"chaos: faults {t.faults}; recoveries {[round(r, 1) for r in t.recoveries]} s; proxy resets "
            f"{sum(p.resets for p in self.proxies.values())}, stalls {sum(p.stalls for p in self.proxies.values())}",
            file=sys.stderr,
        )
        print(
            f"chaos: probe parses {self.load_results}; documents animated after the run {self.computed} of "
            f"{len(texts)}",
            file=sys.stderr,
        )
        t.probe_duplicates = self.probe.duplicates + self.load.duplicates
        print(
            f"chaos: duplicates: edits applied twice {applied_twice}, acks twice {acked_twice}, bus replies "
            f"twice {t.probe_duplicates}; replies to re-sent jobs answered again (dropped by the client) "
            f"{self.probe.redelivered + self.load.redelivered}",
            file=sys.stderr,
        )
        if lost:
            print(f"chaos: acknowledged edits missing: {lost[:20]}", file=sys.stderr)
        return {
            "edits_acked": len(t.acked),
            "edits_lost": len(lost),
            "replies_duplicated": applied_twice + acked_twice + t.probe_duplicates,
            "jobs_failed_clearly": t.failed_clearly,
            "recovery_s_p95": round(p95, 2),
            "broker_rss_mb_max": round(t.rss_max, 1),
        }

    async def teardown(self) -> None:
        for client in (self.probe, self.load):
            if client is not None:
                client.close()
        for c in self.components.values():
            with contextlib.suppress(Exception):
                c.kill()
        for p in self.proxies.values():
            await p.close()
        for ns in self.spaces.values():
            ns.delete()


async def _main(args: argparse.Namespace) -> dict[str, Any]:
    workdir = Path(tempfile.mkdtemp(prefix="wana-chaos-"))
    chaos = Chaos(args.quick, args.seed, workdir)
    loop = asyncio.get_running_loop()
    task = asyncio.current_task()
    loop.add_signal_handler(signal.SIGTERM, lambda: task.cancel() if task else None)
    try:
        seconds = 60.0 if args.quick else float(args.seconds)
        return await asyncio.wait_for(chaos.run(seconds, args.editors), timeout=seconds + 1500)
    finally:
        await chaos.teardown()
        if args.keep_logs:
            print(f"chaos: logs in {workdir / 'logs'}", file=sys.stderr)
        else:
            shutil.rmtree(workdir, ignore_errors=True)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--json", type=Path, help="write the result here")
    p.add_argument("--quick", action="store_true", help="the 60 s version (CI)")
    p.add_argument("--seconds", type=float, default=300.0, help="length of the full run (default 300)")
    p.add_argument("--editors", type=int, default=4, help="editor clients, one document each (default 4)")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument(
        "--keep-logs", action="store_true", help="keep the processes' logs (their folder is printed)"
    )
    args = p.parse_args(argv)
    why = unavailable_reason()
    if why:
        print(f"chaos: skipped: {why}", file=sys.stderr)
        return 0
    result = asyncio.run(_main(args))
    text = json.dumps(result, indent=2)
    print(text)
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(text + "\n")
    good = result["edits_lost"] == 0 and result["replies_duplicated"] == 0
    return 0 if good else 1


if __name__ == "__main__":
    sys.exit(main())
