"""A dead worker's job is re-queued (at most 3 attempts) and exactly one reply reaches the client."""

from __future__ import annotations

import os
import signal
import time

import pytest

from proto.bus import HeartbeatFrame, JobFrame, ReadyFrame, ReplyFrame, RequestFrame
from wana.bus.client import BusError


def _wait_for_job_on_a_worker(client, timeout=10.0):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        busy = [w for w in client.stats().workers if w.job_id]
        if busy:
            return busy[0]
        time.sleep(0.01)
    raise AssertionError("no worker picked up the job")


def test_kill_9_of_a_worker_mid_job_completes_the_job_on_another_worker_with_exactly_one_reply(
    ipc_url, make_broker, make_client, spawn_worker, raw_peer, wait_workers
):
    broker = make_broker(ipc_url)
    workers = {p.pid: p for p in (spawn_worker(ipc_url), spawn_worker(ipc_url))}
    observer = make_client(ipc_url)
    wait_workers(observer, "echo", 2)
    client = raw_peer(ipc_url)
    client.send(RequestFrame("echo", "job-kill", "key", 0, 20_000), b"sleep:0.5:survived")
    holder = _wait_for_job_on_a_worker(observer)
    assert holder.attempt == 1
    os.kill(holder.pid, signal.SIGKILL)
    workers[holder.pid].wait()

    first = client.recv(timeout=10)
    assert first is not None, "no reply after the worker died"
    envelope, body = first
    assert envelope == ReplyFrame("job-kill")
    survivor = next(pid for pid in workers if pid != holder.pid)
    assert body == [f"{survivor}:survived".encode()]
    assert client.recv_all(1.0) == [], "a second reply reached the client"
    stats = broker.stats()
    assert (stats.requeued, stats.completed) == (1, 1)
    assert stats.services["echo"].workers == 1


def test_a_job_whose_worker_dies_on_every_attempt_fails_with_e007_after_three(
    ipc_url, make_broker, make_client, spawn_worker, wait_workers
):
    broker = make_broker(ipc_url, max_attempts=3)
    for _ in range(3):
        spawn_worker(ipc_url)
    client = make_client(ipc_url)
    wait_workers(client, "echo", 3)
    with pytest.raises(BusError) as err:
        client.request("echo", b"die", deadline_s=20)
    assert err.value.code == "E007"
    assert "3 attempts" in err.value.message
    stats = broker.stats()
    assert stats.requeued == 2
    assert stats.services["echo"].workers == 0


def test_a_silent_worker_is_declared_dead_and_its_job_goes_to_a_live_one(
    ipc_url, make_broker, make_client, thread_worker, raw_peer, wait_workers
):
    broker = make_broker(ipc_url)
    client = make_client(ipc_url)
    silent = raw_peer(ipc_url)
    silent.send(ReadyFrame("echo", pid=1))
    wait_workers(client, "echo", 1)
    job = client.submit("echo", b"payload", deadline_s=10)
    envelope, _ = silent.recv(timeout=5)
    assert isinstance(envelope, JobFrame) and envelope.attempt == 1
    thread_worker("echo", lambda p: b"live:" + p, ipc_url)
    start = time.monotonic()
    assert client.result(job, timeout=10) == b"live:payload"
    assert time.monotonic() - start >= 0.15  # only after the silent worker missed its heartbeats
    assert broker.stats().requeued == 1
    assert [w.pid for w in broker.stats().workers] == [os.getpid()]


def test_a_long_job_keeps_its_worker_alive_through_heartbeats(
    ipc_url, make_broker, make_client, spawn_worker, wait_workers
):
    broker = make_broker(ipc_url)  # liveness 3 x 0.1 s: the job lasts three times longer
    proc = spawn_worker(ipc_url)
    client = make_client(ipc_url)
    wait_workers(client, "echo", 1)
    assert client.request("echo", b"sleep:0.9:slow", deadline_s=10) == f"{proc.pid}:slow".encode()
    stats = broker.stats()
    assert (stats.requeued, stats.completed) == (0, 1)


