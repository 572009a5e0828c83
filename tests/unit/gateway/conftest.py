"""A real gateway (uvicorn on a free port, in a thread) over a real SQLite file, for the gateway tests."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import httpx
import pytest

from services.gateway.server import GatewayThread
from services.gateway.settings import Settings
from services.orchestrator.session import Orchestrator

# The gateway is under test here, not the services: its pipeline runs with every service reported
# "not available" (a real configuration, `wana serve --services ""`), so the tests are fast and do not
# depend on the state of the other stages. The browser test in tests/integration runs them all.
GATEWAY_ONLY: dict[str, Any] = {"backend": "inprocess", "services": ()}


@dataclass
class RunningGateway:
    base: str
    ws_base: str
    settings: Settings
    http: httpx.Client


def _running(gw: GatewayThread) -> RunningGateway:
    return RunningGateway(gw.base_url, gw.ws_url, gw.settings, httpx.Client(base_url=gw.base_url, timeout=20))


@pytest.fixture
def gateway_factory(tmp_path: Path) -> Iterator[Any]:
    """Start gateways with chosen settings (and optionally an orchestrator); all are stopped afterwards."""
    running: list[tuple[GatewayThread, RunningGateway]] = []

    def make(orchestrator: Orchestrator | None = None, **overrides: Any) -> RunningGateway:
        settings = Settings(db=tmp_path / f"gw{len(running)}.sqlite", **GATEWAY_ONLY).replace(**overrides)
        gw = GatewayThread(settings, orchestrator).start()
        running.append((gw, _running(gw)))
        return running[-1][1]

    yield make
    for gw, r in running:
        r.http.close()
        gw.stop()


@pytest.fixture(scope="module")
def gateway(tmp_path_factory: pytest.TempPathFactory) -> Iterator[RunningGateway]:
    """One gateway shared by a module's tests (module-scoped, as full-stack-fastapi-template does)."""
    settings = Settings(db=tmp_path_factory.mktemp("gw") / "sessions.sqlite", **GATEWAY_ONLY)
    with GatewayThread(settings) as gw:
        r = _running(gw)
        yield r
        r.http.close()
