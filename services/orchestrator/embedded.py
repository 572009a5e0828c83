"""The embedded default: a broker and one worker per service inside this process, over inproc://.

`Embedded` is a context manager yielding a BusBackend, so `wana animate` runs the same messages through
the same bus as a scaled-out deployment, with no sockets leaving the process.
"""

from __future__ import annotations

import logging
import threading
import uuid
from types import TracebackType

import zmq

from services.orchestrator.backend import BusBackend
from services.orchestrator.registry import SERVICES, contract
from wana.bus.broker import Broker
from wana.bus.client import Client
from wana.bus.service import make_frame_handler
from wana.bus.worker import Worker

log = logging.getLogger(__name__)


class Embedded:
    """Start the broker and one worker thread per service; stop them on exit."""

    def __init__(self, services: tuple[str, ...] = SERVICES, *, deadline_s: float = 300.0) -> None:
        self.services = services
        self.deadline_s = deadline_s
        self.url = f"inproc://wana-{uuid.uuid4().hex[:8]}"
        self.context: zmq.Context[zmq.Socket[bytes]] = zmq.Context.instance()
        self.stop = threading.Event()
        self.threads: list[threading.Thread] = []
        self._broker: Broker | None = None
        self._workers: list[Worker] = []
        self._client: Client | None = None

    def __enter__(self) -> BusBackend:
        self._broker = Broker(self.url, context=self.context)
        self.threads.append(self._broker.start_thread())
        for service in self.services:
            worker = Worker(service, make_frame_handler(contract(service)), self.url, context=self.context)
            t = threading.Thread(
                target=worker.run, kwargs={"stop": self.stop}, name=f"wana-{service}", daemon=True
            )
            t.start()
            self._workers.append(worker)
            self.threads.append(t)
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