def test_a_duplicate_reply_is_dropped(ipc_url, make_broker, raw_peer, wait_workers, make_client):
    broker = make_broker(ipc_url)
    worker = raw_peer(ipc_url)
    worker.send(ReadyFrame("echo"))
    wait_workers(make_client(ipc_url), "echo", 1)
    client = raw_peer(ipc_url)
    client.send(RequestFrame("echo", "job-dup", "key", 0, 10_000), b"question")
    envelope, body = worker.recv()
    assert envelope.job_id == "job-dup" and body == [b"question"]
    worker.send(ReplyFrame("job-dup"), b"first answer")
    worker.send(ReplyFrame("job-dup"), b"second answer")
    replies = client.recv_all(0.6)
    assert replies == [(ReplyFrame("job-dup"), [b"first answer"])]
    assert broker.stats().duplicate_replies == 1


def test_a_duplicate_request_is_run_once(ipc_url, make_broker, raw_peer, wait_workers, make_client):
    broker = make_broker(ipc_url)
    worker = raw_peer(ipc_url)
    worker.send(ReadyFrame("echo"))
    wait_workers(make_client(ipc_url), "echo", 1)
    client = raw_peer(ipc_url)
    for _ in range(2):
        client.send(RequestFrame("echo", "job-twice", "key", 0, 10_000), b"q")
    received = [envelope for envelope, _ in worker.recv_all(0.5) if not isinstance(envelope, HeartbeatFrame)]
    assert received == [JobFrame("job-twice", "key", 1, received[0].deadline_ms)]
    worker.send(ReplyFrame("job-twice"), b"a")
    assert client.recv_all(0.4) == [(ReplyFrame("job-twice"), [b"a"])]
    assert broker.stats().duplicate_requests == 1


def test_a_dead_worker_holding_two_jobs_has_both_completed_elsewhere_exactly_once(
    ipc_url, make_broker, make_client, raw_peer, thread_worker, wait_workers
):
    broker = make_broker(ipc_url)
    doomed = raw_peer(ipc_url)
    doomed.send(ReadyFrame("echo", capacity=2))
    client = make_client(ipc_url)
    wait_workers(client, "echo", 1)
    warm = client.submit("echo", b"warm")  # a quick job first: the broker prefetches only to such workers
    envelope, _ = doomed.recv()
    assert isinstance(envelope, JobFrame) and envelope.job_id == warm
    doomed.send(ReplyFrame(warm), b"ok")
    assert client.result(warm, timeout=5) == b"ok"
    jobs = {
        client.submit("echo", f"job {i}".encode(), deadline_s=10): f"live:job {i}".encode() for i in range(2)
    }
    received = [e for e, _ in doomed.recv_all(0.3) if isinstance(e, JobFrame)]
    assert sorted(e.job_id for e in received) == sorted(jobs)
    doomed.close()  # it never answers and never heartbeats again
    thread_worker("echo", lambda p: b"live:" + p, ipc_url)
    assert client.wait(jobs, timeout=10) == jobs
    stats = broker.stats()
    assert (stats.requeued, stats.completed, stats.duplicate_replies) == (2, 3, 0)  # 3: the warm-up too


def test_a_job_longer_than_the_liveness_window_does_not_make_its_worker_reconnect(
    ipc_url, make_broker, make_client, thread_worker, wait_workers
):
    make_broker(ipc_url)  # liveness 3 x 0.1 s; the job takes 0.6 s without reading the broker's heartbeats

    def slow(payload: bytes) -> bytes:
        time.sleep(0.6)
        return payload

    worker = thread_worker("echo", slow, ipc_url)
    client = make_client(ipc_url)
    wait_workers(client, "echo", 1)
    assert client.request("echo", b"first", deadline_s=10) == b"first"
    assert client.request("echo", b"second", deadline_s=10) == b"second"
    time.sleep(0.2)
    assert worker.reconnects == 0
