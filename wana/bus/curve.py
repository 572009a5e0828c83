"""CURVE keys and allow lists for a bus that leaves the machine (ZeroMQ CURVE + ZAP via ``zmq.auth``).

A key directory, made by ``wana keys new DIR``, holds::

    broker.key  broker.key_secret       the broker's pair (clients and workers need broker.key)
    client.key  client.key_secret       a pair for clients (the orchestrator, the gateway, tools)
    worker.key  worker.key_secret       a pair for workers
    allow/clients/*.key                 public keys that may send REQUEST and STATS
    allow/workers/*.key                 public keys that may register for any service
    allow/workers/<service>/*.key       public keys that may register for that service only

The broker's ZAP handler admits only the public keys of the allow lists (a peer with any other key
never completes its handshake); the broker then checks each command against the sender's role,
which ZAP hands it as the message's ``User-Id`` (the sender's public key, Z85). Workers and clients
find the directory through ``keys=`` or the environment variable ``WANA_BUS_KEYS``. A deployment
mounts it from a Secret; it is never baked into an image.

Binding anything but loopback, ``ipc://`` or ``inproc://`` without keys is refused
(``InsecureBind``) unless the caller passes ``insecure=True``, which logs a warning.
"""

from __future__ import annotations

import logging
import os
import shutil
from dataclasses import dataclass, field
from pathlib import Path

import zmq
import zmq.auth
from zmq.auth.thread import ThreadAuthenticator

log = logging.getLogger(__name__)

KEYS_ENV = "WANA_BUS_KEYS"
ZAP_DOMAIN = "wana"
ROLES = ("broker", "client", "worker")
_LOOPBACK = {"127.0.0.1", "localhost", "::1", "[::1]"}


class InsecureBind(ValueError):
    """An endpoint other than loopback/ipc/inproc would be bound without CURVE keys."""


def new_keys(directory: str | Path, services: tuple[str, ...] = ()) -> list[Path]:
    """Make the broker, client and worker key pairs and the allow lists in ``directory``.

    Args:
        directory: created if missing; existing key files are left alone (never overwritten).
        services: when given, the worker key is allowed for these services only (else for all).

    Returns:
        The files written.
    """
    root = Path(directory)
    root.mkdir(parents=True, exist_ok=True)
    written: list[Path] = []
    for role in ROLES:
        if not (root / f"{role}.key_secret").exists():
            public, secret = zmq.auth.create_certificates(str(root), role)
            written += [Path(public), Path(secret)]
            os.chmod(secret, 0o600)
    clients = root / "allow" / "clients"
    clients.mkdir(parents=True, exist_ok=True)
    targets = [clients]
    if services:
        targets += [root / "allow" / "workers" / s for s in services]
    else:
        targets.append(root / "allow" / "workers")
    for target in targets:
        target.mkdir(parents=True, exist_ok=True)
        role = "client" if target == clients else "worker"
        dest = target / f"{role}.key"
        if not dest.exists():
            shutil.copyfile(root / f"{role}.key", dest)
            written.append(dest)
    return written


def keys_dir(keys: str | os.PathLike[str] | None) -> Path | None:
    """The key directory to use: ``keys``, else ``$WANA_BUS_KEYS``, else None (no CURVE)."""
    chosen = keys if keys is not None else os.environ.get(KEYS_ENV) or None
    return None if chosen is None else Path(chosen)


def _public_keys(directory: Path) -> set[str]:
    found = set()
    for path in sorted(directory.glob("*.key")):
        public, _ = zmq.auth.load_certificate(str(path))
        found.add(public.decode("ascii"))
    return found


@dataclass
class AllowList:
    """Public keys (Z85 text, as ZAP's User-Id) per role."""

    clients: set[str] = field(default_factory=set)
    workers: set[str] = field(default_factory=set)  # may serve any service
    by_service: dict[str, set[str]] = field(default_factory=dict)

    @classmethod
    def load(cls, root: Path) -> AllowList:
        allow = root / "allow"
        workers = allow / "workers"
        by_service = {}
        if workers.is_dir():
            by_service = {d.name: _public_keys(d) for d in sorted(workers.iterdir()) if d.is_dir()}
        return cls(
            clients=_public_keys(allow / "clients") if (allow / "clients").is_dir() else set(),
            workers=_public_keys(workers) if workers.is_dir() else set(),
            by_service=by_service,
        )

    def known(self, key: str) -> bool:
        return key in self.clients or key in self.workers or any(key in s for s in self.by_service.values())

    def may_serve(self, key: str, service: str) -> bool:
        return key in self.workers or key in self.by_service.get(service, ())

    def is_client(self, key: str) -> bool:
        return key in self.clients


class _Provider:
    """ZAP credentials callback: admit only the keys of the allow lists."""

    def __init__(self, allow: AllowList):
        self.allow = allow

    def callback(self, domain: str, key: bytes) -> bool:
        text = key.decode("ascii", "replace")  # pyzmq hands the key Z85-encoded
        admitted = self.allow.known(text)
        if not admitted:
            log.warning("bus: refused a CURVE peer whose key is in no allow list")
        return admitted


def serve_curve(
    socket: zmq.Socket, context: zmq.Context, root: Path
) -> tuple[ThreadAuthenticator, AllowList]:
    """Make ``socket`` (not bound yet) a CURVE server with a ZAP handler in ``context``."""
    public, secret = zmq.auth.load_certificate(str(root / "broker.key_secret"))
    if secret is None:
        raise ValueError(f"{root / 'broker.key_secret'} holds no secret key")
    allow = AllowList.load(root)
    auth = ThreadAuthenticator(context, log=logging.getLogger("wana.bus.zap"))
    auth.start()
    auth.configure_curve_callback(domain=ZAP_DOMAIN, credentials_provider=_Provider(allow))
    socket.setsockopt(zmq.ZAP_DOMAIN, ZAP_DOMAIN.encode())
    socket.curve_secretkey = secret
    socket.curve_publickey = public
    socket.curve_server = True
    return auth, allow


def connect_curve(socket: zmq.Socket, root: Path, role: str) -> None:
    """Make ``socket`` (not connected yet) a CURVE client of the broker with the ``role`` pair."""
    server_public, _ = zmq.auth.load_certificate(str(root / "broker.key"))
    public, secret = zmq.auth.load_certificate(str(root / f"{role}.key_secret"))
    if secret is None:
        raise ValueError(f"{root / f'{role}.key_secret'} holds no secret key")
    socket.curve_serverkey = server_public
    socket.curve_publickey = public
    socket.curve_secretkey = secret


def check_bind(url: str, *, secure: bool, insecure: bool) -> None:
    """Refuse to bind a non-loopback TCP endpoint without keys (unless ``insecure``, which warns).

    Raises:
        InsecureBind: with what to do instead.
    """
    if secure or not url.startswith("tcp://"):
        return
    host = url[len("tcp://") :].rsplit(":", 1)[0]
    if host in _LOOPBACK or host.startswith("127."):
        return
    if insecure:
        log.warning(
            "bus: %s is bound WITHOUT keys (--insecure): any peer that reaches it can read and forge jobs",
            url,
        )
        return
    raise InsecureBind(
        f"refusing to bind {url} without CURVE keys: any peer that can reach it could register as a worker, "
        f"read payloads and forge replies. Make keys with `wana keys new DIR` and pass --keys DIR (or set "
        f"{KEYS_ENV}=DIR) to the broker, its workers and clients; or pass --insecure on a network you trust."
    )
