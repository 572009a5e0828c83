"""The gateway application and `wana serve`.

`create_app(settings, orchestrator=None)` builds the FastAPI app (tests pass their own orchestrator);
`main(argv)` parses the command line, checks the settings and runs uvicorn.
"""

from __future__ import annotations

import argparse
import contextlib
import logging
import sys
from collections.abc import AsyncIterator
from concurrent.futures import ThreadPoolExecutor
from typing import Any

from fastapi import Depends, FastAPI, Response
from fastapi.responses import HTMLResponse, JSONResponse
from fastapi.staticfiles import StaticFiles
from prometheus_client import CONTENT_TYPE_LATEST, generate_latest
from starlette.middleware.gzip import GZipMiddleware
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from proto.common import ErrorCode
from services.gateway import deps
from services.gateway import metrics as gateway_metrics
from services.gateway.live import LiveHub
from services.gateway.meshes import MeshCache
from services.gateway.routers import documents, exports, live, meshes, session
from services.gateway.settings import Settings, is_loopback, parse_services
from services.orchestrator.backend import ServiceSubset
from services.orchestrator.registry import SERVICES
from services.orchestrator.session import Orchestrator

log = logging.getLogger(__name__)

API_VERSION = "1"

NOT_BUILT = """<!doctype html><meta charset="utf-8"><title>wana</title>
<h1>The wana editor is not built</h1>
<p>Build it once with <code>cd editor &amp;&amp; npm ci &amp;&amp; npm run build</code> (or <code>make setup</code>),
then reload. The API is live: <a href="/docs">/docs</a>.</p>"""


class BodyLimit:
    """ASGI middleware: refuse HTTP request bodies over the limit with 413 (WebSocket frames are capped by
    uvicorn's ws_max_size and by the live endpoint)."""

    def __init__(self, app: ASGIApp, limit: int) -> None:
        self.app = app
        self.limit = limit

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        declared = dict(scope.get("headers", [])).get(b"content-length")
        if declared is not None and declared.isdigit() and int(declared) > self.limit:
            await self._too_large(send)
            return
        seen = 0
        refused = False

        async def limited_receive() -> Message:
            # Over the limit: answer 413 now and tell the app the client went away.
            nonlocal seen, refused
            if refused:
                return {"type": "http.disconnect"}
            message = await receive()
            if message["type"] == "http.request":
                seen += len(message.get("body", b""))
                if seen > self.limit:
                    refused = True
                    await self._too_large(send)
                    return {"type": "http.disconnect"}
            return message

        async def guarded_send(message: Message) -> None:
            if not refused:  # the app's own answer after a refusal is dropped
                await send(message)

        await self.app(scope, limited_receive, guarded_send)

    async def _too_large(self, send: Send) -> None:
        response = JSONResponse(
            {"detail": {"code": ErrorCode.TOO_LARGE, "message": f"request body over {self.limit} bytes"}},
            status_code=413,
        )
        await response({"type": "http"}, _no_receive, send)


async def _no_receive() -> Message:  # pragma: no cover - JSONResponse never reads
    return {"type": "http.disconnect"}


def make_backend(settings: Settings, stack: contextlib.ExitStack) -> Any:
    """The orchestrator backend: the embedded bus (broker + workers in-process) or direct handler calls,
    limited to settings.services when given."""
    missing: dict[str, str] = {}
    if settings.services is not None:
        missing = {
            s: "not enabled in this gateway (--services)" for s in SERVICES if s not in settings.services
        }
    backend: Any = None
    if settings.broker and settings.backend in ("auto", "remote"):
        from services.orchestrator.backend import RemoteBusBackend

        remote = RemoteBusBackend(settings.broker)
        stack.callback(remote.close)
        backend = remote
    elif settings.backend in ("auto", "embedded"):
        from services.orchestrator.embedded import Embedded

        backend = stack.enter_context(Embedded(tuple(s for s in SERVICES if s not in missing)))
    if backend is None:
        from services.orchestrator.backend import InProcessBackend

        backend = InProcessBackend()
    return ServiceSubset(backend, missing) if missing else backend


