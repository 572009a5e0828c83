"""Contract-test harness: a real broker and the real worker process on an ipc socket, and a checker.

Usage in ``tests/contract/<service>/test_<service>_contract.py``::

    import msgspec
    import pytest
    from tests.contract.harness import check_contract, service_fixture

    from proto.nlp import ParseRequest
    from services.nlp.handlers import CONTRACT

    nlp = service_fixture("nlp")  # module-scoped fixture: broker + services.nlp.worker.main(url)

    @pytest.mark.contract
    def test_parse_request_gets_a_parse_reply(nlp):
        request = ParseRequest(header=Header(), text="A desk is near a window$.")
        reply = check_contract(CONTRACT, request, nlp.request("nlp", msgspec.msgpack.encode(request)))
        assert reply.sentences  # ...what the service promises

or ``with running_service("nlp") as bus: ...`` outside pytest fixtures; ``bus.call(CONTRACT, request)``
does encode + request + check in one step.

The worker runs in a subprocess started as ``python -c "from services.<name>.worker import main;
main(url)"`` (or any ``"module:function"`` given as ``worker=``), with the repository root on
PYTHONPATH and ``WANA_BUS_HEARTBEAT_S`` set to the harness's heartbeat.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import types
import typing
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any, Literal

import msgpack
import msgspec
import pytest

from proto.common import ERROR_CODES, ErrorReply
from wana.bus.broker import Broker
from wana.bus.client import Client

REPO = Path(__file__).resolve().parents[2]

__all__ = ["ServiceHarness", "check_contract", "reply_types", "running_service", "service_fixture"]


class ServiceHarness:
    """What the harness yields: a client of the running broker plus the processes behind it.

    Attributes:
        service: the service the workers serve (the default of ``call``).
        client: wana.bus.client.Client connected to the broker.
        url: the broker's ipc URL.
        broker: the in-process Broker (its ``stats()`` shows workers and queues).
        processes: the worker subprocesses.
    """

    def __init__(
        self, client: Client, url: str, broker: Broker, processes: list[subprocess.Popen], service: str = ""
    ):
        self.service = service
        self.client = client
        self.url = url
        self.broker = broker
        self.processes = processes

    def request(self, service: str, payload: bytes, **kwargs: Any) -> bytes:
        """Send one request frame; return the reply frame (raises wana.bus.BusError on a bus error)."""
        return self.client.request(service, payload, **kwargs)

    def call(
        self,
        contract: dict[type, Callable[[Any], Any]],
        request: Any,
        *,
        service: str | None = None,
        expect: Literal["ok", "error", "any"] = "ok",
        code: str | None = None,
        deadline_s: float = 60.0,
    ) -> Any:
        """Encode ``request``, send it, and return the reply checked by ``check_contract``."""
        name = service or self.service
        reply = self.client.request(name, msgspec.msgpack.encode(request), deadline_s=deadline_s)
        return check_contract(contract, request, reply, expect=expect, code=code)


def _stderr_tail(path: Path, limit: int = 4000) -> str:
    try:
        return path.read_text(errors="replace")[-limit:]
    except OSError:
        return ""


@contextlib.contextmanager
def running_service(
    service: str,
    worker: str | None = None,
    *,
    workers: int = 1,
    heartbeat_s: float = 0.5,
    startup_timeout_s: float = 180.0,
    env: dict[str, str] | None = None,
) -> Iterator[ServiceHarness]:
    """Start a broker (in this process) and ``workers`` worker processes; yield a ServiceHarness.

    Args:
        service: service name the worker registers, e.g. "nlp".
        worker: "module:function" called with the broker URL; default ``services.<service>.worker:main``.
        workers: number of worker processes.
        heartbeat_s: heartbeat of broker, workers (via WANA_BUS_HEARTBEAT_S) and client.
        startup_timeout_s: time allowed for the workers to import and register.
        env: extra environment variables for the worker processes.

    Raises:
        RuntimeError: a worker exited or did not register in time (its stderr is in the message).
    """
    module, _, function = (worker or f"services.{service}.worker:main").partition(":")
    function = function or "main"
    tmp = Path(tempfile.mkdtemp(prefix="wana-contract-"))  # short: ipc paths are limited to ~100 bytes
    url = f"ipc://{tmp}/bus.sock"
    broker = Broker(url, heartbeat_s=heartbeat_s)
    broker.start_thread()
    child_env = dict(os.environ)
    child_env["PYTHONPATH"] = os.pathsep.join([str(REPO), child_env.get("PYTHONPATH", "")]).rstrip(os.pathsep)
    child_env["WANA_BUS_HEARTBEAT_S"] = str(heartbeat_s)
    child_env.setdefault("OMP_NUM_THREADS", "1")
    child_env.update(env or {})
    code = f"import sys; from {module} import {function} as main; main(sys.argv[1])"
    processes: list[subprocess.Popen] = []
    logs: list[Path] = []
    client: Client | None = None
    try:
        for i in range(workers):
            log_path = tmp / f"worker-{i}.stderr"
            logs.append(log_path)
            with open(log_path, "wb") as err:
                processes.append(
                    subprocess.Popen([sys.executable, "-c", code, url], cwd=REPO, env=child_env, stderr=err)
                )
        client = Client(url, heartbeat_s=heartbeat_s)
        end = time.monotonic() + startup_timeout_s
        while True:
            for proc, log_path in zip(processes, logs, strict=True):
                if proc.poll() is not None:
                    raise RuntimeError(
                        f"{service} worker ({module}:{function}) exited with code {proc.returncode} before "
                        f"registering; its stderr:\n{_stderr_tail(log_path)}"
                    )
            stats = client.stats()
            svc = stats.services.get(service)
            if svc is not None and svc.workers >= workers:
                break
            if time.monotonic() > end:
                raise RuntimeError(
                    f"{service} worker did not register within {startup_timeout_s} s (broker saw {stats.services}); "
                    f"stderr:\n{_stderr_tail(logs[0])}"
                )
            time.sleep(0.05)
        yield ServiceHarness(client, url, broker, processes, service)
    finally:
        for proc in processes:
            if proc.poll() is None:
                proc.send_signal(signal.SIGTERM)
        for proc in processes:
            try:
                proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()
        if client is not None:
            client.close()
        broker.close()
        shutil.rmtree(tmp, ignore_errors=True)


def service_fixture(
    service: str,
    worker: str | None = None,
    *,
    scope: Literal["function", "module", "session"] = "module",
    **kwargs: Any,
) -> Any:
    """A pytest fixture running ``service`` (see ``running_service``); assign it to a module-level name."""

    @pytest.fixture(scope=scope)
    def _service() -> Iterator[ServiceHarness]:
        with running_service(service, worker, **kwargs) as harness:
            yield harness

    return _service


def reply_types(contract: dict[type, Callable[[Any], Any]], request_type: type) -> tuple[type, ...]:
    """The reply struct types a contract's handler declares for ``request_type`` (its return annotation)."""
    if request_type not in contract:
        raise AssertionError(
            f"{request_type.__name__} is not a request type of this contract: {list(contract)}"
        )
    handler = contract[request_type]
    try:
        returned = typing.get_type_hints(handler).get("return")
    except Exception as exc:  # unresolvable annotation: say so plainly
        raise AssertionError(f"cannot read the return annotation of {handler!r}: {exc}") from exc
    if returned is None:
        raise AssertionError(f"handler {handler!r} needs a return annotation naming its reply type")
    args = (
        typing.get_args(returned)
        if typing.get_origin(returned) in (typing.Union, types.UnionType)
        else (returned,)
    )
    found = tuple(a for a in args if isinstance(a, type) and issubclass(a, msgspec.Struct))
    if not found:
        raise AssertionError(
            f"handler {handler!r} returns {returned!r}, which names no msgspec.Struct reply type"
        )
    return found


