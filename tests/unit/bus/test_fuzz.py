"""Property tests over the bus's decode paths: whatever arrives, the broker and workers stay up and answer.

Hostile input comes in four shapes: random bytes, random msgpack of every type (with lying size
claims in raw bytes), valid envelopes with hostile field values, and wrong frame counts. The
coverage-guided counterpart is eval/fuzz_bus.py (atheris).
"""

from __future__ import annotations

import os
import shutil
import tempfile
import threading
import time
from collections.abc import Iterator

import msgspec
import pytest
import zmq
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from proto.bus import EchoReply, EchoRequest, Envelope, PingFrame
from proto.common import ErrorReply, Header
from wana.bus import wire
from wana.bus.broker import Broker
from wana.bus.client import Client
from wana.bus.echo import CONTRACT
from wana.bus.service import make_frame_handler
from wana.bus.worker import Worker

HEARTBEAT_S = 0.1
FUZZ = settings(
    max_examples=int(os.environ.get("WANA_FUZZ_EXAMPLES", "150")),
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)
COMMANDS = [
    "READY",
    "REQUEST",
    "JOB",
    "REPLY",
    "ERROR",
    "BATCH",
    "HEARTBEAT",
    "DISCONNECT",
    "PING",
    "PONG",
    "STATS",
]

hostile_ints = st.one_of(
    st.integers(min_value=-(2**63), max_value=2**64 - 1),
    st.sampled_from([0, -1, 1, 2**31, 2**53, 2**53 + 1, 2**63 - 1, 2**64 - 1, -(2**63)]),
)
hostile_strs = st.one_of(st.text(max_size=40), st.sampled_from(["", "x" * 65, "x" * 129, "é" * 300, "\x00"]))
msgpack_values = st.recursive(
    st.none() | st.booleans() | hostile_ints | st.floats() | hostile_strs | st.binary(max_size=64),
    lambda inner: st.lists(inner, max_size=6) | st.dictionaries(hostile_strs, inner, max_size=4),
    max_leaves=20,
)
# Raw msgpack heads that claim more than follows (str/bin/array/map 32 with huge lengths).
lying_heads = st.sampled_from(
    [
        b"\xdb\xff\xff\xff\xff",
        b"\xc6\xff\xff\xff\xff",
        b"\xdd\xff\xff\xff\xff",
        b"\xdf\x7f\xff\xff\xff",
        b"\x91\xa1\xff",
    ]
)


@st.composite
def hostile_envelopes(draw) -> bytes:
    """A msgpack array whose first element is a bus command (or near one) and whose fields are hostile."""
    command = draw(st.sampled_from(COMMANDS) | hostile_strs)
    fields = draw(st.lists(msgpack_values, max_size=8))
    return msgspec.msgpack.encode([command, *fields])


frames_strategy = st.lists(
    st.one_of(
        st.binary(max_size=80),
        msgpack_values.map(msgspec.msgpack.encode),
        hostile_envelopes(),
        st.tuples(lying_heads, st.binary(max_size=16)).map(lambda t: t[0] + t[1]),
    ),
    min_size=1,
    max_size=6,
)


@pytest.fixture(scope="module")
def bus() -> Iterator[tuple[Broker, str]]:
    """One broker with a real echo worker (the contract's frame handler) on an ipc socket."""
    tmp = tempfile.mkdtemp(prefix="wana-fuzz-")
    url = f"ipc://{tmp}/bus.sock"
    broker = Broker(url, heartbeat_s=HEARTBEAT_S)
    broker.start_thread()
    worker = Worker("echo", make_frame_handler(CONTRACT), url, heartbeat_s=HEARTBEAT_S)
    stop = threading.Event()
    thread = threading.Thread(target=worker.run, args=(stop,), daemon=True)
    thread.start()
    yield broker, url
    stop.set()
    thread.join(timeout=5)
    broker.close()
    shutil.rmtree(tmp, ignore_errors=True)


@pytest.fixture(scope="module")
def peer(bus) -> Iterator[zmq.Socket]:
    sock = zmq.Context.instance().socket(zmq.DEALER)
    sock.setsockopt(zmq.LINGER, 0)
    sock.connect(bus[1])
    yield sock
    sock.close(0)


def _answers_ping(sock: zmq.Socket, seq: int) -> bool:
    """Send a PING; read until its PONG (other answers to the fuzz input are skipped)."""
    sock.send(msgspec.msgpack.encode(PingFrame(seq)))
    end = time.monotonic() + 5.0
    decoder = msgspec.msgpack.Decoder()
    while time.monotonic() < end:
        if not sock.poll(100):
            continue
        frames = sock.recv_multipart()
        head = decoder.decode(frames[0])
        if isinstance(head, list) and head[:1] == ["PONG"] and head[2:3] == [seq]:
            return True
    return False


