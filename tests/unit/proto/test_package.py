"""Our `proto` package is the one imported (PyPI's proto-plus also installs a top-level `proto`)."""

import importlib
import pkgutil
from pathlib import Path

import msgspec
import pytest

import proto
from proto.bus import EchoRequest
from proto.common import ERROR_CODES, ErrorCode, Header, Request, reply_header, reply_type

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
                and obj is not Request  # the generic base every request derives from
            ):
                fields = obj.__struct_fields__
                assert fields and fields[0] == "header", f"{info.name}.{name} must start with header"
                if name.endswith("Reply"):
                    assert "status" in fields, f"{info.name}.{name} needs a status"


def test_every_request_of_a_service_declares_a_reply_type_with_a_status():
    for info in pkgutil.iter_modules([str(REPO / "proto")]):
        module = importlib.import_module(f"proto.{info.name}")
        for name, obj in vars(module).items():
            if isinstance(obj, type) and issubclass(obj, Request) and obj is not Request:
                reply = reply_type(obj)
                assert reply.__module__ == module.__name__, (
                    f"{name} is answered by {reply.__name__} of another module"
                )
                assert "status" in reply.__struct_fields__, f"{reply.__name__} needs a status"


def test_a_struct_that_declares_no_reply_is_refused():
    with pytest.raises(TypeError, match="does not declare its reply type"):
        reply_type(Header)


def test_every_error_code_is_in_the_table_and_every_numbered_error_has_a_name():
    assert {str(c) for c in ErrorCode} == {k for k in ERROR_CODES if k.startswith("E")}


def test_a_reply_header_answers_its_request():
    request = EchoRequest(header=Header(doc_id="d", revision=3), text="hi")
    h = reply_header(request)
    assert (h.parent_id, h.doc_id, h.revision) == (
        request.header.msg_id,
        "d",
        3,
    ) and h.msg_id != request.header.msg_id
    assert reply_header(object()).parent_id == ""
