"""wana's message bus: a Majordomo-style broker, a worker runtime and a client, over ZeroMQ + msgpack.

proto/PROTOCOL.md is the authoritative description. In short, every message is one envelope frame
(a msgpack array led by the command name; the structs are in proto/bus.py) plus, for jobs, one body
frame with the payload; the broker's ROUTER socket adds the peer's routing id in front:

    client -> broker   ["REQUEST", service, job_id, key, attempt, deadline_ms, doc_id, revision] + payload
    broker -> worker   ["JOB", job_id, key, attempt, deadline_ms, doc_id, revision] + payload
    worker -> broker   ["REPLY", job_id] + reply payload   (forwarded unchanged to the client)
    broker -> any peer ["ERROR", job_id] + ErrorReply      (E001 E002 E003 E005 E006 E007 E009 E010 E012)
    worker -> broker   ["READY", service, protocol, pid, host, max_frame, capacity]
    both ways          ["HEARTBEAT"]   ["DISCONNECT"]
    client -> broker   ["PING", seq] -> ["PONG", broker_instance, seq, max_frame];   ["STATS"] -> ["STATS"] + BrokerStats
    any job direction  ["BATCH", n] + n (envelope, body) pairs of REQUEST, JOB, REPLY or ERROR

Payloads are whatever the service speaks (msgpack-encoded msgspec structs); the bus never decodes them.
No frame crashes the broker, a worker or a client: each message is handled inside a guard (E001 for
anything that does not decode or validate, E009 for anything else, logged once per kind).

Python API:

    Broker(bind, *, heartbeat_s=1.0, liveness=3, queue_limit=256, max_frame=32 MiB, max_attempts=3,
           max_queued_bytes=128 MiB, max_client_jobs=4096, max_unserved=64, keys=None, insecure=False,
           context=None).run(stop) / .start_thread() / .close() / .stats()
    Worker(service, handler, connect, *, heartbeat_s=1.0, liveness=3, max_frame=32 MiB, capacity=16,
           keys=None, context=None).run(stop)
    serve(service, handler, connect)                  blocking; SIGTERM/SIGINT end it cleanly
    Client(connect, *, heartbeat_s=1.0, liveness=3, keys=None, context=None)      one per thread
        .request(service, payload, *, idempotency_key=None, deadline_s=30.0, doc_id="", revision=0) -> bytes
        .submit(same arguments) -> job_id
        .submit_many(service, payloads, *, deadline_s=30.0, doc_id="", revision=0) -> [job_id]   one BATCH
        .wait(job_ids, timeout=None, *, return_when="all"|"any") -> {job_id: bytes | BusError}
        .collect(timeout=0.0) -> {job_id: bytes | BusError}           whatever finished (as completed)
        .result(job_id, timeout=None) -> bytes ; .cancel(job_ids) ; .stats() -> BrokerStats ; .close()
    BusError(code, message, retryable)                               bus-level failure of one job
    wana.bus.curve: new_keys(dir), InsecureBind; keys=None reads $WANA_BUS_KEYS (workers, clients, tcp://)
"""

from wana.bus.broker import Broker
from wana.bus.client import BusError, Client, idempotency_key
from wana.bus.worker import Worker, serve

__all__ = ["Broker", "BusError", "Client", "Worker", "idempotency_key", "serve"]
