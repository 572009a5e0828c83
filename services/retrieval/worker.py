"""The retrieval worker: the bus shell around services.retrieval.handlers."""

from __future__ import annotations

from services.retrieval.handlers import CONTRACT
from wana.bus.service import make_frame_handler
from wana.bus.worker import serve


def main(connect: str) -> None:
    from services.retrieval.database import default_db

    default_db()  # load the scene database before registering, so the first job is not slow
    serve("retrieval", make_frame_handler(CONTRACT), connect)
