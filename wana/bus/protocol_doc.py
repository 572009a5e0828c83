"""Write the message catalogue of proto/PROTOCOL.md from the structs in proto/*.py.

    .venv/bin/python -m wana.bus.protocol_doc            # print the catalogue (Markdown)
    .venv/bin/python -m wana.bus.protocol_doc --write    # replace it in proto/PROTOCOL.md
    .venv/bin/python -m wana.bus.protocol_doc --check    # exit 1 when PROTOCOL.md is out of date

The catalogue sits between the markers ``<!-- messages:begin -->`` and ``<!-- messages:end -->``;
everything else in PROTOCOL.md is written by hand.
"""

from __future__ import annotations

import argparse
import importlib
import inspect
import pkgutil
import re
import sys
import typing
from pathlib import Path

import msgspec

import proto

BEGIN = "<!-- messages:begin -->"
END = "<!-- messages:end -->"
PROTOCOL_MD = Path(proto.__file__).with_name("PROTOCOL.md")


def _type_name(t: object) -> str:
    text = repr(t) if not isinstance(t, type) else t.__name__
    text = re.sub(r"\b(typing|proto\.\w+)\.", "", text)
    return text.replace("NoneType", "None").replace("|", "\\|")


def _field_comments(cls: type) -> dict[str, str]:
    """Trailing ``# comments`` of the field lines in the class source (units, frames, meaning)."""
    try:
        lines = inspect.getsource(cls).splitlines()
    except (OSError, TypeError):
        return {}
    comments = {}
    for line in lines:
        code, sep, comment = line.partition("  # ")
        name = code.strip().split(":", 1)[0]
        if sep and ":" in code and name.isidentifier():
            comments[name] = comment.strip()
    return comments


def _struct_section(cls: type[msgspec.Struct]) -> list[str]:
    config = cls.__struct_config__
    hints = typing.get_type_hints(cls)
    kind = "array" if config.array_like else "map"
    tag = (
        f', tag `{config.tag_field}: "{config.tag}"`'
        if config.tag is not None and not config.array_like
        else ""
    )
    if config.array_like and config.tag is not None:
        tag = f', first element `"{config.tag}"`'
    doc = (inspect.getdoc(cls) or "").split("\n\n")[0].replace("\n", " ")
    if doc.startswith(("Struct(", "A base class")):
        doc = ""
    out = [f"#### `{cls.__name__}` ({kind}{tag})", ""]
    if doc:
        out += [doc, ""]
    comments = _field_comments(cls)
    fields = msgspec.structs.fields(cls)
    if fields:
        out += ["| field | type | default | notes |", "|---|---|---|---|"]
        for f in fields:
            if f.default is not msgspec.NODEFAULT:
                default = f"`{f.default!r}`"
            elif f.default_factory in (dict, list, set, tuple):
                default = f"`{f.default_factory()!r}`"
            elif f.default_factory is not msgspec.NODEFAULT:
                default = "generated"
            else:
                default = "required"
            note = comments.get(f.name, "").replace("|", "\\|")
            out.append(
                f"| `{f.encode_name}` | `{_type_name(hints.get(f.name, f.type))}` | {default} | {note} |"
            )
        out.append("")
    return out


def catalogue() -> str:
    """Markdown listing every struct of every proto module, module by module."""
    out = [BEGIN, ""]
    for info in sorted(pkgutil.iter_modules(proto.__path__), key=lambda i: i.name):
        module = importlib.import_module(f"proto.{info.name}")
        structs = [
            v
            for v in vars(module).values()
            if isinstance(v, type) and issubclass(v, msgspec.Struct) and v.__module__ == module.__name__
        ]
        if not structs:
            continue
        summary = (inspect.getdoc(module) or "").split("\n")[0]
        out += [f"### `proto/{info.name}.py`", "", summary, ""]
        for cls in structs:  # definition order
            out += _struct_section(cls)
    out.append(END)
    return "\n".join(out) + "\n"


def updated_document(text: str) -> str:
    """PROTOCOL.md with its catalogue replaced (appended when the markers are missing)."""
    if BEGIN in text and END in text:
        head, _, rest = text.partition(BEGIN)
        _, _, tail = rest.partition(END)
        return head + catalogue().rstrip("\n") + tail
    return text.rstrip("\n") + "\n\n" + catalogue()


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    mode = parser.add_mutually_exclusive_group()
    mode.add_argument("--write", action="store_true", help=f"update the catalogue in {PROTOCOL_MD}")
    mode.add_argument("--check", action="store_true", help="exit 1 when the catalogue is out of date")
    args = parser.parse_args(argv)
    if not (args.write or args.check):
        sys.stdout.write(catalogue())
        return 0
    current = PROTOCOL_MD.read_text() if PROTOCOL_MD.exists() else ""
    wanted = updated_document(current)
    if args.check:
        if wanted != current:
            print(f"{PROTOCOL_MD} is out of date: run .venv/bin/python -m wana.bus.protocol_doc --write")
            return 1
        return 0
    PROTOCOL_MD.write_text(wanted)
    print(f"wrote the message catalogue of {PROTOCOL_MD}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
