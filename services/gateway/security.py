"""Who may call the gateway: a bearer token (when configured) and an Origin check against cross-site use.

The token travels as `Authorization: Bearer TOKEN` or, where a browser cannot set headers (WebSocket,
download links), as `?token=TOKEN`. The Origin check applies to WebSocket handshakes and to every
state-changing request (POST, PUT, PATCH, DELETE): a browser page from another site must not drive the
editor. Requests without an Origin header (curl, scripts) are not browsers and pass this check.
"""

from __future__ import annotations

import hmac
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


def origin_ok(headers: Headers, allowed: tuple[str, ...]) -> bool:
    """True when the request has no Origin, comes from the page's own host, or from an allowed origin."""
    origin = headers.get("origin")
    if origin is None:
        return True
    origin = origin.rstrip("/")
    if origin in allowed:
        return True
    parts = urlsplit(origin)
    if parts.scheme not in ("http", "https") or not parts.netloc:
        return False
    host = headers.get("host", "")
    return bool(host) and parts.netloc.lower() == host.lower()
