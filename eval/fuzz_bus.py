"""Coverage-guided fuzzing (atheris) of the bus's and the gateway's decode paths: any exception is a crash.

    .venv/bin/python eval/fuzz_bus.py --json out/eval/fuzz_bus.json [--quick] [--runs N] [--max-s S]

The target feeds each input to one of four decode paths, unguarded, so that anything the per-message
guards would have had to catch counts as a crash: the broker's message handler (``Broker._on_message``
on frames from one of four peers, with its timers run now and then), a worker's frame handler
(``make_frame_handler`` of the echo contract: the reply must decode as a reply or an ErrorReply),
``wire.recv_from_broker`` on a real socket pair (what workers and clients read), and the gateway's
WebSocket message decoder. The full run is 1,000,000 inputs (the issue's target); ``--quick`` runs
20,000 (a CI-sized bounded run). libFuzzer runs in a child process; this script reads its summary.
Keys: ``inputs``, ``seconds``, ``inputs_per_s``, ``crashes``, ``coverage_edges``.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

COMMANDS = ["READY", "REQUEST", "JOB", "REPLY", "ERROR", "BATCH", "HEARTBEAT", "DISCONNECT", "PING", "PONG"]
COMMANDS += ["STATS", "edit", "resume", "ping"]


def _child(argv: list[str]) -> None:
    """Run libFuzzer over the target (never returns: libFuzzer exits when done)."""
    import atheris

    with atheris.instrument_imports():
        import msgspec
        import zmq

        from proto.bus import EchoReply
        from proto.common import ErrorReply
        from services.gateway.protocol import decoder as gateway_decoder
        from wana.bus import wire
        from wana.bus.broker import Broker
        from wana.bus.echo import CONTRACT
        from wana.bus.service import make_frame_handler

    context = zmq.Context.instance()
    broker = Broker(f"inproc://fuzz-{os.getpid()}", context=context, heartbeat_s=0.05, queue_limit=64)
    handle_frame = make_frame_handler(CONTRACT)
    reply_decoder = msgspec.msgpack.Decoder(EchoReply | ErrorReply)
    url = f"inproc://fuzz-pair-{os.getpid()}"
    pair_out, pair_in = context.socket(zmq.PAIR), context.socket(zmq.PAIR)
    pair_out.bind(url)
    pair_in.connect(url)
    seen = [0]

    def frame(fdp) -> bytes:
        """Raw bytes, or a msgpack array led by a command name with fields of any type."""
        if fdp.ConsumeBool():
            return fdp.ConsumeBytes(fdp.ConsumeIntInRange(0, 48))
        fields: list[object] = [fdp.PickValueInList(COMMANDS)]
        for _ in range(fdp.ConsumeIntInRange(0, 8)):
            kind = fdp.ConsumeIntInRange(0, 4)
            if kind == 0:
                fields.append(fdp.ConsumeIntInRange(-(2**63), 2**64 - 1))
            elif kind == 1:
                fields.append(fdp.ConsumeUnicodeNoSurrogates(fdp.ConsumeIntInRange(0, 80)))
            elif kind == 2:
                fields.append(fdp.ConsumeBytes(fdp.ConsumeIntInRange(0, 16)))
            elif kind == 3:
                fields.append(fdp.ConsumeRegularFloat())
            else:
                fields.append("echo")
        return msgspec.msgpack.encode(fields)

    def one_input(data: bytes) -> None:
        fdp = atheris.FuzzedDataProvider(data)
        target = fdp.ConsumeIntInRange(0, 3)
        seen[0] += 1
        if target == 0:
            sender = b"P" + bytes([fdp.ConsumeIntInRange(0, 3)])
            frames = [frame(fdp) for _ in range(fdp.ConsumeIntInRange(1, 5))]
            broker._now = time.monotonic()
            broker._on_message([sender, *frames])
            if seen[0] % 64 == 0:
                broker._flush()
                broker._heartbeat(broker._now)
                broker._expire_jobs(broker._now)
        elif target == 1:
            reply = handle_frame(frame(fdp) if fdp.ConsumeBool() else fdp.ConsumeBytes(256))
            reply_decoder.decode(reply)
        elif target == 2:
            frames = [frame(fdp) for _ in range(fdp.ConsumeIntInRange(1, 5))]
            pair_out.send_multipart(frames)
            if not wire.poll(pair_in, 1.0) or wire.recv_from_broker(pair_in) is None:
                raise AssertionError("a sent message did not arrive")
            if wire.readable(pair_in):
                raise AssertionError("recv_from_broker left frames of the message behind")
        else:
            text = fdp.ConsumeUnicodeNoSurrogates(fdp.ConsumeIntInRange(0, 200))
            try:
                gateway_decoder.decode(text)
            except (msgspec.DecodeError, msgspec.ValidationError):
                pass

    atheris.Setup([sys.argv[0], *argv], one_input)
    atheris.Fuzz()


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="Fuzz the bus and gateway decode paths (issue 18).")
    parser.add_argument("--json", help="write the summary to this JSON file")
    parser.add_argument("--quick", action="store_true", help="20,000 inputs (CI)")
    parser.add_argument("--runs", type=int, default=1_000_000, help="inputs to run (default 1,000,000)")
    parser.add_argument("--max-s", type=float, default=3600.0, help="stop after this many seconds")
    parser.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    args, rest = parser.parse_known_args(argv)
    if args.child:
        _child(rest)
        return 0
    runs = 20_000 if args.quick else args.runs
    with tempfile.TemporaryDirectory(prefix="wana-fuzz-") as tmp:
        command = [
            sys.executable,
            __file__,
            "--child",
            f"-runs={runs}",
            f"-max_total_time={int(args.max_s)}",
            "-max_len=512",
            "-print_final_stats=1",
            f"-artifact_prefix={tmp}/",
            "-rss_limit_mb=2048",
        ]
        env = {**os.environ, "PYTHONPATH": str(REPO)}
        started = time.perf_counter()
        proc = subprocess.run(command, capture_output=True, text=True, env=env, cwd=REPO)
        seconds = time.perf_counter() - started
        log = proc.stderr
        crashes = len(list(Path(tmp).glob("crash-*"))) + len(list(Path(tmp).glob("oom-*")))
        if proc.returncode != 0 and crashes == 0:
            crashes = 1
    done = re.findall(r"Done (\d+) runs in (\d+) second", log)
    inputs = int(done[-1][0]) if done else int((re.findall(r"#(\d+)", log) or ["0"])[-1])
    edges = re.findall(r"cov: (\d+)", log)
    result = {
        "inputs": inputs,
        "seconds": round(seconds, 1),
        "inputs_per_s": round(inputs / seconds, 1) if seconds else 0.0,
        "crashes": crashes,
        "coverage_edges": int(edges[-1]) if edges else 0,
    }
    print(f"{'inputs':<16}{result['inputs']:>12,}")
    print(f"{'seconds':<16}{result['seconds']:>12}")
    print(f"{'inputs per s':<16}{result['inputs_per_s']:>12,}")
    print(f"{'crashes':<16}{result['crashes']:>12}")
    print(f"{'coverage edges':<16}{result['coverage_edges']:>12}")
    if crashes:
        print(log[-4000:], file=sys.stderr)
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps(result, indent=2) + "\n")
    return 1 if crashes else 0


if __name__ == "__main__":
    raise SystemExit(main())
