"""Bounded queues answer busy, frame sizes are capped, malformed frames get error replies, deadlines hold."""

from __future__ import annotations

import time

import msgspec
import pytest

from proto.bus import EchoRequest, ErrorFrame, PongFrame, RequestFrame
from proto.common import ErrorReply, Header
from wana.bus.client import BusError
from wana.bus.echo import CONTRACT
from wana.bus.service import make_frame_handler


def _echo(payload: bytes) -> bytes:
    return b"echo:" + payload


def test_a_full_service_queue_answers_busy_instead_of_dropping(ipc_url, make_broker, make_client):
    broker = make_broker(ipc_url, queue_limit=2)
    client = make_client(ipc_url)
    queued = [client.submit("echo", b"x", deadline_s=5) for _ in range(2)]
    with pytest.raises(BusError) as err:
        client.request("echo", b"one too many", deadline_s=5)
    assert err.value.code == "E005" and err.value.retryable
    assert broker.stats().services["echo"].queued == 2
    assert client.wait(queued, timeout=0.2) == {}  # the queued jobs are still waiting, not dropped


def test_busy_clears_once_workers_drain_the_queue(ipc_url, make_broker, make_client, thread_worker):
    make_broker(ipc_url, queue_limit=2)
    client = make_client(ipc_url)
    queued = [client.submit("echo", f"{i}".encode(), deadline_s=5) for i in range(2)]
    with pytest.raises(BusError, match="E005"):
        client.request("echo", b"x", deadline_s=5)
    thread_worker("echo", _echo, ipc_url)
    assert sorted(client.wait(queued, timeout=5).values()) == [b"echo:0", b"echo:1"]
    assert client.request("echo", b"x") == b"echo:x"


def test_an_oversize_request_gets_e002_from_the_broker(ipc_url, make_broker, make_client, thread_worker):
    make_broker(ipc_url, max_frame=1000)
    thread_worker("echo", _echo, ipc_url)
    client = make_client(ipc_url)
    with pytest.raises(BusError) as err:
        client.request("echo", b"x" * 1001)
    assert err.value.code == "E002"
    assert client.request("echo", b"x" * 995) == b"echo:" + b"x" * 995  # reply: 1000 bytes, at the cap


def test_an_oversize_frame_gets_an_error_reply_from_the_worker_which_keeps_serving(
    ipc_url, make_broker, make_client, thread_worker
):
    make_broker(ipc_url)
    thread_worker("echo", _echo, ipc_url, max_frame=100)
    client = make_client(ipc_url)
    reply = msgspec.msgpack.decode(
        client.request("echo", b"x" * 500, doc_id="d", revision=4), type=ErrorReply
    )
    assert reply.code == "E002" and "500 bytes" in reply.message
    assert (reply.header.doc_id, reply.header.revision) == ("d", 4)
    assert client.request("echo", b"small") == b"echo:small"


def test_an_oversize_reply_becomes_an_e002_error_reply(ipc_url, make_broker, make_client, thread_worker):
    make_broker(ipc_url)
    thread_worker("echo", lambda p: b"y" * int(p), ipc_url, max_frame=1000)
    client = make_client(ipc_url)
    assert msgspec.msgpack.decode(client.request("echo", b"5000"), type=ErrorReply).code == "E002"
    assert client.request("echo", b"10") == b"y" * 10


def test_a_malformed_frame_gets_an_e001_error_reply_and_the_worker_keeps_serving(
    ipc_url, make_broker, make_client, thread_worker
):
    make_broker(ipc_url)
    thread_worker("echo", make_frame_handler(CONTRACT), ipc_url)
    client = make_client(ipc_url)
    for garbage in (b"\xc1\xc1", b"", msgspec.msgpack.encode({"type": "echo_request", "text": 3})):
        reply = msgspec.msgpack.decode(client.request("echo", garbage), type=ErrorReply)
        assert reply.code == "E001"
    request = EchoRequest(header=Header(), text="still serving")
    assert b"still serving" in client.request("echo", msgspec.msgpack.encode(request))


def test_a_handler_that_raises_gives_e009_and_the_worker_keeps_serving(
    ipc_url, make_broker, make_client, thread_worker
):
    def fragile(payload: bytes) -> bytes:
        if payload == b"boom":
            raise RuntimeError("boom")
        return payload

    make_broker(ipc_url)
    thread_worker("echo", fragile, ipc_url)
    client = make_client(ipc_url)
    assert msgspec.msgpack.decode(client.request("echo", b"boom"), type=ErrorReply).code == "E009"
    assert client.request("echo", b"fine") == b"fine"


