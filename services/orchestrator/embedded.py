"""The embedded default: a broker and one worker per service inside this process, over inproc://.

`Embedded` is a context manager yielding a BusBackend, so `wana animate` runs the same messages through
the same bus as a scaled-out deployment, with no sockets leaving the process.
"""

from __future__ import annotations

import logging
import threading
import uuid
from collections.abc import Callable
from types import TracebackType

import zmq

from services.orchestrator.backend import BusBackend
from services.orchestrator.registry import SERVICES, contract
from wana.bus.broker import Broker
from wana.bus.client import Client
from wana.bus.service import make_frame_handler
from wana.bus.worker import Worker

log = logging.getLogger(__name__)


def lazy_frame_handler(service: str) -> Callable[[bytes], bytes]:
    """A worker's frame handler that imports the service's handlers on its first job, in its own thread.

    Importing every service (spaCy, open3d, onnxruntime, trimesh...) before the first compute would keep
    the pipeline waiting seconds for stages it reaches much later; the worker heartbeats while a job
    runs, so the import inside the first job is safe.
    """
    ready: list[Callable[[bytes], bytes]] = []
    lock = threading.Lock()

    def handle(payload: bytes) -> bytes:
        if not ready:
            with lock:
                if not ready:
                    ready.append(make_frame_handler(contract(service)))
        return ready[0](payload)

    return handle


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
            worker = Worker(service, lazy_frame_handler(service), self.url, context=self.context)
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
