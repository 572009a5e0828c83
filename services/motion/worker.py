"""The motion worker: the bus shell around services.motion.handlers."""

from __future__ import annotations

from services.motion.handlers import CONTRACT
from wana.bus.service import make_frame_handler
from wana.bus.worker import serve


def main(connect: str) -> None:
    serve("motion", make_frame_handler(CONTRACT), connect)
