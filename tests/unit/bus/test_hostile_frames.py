"""Regression tests for issue 18: no frame crashes a bus component, every request is answered.

Each test plays the hostile peer on a real socket and then checks that the component still serves.
"""

from __future__ import annotations

import logging
import threading

import msgspec
import pytest
import zmq

from proto.bus import (
    MAX_DEADLINE_MS,
    BatchFrame,
    EchoReply,
    EchoRequest,
    ErrorFrame,
    HeartbeatFrame,
    JobFrame,
    PingFrame,
    PongFrame,
    ReadyFrame,
    ReplyFrame,
    RequestFrame,
    StatsFrame,
)
from proto.common import ErrorReply, Header
from wana.bus.broker import Broker
from wana.bus.client import BusError, Client
from wana.bus.echo import CONTRACT
from wana.bus.service import make_frame_handler
from wana.bus.worker import Worker

BAD_UTF8 = b"\x91\xa1\xff"  # a 1-array holding a 1-byte string that is not UTF-8


def _echo(payload: bytes) -> bytes:
    return b"echo:" + payload


def _error_of(got) -> ErrorReply:
    envelope, body = got
    assert isinstance(envelope, ErrorFrame), envelope
    return msgspec.msgpack.decode(body[0], type=ErrorReply)


def _next_not_heartbeat(peer, timeout=3.0):
    while True:
        got = peer.recv(timeout)
        if got is None or not isinstance(got[0], HeartbeatFrame):
            return got


def _still_serves(peer) -> None:
    peer.send(PingFrame(7))
    got = _next_not_heartbeat(peer)
    assert got is not None and isinstance(got[0], PongFrame) and got[0].seq == 7


def test_the_three_byte_frame_that_killed_the_broker_gets_e001(ipc_url, make_broker, raw_peer):
    make_broker(ipc_url)
    peer = raw_peer(ipc_url)
    peer.send_raw(BAD_UTF8)
    error = _error_of(peer.recv())
    assert error.code == "E001" and "utf-8" in error.message.lower()
    _still_serves(peer)


def test_invalid_utf8_inside_a_request_envelope_gets_e001(ipc_url, make_broker, raw_peer):
    make_broker(ipc_url)
    peer = raw_peer(ipc_url)
    envelope = msgspec.msgpack.encode(["REQUEST", "echo", "j", "k", 0, 1000])
    peer.send_raw(envelope.replace(b"\xa4echo", b"\xa4ech\xff"), b"x")
    assert _error_of(peer.recv()).code == "E001"
    _still_serves(peer)


def test_a_deadline_of_2_to_the_64_minus_1_is_refused_and_the_broker_lives(
    ipc_url, make_broker, raw_peer, thread_worker, make_client
):
    make_broker(ipc_url)
    thread_worker("echo", _echo, ipc_url)
    peer = raw_peer(ipc_url)
    peer.send(RequestFrame("echo", "j-huge", "k", 0, 2**64 - 1), b"x")
    got = peer.recv()
    assert got[0] == ErrorFrame("j-huge")  # named, so the sender learns at once, not at its deadline
    assert _error_of(got).code == "E001" and "$[5]" in _error_of(got).message  # field 5: deadline_ms
    assert make_client(ipc_url).request("echo", b"after") == b"echo:after"


def test_a_deadline_longer_than_a_day_is_clamped_to_a_day(
    ipc_url, make_broker, raw_peer, wait_workers, make_client
):
    make_broker(ipc_url)
    worker = raw_peer(ipc_url)
    worker.send(ReadyFrame("echo"))
    wait_workers(make_client(ipc_url), "echo", 1)
    client = raw_peer(ipc_url)
    client.send(RequestFrame("echo", "j-long", "k", 0, 2**53), b"x")
    job, _ = _next_not_heartbeat(worker)
    assert isinstance(job, JobFrame) and 0 < job.deadline_ms <= MAX_DEADLINE_MS


