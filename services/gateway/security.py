"""Who may call the gateway: a bearer token (when configured) and an Origin check against cross-site use.

The token travels as `Authorization: Bearer TOKEN`, or, where a browser cannot set headers (WebSocket,
download links), as a short-lived session cookie that `POST /api/session` (the `/login` page) hands out
for the token: an HMAC of its expiry under the token, HttpOnly and SameSite=Strict. Never in a URL:
`?token=` ended up in access logs and in the printed start-up address. The Origin check applies to WebSocket handshakes and to every
state-changing request (POST, PUT, PATCH, DELETE): a browser page from another site must not drive the
editor. Requests without an Origin header (curl, scripts) are not browsers and pass this check.

An Origin passes only when it is in the allow list: the gateway's own loopback origins on the port it
serves (``http://127.0.0.1:PORT``, ``http://localhost:PORT``, ``http://[::1]:PORT``) plus
``WANA_ALLOWED_ORIGINS``. ``Origin`` equal to ``Host`` is not enough: a DNS-rebinding page
(``http://evil.example:PORT`` resolving to 127.0.0.1) sends exactly that.
"""

from __future__ import annotations

import hashlib
import hmac
import time
from collections.abc import Mapping
from typing import Any
from urllib.parse import urlsplit

from starlette.datastructures import Headers

STATE_CHANGING = frozenset({"POST", "PUT", "PATCH", "DELETE"})
SESSION_COOKIE = "wana_session"


def bearer_ok(expected: str, headers: Headers) -> bool:
    """True when the request carries ``Authorization: Bearer <expected>``."""
    auth = headers.get("authorization", "")
    given = auth[7:].strip() if auth.lower().startswith("bearer ") else ""
    return bool(given) and hmac.compare_digest(given.encode(), expected.encode())


def session_cookie(token: str, ttl_s: float, now: float | None = None) -> str:
    """A session cookie value valid for ``ttl_s`` seconds: ``EXPIRY.HMAC(token, EXPIRY)``."""
    expiry = int((time.time() if now is None else now) + ttl_s)
    return f"{expiry}.{_sign(token, expiry)}"


def cookie_ok(token: str, value: str, now: float | None = None) -> bool:
    """True for a session cookie signed with ``token`` that has not expired."""
    expiry_text, _, signature = value.partition(".")
    if not expiry_text.isdigit() or not signature:
        return False
    expiry = int(expiry_text)
    if expiry < (time.time() if now is None else now):
        return False
    return hmac.compare_digest(signature.encode(), _sign(token, expiry).encode())


def _sign(token: str, expiry: int) -> str:
    return hmac.new(token.encode(), f"wana-session:{expiry}".encode(), hashlib.sha256).hexdigest()


def token_ok(expected: str, headers: Headers, cookies: Mapping[str, str] | None = None) -> bool:
    """True when no token is configured, or the request carries it as a bearer header or a valid cookie."""
    if not expected:
        return True
    if bearer_ok(expected, headers):
        return True
    cookie = (cookies or {}).get(SESSION_COOKIE, "")
    return bool(cookie) and cookie_ok(expected, cookie)


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
