"""Scale-out as the README describes it: `wana broker` and `wana worker` processes joined over tcp."""

from __future__ import annotations

import os
import socket
import subprocess
import sys
import time

import msgspec
import pytest

from proto.common import Header
from proto.nlp import ParseReply, ParseRequest
from wana.bus.client import Client

pytestmark = [pytest.mark.integration, pytest.mark.slow]


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def spawn(*args: str) -> subprocess.Popen[bytes]:
    env = dict(os.environ, WANA_BUS_HEARTBEAT_S="0.2")
    return subprocess.Popen(
        [sys.executable, "-m", "wana.cli", *args], env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE
    )


def test_the_cli_broker_and_two_workers_answer_parse_requests_over_tcp():
    url = f"tcp://127.0.0.1:{free_port()}"
    procs = [spawn("broker", "--bind", url)]
    try:
        time.sleep(0.5)
        procs += [spawn("worker", "nlp", "--connect", url) for _ in range(2)]
        client = Client(url)
        decoder = msgspec.msgpack.Decoder(ParseReply)
        try:
            texts = ["Eve sits on the chair.", "A lamp is on the desk$.", "camera top"]
            for text in texts:
                request = ParseRequest(header=Header(), sentence_id="s1", text=text)
                reply = decoder.decode(client.request("nlp", msgspec.msgpack.encode(request), deadline_s=120))
                assert reply.status == "ok"
                assert reply.graph.text == text
            kinds = [
                decoder.decode(
                    client.request(
                        "nlp",
                        msgspec.msgpack.encode(ParseRequest(header=Header(), sentence_id="x", text=t)),
                        deadline_s=120,
                    )
                ).graph.kind
                for t in texts
            ]
            assert kinds == ["action", "scene", "command"]
        finally:
            client.close()
    finally:
        for p in procs:
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                p.kill()
    for p in procs:
        assert p.returncode in (0, -15), p.stderr.read().decode() if p.stderr else ""


def test_the_orchestrator_reaches_remote_workers_from_several_threads():
    from concurrent.futures import ThreadPoolExecutor

    from services.orchestrator.backend import RemoteBusBackend
    from services.orchestrator.session import Orchestrator

    url = f"tcp://127.0.0.1:{free_port()}"
    procs = [spawn("broker", "--bind", url)]
    try:
        time.sleep(0.5)
        procs += [
            spawn("worker", service, "--connect", url) for service in ("nlp", "retrieval", "motion", "social")
        ]
        backend = RemoteBusBackend(url)
        orchestrator = Orchestrator(":memory:", backend)
        try:
            stories = ["A chair is near a desk$. Eve walks to the chair.", "Tom waves. Tom sits."]
            sessions = [orchestrator.create(text) for text in stories]
            with ThreadPoolExecutor(2) as pool:
                results = list(pool.map(lambda s: s.compute(stages=("parse", "scene", "motion")), sessions))
            assert [sorted(r.motions) for r in results] == [["Eve"], ["Tom"]]
            assert all(not r.unavailable for r in results)
        finally:
            backend.close()
            orchestrator.close()
    finally:
        for p in procs:
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                p.kill()