def test_a_worker_answers_a_payload_with_invalid_utf8_with_e001_not_e009(
    ipc_url, make_broker, make_client, thread_worker
):
    make_broker(ipc_url)
    thread_worker("echo", make_frame_handler(CONTRACT), ipc_url)
    client = make_client(ipc_url)
    reply = msgspec.msgpack.decode(client.request("echo", BAD_UTF8), type=ErrorReply)
    assert reply.code == "E001"
    good = msgspec.msgpack.encode(EchoRequest(header=Header(), text="hi"))
    assert msgspec.msgpack.decode(client.request("echo", good), type=EchoReply).text == "hi"


def test_a_request_of_an_unknown_schema_version_gets_e012(ipc_url, make_broker, make_client, thread_worker):
    make_broker(ipc_url)
    thread_worker("echo", make_frame_handler(CONTRACT), ipc_url)
    future = msgspec.msgpack.encode(EchoRequest(header=Header(version=99), text="hi"))
    reply = msgspec.msgpack.decode(make_client(ipc_url).request("echo", future), type=ErrorReply)
    assert reply.code == "E012" and "99" in reply.message


def test_a_ready_of_another_protocol_version_gets_e012_and_is_not_registered(
    ipc_url, make_broker, raw_peer, make_client
):
    broker = make_broker(ipc_url)
    worker = raw_peer(ipc_url)
    worker.send(ReadyFrame("echo", protocol=99))
    assert _error_of(_next_not_heartbeat(worker)).code == "E012"
    assert "echo" not in broker.stats().services


def test_a_worker_survives_garbage_from_its_broker_and_serves_the_next_job():
    ctx = zmq.Context.instance()
    router = ctx.socket(zmq.ROUTER)
    router.setsockopt(zmq.LINGER, 0)
    port = router.bind_to_random_port("tcp://127.0.0.1")
    worker = Worker("echo", _echo, f"tcp://127.0.0.1:{port}", heartbeat_s=0.1)
    stop = threading.Event()
    thread = threading.Thread(target=worker.run, args=(stop,), daemon=True)
    thread.start()
    try:
        assert router.poll(5000)
        identity, ready = router.recv_multipart()
        assert isinstance(msgspec.msgpack.decode(ready, type=ReadyFrame), ReadyFrame)
        for garbage in ([BAD_UTF8], [msgspec.msgpack.encode(BatchFrame(3)), BAD_UTF8], [b"\xc1"]):
            router.send_multipart([identity, *garbage])
        job = msgspec.msgpack.encode(JobFrame("j1", "k", 1, 5000))
        router.send_multipart([identity, job, b"still here"])
        while True:
            assert router.poll(5000)
            frames = router.recv_multipart()
            if frames[1] != msgspec.msgpack.encode(HeartbeatFrame()):
                break
        assert frames[1:] == [msgspec.msgpack.encode(ReplyFrame("j1")), b"echo:still here"]
        assert thread.is_alive()
    finally:
        stop.set()
        thread.join(timeout=5)
        router.close(0)


def test_a_client_survives_garbage_from_its_broker_and_gets_its_reply():
    ctx = zmq.Context.instance()
    router = ctx.socket(zmq.ROUTER)
    router.setsockopt(zmq.LINGER, 0)
    port = router.bind_to_random_port("tcp://127.0.0.1")
    client = Client(f"tcp://127.0.0.1:{port}", heartbeat_s=0.1)
    try:
        job_id = client.submit("echo", b"q", deadline_s=5)
        identity = None
        while True:  # skip the PINGs up to the REQUEST
            assert router.poll(5000)
            frames = router.recv_multipart()
            identity = frames[0]
            if len(frames) == 3:
                break
        router.send_multipart([identity, BAD_UTF8])
        router.send_multipart([identity, msgspec.msgpack.encode(StatsFrame()), b"\xc1not stats"])
        router.send_multipart([identity, msgspec.msgpack.encode(ReplyFrame(job_id)), b"answer"])
        assert client.result(job_id, timeout=5) == b"answer"
    finally:
        client.close()
        router.close(0)


