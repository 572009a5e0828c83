"""The hot-path frame helpers read and write exactly the protocol's frames."""

from __future__ import annotations

import hashlib
import os
import time

import msgspec
import pytest
import zmq

from proto.bus import HeartbeatFrame, JobFrame, PongFrame, ReplyFrame
from wana.bus import wire
from wana.bus.client import idempotency_key
from wana.bus.worker import reply_envelope


@pytest.mark.parametrize("job_id", ["", "j1", "a1b2c3d4e5f6-17", "x" * 31, "y" * 32, "z" * 300, "é" * 70000])
def test_the_prebuilt_reply_envelope_is_byte_for_byte_the_struct_encoding(job_id):
    assert reply_envelope(job_id) == msgspec.msgpack.encode(ReplyFrame(job_id))


@pytest.fixture
def pair():
    ctx = zmq.Context.instance()
    url = f"inproc://wire-{os.getpid()}-{time.monotonic_ns()}"
    a, b = ctx.socket(zmq.PAIR), ctx.socket(zmq.PAIR)
    a.bind(url)
    b.connect(url)
    yield a, b
    a.close(0)
    b.close(0)


def test_a_job_and_its_body_come_back_as_a_struct_and_bytes(pair):
    sender, receiver = pair
    assert wire.recv_from_broker(receiver) is None  # nothing waiting
    wire.send(sender, (msgspec.msgpack.encode(JobFrame("j", "k", 1, 500)), b"payload"))
    assert wire.poll(receiver, 1.0)
    msg, body = wire.recv_from_broker(receiver)
    assert msg == JobFrame("j", "k", 1, 500) and body == b"payload" and type(body) is bytes
    wire.send(sender, (msgspec.msgpack.encode(PongFrame("inst", 3)),))
    assert wire.poll(receiver, 1.0)
    assert wire.recv_from_broker(receiver) == (PongFrame("inst", 3), None)


def test_an_undecodable_envelope_is_reported_and_the_rest_of_its_message_dropped(pair):
    sender, receiver = pair
    wire.send(sender, (b"\xc1garbage", b"body 1", b"body 2"))
    wire.send(sender, (msgspec.msgpack.encode(HeartbeatFrame()),))
    assert wire.poll(receiver, 1.0)
    msg, body = wire.recv_from_broker(receiver)
    assert isinstance(msg, wire.Undecodable) and body is None
    assert wire.recv_from_broker(receiver) == (HeartbeatFrame(), None)  # the next message intact


def test_the_router_receive_gives_the_routing_id_as_bytes_and_counts_frames():
    ctx = zmq.Context.instance()
    url = f"inproc://wire-router-{os.getpid()}-{time.monotonic_ns()}"
    router, dealer = ctx.socket(zmq.ROUTER), ctx.socket(zmq.DEALER)
    try:
        router.bind(url)
        dealer.setsockopt(zmq.ROUTING_ID, b"peer-1")
        dealer.connect(url)
        dealer.send_multipart([b"env", b"body", b"extra"])
        assert wire.poll(router, 1.0)
        frames = wire.recv(router)
        assert frames[0] == b"peer-1" and type(frames[0]) is bytes
        assert [f.bytes for f in frames[1:]] == [b"env", b"body", b"extra"]
        assert not wire.poll(router, 0)
    finally:
        router.close(0)
        dealer.close(0)


def test_the_default_idempotency_key_is_truncated_sha256_of_service_version_and_payload():
    expected = hashlib.sha256(b"nlp\x001.2\x00some payload").hexdigest()[:32]
    assert idempotency_key("nlp", b"some payload", "1.2") == expected
    assert idempotency_key("nlp", b"some payload", "1.2") == expected  # the cached prefix is not consumed
    assert idempotency_key("motion", b"some payload", "1.2") != expected
    assert idempotency_key("nlp", b"some payload", "1.3") != expected
    assert idempotency_key("nlp", b"other payload", "1.2") != expected
