"""BATCH messages: several jobs in one message, each still its own job (id, routing, reply, errors)."""

from __future__ import annotations

import time

import msgspec
import pytest
import zmq

from proto.bus import MAX_BATCH, BatchFrame, ErrorFrame, JobFrame, ReadyFrame, ReplyFrame, RequestFrame
from proto.common import ErrorReply


def _echo(payload: bytes) -> bytes:
    return b"echo:" + payload


def _encode(envelope: object) -> bytes:
    return msgspec.msgpack.encode(envelope)


def test_submit_many_sends_jobs_that_each_get_their_own_reply(
    ipc_url, make_broker, make_client, thread_worker, wait_workers
):
    broker = make_broker(ipc_url)
    client = make_client(ipc_url)
    for _ in range(2):
        thread_worker("echo", _echo, ipc_url)
    wait_workers(client, "echo", 2)
    payloads = [f"{i}".encode() for i in range(MAX_BATCH * 2 + 5)]  # more than one BATCH's worth
    job_ids = client.submit_many("echo", payloads)
    assert len(set(job_ids)) == len(payloads)
    got = client.wait(job_ids, timeout=10)
    assert [got[j] for j in job_ids] == [b"echo:" + p for p in payloads]
    stats = broker.stats()
    assert stats.completed == len(payloads) and stats.duplicate_requests == 0
    assert sum(w.jobs for w in stats.workers) == 0


def test_a_batch_with_a_wrong_frame_count_gets_e001_and_the_broker_keeps_serving(
    ipc_url, make_broker, make_client, raw_peer, thread_worker
):
    make_broker(ipc_url)
    thread_worker("echo", _echo, ipc_url)
    peer = raw_peer(ipc_url)
    request = RequestFrame("echo", "j1", "k", 0, 5000)
    peer.send_raw(_encode(BatchFrame(2)), _encode(request), b"x")  # says 2 pairs, carries 1
    envelope, body = peer.recv()
    assert isinstance(envelope, ErrorFrame)
    assert msgspec.msgpack.decode(body[0], type=ErrorReply).code == "E001"
    assert make_client(ipc_url).request("echo", b"still") == b"echo:still"


def test_an_undecodable_envelope_inside_a_batch_fails_alone(ipc_url, make_broker, raw_peer, thread_worker):
    make_broker(ipc_url)
    thread_worker("echo", _echo, ipc_url)
    peer = raw_peer(ipc_url)
    frames = [_encode(BatchFrame(3))]
    frames += [_encode(RequestFrame("echo", "a", "k", 0, 5000)), b"1"]
    frames += [b"\xc1 not msgpack", b"2"]
    frames += [_encode(RequestFrame("echo", "c", "k", 0, 5000)), b"3"]
    peer.send_raw(*frames)
    got = peer.recv_all(1.0)
    replies = {e.job_id: b[0] for e, b in got if isinstance(e, ReplyFrame)}
    errors = [msgspec.msgpack.decode(b[0], type=ErrorReply).code for e, b in got if isinstance(e, ErrorFrame)]
    assert replies == {"a": b"echo:1", "c": b"echo:3"}
    assert errors == ["E001"]


@pytest.fixture
def fake_broker(ipc_url, thread_worker):
    """``fake_broker(handler)``: a bare ROUTER plays the broker for a real Worker serving ``handler``;
    returns the socket and the worker's routing id once its READY arrived."""
    sockets = []

    def start(handler):
        router = zmq.Context.instance().socket(zmq.ROUTER)
        router.setsockopt(zmq.LINGER, 0)
        router.bind(ipc_url)
        sockets.append(router)
        thread_worker("echo", handler, ipc_url, heartbeat_s=1.0)
        assert router.poll(5000)
        worker_id, ready = router.recv_multipart()
        assert isinstance(msgspec.msgpack.decode(ready, type=ReadyFrame), ReadyFrame)
        return router, worker_id

    yield start
    for router in sockets:
        router.close(0)


def test_a_worker_answers_a_batch_of_quick_jobs_in_one_batch(fake_broker):
    router, worker_id = fake_broker(_echo)
    frames = [worker_id, _encode(BatchFrame(3))]
    for i in range(3):
        frames += [_encode(JobFrame(f"j{i}", "k", 1, 5000)), f"{i}".encode()]
    router.send_multipart(frames)
    assert router.poll(5000)
    reply = router.recv_multipart()
    assert msgspec.msgpack.decode(reply[1]) == ["BATCH", 3]
    pairs = [(msgspec.msgpack.decode(reply[i]), reply[i + 1]) for i in range(2, len(reply), 2)]
    assert pairs == [(["REPLY", f"j{i}"], b"echo:" + f"{i}".encode()) for i in range(3)]


def test_a_worker_does_not_hold_a_reply_behind_a_slow_job(fake_broker):
    def handler(payload: bytes) -> bytes:
        time.sleep(float(payload))
        return payload

    router, worker_id = fake_broker(handler)
    frames = [worker_id, _encode(BatchFrame(2))]
    frames += [
        _encode(JobFrame("fast", "k", 1, 5000)),
        b"0.02",
        _encode(JobFrame("slow", "k", 1, 5000)),
        b"0.5",
    ]
    start = time.monotonic()
    router.send_multipart(frames)
    assert router.poll(5000)
    first = router.recv_multipart()
    first_at = time.monotonic() - start
    assert msgspec.msgpack.decode(first[1]) == ["REPLY", "fast"] and first_at < 0.4
    assert router.poll(5000)
    assert msgspec.msgpack.decode(router.recv_multipart()[1]) == ["REPLY", "slow"]


def test_jobs_queued_for_a_vanished_worker_go_to_another_without_counting_an_attempt(
    ipc_url, make_broker, make_client, raw_peer, wait_workers
):
    """A worker gone before its JOBs leave the outbox (EHOSTUNREACH): they are not attempts."""
    make_broker(ipc_url, heartbeat_s=1.0)
    client = make_client(ipc_url)
    doomed = raw_peer(ipc_url)
    doomed.send(ReadyFrame("echo", capacity=4))
    wait_workers(client, "echo", 1)
    doomed.close()  # registered, then gone without a word
    time.sleep(0.1)
    job_ids = client.submit_many("echo", [b"a", b"b", b"c"])
    heir = raw_peer(ipc_url)
    heir.send(ReadyFrame("echo", capacity=4))
    for _ in job_ids:
        envelope, body = heir.recv()
        assert isinstance(envelope, JobFrame) and envelope.attempt == 1
        heir.send(ReplyFrame(envelope.job_id), body[0])
    got = client.wait(job_ids, timeout=10)
    assert [got[j] for j in job_ids] == [b"a", b"b", b"c"]
    stats = client.stats()
    assert stats.requeued == 0 and stats.errors == {}


def test_submit_many_refuses_a_non_bytes_payload_before_sending_any(ipc_url, make_broker, make_client):
    make_broker(ipc_url)
    client = make_client(ipc_url)
    with pytest.raises(TypeError, match="item 1"):
        client.submit_many("echo", [b"a", "not bytes", b"c"])  # type: ignore[list-item]
    assert client.pending == 0
    assert client.submit_many("echo", []) == []