def test_a_forged_reply_from_a_peer_that_never_held_the_job_is_not_delivered(
    ipc_url, make_broker, raw_peer, wait_workers, make_client
):
    broker = make_broker(ipc_url)
    worker = raw_peer(ipc_url)
    worker.send(ReadyFrame("echo"))
    wait_workers(make_client(ipc_url), "echo", 1)
    client = raw_peer(ipc_url)
    client.send(RequestFrame("echo", "j-target", "k", 0, 10_000), b"q")
    job, _ = _next_not_heartbeat(worker)
    assert job.job_id == "j-target"
    forger = raw_peer(ipc_url)
    forger.send(ReplyFrame("j-target"), b"forged")
    other_worker = raw_peer(ipc_url)
    other_worker.send(ReadyFrame("echo"))
    wait_workers(make_client(ipc_url), "echo", 2)
    other_worker.send(ReplyFrame("j-target"), b"forged by a registered worker")
    worker.send(ReplyFrame("j-target"), b"genuine")
    assert client.recv_all(0.5) == [(ReplyFrame("j-target"), [b"genuine"])]
    assert broker.stats().refused_replies == 2


def test_a_re_sent_request_from_another_peer_never_re_points_the_job(
    ipc_url, make_broker, raw_peer, wait_workers, make_client
):
    make_broker(ipc_url)
    worker = raw_peer(ipc_url)
    worker.send(ReadyFrame("echo"))
    wait_workers(make_client(ipc_url), "echo", 1)
    victim, thief = raw_peer(ipc_url), raw_peer(ipc_url)
    victim.send(RequestFrame("echo", "j-victim", "k", 0, 10_000), b"q")
    _next_not_heartbeat(worker)
    thief.send(RequestFrame("echo", "j-victim", "k", 0, 10_000), b"q")
    assert _error_of(thief.recv()).code == "E013"
    worker.send(ReplyFrame("j-victim"), b"for the victim")
    assert victim.recv() == (ReplyFrame("j-victim"), [b"for the victim"])
    assert thief.recv(0.3) is None
    thief.send(RequestFrame("echo", "j-victim", "k", 0, 10_000), b"q")  # answered: still not the thief's
    assert _error_of(thief.recv()).code == "E013"


def test_a_nested_batch_and_a_command_the_broker_never_takes_are_answered(ipc_url, make_broker, raw_peer):
    make_broker(ipc_url)
    peer = raw_peer(ipc_url)
    peer.send_raw(msgspec.msgpack.encode(BatchFrame(1)), msgspec.msgpack.encode(BatchFrame(1)), b"")
    assert _error_of(peer.recv()).code == "E001"
    peer.send(JobFrame("j-odd", "k", 1, 1000))
    error = peer.recv()
    assert error[0] == ErrorFrame("j-odd") and _error_of(error).code == "E001"
    _still_serves(peer)


def test_a_too_long_service_name_gets_e001(ipc_url, make_broker, raw_peer):
    make_broker(ipc_url)
    peer = raw_peer(ipc_url)
    peer.send(RequestFrame("s" * 65, "j", "k", 0, 1000), b"x")
    assert _error_of(peer.recv()).code == "E001"


def test_a_client_refuses_a_payload_over_the_brokers_cap_instead_of_losing_its_connection(
    ipc_url, make_broker, make_client, thread_worker
):
    make_broker(ipc_url, max_frame=1000)
    thread_worker("echo", _echo, ipc_url)
    client = make_client(ipc_url)
    client.stats()  # a PONG has arrived by now, with the cap
    assert client.broker_max_frame == 1000
    with pytest.raises(BusError) as err:
        client.submit("echo", b"x" * 10_000)
    assert err.value.code == "E002"
    assert client.request("echo", b"fine") == b"echo:fine"