def create_app(settings: Settings | None = None, orchestrator: Orchestrator | None = None) -> FastAPI:
    """The gateway app. Without an orchestrator, one is opened on settings.db at start-up and closed at exit."""
    settings = settings or Settings.from_env()

    @contextlib.asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        with contextlib.ExitStack() as stack:
            orch = orchestrator
            if orch is None:
                backend = make_backend(settings, stack)
                orch = Orchestrator(settings.db, backend, seed=settings.seed, budget=settings.budget)
                stack.callback(orch.close)
            executor = ThreadPoolExecutor(settings.compute_threads, thread_name_prefix="wana-compute")
            stack.callback(executor.shutdown, wait=False, cancel_futures=True)
            app.state.orchestrator = orch
            app.state.hub = LiveHub(orch, executor)
            yield
            for channel in list(app.state.hub.channels.values()):
                if channel._task is not None:  # noqa: SLF001 - stop pending computes before closing the db
                    channel._task.cancel()  # noqa: SLF001

    app = FastAPI(
        title="wana gateway",
        version=API_VERSION,
        description="Documents, text edits and live animation for the wana editor. The WebSocket protocol "
        "(/api/documents/{doc_id}/live) is described in services/gateway/README.md.",
        lifespan=lifespan,
    )
    app.state.settings = settings
    app.state.meshes = MeshCache(settings.mesh_cache)
    guarded = [Depends(deps.guard)]
    app.include_router(documents.router, dependencies=guarded)
    app.include_router(exports.router, dependencies=guarded)
    app.include_router(meshes.router, dependencies=guarded)
    app.include_router(live.router)
    app.include_router(session.router)

    @app.get("/api/health", tags=["health"], summary="Liveness and which pipeline stages this build has")
    async def health() -> dict[str, Any]:
        return {"status": "ok", "api_version": API_VERSION}

    @app.get("/healthz", include_in_schema=False)
    async def healthz() -> JSONResponse:
        # Readiness (the Kubernetes probe, compose's healthcheck): 200 once the session database is open.
        ready = getattr(app.state, "orchestrator", None) is not None
        return JSONResponse({"status": "ok" if ready else "starting"}, status_code=200 if ready else 503)

    @app.get("/metrics", include_in_schema=False)
    async def prometheus_metrics() -> Response:
        return Response(generate_latest(gateway_metrics.REGISTRY), media_type=CONTENT_TYPE_LATEST)

    if (settings.editor_dist / "index.html").is_file():
        # the bundle gzipped for a browser that accepts it (about a quarter of its size)
        editor = GZipMiddleware(StaticFiles(directory=settings.editor_dist, html=True), minimum_size=1024)
        app.mount("/", editor, name="editor")
    else:

        @app.get("/", include_in_schema=False)
        async def editor_missing() -> HTMLResponse:
            return HTMLResponse(NOT_BUILT, status_code=503)

    app.add_middleware(BodyLimit, limit=settings.max_message_bytes)
    return app


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="wana serve",
        description="Serve the web editor and its gateway (REST + WebSocket). Binds 127.0.0.1 unless told "
        "otherwise; any other address needs a token. Every option also reads a WANA_* environment variable.",
        epilog="example: wana serve --port 8765 --db ~/.wana/sessions.sqlite   (then open http://127.0.0.1:8765)",
    )
    p.add_argument("--host", default=None, help="address to bind (WANA_HOST; default 127.0.0.1)")
    p.add_argument(
        "--port", type=int, default=None, help="port (WANA_PORT; default 8765; 0 picks a free one)"
    )
    p.add_argument(
        "--db", default=None, help="session database file (WANA_DB; default ~/.wana/sessions.sqlite)"
    )
    p.add_argument(
        "--token",
        default=None,
        help="token every client must send (WANA_TOKEN); required when --host is not a loopback address",
    )
    p.add_argument(
        "--allow-origin",
        action="append",
        default=None,
        metavar="ORIGIN",
        help="another origin allowed to use the API, e.g. http://localhost:5173 (repeatable; "
        "WANA_ALLOWED_ORIGINS, comma separated)",
    )
    p.add_argument(
        "--backend",
        choices=("auto", "inprocess", "embedded", "remote"),
        default=None,
        help="how the orchestrator reaches the services: the embedded bus, direct handler calls, or the "
        "workers of a remote broker (WANA_BACKEND; default auto = remote with --broker, else embedded)",
    )
    p.add_argument(
        "--broker",
        default=None,
        metavar="URL",
        help="use the workers of the broker at URL, e.g. tcp://HOST:5555 (WANA_BROKER); scale out with "
        "`wana broker` and `wana worker SERVICE --connect URL`",
    )
    p.add_argument(
        "--services",
        default=None,
        metavar="LIST",
        help=f"comma-separated services the pipeline may use, from {','.join(SERVICES)} (WANA_SERVICES; "
        "default all; e.g. --services nlp gives diagnostics only, fast)",
    )
    p.add_argument(
        "--seed", type=int, default=None, help="seed of every random choice (WANA_SEED; default 0)"
    )
    p.add_argument(
        "--max-seconds",
        type=float,
        default=None,
        metavar="S",
        help="compute budget: wall time of one document's compute (WANA_MAX_SECONDS; default 600); what "
        "goes over it, or over WANA_MAX_SENTENCES (200), WANA_MAX_SENTENCE_CHARS (2000), WANA_MAX_WAIT_S "
        "(60) or WANA_MAX_DURATION_S (600), is cut with a W501 warning and the rest still animates",
    )
    p.add_argument("--log-level", default="info", choices=("critical", "error", "warning", "info", "debug"))
    return p


def main(argv: list[str] | None = None) -> int:
    """`wana serve`: run the gateway with uvicorn until interrupted. Returns the exit status."""
    args = build_parser().parse_args(argv)
    try:
        settings = Settings.from_env(
            host=args.host,
            port=args.port,
            db=args.db,
            token=args.token,
            backend=args.backend,
            broker=args.broker,
            seed=args.seed,
            services=parse_services(args.services) if args.services is not None else None,
            allowed_origins=tuple(o.rstrip("/") for o in args.allow_origin) if args.allow_origin else None,
            max_seconds=args.max_seconds,
        )
        settings.check()
    except ValueError as exc:
        print(f"wana serve: {exc}", file=sys.stderr)
        return 2
    import uvicorn

    logging.basicConfig(level=args.log_level.upper(), format="%(asctime)s %(name)s %(levelname)s %(message)s")
    shown = settings.host if is_loopback(settings.host) or settings.host not in ("0.0.0.0", "::") else "HOST"
    login = "  (log in at /login with the token from --token / WANA_TOKEN)" if settings.token else ""
    print(  # the token itself is never printed, nor put in a URL
        f"wana editor: http://{shown}:{settings.port}/{login}  (database {settings.db})",
        file=sys.stderr,
        flush=True,
    )
    if not (settings.editor_dist / "index.html").is_file():
        print(
            f"wana serve: the editor is not built ({settings.editor_dist} is missing): run "
            "`cd editor && npm ci && npm run build`; the API works without it",
            file=sys.stderr,
        )
    uvicorn.run(
        create_app(settings),
        host=settings.host,
        port=settings.port,
        log_level=args.log_level,
        ws_max_size=settings.ws_max_size,
        ws_per_message_deflate=settings.ws_compression,
        timeout_graceful_shutdown=2,
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
