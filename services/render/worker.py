"""The render worker: bus sockets around services.render.handlers."""

from __future__ import annotations

from services.render.handlers import CONTRACT
from wana.bus.service import make_frame_handler
from wana.bus.worker import serve


def main(connect: str) -> None:
    """Serve "render" requests from the broker at ``connect`` (blocks)."""
    serve("render", make_frame_handler(CONTRACT), connect)


if __name__ == "__main__":
    import sys

    main(sys.argv[1] if len(sys.argv) > 1 else "ipc:///tmp/wana-bus.sock")
