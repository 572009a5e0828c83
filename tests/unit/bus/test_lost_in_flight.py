"""A message lost with its connection (a reset drops what was in flight) is recovered, not waited out.

ZeroMQ reconnects by itself, but neither end learns that the bytes in flight are gone: found by
eval/chaos.py, where computes hung until their 120 s deadline. A client re-sends its pending jobs when
its connection drops, and the broker answers a re-sent job from the reply it kept; a worker registers again,
and the broker re-queues the job it thought the worker held.
"""

from __future__ import annotations

import socket
import threading
import time

import pytest

from tests.unit.bus.conftest import HEARTBEAT_S


class Relay:
    """A TCP relay to ``port`` that can swallow one large chunk in one direction and reset the connection."""

    def __init__(self, port: int) -> None:
        self.target = port
        self.server = socket.create_server(("127.0.0.1", 0))
        self.port = self.server.getsockname()[1]
        self.swallow: str = ""  # "up" (towards the target) or "down": the next chunk over 1000 bytes
        self.swallowed = 0
        self._stop = threading.Event()
        threading.Thread(target=self._accept, daemon=True).start()

    def _accept(self) -> None:
        self.server.settimeout(0.1)
        while not self._stop.is_set():
            try:
                peer, _ = self.server.accept()
            except TimeoutError:
                continue
            except OSError:  # closed
                return
            upstream = socket.create_connection(("127.0.0.1", self.target))
            for a, b, direction in ((peer, upstream, "up"), (upstream, peer, "down")):
                threading.Thread(
                    target=self._pipe, args=(a, b, direction, (peer, upstream)), daemon=True
                ).start()

    def _pipe(self, src: socket.socket, dst: socket.socket, direction: str, pair: tuple) -> None:
        try:
            while data := src.recv(65536):
                if self.swallow == direction and len(data) > 1000:
                    self.swallow = ""
                    self.swallowed += 1
                    for s in pair:  # a reset: what was in flight is gone with the connection
                        s.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, b"\x01\x00\x00\x00\x00\x00\x00\x00")
                        s.close()
                    return
                dst.sendall(data)
        except OSError:
            pass
        for s in pair:
            try:
                s.close()
            except OSError:
                pass

    def close(self) -> None:
        self._stop.set()
        self.server.close()


@pytest.fixture
def tcp_broker(make_broker):
    broker = make_broker("tcp://127.0.0.1:*")
    return broker, int(broker.endpoints[0].rsplit(":", 1)[1])


def test_a_reply_lost_with_the_clients_connection_is_delivered_again(tcp_broker, make_client, thread_worker):
    broker, port = tcp_broker
    thread_worker("echo", lambda p: (time.sleep(0.3), b"echo:" + p)[1], broker.endpoints[0])
    relay = Relay(port)
    try:
        client = make_client(f"tcp://127.0.0.1:{relay.port}")
        assert client.request("echo", b"warm", deadline_s=10) == b"echo:warm"
        relay.swallow = "down"  # the reply (the only large message to the client) is lost in flight
        started = time.monotonic()
        assert client.request("echo", b"x" * 2000, deadline_s=10) == b"echo:" + b"x" * 2000
        assert relay.swallowed == 1
        assert time.monotonic() - started < 10 * HEARTBEAT_S + 2  # recovered, not waited out
    finally:
        relay.close()


@pytest.mark.parametrize("lost", ["the JOB", "the REPLY"])
def test_a_job_or_reply_lost_with_the_workers_connection_is_run_again(
    lost, tcp_broker, make_client, thread_worker
):
    broker, port = tcp_broker
    relay = Relay(port)
    runs = []
    try:

        def handler(payload: bytes) -> bytes:
            runs.append(len(payload))
            return b"echo:" + payload

        thread_worker("echo", handler, f"tcp://127.0.0.1:{relay.port}")
        client = make_client(broker.endpoints[0])
        assert client.request("echo", b"warm", deadline_s=10) == b"echo:warm"
        relay.swallow = "down" if lost == "the JOB" else "up"
        assert client.request("echo", b"y" * 2000, deadline_s=10) == b"echo:" + b"y" * 2000
        assert relay.swallowed == 1
        assert runs.count(2000) == (1 if lost == "the JOB" else 2)
    finally:
        relay.close()