def check_contract(
    contract: dict[type, Callable[[Any], Any]],
    request_struct: Any,
    reply_bytes: bytes,
    *,
    expect: Literal["ok", "error", "any"] = "ok",
    code: str | None = None,
) -> Any:
    """Check a reply frame against the service's contract and return it decoded.

    Checks: plain ``msgpack`` reads the frame and its re-packed bytes decode to an equal struct;
    the frame decodes (strictly, with msgspec) into a reply type the handler declares or into
    ErrorReply; ``status`` is "ok" for a reply and "error" for an ErrorReply whose code is in
    ERROR_CODES; an ok reply's ``header.parent_id`` is the request's ``header.msg_id``.

    Args:
        contract: the service's ``CONTRACT`` (request type -> handler with a return annotation).
        request_struct: the request that was sent.
        reply_bytes: the reply frame received.
        expect: "ok" (the default), "error", or "any".
        code: with expect="error", the error code expected.

    Returns:
        The decoded reply struct (a declared reply type or ErrorReply).
    """
    declared = tuple(t for t in reply_types(contract, type(request_struct)) if t is not ErrorReply)
    try:
        plain = msgpack.unpackb(reply_bytes, raw=False, strict_map_key=False)
    except Exception as exc:
        raise AssertionError(f"the plain msgpack package cannot read the reply: {exc}") from exc
    config = ErrorReply.__struct_config__
    tag = plain.get(config.tag_field) if isinstance(plain, dict) else None
    candidates = (ErrorReply,) if tag == config.tag else (*declared, ErrorReply)
    reply: Any = None
    failures = []
    for reply_type in candidates:
        try:
            reply = msgspec.msgpack.decode(reply_bytes, type=reply_type, strict=True)
            break
        except (msgspec.DecodeError, msgspec.ValidationError) as exc:
            failures.append(f"{reply_type.__name__}: {exc}")
    if reply is None:
        raise AssertionError(
            f"reply to {type(request_struct).__name__} decodes into none of its contract's types: "
            + "; ".join(failures)
            + f"; plain msgpack sees {str(plain)[:300]}"
        )
    again = msgspec.msgpack.decode(msgpack.packb(plain, use_bin_type=True), type=type(reply))
    assert again == reply, f"round trip through plain msgpack changed the reply: {again!r} != {reply!r}"
    if isinstance(reply, ErrorReply):
        assert reply.status == "error", f"ErrorReply with status {reply.status!r}"
        assert reply.code in ERROR_CODES, f"error code {reply.code!r} is not in proto.common.ERROR_CODES"
        if expect == "ok":
            raise AssertionError(
                f"expected an ok reply to {type(request_struct).__name__}, got {reply.code}: {reply.message}"
            )
        if code is not None:
            assert reply.code == code, f"expected error {code}, got {reply.code}: {reply.message}"
        return reply
    status = getattr(reply, "status", None)
    assert status == "ok", f"{type(reply).__name__}.status is {status!r}; a reply must carry status 'ok'"
    if expect == "error":
        raise AssertionError(
            f"expected an ErrorReply to {type(request_struct).__name__}, got {type(reply).__name__}"
        )
    request_header = getattr(request_struct, "header", None)
    reply_header = getattr(reply, "header", None)
    if request_header is not None:
        assert reply_header is not None, f"{type(reply).__name__} has no header"
        assert reply_header.parent_id == request_header.msg_id, (
            f"{type(reply).__name__}.header.parent_id is {reply_header.parent_id!r}; it must be the request's "
            f"header.msg_id {request_header.msg_id!r}"
        )
    return reply
