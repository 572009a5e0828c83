"""Requests are routed by service name to registered workers, over every transport."""

from __future__ import annotations

import os
import time

import msgspec
import pytest
import zmq

from proto.bus import EchoReply, EchoRequest
from proto.common import Header
from wana.bus.client import BusError
from wana.bus.echo import CONTRACT
from wana.bus.service import make_frame_handler


def _echo(payload: bytes) -> bytes:
    return b"echo:" + payload


@pytest.mark.parametrize("transport", ["inproc", "ipc", "tcp"])
def test_a_request_gets_its_reply_over_each_transport(
    transport, ipc_url, make_broker, make_client, thread_worker
):
    context = zmq.Context.instance()
    bind = {
        "inproc": f"inproc://bus-{os.getpid()}-{time.monotonic_ns()}",
        "ipc": ipc_url,
        "tcp": "tcp://127.0.0.1:*",
    }
    broker = make_broker(bind[transport], context=context)
    url = broker.endpoints[0]
    thread_worker("echo", _echo, url, context=context)
    client = make_client(url, context=context)
    assert (
        client.request("echo", b"hello " + transport.encode(), deadline_s=10)
        == b"echo:hello " + transport.encode()
    )


def test_a_typed_service_answers_through_the_bus_and_plain_msgpack_reads_the_reply(
    ipc_url, make_broker, make_client, thread_worker
):
    make_broker(ipc_url)
    thread_worker("echo", make_frame_handler(CONTRACT), ipc_url)
    client = make_client(ipc_url)
    request = EchoRequest(header=Header(doc_id="d", revision=2), text="Tom waves at Eve.")
    raw = client.request("echo", msgspec.msgpack.encode(request), doc_id="d", revision=2)
    reply = msgspec.msgpack.decode(raw, type=EchoReply)
    assert reply.text == "Tom waves at Eve." and reply.header.parent_id == request.header.msg_id
    import msgpack

    assert msgpack.unpackb(raw)["text"] == "Tom waves at Eve."


@pytest.mark.parametrize("transport", ["ipc", "tcp"])
def test_worker_processes_take_jobs_in_least_recently_used_order(
    transport, ipc_url, make_broker, make_client, spawn_worker, wait_workers
):
    url = make_broker(ipc_url if transport == "ipc" else "tcp://127.0.0.1:*").endpoints[0]
    first = spawn_worker(url)
    client = make_client(url)
    wait_workers(client, "echo", 1)
    second = spawn_worker(url)
    wait_workers(client, "echo", 2)
    pids = [int(client.request("echo", b"x").split(b":")[0]) for _ in range(4)]
    assert pids == [first.pid, second.pid, first.pid, second.pid]


def test_many_requests_in_flight_each_get_their_own_reply(ipc_url, make_broker, make_client, thread_worker):
    make_broker(ipc_url)
    thread_worker("echo", _echo, ipc_url)
    thread_worker("echo", _echo, ipc_url)
    client = make_client(ipc_url)
    jobs = {client.submit("echo", f"job {i}".encode()): f"echo:job {i}".encode() for i in range(200)}
    results = client.wait(jobs, timeout=20)
    assert results == jobs
    assert client.pending == 0


def test_collect_returns_replies_as_they_complete(ipc_url, make_broker, make_client, thread_worker):
    make_broker(ipc_url)
    thread_worker("echo", lambda p: (time.sleep(float(p)), p)[1], ipc_url)
    thread_worker("echo", lambda p: (time.sleep(float(p)), p)[1], ipc_url)
    client = make_client(ipc_url)
    slow = client.submit("echo", b"0.5")
    fast = client.submit("echo", b"0.01")
    first = client.collect(timeout=5)
    assert list(first) == [fast]
    assert client.wait([slow], timeout=5) == {slow: b"0.5"}


def test_a_request_waits_for_a_worker_that_registers_later(ipc_url, make_broker, make_client, thread_worker):
    make_broker(ipc_url)
    client = make_client(ipc_url)
    job = client.submit("late", b"x", deadline_s=10)
    assert client.wait([job], timeout=0.3) == {}
    thread_worker("late", _echo, ipc_url)
    assert client.result(job, timeout=10) == b"echo:x"


def test_a_service_with_no_worker_fails_with_e003_at_the_deadline(ipc_url, make_broker, make_client):
    make_broker(ipc_url)
    client = make_client(ipc_url)
    start = time.monotonic()
    with pytest.raises(BusError) as err:
        client.request("no-such-service", b"x", deadline_s=0.3)
    assert err.value.code == "E003"
    assert "no-such-service" in err.value.message
    assert 0.25 <= time.monotonic() - start < 3.0


def test_the_broker_reports_queue_depths_and_workers(
    ipc_url, make_broker, make_client, thread_worker, wait_workers
):
    broker = make_broker(ipc_url)
    thread_worker("echo", _echo, ipc_url)
    client = make_client(ipc_url)
    wait_workers(client, "echo", 1)
    client.request("echo", b"x")
    stats = client.stats()
    assert stats.instance == broker.instance
    assert stats.services["echo"].workers == 1 and stats.services["echo"].queued == 0
    assert stats.completed == 1
    assert stats.workers[0].pid == os.getpid()


def test_a_worker_with_capacity_two_holds_a_second_job_only_when_no_worker_is_idle(
    ipc_url, make_broker, make_client, raw_peer, wait_workers
):
    from proto.bus import JobFrame, ReadyFrame, ReplyFrame

    broker = make_broker(ipc_url, heartbeat_s=1.0)  # the raw peers do not heartbeat: give them 3 s
    first, second = raw_peer(ipc_url), raw_peer(ipc_url)
    first.send(ReadyFrame("echo", capacity=2))
    client = make_client(ipc_url)
    wait_workers(client, "echo", 1)
    second.send(ReadyFrame("echo", capacity=2))
    wait_workers(client, "echo", 2)
    for peer in (first, second):  # each answers a quick job: the broker prefetches only to such workers
        warm = client.submit("echo", b"warm")
        envelope, _ = peer.recv()
        assert isinstance(envelope, JobFrame) and envelope.job_id == warm
        peer.send(ReplyFrame(warm), b"ok")
        assert client.result(warm, timeout=5) == b"ok"
    jobs = [client.submit("echo", f"{i}".encode()) for i in range(5)]

    def job_ids(peer):
        return [e.job_id for e, _ in peer.recv_all(0.4) if isinstance(e, JobFrame)]

    got_first, got_second = job_ids(first), job_ids(second)
    assert sorted(got_first + got_second) == sorted(jobs[:4])  # two each; the fifth waits in the queue
    assert len(got_first) == len(got_second) == 2
    assert got_first[0] == jobs[0] and got_second[0] == jobs[1]  # idle workers first, in order
    stats = broker.stats()
    assert stats.services["echo"].queued == 1 and stats.services["echo"].in_flight == 4
    assert sorted(w.jobs for w in stats.workers) == [2, 2]
