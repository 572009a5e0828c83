"""Typed FastAPI dependencies: settings, orchestrator, live hub, and the token / Origin guard."""

from __future__ import annotations

from typing import Annotated

from fastapi import Depends, HTTPException, Request

from proto.common import ErrorCode
from services.gateway.live import LiveHub
from services.gateway.meshes import MeshCache
from services.gateway.security import STATE_CHANGING, origin_ok, server_port, token_ok
from services.gateway.settings import Settings
from services.orchestrator.session import Orchestrator


def get_settings(request: Request) -> Settings:
    return request.app.state.settings  # type: ignore[no-any-return]


def get_orchestrator(request: Request) -> Orchestrator:
    return request.app.state.orchestrator  # type: ignore[no-any-return]


def get_hub(request: Request) -> LiveHub:
    return request.app.state.hub  # type: ignore[no-any-return]


def get_meshes(request: Request) -> MeshCache:
    return request.app.state.meshes  # type: ignore[no-any-return]


SettingsDep = Annotated[Settings, Depends(get_settings)]
OrchestratorDep = Annotated[Orchestrator, Depends(get_orchestrator)]
HubDep = Annotated[LiveHub, Depends(get_hub)]
MeshesDep = Annotated[MeshCache, Depends(get_meshes)]


def error(status: int, code: str, message: str) -> HTTPException:
    """An HTTP error whose body is {"detail": {"code": ..., "message": ...}} (codes from proto.common)."""
    return HTTPException(status_code=status, detail={"code": code, "message": message})


def guard(request: Request, settings: SettingsDep) -> None:
    """Every API call: the token when one is configured; state-changing calls: the Origin."""
    if not token_ok(settings.token, request.headers, request.cookies):
        raise error(
            401,
            ErrorCode.INVALID_INPUT,
            "missing or wrong token: send 'Authorization: Bearer TOKEN' or log in at /login",
        )
    if request.method in STATE_CHANGING and not origin_ok(
        request.headers, settings.allowed_origins, server_port(request.scope)
    ):
        raise error(
            403,
            ErrorCode.INVALID_INPUT,
            f"requests from origin {request.headers.get('origin')!r} are not allowed",
        )
