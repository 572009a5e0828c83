"""A small worker process for the bus tests: echo, sleep, die, or answer big.

    python echo_worker.py URL [--service echo] [--heartbeat 0.1] [--max-frame BYTES]

Payload commands (bytes): ``sleep:<seconds>:<text>`` answers ``<pid>:<text>`` after sleeping;
``die`` kills this process with SIGKILL mid-job; ``big:<n>`` answers n bytes; anything else is
answered as ``<pid>:<payload>``.
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[3]))

from wana.bus.worker import serve  # noqa: E402


def handle(payload: bytes) -> bytes:
    pid = str(os.getpid()).encode()
    if payload.startswith(b"sleep:"):
        _, seconds, text = payload.split(b":", 2)
        time.sleep(float(seconds))
        return pid + b":" + text
    if payload == b"die":
        os.kill(os.getpid(), signal.SIGKILL)
    if payload.startswith(b"big:"):
        return b"b" * int(payload[4:])
    return pid + b":" + payload


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("url")
    parser.add_argument("--service", default="echo")
    parser.add_argument("--heartbeat", type=float, default=0.1)
    args = parser.parse_args()
    serve(args.service, handle, args.url, heartbeat_s=args.heartbeat)


if __name__ == "__main__":
    main()