_seq = iter(range(1, 10**9))


@FUZZ
@given(frames=frames_strategy)
def test_the_broker_survives_any_frames_and_still_answers(bus, peer, frames):
    broker, _ = bus
    peer.send_multipart(frames)
    assert _answers_ping(peer, next(_seq))
    assert broker._thread is not None and broker._thread.is_alive()
    assert not broker._failures, broker._failures  # the guard never had to catch anything


@FUZZ
@given(
    deadline_ms=hostile_ints,
    doc_id=hostile_strs,
    revision=hostile_ints,
    attempt=hostile_ints,
    job_id=hostile_strs,
    extra_frames=st.integers(min_value=0, max_value=3),
)
def test_every_request_with_hostile_values_gets_a_reply_or_an_error(
    bus, peer, deadline_ms, doc_id, revision, attempt, job_id, extra_frames
):
    broker, _ = bus
    job_id = f"{next(_seq)}-{job_id}"
    envelope = msgspec.msgpack.encode(
        ["REQUEST", "echo", job_id, "k", attempt, deadline_ms, doc_id, revision]
    )
    body = msgspec.msgpack.encode(EchoRequest(header=Header(), text="hi"))
    peer.send_multipart([envelope, *([body] * extra_frames)])
    end = time.monotonic() + 5.0
    got = None
    decoder = msgspec.msgpack.Decoder()
    while time.monotonic() < end and got is None:
        if peer.poll(100):
            frames = peer.recv_multipart()
            head = decoder.decode(frames[0])
            if head[0] in ("REPLY", "ERROR") and head[1] in (job_id, job_id[:128], ""):
                got = head[0]
            elif head[0] == "BATCH":
                got = "BATCH"
    assert got is not None, "no reply and no error before the deadline"
    assert not broker._failures, broker._failures


@FUZZ
@given(payload=st.one_of(st.binary(max_size=200), msgpack_values.map(msgspec.msgpack.encode)))
def test_the_echo_worker_answers_any_payload_with_a_reply_or_an_error(bus, payload):
    _, url = bus
    with Client(url, heartbeat_s=HEARTBEAT_S) as client:
        reply = client.request("echo", payload, deadline_s=10)
    decoded = msgspec.msgpack.decode(reply, type=EchoReply | ErrorReply)
    if isinstance(decoded, ErrorReply):
        assert decoded.code in ("E001", "E010", "E012")


@FUZZ
@given(frames=frames_strategy)
def test_a_worker_or_client_reading_any_frames_from_its_broker_never_raises(frames):
    ctx = zmq.Context.instance()
    url = f"inproc://fuzz-{os.getpid()}-{time.monotonic_ns()}"
    a, b = ctx.socket(zmq.PAIR), ctx.socket(zmq.PAIR)
    try:
        a.bind(url)
        b.connect(url)
        a.send_multipart(frames)
        assert wire.poll(b, 2.0)
        got = wire.recv_from_broker(b)
        assert got is not None
        msg, _ = got
        assert isinstance(msg, (wire.Undecodable, *Envelope.__args__))
        assert not wire.readable(b)  # the whole message was consumed, whatever its shape
    finally:
        a.close(0)
        b.close(0)


def test_a_valid_job_still_works_after_the_fuzzing(bus):
    _, url = bus
    with Client(url, heartbeat_s=HEARTBEAT_S) as client:
        good = msgspec.msgpack.encode(EchoRequest(header=Header(), text="alive"))
        assert msgspec.msgpack.decode(client.request("echo", good), type=EchoReply).text == "alive"


def test_a_short_message_never_swallows_the_next_one():
    """A JOB without its body, then a HEARTBEAT: the JOB is undecodable, the HEARTBEAT still arrives."""
    ctx = zmq.Context.instance()
    url = f"inproc://short-{os.getpid()}-{time.monotonic_ns()}"
    a, b = ctx.socket(zmq.PAIR), ctx.socket(zmq.PAIR)
    try:
        a.bind(url)
        b.connect(url)
        a.send(msgspec.msgpack.encode(["JOB", "j", "k", 1, 100]))
        a.send(msgspec.msgpack.encode(["HEARTBEAT"]))
        assert wire.poll(b, 2.0)
        first, _ = wire.recv_from_broker(b)
        assert isinstance(first, wire.Undecodable)
        assert wire.poll(b, 2.0)
        second, body = wire.recv_from_broker(b)
        assert type(second).__name__ == "HeartbeatFrame" and body is None
    finally:
        a.close(0)
        b.close(0)
