"""How the orchestrator reaches a service: in-process handler calls or requests over the bus.

Every backend has one method, ``call(request) -> reply``: the service is found from the request's type and
the reply type from its declaration (``proto.common.Request[Reply]``, see services/orchestrator/registry.py),
so ``call(ParseRequest(...))`` is typed ``ParseReply``. An error reply or a failing handler raises
StageFailed; a service this process is not allowed to reach raises StageUnavailable. The embedded default
(`wana animate`) uses the bus over inproc:// with a worker thread per service; unit tests may call handlers
in-process.
"""

from __future__ import annotations

import threading
from typing import Any, Protocol, TypeVar, Union, cast

import msgspec

from proto.common import ErrorCode, ErrorReply, Request, reply_type
from services.orchestrator.registry import contract, service_of
from wana.bus.client import BusError, Client
from wana.bus.service import InvalidInput, call_in_process

R = TypeVar("R")


class StageUnavailable(RuntimeError):
    """A pipeline stage whose service this process may not reach (e.g. not enabled in this gateway)."""

    def __init__(self, service: str, detail: str) -> None:
        super().__init__(f"the {service} stage is not available: {detail}")
        self.service = service


class StageFailed(RuntimeError):
    """A service answered with an error reply (or, in-process, its handler raised)."""

    def __init__(self, service: str, code: str, message: str) -> None:
        super().__init__(f"{service} failed with {code}: {message}")
        self.service = service
        self.code = code


class Backend(Protocol):
    def call(self, request: Request[R]) -> R: ...


def _checked(service: str, request: Request[R], reply: object) -> R:
    if isinstance(reply, ErrorReply):
        raise StageFailed(service, reply.code, reply.message)
    expected = reply_type(type(request))
    if not isinstance(reply, expected):
        raise StageFailed(
            service,
            ErrorCode.HANDLER_FAILED,
            f"{type(request).__name__} was answered with {type(reply).__name__}, not {expected.__name__}",
        )
    return cast(R, reply)


class InProcessBackend:
    """Calls each service's pure handlers directly (no sockets)."""

    def call(self, request: Request[R]) -> R:
        service = service_of(type(request))
        try:
            reply = call_in_process(contract(service), request)
        except InvalidInput as exc:  # as the bus's frame handler answers: E010 for refused input
            raise StageFailed(service, ErrorCode.INVALID_INPUT, f"{type(exc).__name__}: {exc}") from exc
        except Exception as exc:  # a handler bug is that stage's failure, as over the bus (E009)
            raise StageFailed(service, ErrorCode.HANDLER_FAILED, f"{type(exc).__name__}: {exc}") from exc
        return _checked(service, request, reply)


class BusBackend:
    """Sends requests through a broker with a bus Client."""

    def __init__(self, client: Client, *, deadline_s: float = 120.0) -> None:
        self.client = client
        self.deadline_s = deadline_s
        self._encoder = msgspec.msgpack.Encoder()
        self._decoders: dict[type, msgspec.msgpack.Decoder[Any]] = {}

    def call(self, request: Request[R]) -> R:
        service = service_of(type(request))
        decoder = self._decoders.get(type(request))
        if decoder is None:
            wanted = reply_type(type(request))
            decoder = msgspec.msgpack.Decoder(Union[wanted, ErrorReply])  # noqa: UP007 - runtime union
            self._decoders[type(request)] = decoder
        header = getattr(request, "header", None)
        try:
            payload = self.client.request(
                service,
                self._encoder.encode(request),
                deadline_s=self.deadline_s,
                doc_id=getattr(header, "doc_id", ""),
                revision=getattr(header, "revision", 0),
            )
        except BusError as exc:
            raise StageFailed(service, exc.code, str(exc)) from exc
        return _checked(service, request, decoder.decode(payload))


class RemoteBusBackend:
    """Reaches the services through a broker at a URL (scale-out), with one bus Client per thread."""

    def __init__(self, url: str, *, deadline_s: float = 120.0) -> None:
        self.url = url
        self.deadline_s = deadline_s
        self._local = threading.local()
        self._clients: list[Client] = []
        self._lock = threading.Lock()

    def _backend(self) -> BusBackend:
        backend: BusBackend | None = getattr(self._local, "backend", None)
        if backend is None:
            client = Client(self.url)
            with self._lock:
                self._clients.append(client)
            backend = self._local.backend = BusBackend(client, deadline_s=self.deadline_s)
        return backend

    def call(self, request: Request[R]) -> R:
        return self._backend().call(request)

    def close(self) -> None:
        with self._lock:
            for client in self._clients:
                client.close()
            self._clients.clear()


class ServiceSubset:
    """A backend limited to some services: a call to any other raises StageUnavailable with the reason."""

    def __init__(self, backend: Backend, missing: dict[str, str]) -> None:
        self.backend = backend
        self.missing = dict(missing)

    def call(self, request: Request[R]) -> R:
        service = service_of(type(request))
        if service in self.missing:
            raise StageUnavailable(service, self.missing[service])
        return self.backend.call(request)
