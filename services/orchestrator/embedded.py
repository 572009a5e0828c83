"""The embedded default: a broker and one worker per service inside this process, over inproc://.

`Embedded` is a context manager yielding a BusBackend, so `wana animate` runs the same messages through
the same bus as a scaled-out deployment, with no sockets leaving the process.
"""

from __future__ import annotations

import importlib
import logging
import threading
import uuid
from types import TracebackType
from typing import TYPE_CHECKING

import zmq

from services.orchestrator.backend import BusBackend

if TYPE_CHECKING:
    from wana.bus.broker import Broker
    from wana.bus.client import Client

log = logging.getLogger(__name__)

SERVICES = ("nlp", "retrieval", "motion", "optimizer", "social", "render")


class Embedded:
    """Start the broker and the available workers in threads; stop them on exit."""

    def __init__(self, services: tuple[str, ...] = SERVICES, *, deadline_s: float = 300.0) -> None:
        self.services = services
        self.deadline_s = deadline_s
        self.url = f"inproc://wana-{uuid.uuid4().hex[:8]}"
        self.context: zmq.Context = zmq.Context.instance()
        self.stop = threading.Event()
        self.threads: list[threading.Thread] = []
        self.available: list[str] = []
        self.missing: dict[str, str] = {}
        self._broker: Broker | None = None
        self._workers: list[object] = []
        self._client: Client | None = None

    def __enter__(self) -> BusBackend:
        from wana.bus.broker import Broker
        from wana.bus.client import Client
        from wana.bus.service import make_frame_handler
        from wana.bus.worker import Worker
        from wana.compose import compose

        compose()  # what one service needs of another (the optimiser's motion) is wired in here

        self._broker = Broker(self.url, context=self.context)
        self.threads.append(self._broker.start_thread())
        for service in self.services:
            try:
                contract = importlib.import_module(f"services.{service}.handlers").CONTRACT
            except (ImportError, AttributeError) as exc:
                self.missing[service] = str(exc)
                continue
            worker = Worker(service, make_frame_handler(contract), self.url, context=self.context)
            t = threading.Thread(
                target=worker.run, kwargs={"stop": self.stop}, name=f"wana-{service}", daemon=True
            )
            t.start()
            self._workers.append(worker)
            self.threads.append(t)
            self.available.append(service)
        self._client = Client(self.url, context=self.context)
        return BusBackend(self._client, deadline_s=self.deadline_s)

    def __exit__(
        self, exc_type: type[BaseException] | None, exc: BaseException | None, tb: TracebackType | None
    ) -> None:
        self.stop.set()
        if self._client is not None:
            self._client.close()
        if self._broker is not None:
            self._broker.close()
        for t in self.threads:
            t.join(timeout=5)
