"""The NLP worker: the bus shell around services.nlp.handlers."""

from __future__ import annotations

from services.nlp.handlers import CONTRACT
from wana.bus.service import make_frame_handler
from wana.bus.worker import serve


def main(connect: str) -> None:
    from services.nlp.pipeline import get_nlp

    get_nlp()  # load the pipeline before registering, so the first job is not slow
    serve("nlp", make_frame_handler(CONTRACT), connect)
