"""How the orchestrator reaches a service: in-process handler calls or requests over the bus.

Both take a request struct and return the decoded reply struct, so the pipeline does not care which one
it runs on. The embedded default (`wana animate`) uses the bus over inproc:// with a worker thread per
service; unit tests may call handlers in-process.
"""

from __future__ import annotations

import importlib
from typing import Any, Protocol, Union

import msgspec

from proto.common import ErrorReply
from wana.bus.service import call_in_process


class StageUnavailable(RuntimeError):
    """A pipeline stage whose service logic is not in this build."""

    def __init__(self, service: str, detail: str) -> None:
        super().__init__(f"the {service} stage is not available yet: {detail}")
        self.service = service


class StageFailed(RuntimeError):
    """A service answered with an error reply."""

    def __init__(self, service: str, code: str, message: str) -> None:
        super().__init__(f"{service} failed with {code}: {message}")
        self.service = service
        self.code = code


def load_contract(service: str) -> dict[type, Any]:
    from wana.compose import compose

    compose()  # what one service needs of another (the optimiser's motion) is wired in here
    try:
        handlers = importlib.import_module(f"services.{service}.handlers")
    except ImportError as exc:
        raise StageUnavailable(service, str(exc)) from exc
    contract = getattr(handlers, "CONTRACT", None)
    if not contract:
        raise StageUnavailable(service, f"services.{service}.handlers has no CONTRACT")
    return contract  # type: ignore[no-any-return]


class Backend(Protocol):
    def call(self, service: str, request: Any, reply_type: type) -> Any: ...


def _check(service: str, reply: Any) -> Any:
    if isinstance(reply, ErrorReply):
        raise StageFailed(service, reply.code, reply.message)
    return reply


class InProcessBackend:
    """Calls each service's pure handlers directly (no sockets)."""

    def __init__(self) -> None:
        self._contracts: dict[str, dict[type, Any]] = {}

    def call(self, service: str, request: Any, reply_type: type) -> Any:
        if service not in self._contracts:
            self._contracts[service] = load_contract(service)
        contract = self._contracts[service]
        try:
            reply = call_in_process(contract, request)
        except Exception as exc:  # a handler bug is that stage's failure, as over the bus (E009)
            code = "E010" if type(exc).__name__ == "InvalidInput" else "E009"
            raise StageFailed(service, code, f"{type(exc).__name__}: {exc}") from exc
        return _check(service, reply)


class BusBackend:
    """Sends requests through a broker with a bus Client."""

    def __init__(self, client: Any, *, deadline_s: float = 120.0) -> None:
        self.client = client
        self.deadline_s = deadline_s
        self._encoder = msgspec.msgpack.Encoder()
        self._decoders: dict[type, msgspec.msgpack.Decoder[Any]] = {}

    def call(self, service: str, request: Any, reply_type: type) -> Any:
        from wana.bus.client import BusError

        decoder = self._decoders.get(reply_type)
        if decoder is None:
            decoder = msgspec.msgpack.Decoder(Union[reply_type, ErrorReply])  # noqa: UP007
            self._decoders[reply_type] = decoder
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
            raise StageFailed(service, getattr(exc, "code", "E000"), str(exc)) from exc
        return _check(service, decoder.decode(payload))


class RemoteBusBackend:
    """Reaches the services through a broker at a URL (scale-out), with one bus Client per thread."""

    def __init__(self, url: str, *, deadline_s: float = 120.0) -> None:
        import threading

        self.url = url
        self.deadline_s = deadline_s
        self._local = threading.local()
        self._clients: list[Any] = []
        self._lock = threading.Lock()

    def _backend(self) -> BusBackend:
        backend = getattr(self._local, "backend", None)
        if backend is None:
            from wana.bus.client import Client

            client = Client(self.url)
            with self._lock:
                self._clients.append(client)
            backend = self._local.backend = BusBackend(client, deadline_s=self.deadline_s)
        return backend

    def call(self, service: str, request: Any, reply_type: type) -> Any:
        return self._backend().call(service, request, reply_type)

    def close(self) -> None:
        with self._lock:
            for client in self._clients:
                client.close()
            self._clients.clear()
