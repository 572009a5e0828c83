"""The optimizer worker: the bus shell around services.optimizer.handlers."""

from __future__ import annotations

from services.optimizer.handlers import CONTRACT
from wana.bus.service import make_frame_handler
from wana.bus.worker import serve


def main(connect: str) -> None:
    serve("optimizer", make_frame_handler(CONTRACT), connect)
