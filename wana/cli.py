"""The `wana` command: animate, serve, broker, worker, metrics, keys, parse, assets, motion.

Each sub-command delegates to the module that owns the work, imported lazily so that `wana --help` is fast
and a stage whose logic is missing reports itself instead of breaking the others.
"""

from __future__ import annotations

import argparse
import importlib
import logging
import os
import sys
from collections.abc import Callable

from services.orchestrator.registry import SERVICES  # the one service list (imports only proto and wana.bus)

DESCRIPTION = """\
wana (Write-An-Animation) turns a text you write into a 3D animation.

Scene sentences end in `$` and furnish a room ("A laptop is on the desk$."); other sentences make
characters act ("Eve walks to the chair. She sits."); lines like `camera left` or `night` are commands.

examples:
  wana animate examples/office.txt -o out/      # the whole pipeline, embedded, writes out/animation.mp4 ...
  wana parse "Eve sits on the chair."           # the semantic scene graph as JSON
  wana serve                                    # the web editor on http://127.0.0.1:8765
  wana keys new keys/                           # CURVE key pairs and allow lists for a bus across hosts
  wana broker --bind tcp://0.0.0.0:5555 --keys keys/         # scale out: a broker here ...
  wana worker motion --connect tcp://HOST:5555 --keys keys/  # ... and workers anywhere
  wana metrics --broker tcp://HOST:5555 --port 9108          # its queue depths for Prometheus
"""


def _delegate(module: str, argv: list[str], what: str) -> int:
    try:
        mod = importlib.import_module(module)
    except ImportError as exc:
        print(f"wana: {what} is not available in this build ({exc})", file=sys.stderr)
        return 3
    main: Callable[[list[str]], int] = mod.main
    return int(main(argv) or 0)


def _cmd_broker(args: argparse.Namespace) -> int:
    from wana.bus.broker import Broker
    from wana.bus.curve import InsecureBind, keys_dir

    try:
        broker = Broker(
            args.bind, queue_limit=args.queue_limit, keys=keys_dir(args.keys), insecure=args.insecure
        )
    except InsecureBind as exc:
        print(f"wana broker: {exc}", file=sys.stderr)
        return 2
    print(f"wana broker listening on {', '.join(args.bind)}", file=sys.stderr, flush=True)
    try:
        broker.run()
    except KeyboardInterrupt:
        pass
    finally:
        broker.close()
    return 0


def _cmd_worker(args: argparse.Namespace) -> int:
    try:
        importlib.import_module(f"services.{args.service}.worker")  # in this build?
    except ImportError as exc:
        print(f"wana: the {args.service} worker is not available in this build ({exc})", file=sys.stderr)
        return 3
    if args.keys:  # the worker (deep inside the service's main) reads the key directory from here
        os.environ["WANA_BUS_KEYS"] = args.keys
    print(f"wana worker {args.service} connecting to {args.connect}", file=sys.stderr, flush=True)
    from wana.compose import serve_worker  # wires what the service needs of others (the optimiser's motion)

    try:
        serve_worker(args.service, args.connect)
    except KeyboardInterrupt:
        pass
    return 0


def _cmd_keys(args: argparse.Namespace) -> int:
    from wana.bus.curve import new_keys

    written = new_keys(args.directory, tuple(args.service or ()))
    for path in written:
        print(path)
    print(
        f"wana keys: {len(written)} files in {args.directory}; keep the *_secret files secret "
        "(mount them from a Secret, never bake them into an image)",
        file=sys.stderr,
    )
    return 0


_KEYS_HELP = "CURVE key directory from `wana keys new` (default: $WANA_BUS_KEYS)"


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="wana", description=DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("-v", "--verbose", action="count", default=0, help="more logging (-vv for debug)")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")

    p = sub.add_parser(
        "animate", help="text file -> animation.mp4, scene.glb, <character>.bvh, report.json", add_help=False
    )
    p.add_argument("rest", nargs=argparse.REMAINDER)
    p = sub.add_parser("serve", help="the web editor and its gateway on 127.0.0.1", add_help=False)
    p.add_argument("rest", nargs=argparse.REMAINDER)
    p = sub.add_parser("parse", help="print the semantic scene graph of a text as JSON", add_help=False)
    p.add_argument("rest", nargs=argparse.REMAINDER)
    p = sub.add_parser("assets", help="list, show and export catalog objects and scenes", add_help=False)
    p.add_argument("rest", nargs=argparse.REMAINDER)
    p = sub.add_parser("motion", help="manage the action library (import BVH clips)", add_help=False)
    p.add_argument("rest", nargs=argparse.REMAINDER)
    p = sub.add_parser(
        "metrics", help="export a broker's queue depths and job counters to Prometheus", add_help=False
    )
    p.add_argument("rest", nargs=argparse.REMAINDER)

    p = sub.add_parser(
        "broker",
        help="run a message broker (scale-out)",
        description="Run the message broker that routes requests to workers by service name.",
    )
    p.add_argument(
        "--bind",
        action="append",
        required=True,
        metavar="URL",
        help="endpoint to bind, e.g. tcp://0.0.0.0:5555 or ipc:///tmp/wana.sock (repeatable)",
    )
    p.add_argument("--queue-limit", type=int, default=256, help="pending requests per service before 'busy'")
    p.add_argument("--keys", metavar="DIR", help=_KEYS_HELP)
    p.add_argument(
        "--insecure",
        action="store_true",
        help="bind a non-loopback endpoint without keys (anyone who reaches it can forge jobs)",
    )
    p.set_defaults(func=_cmd_broker)

    p = sub.add_parser(
        "worker",
        help="run one worker of a service, connected to a broker",
        description="Run one worker that serves SERVICE for the broker at --connect.",
    )
    p.add_argument("service", choices=SERVICES, help="which service this worker serves")
    p.add_argument("--connect", required=True, metavar="URL", help="broker endpoint, e.g. tcp://HOST:5555")
    p.add_argument("--keys", metavar="DIR", help=_KEYS_HELP)
    p.set_defaults(func=_cmd_worker)

    p = sub.add_parser("keys", help="make CURVE keys for a bus across hosts")
    keys_sub = p.add_subparsers(dest="keys_command", metavar="ACTION", required=True)
    k = keys_sub.add_parser("new", help="broker, client and worker key pairs plus allow lists in DIR")
    k.add_argument("directory", metavar="DIR")
    k.add_argument(
        "--service", action="append", help="allow the worker key for this service only (repeatable)"
    )
    k.set_defaults(func=_cmd_keys)
    return parser


_DELEGATES = {
    "animate": ("services.orchestrator.animate", "animation"),
    "serve": ("services.gateway.app", "the editor gateway"),
    "parse": ("services.nlp.cli", "the parser"),
    "assets": ("wana.assets.cli", "the asset library"),
    "motion": ("services.motion.cli", "the motion library tools"),
    "metrics": ("wana.metrics", "the metrics exporter"),
}


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    # Delegated sub-commands parse their own arguments (their --help included).
    verbose = 0
    while argv and argv[0] in ("-v", "-vv", "--verbose"):
        verbose += 2 if argv.pop(0) == "-vv" else 1
    logging.basicConfig(
        level=[logging.WARNING, logging.INFO, logging.DEBUG][min(verbose, 2)],
        format="%(asctime)s %(name)s %(levelname)s %(message)s",
    )
    if argv and argv[0] in _DELEGATES:
        module, what = _DELEGATES[argv[0]]
        return _delegate(module, argv[1:], what)
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return 2
    return int(args.func(args))


if __name__ == "__main__":
    sys.exit(main())
