"""Browser login: trade the gateway's token for a short-lived session cookie, so no URL ever carries it.

`GET /login` is a one-field form; `POST /api/session` takes the token as `Authorization: Bearer` (scripts)
or as the form's `token` field (the page) and sets the `wana_session` cookie (HttpOnly, SameSite=Strict,
`settings.session_ttl_s`), which the REST API, downloads and the document WebSocket accept.
`DELETE /api/session` logs out.
"""

from __future__ import annotations

import hmac
from urllib.parse import parse_qs

from fastapi import APIRouter, Request, Response
from fastapi.responses import HTMLResponse, RedirectResponse

from proto.common import ErrorCode
from services.gateway.deps import SettingsDep, error
from services.gateway.security import (
    SESSION_COOKIE,
    bearer_ok,
    origin_ok,
    server_port,
    session_cookie,
)

router = APIRouter(tags=["session"])

LOGIN_PAGE = """<!doctype html><meta charset="utf-8"><title>wana: log in</title>
<form method="post" action="api/session"><label>Token <input name="token" type="password" autofocus></label>
<button>Log in</button></form>"""


@router.get("/login", include_in_schema=False)
async def login_page() -> HTMLResponse:
    return HTMLResponse(LOGIN_PAGE)


@router.post("/api/session", status_code=204, summary="Log in: the token for a session cookie")
async def log_in(request: Request, settings: SettingsDep) -> Response:
    if not origin_ok(request.headers, settings.allowed_origins, server_port(request.scope)):
        raise error(
            403,
            ErrorCode.INVALID_INPUT,
            f"requests from origin {request.headers.get('origin')!r} are not allowed",
        )
    from_form = False
    ok = not settings.token or bearer_ok(settings.token, request.headers)
    if not ok and request.headers.get("content-type", "").startswith("application/x-www-form-urlencoded"):
        given = parse_qs((await request.body()).decode("utf-8", "replace")).get("token", [""])[0]
        ok = bool(given) and hmac.compare_digest(given.encode(), settings.token.encode())
        from_form = True
    if not ok:
        raise error(401, ErrorCode.INVALID_INPUT, "wrong token")
    response: Response = RedirectResponse("/", status_code=303) if from_form else Response(status_code=204)
    if settings.token:
        response.set_cookie(
            SESSION_COOKIE,
            session_cookie(settings.token, settings.session_ttl_s),
            max_age=settings.session_ttl_s,
            httponly=True,
            samesite="strict",
            path="/",
        )
    return response


@router.delete("/api/session", status_code=204, summary="Log out: drop the session cookie")
async def log_out() -> Response:
    response = Response(status_code=204)
    response.delete_cookie(SESSION_COOKIE, path="/")
    return response
