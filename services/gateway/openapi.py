"""Write or check the committed OpenAPI spec: `python -m services.gateway.openapi [--check]`."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any

SPEC_PATH = Path(__file__).with_name("openapi.json")


def current_spec() -> dict[str, Any]:
    """The spec of the app as the code defines it now (no server, no database)."""
    from services.gateway.app import create_app
    from services.gateway.settings import Settings

    return create_app(Settings()).openapi()


def render(spec: dict[str, Any]) -> str:
    return json.dumps(spec, indent=2, sort_keys=True) + "\n"


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(
        prog="python -m services.gateway.openapi",
        description="Regenerate services/gateway/openapi.json from the app, or check it.",
    )
    p.add_argument("--check", action="store_true", help="exit 1 when the committed file is out of date")
    p.add_argument("--out", type=Path, default=SPEC_PATH, help=f"where to write (default {SPEC_PATH})")
    args = p.parse_args(argv)
    text = render(current_spec())
    if args.check:
        if not args.out.is_file() or args.out.read_text() != text:
            print(f"{args.out} is out of date: run python -m services.gateway.openapi", file=sys.stderr)
            return 1
        return 0
    args.out.write_text(text)
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
