"""Gateway settings, read from the environment (WANA_*) in one place, overridable from the command line."""

from __future__ import annotations

import dataclasses
import ipaddress
import os
from dataclasses import dataclass
from pathlib import Path

from services.orchestrator.budget import Budget
from services.orchestrator.registry import SERVICES  # the one service list

REPO = Path(__file__).resolve().parents[2]
DEFAULT_DB = Path(os.path.expanduser("~")) / ".wana" / "sessions.sqlite"


def _env_int(name: str, default: int) -> int:
    raw = os.environ.get(name, "")
    if not raw:
        return default
    try:
        return int(raw)
    except ValueError as exc:
        raise ValueError(f"{name} must be an integer, got {raw!r}") from exc


def _env_bool(name: str, default: bool) -> bool:
    raw = os.environ.get(name, "").strip().lower()
    if not raw:
        return default
    if raw in ("1", "true", "yes", "on"):
        return True
    if raw in ("0", "false", "no", "off"):
        return False
    raise ValueError(f"{name} must be true or false, got {raw!r}")


def _env_float(name: str, default: float) -> float:
    raw = os.environ.get(name, "")
    if not raw:
        return default
    try:
        return float(raw)
    except ValueError as exc:
        raise ValueError(f"{name} must be a number, got {raw!r}") from exc


def is_loopback(host: str) -> bool:
    """True for addresses only this machine can reach (127.0.0.0/8, ::1, localhost)."""
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host.strip("[]")).is_loopback
    except ValueError:
        return False


def parse_services(raw: str) -> tuple[str, ...]:
    """A comma-separated list of service names ("" = none).

    Raises:
        ValueError: an unknown service name.
    """
    names = tuple(n.strip() for n in raw.split(",") if n.strip())
    unknown = [n for n in names if n not in SERVICES]
    if unknown:
        raise ValueError(f"unknown service(s) {', '.join(unknown)}; choose from {', '.join(SERVICES)}")
    return names


