"""Fixtures for the bus tests: brokers in threads, worker processes, raw protocol peers."""

from __future__ import annotations

import collections
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Callable, Iterator
from pathlib import Path

import msgspec
import pytest
import zmq

from proto.bus import BatchFrame, Envelope
from wana.bus.broker import Broker
from wana.bus.client import Client
from wana.bus.worker import Worker

HEARTBEAT_S = 0.1  # short heartbeats keep the whole bus suite fast
WORKER_SCRIPT = Path(__file__).with_name("echo_worker.py")


@pytest.fixture
def ipc_url() -> Iterator[str]:
    """An ipc URL in a fresh, short temp dir (ipc paths are limited to ~100 bytes)."""
    tmp = tempfile.mkdtemp(prefix="wana-bus-")
    yield f"ipc://{tmp}/bus.sock"
    shutil.rmtree(tmp, ignore_errors=True)


@pytest.fixture
def make_broker() -> Iterator[Callable[..., Broker]]:
    """Start brokers in threads (heartbeat 0.1 s unless given); all are closed after the test."""
    brokers: list[Broker] = []

    def make(bind: str, **kwargs) -> Broker:
        kwargs.setdefault("heartbeat_s", HEARTBEAT_S)
        broker = Broker(bind, **kwargs)
        broker.start_thread()
        brokers.append(broker)
        return broker

    yield make
    for broker in brokers:
        broker.close()


@pytest.fixture
def make_client() -> Iterator[Callable[..., Client]]:
    clients: list[Client] = []

    def make(connect: str, **kwargs) -> Client:
        kwargs.setdefault("heartbeat_s", HEARTBEAT_S)
        client = Client(connect, **kwargs)
        clients.append(client)
        return client

    yield make
    for client in clients:
        client.close()


@pytest.fixture
def spawn_worker() -> Iterator[Callable[..., subprocess.Popen]]:
    """Start tests/unit/bus/echo_worker.py processes; any still running are killed after the test."""
    procs: list[subprocess.Popen] = []

    def spawn(url: str, *args: str) -> subprocess.Popen:
        proc = subprocess.Popen(
            [sys.executable, str(WORKER_SCRIPT), url, "--heartbeat", str(HEARTBEAT_S), *args],
            stderr=subprocess.DEVNULL,
        )
        procs.append(proc)
        return proc

    yield spawn
    for proc in procs:
        if proc.poll() is None:
            proc.send_signal(signal.SIGKILL)
        proc.wait()


def wait_for_workers(client: Client, service: str, count: int, timeout: float = 30.0) -> None:
    """Block until the broker reports ``count`` registered workers for ``service``."""
    end = time.monotonic() + timeout
    while True:
        svc = client.stats().services.get(service)
        if svc is not None and svc.workers == count:
            return
        if time.monotonic() > end:
            raise AssertionError(f"expected {count} {service} workers, broker has {svc}")
        time.sleep(0.02)


class RawPeer:
    """A bare DEALER socket speaking the bus protocol by hand, to play a misbehaving client or worker."""

    def __init__(self, url: str, context: zmq.Context | None = None):
        self.socket = (context or zmq.Context.instance()).socket(zmq.DEALER)
        self.socket.setsockopt(zmq.LINGER, 0)
        self.socket.connect(url)
        self._decoder = msgspec.msgpack.Decoder(Envelope)
        self._unbatched: collections.deque[tuple[object, list[bytes]]] = collections.deque()

    def send(self, envelope: object, *body: bytes) -> None:
        self.socket.send_multipart([msgspec.msgpack.encode(envelope), *body])

    def send_raw(self, *frames: bytes) -> None:
        self.socket.send_multipart(list(frames))

    def recv(self, timeout: float = 5.0, *, unbatch: bool = True) -> tuple[object, list[bytes]] | None:
        """Next message as (decoded envelope, body frames), or None after ``timeout`` seconds.

        A BATCH is split into its messages (returned one per call) unless ``unbatch`` is False.
        """
        if self._unbatched:
            return self._unbatched.popleft()
        if not self.socket.poll(int(timeout * 1000)):
            return None
        frames = self.socket.recv_multipart()
        envelope = self._decoder.decode(frames[0])
        if not (unbatch and isinstance(envelope, BatchFrame)):
            return envelope, frames[1:]
        for i in range(1, len(frames), 2):
            self._unbatched.append((self._decoder.decode(frames[i]), frames[i + 1 : i + 2]))
        return self._unbatched.popleft()

    def recv_all(self, seconds: float) -> list[tuple[object, list[bytes]]]:
        """Every message that arrives within ``seconds``."""
        out = []
        end = time.monotonic() + seconds
        while (left := end - time.monotonic()) > 0:
            got = self.recv(left)
            if got is not None:
                out.append(got)
        return out

    def close(self) -> None:
        self.socket.close(0)


@pytest.fixture
def raw_peer() -> Iterator[Callable[[str], RawPeer]]:
    peers: list[RawPeer] = []

    def make(url: str, context: zmq.Context | None = None) -> RawPeer:
        peer = RawPeer(url, context)
        peers.append(peer)
        return peer

    yield make
    for peer in peers:
        peer.close()


@pytest.fixture
def wait_workers() -> Callable[..., None]:
    """``wait_workers(client, service, count)``: block until the broker has that many workers."""
    return wait_for_workers


@pytest.fixture
def thread_worker() -> Iterator[Callable[..., Worker]]:
    """``thread_worker(service, handler, url, **kwargs)``: a Worker running in a thread until teardown."""
    running: list[tuple[threading.Event, threading.Thread]] = []

    def start(service: str, handler: Callable[[bytes], bytes], url: str, **kwargs) -> Worker:
        kwargs.setdefault("heartbeat_s", HEARTBEAT_S)
        worker = Worker(service, handler, url, **kwargs)
        stop = threading.Event()
        thread = threading.Thread(target=worker.run, args=(stop,), daemon=True)
        thread.start()
        running.append((stop, thread))
        return worker

    yield start
    for stop, _ in running:
        stop.set()
    for _, thread in running:
        thread.join(timeout=5)
