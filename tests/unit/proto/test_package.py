"""Our `proto` package is the one imported (PyPI's proto-plus also installs a top-level `proto`)."""

import importlib
import pkgutil
from pathlib import Path

import msgspec

import proto

REPO = Path(__file__).resolve().parents[3]


def test_proto_is_this_repository():
    assert Path(proto.__file__).resolve().parent == REPO / "proto"


def test_proto_imports_only_msgspec_and_the_standard_library():
    import sys

    allowed_third_party = {"msgspec", "proto"}
    for info in pkgutil.iter_modules([str(REPO / "proto")]):
        source = (REPO / "proto" / f"{info.name}.py").read_text()
        for line in source.splitlines():
            words = line.split()
            if len(words) >= 2 and words[0] in ("import", "from"):
                top = words[1].split(".")[0]
                assert top in allowed_third_party or top in sys.stdlib_module_names or top == "__future__", (
                    f"proto/{info.name}.py imports {top}"
                )


def test_every_request_and_reply_carries_a_header_first():
    for info in pkgutil.iter_modules([str(REPO / "proto")]):
        module = importlib.import_module(f"proto.{info.name}")
        for name, obj in vars(module).items():
            if (
                isinstance(obj, type)
                and issubclass(obj, msgspec.Struct)
                and name.endswith(("Request", "Reply"))
            ):
                fields = obj.__struct_fields__
                assert fields and fields[0] == "header", f"{info.name}.{name} must start with header"
                if name.endswith("Reply"):
                    assert "status" in fields, f"{info.name}.{name} needs a status"