def test_stats_shows_no_job_ids(ipc_url, make_broker, raw_peer, wait_workers, make_client):
    make_broker(ipc_url)
    worker = raw_peer(ipc_url)
    worker.send(ReadyFrame("echo"))
    client = make_client(ipc_url)
    wait_workers(client, "echo", 1)
    job_id = client.submit("echo", b"secret")
    _next_not_heartbeat(worker)
    shown = [w.job_id for w in client.stats().workers]
    assert shown and shown[0] and job_id not in shown[0]


def test_the_payload_byte_budget_answers_busy(ipc_url, make_broker, make_client, raw_peer, wait_workers):
    broker = make_broker(ipc_url, max_queued_bytes=10_000)
    client = make_client(ipc_url)
    slow_worker = raw_peer(ipc_url)  # registered, never answers: jobs pile up in the broker
    slow_worker.send(ReadyFrame("echo"))
    wait_workers(client, "echo", 1)
    held = [client.submit("echo", b"x" * 4000, deadline_s=5) for _ in range(2)]
    with pytest.raises(BusError) as err:
        client.request("echo", b"x" * 4000, deadline_s=5)
    assert err.value.code == "E005" and err.value.retryable and "budget" in err.value.message
    assert broker.queued_bytes == 8000
    client.cancel(held)


def test_jobs_for_services_nobody_serves_get_a_quarter_of_the_budget(ipc_url, make_broker, make_client):
    broker = make_broker(ipc_url, max_queued_bytes=10_000)
    client = make_client(ipc_url)
    held = client.submit("nobody", b"x" * 2000, deadline_s=5)
    with pytest.raises(BusError) as err:
        client.request("nobody-else", b"x" * 1000, deadline_s=5)
    assert err.value.code == "E005" and "without a worker" in err.value.message
    assert broker.queued_bytes == 2000
    client.cancel([held])


def test_one_client_may_hold_only_its_share_of_jobs(ipc_url, make_broker, make_client):
    make_broker(ipc_url, max_client_jobs=2)
    greedy, polite = make_client(ipc_url), make_client(ipc_url)
    [greedy.submit("echo", b"x", deadline_s=5) for _ in range(2)]
    with pytest.raises(BusError, match="E005"):
        greedy.request("echo", b"x", deadline_s=5)
    assert polite.wait([polite.submit("echo", b"x", deadline_s=0.3)])  # not refused: it expires E003


def test_made_up_service_names_cannot_keep_a_real_worker_out(
    ipc_url, make_broker, make_client, thread_worker, wait_workers
):
    make_broker(ipc_url, max_unserved=4)
    client = make_client(ipc_url)
    for i in range(4):
        client.submit(f"made-up-{i}", b"x", deadline_s=30)
    with pytest.raises(BusError) as err:
        client.request("made-up-4", b"x", deadline_s=30)
    assert err.value.code == "E003"
    thread_worker("echo", _echo, ipc_url)
    wait_workers(client, "echo", 1)
    assert client.request("echo", b"real") == b"echo:real"


class _BrokerWithABug(Broker):
    """A broker whose READY handling has a bug: the per-message guard must contain it."""

    def _on_ready(self, sender, worker, ready):  # noqa: ANN001 - the overridden signature
        raise RuntimeError("a bug in the READY handling")


def test_a_bug_while_handling_one_message_is_answered_e009_logged_once_and_the_loop_goes_on(
    ipc_url, raw_peer, caplog
):
    broker = _BrokerWithABug(ipc_url, heartbeat_s=0.1)
    broker.start_thread()
    try:
        peer = raw_peer(ipc_url)
        with caplog.at_level(logging.DEBUG, logger="wana.bus.broker"):
            for _ in range(3):
                peer.send(ReadyFrame("echo"))
                error = _error_of(_next_not_heartbeat(peer))
                assert error.code == "E009" and "RuntimeError" in error.message
            _still_serves(peer)
        tracebacks = [r for r in caplog.records if r.levelno >= logging.ERROR]
        assert len(tracebacks) == 1 and tracebacks[0].exc_info is not None
        assert sum(broker._failures.values()) == 3
    finally:
        broker.close()