def test_malformed_envelopes_get_e001_and_the_broker_keeps_serving(
    ipc_url, make_broker, make_client, thread_worker, raw_peer
):
    make_broker(ipc_url)
    thread_worker("echo", _echo, ipc_url)
    peer = raw_peer(ipc_url)
    peer.send_raw(b"not an envelope")
    envelope, body = peer.recv()
    assert envelope == ErrorFrame("")
    assert msgspec.msgpack.decode(body[0], type=ErrorReply).code == "E001"
    peer.send(RequestFrame("echo", "job-no-body", "k", 0, 5000))  # the payload frame is missing
    envelope, body = peer.recv()
    assert envelope == ErrorFrame("job-no-body")
    assert msgspec.msgpack.decode(body[0], type=ErrorReply).code == "E001"
    peer.send_raw(msgspec.msgpack.encode(["PING", "not a number"]))
    assert peer.recv()[0] == ErrorFrame("")
    assert make_client(ipc_url).request("echo", b"ok") == b"echo:ok"
    peer.send_raw(msgspec.msgpack.encode(["PING", 7]))
    envelope, _ = peer.recv()
    assert isinstance(envelope, PongFrame) and envelope.seq == 7


def test_a_job_running_past_its_deadline_gets_e006(ipc_url, make_broker, make_client, thread_worker):
    broker = make_broker(ipc_url)
    thread_worker("echo", lambda p: (time.sleep(float(p)), p)[1], ipc_url)
    client = make_client(ipc_url)
    start = time.monotonic()
    with pytest.raises(BusError) as err:
        client.request("echo", b"0.6", deadline_s=0.2)
    assert err.value.code == "E006" and "on a worker" in err.value.message
    assert time.monotonic() - start < 0.55
    assert client.request("echo", b"0", deadline_s=5) == b"0"  # the worker is free again afterwards
    assert broker.stats().duplicate_replies == 1  # the late reply was dropped


def test_a_job_waiting_in_the_queue_past_its_deadline_gets_e006(
    ipc_url, make_broker, make_client, thread_worker
):
    make_broker(ipc_url)
    thread_worker("echo", lambda p: (time.sleep(float(p)), p)[1], ipc_url)
    client = make_client(ipc_url)
    busy = client.submit("echo", b"0.5", deadline_s=5)
    time.sleep(0.05)
    with pytest.raises(BusError) as err:
        client.request("echo", b"0", deadline_s=0.2)
    assert err.value.code == "E006" and "in the queue" in err.value.message
    assert client.result(busy, timeout=5) == b"0.5"


def test_a_worker_busy_with_a_long_job_is_not_handed_another_one(
    ipc_url, make_broker, make_client, thread_worker
):
    make_broker(ipc_url)
    worker = thread_worker("echo", lambda p: (time.sleep(float(p)), p)[1], ipc_url)  # default capacity
    assert worker.capacity > 1
    client = make_client(ipc_url)
    assert client.request("echo", b"0") == b"0"  # a short job first: its worker may be prefetched to
    busy = client.submit("echo", b"0.6", deadline_s=5)
    time.sleep(0.2)  # the worker has been inside its job for longer than the broker's prefetch window
    with pytest.raises(BusError) as err:
        client.request("echo", b"0", deadline_s=0.2)
    assert err.value.code == "E006" and "in the queue" in err.value.message
    assert client.result(busy, timeout=5) == b"0.6"


def test_a_flood_past_the_receive_high_water_mark_waits_instead_of_being_dropped(
    ipc_url, make_broker, make_client, thread_worker
):
    """RCVHWM bounds what the broker queues per peer; ZeroMQ then stops reading that peer (back-pressure),
    so a burst of many times that many requests is all answered, none lost."""
    import zmq

    from wana.bus import wire

    n = 2 * wire.RCVHWM
    broker = make_broker(ipc_url, queue_limit=n, max_client_jobs=n)
    assert broker._socket.getsockopt(zmq.RCVHWM) == wire.RCVHWM  # noqa: SLF001 - the bound under test
    thread_worker("echo", _echo, ipc_url)
    client = make_client(ipc_url)
    jobs = [client.submit("echo", f"{i}".encode(), deadline_s=60) for i in range(n)]  # one message each
    replies = client.wait(jobs, timeout=60)
    assert sorted(replies.values()) == sorted(f"echo:{i}".encode() for i in range(n))
