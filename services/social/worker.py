"""The social worker: the bus shell around services.social.handlers."""

from __future__ import annotations

from services.social.handlers import CONTRACT
from wana.bus.service import make_frame_handler
from wana.bus.worker import serve


def main(connect: str) -> None:
    serve("social", make_frame_handler(CONTRACT), connect)
