"""Who may call the gateway: a bearer token (when configured) and an Origin check against cross-site use.

The token travels as `Authorization: Bearer TOKEN` or, where a browser cannot set headers (WebSocket,
download links), as `?token=TOKEN`. The Origin check applies to WebSocket handshakes and to every
state-changing request (POST, PUT, PATCH, DELETE): a browser page from another site must not drive the
editor. Requests without an Origin header (curl, scripts) are not browsers and pass this check.

An Origin passes only when it is in the allow list: the gateway's own loopback origins on the port it
serves (``http://127.0.0.1:PORT``, ``http://localhost:PORT``, ``http://[::1]:PORT``) plus
``WANA_ALLOWED_ORIGINS``. ``Origin`` equal to ``Host`` is not enough: a DNS-rebinding page
(``http://evil.example:PORT`` resolving to 127.0.0.1) sends exactly that.
"""

from __future__ import annotations

import hmac
from collections.abc import Mapping
from typing import Any
from urllib.parse import urlsplit

from starlette.datastructures import Headers, QueryParams

STATE_CHANGING = frozenset({"POST", "PUT", "PATCH", "DELETE"})


def token_ok(expected: str, headers: Headers, query: QueryParams) -> bool:
    """True when no token is configured or the request carries the right one."""
    if not expected:
        return True
    given = ""
    auth = headers.get("authorization", "")
    if auth.lower().startswith("bearer "):
        given = auth[7:].strip()
    given = given or query.get("token", "")
    return hmac.compare_digest(given.encode(), expected.encode())


def own_origins(port: int | None) -> tuple[str, ...]:
    """The gateway's own loopback origins on ``port`` (none when the port is unknown)."""
    if not port:
        return ()
    return tuple(f"http://{host}:{port}" for host in ("127.0.0.1", "localhost", "[::1]"))


def server_port(scope: Mapping[str, Any]) -> int | None:
    """The port this request reached (the ASGI scope's ``server``), None when unknown."""
    server = scope.get("server")
    return int(server[1]) if server and server[1] is not None else None


def origin_ok(headers: Headers, allowed: tuple[str, ...], port: int | None = None) -> bool:
    """True when the request has no Origin, or its Origin is allowed or one of the gateway's own on ``port``."""
    origin = headers.get("origin")
    if origin is None:
        return True
    origin = origin.rstrip("/")
    if origin in allowed:
        return True
    parts = urlsplit(origin)
    if parts.scheme != "http" or not parts.netloc:
        return False
    return origin.lower() in own_origins(port)
