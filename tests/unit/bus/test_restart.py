"""Broker restart, worker reconnection with back-off, and clean worker shutdown."""

from __future__ import annotations

import signal
import time

from wana.bus.broker import Broker


def test_after_a_broker_restart_workers_re_register_and_pending_work_completes(
    ipc_url, make_broker, make_client, spawn_worker, wait_workers
):
    first = make_broker(ipc_url)
    workers = [spawn_worker(ipc_url), spawn_worker(ipc_url)]
    client = make_client(ipc_url)
    wait_workers(client, "echo", 2)
    jobs = {client.submit("echo", f"sleep:0.3:job {i}".encode(), deadline_s=30): i for i in range(4)}
    time.sleep(0.1)  # two jobs run on the workers, two wait in the queue
    assert first.stats().services["echo"].in_flight == 2
    first.close()  # the broker dies with everything it knew
    time.sleep(0.3)
    second = make_broker(ipc_url)
    assert second.instance != first.instance
    results = client.wait(jobs, timeout=20)
    pids = {str(w.pid) for w in workers}
    assert sorted(results) == sorted(jobs), "pending jobs did not complete"
    for job_id, i in jobs.items():
        pid, text = results[job_id].split(b":", 1)
        assert text == f"job {i}".encode() and pid.decode() in pids
    assert client.resent >= 4
    stats = second.stats()
    assert stats.services["echo"].workers == 2
    assert stats.completed == 4


def test_a_worker_backs_off_exponentially_while_the_broker_is_away_then_registers(
    ipc_url, make_client, thread_worker, wait_workers
):
    worker = thread_worker("echo", lambda p: p, ipc_url, reconnect_max_s=0.8)
    time.sleep(2.0)  # no broker: 0.3 s of silence, then reconnects after 0.1, 0.2, 0.4, 0.8 s...
    assert 2 <= worker.reconnects <= 4
    assert worker.backoff_s >= 0.4
    broker = Broker(ipc_url, heartbeat_s=0.1)
    broker.start_thread()
    try:
        client = make_client(ipc_url)
        wait_workers(client, "echo", 1, timeout=10)
        assert client.request("echo", b"back") == b"back"
        assert worker.backoff_s == 0.1  # reset once the broker answered
    finally:
        broker.close()


def test_sigterm_makes_a_worker_finish_and_deregister_at_once(
    ipc_url, make_broker, make_client, spawn_worker, wait_workers
):
    make_broker(ipc_url, heartbeat_s=1.0)  # expiry would take 3 s: deregistration must be explicit
    proc = spawn_worker(ipc_url, "--heartbeat", "1.0")
    client = make_client(ipc_url)
    wait_workers(client, "echo", 1)
    job = client.submit("echo", b"sleep:0.3:last job")
    time.sleep(0.1)
    proc.send_signal(signal.SIGTERM)
    assert client.result(job, timeout=5) == f"{proc.pid}:last job".encode()
    assert proc.wait(timeout=5) == 0
    wait_workers(client, "echo", 0, timeout=1.0)


def test_jobs_sent_before_any_broker_exists_complete_once_it_starts(
    ipc_url, make_broker, make_client, thread_worker
):
    client = make_client(ipc_url)
    jobs = [client.submit("echo", f"early {i}".encode(), deadline_s=20) for i in range(3)]
    assert client.wait(jobs, timeout=0.3) == {}
    make_broker(ipc_url)
    thread_worker("echo", lambda p: b"done " + p, ipc_url)
    assert sorted(client.wait(jobs, timeout=10).values()) == [
        b"done early 0",
        b"done early 1",
        b"done early 2",
    ]
