"""The built-in ``echo`` service: a health check for a deployment and the contract harness's example.

CONTRACT: EchoRequest -> EchoReply (proto/bus.py). Serve it with
``.venv/bin/python -m wana.bus.echo tcp://HOST:5555``; its reply carries the worker's pid so that tests
and operators can see which worker answered.
"""

from __future__ import annotations

import argparse
import logging
import os
import time

from proto.bus import EchoReply, EchoRequest
from proto.common import Header
from wana.bus.service import Contract, InvalidInput, make_frame_handler

MAX_SLEEP_S = 60.0


def echo(request: EchoRequest) -> EchoReply:
    """Answer with the same text after ``sleep_s`` seconds.

    Raises:
        InvalidInput: sleep_s outside [0, 60].
    """
    if not 0.0 <= request.sleep_s <= MAX_SLEEP_S:
        raise InvalidInput(f"sleep_s must be within [0, {MAX_SLEEP_S:g}] seconds, got {request.sleep_s}")
    if request.sleep_s:
        time.sleep(request.sleep_s)
    h = request.header
    return EchoReply(
        header=Header(parent_id=h.msg_id, doc_id=h.doc_id, revision=h.revision),
        text=request.text,
        worker_pid=os.getpid(),
    )


CONTRACT: Contract = {EchoRequest: echo}


def main(connect: str) -> None:
    """Serve the echo service at ``connect`` until SIGTERM/SIGINT."""
    from wana.bus.worker import serve

    serve("echo", make_frame_handler(CONTRACT), connect)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description="Serve the built-in echo service (a bus health check).")
    parser.add_argument("connect", help="broker URL, e.g. tcp://127.0.0.1:5555 or ipc:///tmp/wana.sock")
    logging.basicConfig(level=logging.INFO, format="%(asctime)s %(name)s %(levelname)s %(message)s")
    main(parser.parse_args().connect)
