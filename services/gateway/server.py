"""Run the gateway inside this process on a background thread (tests, benchmarks, embedding)."""

from __future__ import annotations

import threading
import time
from types import TracebackType

import uvicorn

from services.gateway.app import create_app
from services.gateway.settings import Settings
from services.orchestrator.session import Orchestrator


class GatewayThread:
    """uvicorn serving the gateway on settings.host and a free port (settings.port is ignored).

    Use as a context manager; `base_url` / `ws_url` are ready once it is entered.
    """

    def __init__(
        self, settings: Settings, orchestrator: Orchestrator | None = None, *, start_timeout_s: float = 60
    ) -> None:
        self.settings = settings
        self.app = create_app(settings, orchestrator)
        config = uvicorn.Config(
            self.app,
            host=settings.host,
            port=0,
            log_level="warning",
            lifespan="on",
            ws_max_size=settings.ws_max_size,
            ws_per_message_deflate=settings.ws_compression,
        )
        self.server = uvicorn.Server(config)
        self.thread = threading.Thread(target=self.server.run, name="wana-gateway", daemon=True)
        self.start_timeout_s = start_timeout_s
        self.port = 0

    def start(self) -> GatewayThread:
        self.thread.start()
        deadline = time.monotonic() + self.start_timeout_s
        while not self.server.started:
            if time.monotonic() > deadline or not self.thread.is_alive():
                raise RuntimeError("the gateway did not start")
            time.sleep(0.02)
        self.port = int(self.server.servers[0].sockets[0].getsockname()[1])
        return self

    @property
    def base_url(self) -> str:
        return f"http://{self.settings.host}:{self.port}"

    @property
    def ws_url(self) -> str:
        return f"ws://{self.settings.host}:{self.port}"

    def stop(self) -> None:
        self.server.should_exit = True
        self.thread.join(timeout=30)

    def __enter__(self) -> GatewayThread:
        return self.start()

    def __exit__(
        self, exc_type: type[BaseException] | None, exc: BaseException | None, tb: TracebackType | None
    ) -> None:
        self.stop()
