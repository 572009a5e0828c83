"""`wana parse TEXT` / `wana parse -` (stdin): print each sentence's SSG and diagnostics as JSON."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import msgspec


def _entries(text: str) -> list[dict]:
    from services.nlp.parse import parse_document_with_spans

    pieces, graphs = parse_document_with_spans(text)
    return [
        {"start": s, "end": e, **msgspec.to_builtins(g)} for (s, e, _), g in zip(pieces, graphs, strict=True)
    ]


def main(argv: list[str] | None = None) -> int:
    """Entry point; returns the exit status (0 ok, 1 some sentence has an error diagnostic, 2 bad usage)."""
    ap = argparse.ArgumentParser(
        prog="wana parse",
        description="Parse a wana story into semantic scene graphs: one JSON entry per sentence with its "
        "objects, relations, characters and actions, commands and diagnostics (character spans "
        "in the input text). Sentences ending in '$' describe the scene.",
        epilog="example: wana parse 'A laptop is on the desk$. Eve sits on the chair.'",
    )
    ap.add_argument(
        "text",
        help="the text to parse, '-' to read it from standard input, or a file (a .fountain screenplay "
        "or a story)",
    )
    ap.add_argument(
        "--show-story",
        action="store_true",
        help="print the story a Fountain screenplay becomes instead of its scene graphs",
    )
    ap.add_argument("--compact", action="store_true", help="one line of JSON instead of indented output")
    ap.add_argument(
        "--strict", action="store_true", help="exit with status 1 when any diagnostic is an error"
    )
    args = ap.parse_args(argv)
    if args.text == "-":
        raw = sys.stdin.buffer.read()
        text = raw.decode("utf-8", errors="replace")
    else:
        text = args.text
    path = ""
    if args.text != "-" and "\n" not in args.text and len(args.text) < 4096 and Path(args.text).is_file():
        path = args.text
        text = Path(path).read_text(encoding="utf-8", errors="replace")
    from wana.screenplay import looks_like_fountain, to_story

    if looks_like_fountain(text, path):
        text = to_story(text)  # spans are in the converted story (see --show-story)
        if args.show_story:
            sys.stdout.write(text)
            return 0
    entries = _entries(text)
    out = msgspec.json.encode(entries)
    if not args.compact:
        out = msgspec.json.format(out, indent=2)
    sys.stdout.write(out.decode("utf-8") + "\n")
    if args.strict and any(d["severity"] == "error" for e in entries for d in e["diagnostics"]):
        return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