@dataclass(frozen=True)
class Settings:
    """Everything the gateway can be told. `from_env()` reads WANA_<FIELD NAME IN CAPITALS>."""

    host: str = "127.0.0.1"  # WANA_HOST
    port: int = 8765  # WANA_PORT
    db: Path = DEFAULT_DB  # WANA_DB: the session database (SQLite, WAL)
    token: str = ""  # WANA_TOKEN: required on every API call when set; must be set off loopback
    allowed_origins: tuple[str, ...] = ()  # WANA_ALLOWED_ORIGINS (comma separated), besides same-origin
    editor_dist: Path = REPO / "editor" / "dist"  # WANA_EDITOR_DIST: the built web client
    backend: str = "auto"  # WANA_BACKEND: auto | inprocess | embedded | remote (needs WANA_BROKER)
    seed: int = 0  # WANA_SEED: seed of every session's pipeline
    services: tuple[str, ...] | None = (
        None  # WANA_SERVICES: services the pipeline may use (comma list); None = all
    )
    max_message_bytes: int = 1 << 20  # WANA_MAX_MESSAGE_BYTES: one WebSocket message or REST body
    max_changes: int = 256  # WANA_MAX_CHANGES: text changes in one edit message
    compute_threads: int = 2  # WANA_COMPUTE_THREADS: documents computed at the same time
    mesh_cache: int = 256  # WANA_MESH_CACHE: GLB variants kept in memory
    broker: str = ""  # WANA_BROKER: a broker URL (tcp://HOST:5555) whose workers do the work; implies remote
    # WANA_WS_COMPRESSION: permessage-deflate on the WebSocket. Off by default: deflating a 1 MB animation
    # costs ~50-70 ms of the event loop and saves only ~25% (base64 of float32 compresses poorly).
    ws_compression: bool = False
    session_ttl_s: int = 12 * 3600  # WANA_SESSION_TTL_S: lifetime of the login cookie (seconds)
    # The compute budget of one document (services/orchestrator/budget.py): what is over it is cut, with a
    # W501 warning on the sentence, and the rest still animates.
    max_seconds: float = Budget.max_seconds  # WANA_MAX_SECONDS: wall time of one compute
    max_sentences: int = Budget.max_sentences  # WANA_MAX_SENTENCES
    max_sentence_chars: int = Budget.max_sentence_chars  # WANA_MAX_SENTENCE_CHARS
    max_wait_s: float = Budget.max_wait_s  # WANA_MAX_WAIT_S: one `wait` command
    max_duration_s: float = Budget.max_duration_s  # WANA_MAX_DURATION_S: all waits together

    @property
    def budget(self) -> Budget:
        return Budget(
            max_seconds=self.max_seconds,
            max_sentences=self.max_sentences,
            max_sentence_chars=self.max_sentence_chars,
            max_wait_s=self.max_wait_s,
            max_duration_s=self.max_duration_s,
        )

    @property
    def ws_max_size(self) -> int:
        """uvicorn's hard WebSocket frame cap: well above max_message_bytes, so that the app itself
        answers an oversize message with E002 instead of the connection closing (1009) unanswered."""
        return 4 * self.max_message_bytes + 4096

    @classmethod
    def from_env(cls, **overrides: object) -> Settings:
        """Settings from WANA_* environment variables; keyword overrides (not None) win."""
        env = os.environ
        origins = tuple(
            o.strip().rstrip("/") for o in env.get("WANA_ALLOWED_ORIGINS", "").split(",") if o.strip()
        )
        base = cls(
            host=env.get("WANA_HOST", cls.host),
            port=_env_int("WANA_PORT", cls.port),
            db=Path(env["WANA_DB"]) if env.get("WANA_DB") else DEFAULT_DB,
            token=env.get("WANA_TOKEN", ""),
            allowed_origins=origins,
            editor_dist=Path(env["WANA_EDITOR_DIST"]) if env.get("WANA_EDITOR_DIST") else cls.editor_dist,
            backend=env.get("WANA_BACKEND", cls.backend),
            broker=env.get("WANA_BROKER", ""),
            seed=_env_int("WANA_SEED", cls.seed),
            services=parse_services(env["WANA_SERVICES"]) if "WANA_SERVICES" in env else None,
            max_message_bytes=_env_int("WANA_MAX_MESSAGE_BYTES", cls.max_message_bytes),
            max_changes=_env_int("WANA_MAX_CHANGES", cls.max_changes),
            compute_threads=_env_int("WANA_COMPUTE_THREADS", cls.compute_threads),
            mesh_cache=_env_int("WANA_MESH_CACHE", cls.mesh_cache),
            ws_compression=_env_bool("WANA_WS_COMPRESSION", cls.ws_compression),
            session_ttl_s=_env_int("WANA_SESSION_TTL_S", cls.session_ttl_s),
            max_seconds=_env_float("WANA_MAX_SECONDS", cls.max_seconds),
            max_sentences=_env_int("WANA_MAX_SENTENCES", cls.max_sentences),
            max_sentence_chars=_env_int("WANA_MAX_SENTENCE_CHARS", cls.max_sentence_chars),
            max_wait_s=_env_float("WANA_MAX_WAIT_S", cls.max_wait_s),
            max_duration_s=_env_float("WANA_MAX_DURATION_S", cls.max_duration_s),
        )
        return base.replace(**{k: v for k, v in overrides.items() if v is not None})

    def replace(self, **changes: object) -> Settings:
        if "db" in changes:
            changes["db"] = Path(str(changes["db"]))
        return dataclasses.replace(self, **changes)  # type: ignore[arg-type]

    def check(self) -> None:
        """Refuse unsafe or impossible settings with a message a user can act on.

        Raises:
            ValueError: a non-loopback bind without a token, a bad backend name or a bad limit.
        """
        if not is_loopback(self.host) and not self.token:
            raise ValueError(
                f"binding to {self.host} exposes the editor to the network; set a token with --token or "
                "WANA_TOKEN (clients then pass it as 'Authorization: Bearer TOKEN'; browsers log in at /login)"
            )
        if self.backend not in ("auto", "inprocess", "embedded", "remote"):
            raise ValueError(f"backend must be auto, inprocess, embedded or remote, not {self.backend!r}")
        if self.backend == "remote" and not self.broker:
            raise ValueError("the remote backend needs a broker URL (--broker or WANA_BROKER)")
        if self.max_message_bytes < 1024:
            raise ValueError("max_message_bytes must be at least 1024")
        self.budget.check()
        if not 0 <= self.port <= 65535:
            raise ValueError(f"port {self.port} is outside 0..65535")
