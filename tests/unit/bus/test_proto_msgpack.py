"""Every message in proto/ can be read by the plain msgpack package (any msgpack library reads the wire).

The structs are found by introspecting every module of the proto package, so messages other
services add are covered without editing this test. An example instance of each is built from its
type annotations (every field filled, defaults included), encoded by msgspec, read by msgpack,
re-packed by msgpack and decoded by msgspec into an equal struct.
"""

from __future__ import annotations

import datetime
import decimal
import enum
import importlib
import pkgutil
import uuid
from pathlib import Path

import msgpack
import msgspec
import pytest

import proto
from proto.bus import WITH_BODY, Envelope


def _proto_structs() -> list[type]:
    found = []
    for info in pkgutil.iter_modules(proto.__path__):
        module = importlib.import_module(f"proto.{info.name}")
        for value in vars(module).values():
            if (
                isinstance(value, type)
                and issubclass(value, msgspec.Struct)
                and value.__module__ == module.__name__
            ):
                found.append(value)
    return sorted(found, key=lambda t: f"{t.__module__}.{t.__qualname__}")


def example(t: msgspec.inspect.Type, depth: tuple[type, ...] = ()) -> object:
    """A value of msgspec type ``t`` with every field and container filled (``depth``: structs being built)."""
    mi = msgspec.inspect
    if isinstance(t, mi.StructType):
        if t.cls in depth:
            raise RecursionError(f"{t.cls.__name__} contains itself: no finite example")
        return t.cls(**{f.name: example(f.type, (*depth, t.cls)) for f in t.fields})
    if isinstance(t, mi.UnionType):
        options = [o for o in t.types if not isinstance(o, mi.NoneType)]
        for option in options:
            try:
                return example(option, depth)
            except RecursionError:
                continue
        if any(isinstance(o, mi.NoneType) for o in t.types):
            return None
        raise RecursionError(f"no finite example for {t!r}")
    if isinstance(t, mi.LiteralType):
        return t.values[0]
    if isinstance(t, mi.EnumType):
        return next(iter(t.cls))
    if isinstance(t, mi.BoolType):
        return True
    if isinstance(t, mi.IntType):
        low = t.ge if t.ge is not None else (t.gt + 1 if t.gt is not None else 1)
        return low if t.le is None or low <= t.le else t.le
    if isinstance(t, mi.FloatType):
        return 0.5 if t.ge is None and t.gt is None else (t.ge if t.ge is not None else t.gt + 0.5)
    if isinstance(t, mi.StrType):
        return "x" * max(1, t.min_length or 0)
    if isinstance(t, (mi.BytesType, mi.ByteArrayType, mi.MemoryViewType)):
        return b"\x00\x01" * max(1, t.min_length or 0)
    if isinstance(t, (mi.ListType, mi.SetType, mi.FrozenSetType, mi.VarTupleType)):
        items = [example(t.item_type, depth)]
        cast = {mi.ListType: list, mi.SetType: set, mi.FrozenSetType: frozenset, mi.VarTupleType: tuple}
        return cast[type(t)](items)
    if isinstance(t, mi.TupleType):
        return tuple(example(item, depth) for item in t.item_types)
    if isinstance(t, mi.DictType):
        return {example(t.key_type, depth): example(t.value_type, depth)}
    if isinstance(t, mi.NoneType):
        return None
    if isinstance(t, mi.AnyType):
        return "any"
    if isinstance(t, mi.DateTimeType):
        return datetime.datetime(2025, 1, 2, 3, 4, 5, tzinfo=datetime.UTC)
    if isinstance(t, mi.DateType):
        return datetime.date(2025, 1, 2)
    if isinstance(t, mi.UUIDType):
        return uuid.UUID(int=1)
    if isinstance(t, mi.DecimalType):
        return decimal.Decimal("1.5")
    raise NotImplementedError(
        f"no example for msgspec type {t!r}: extend tests/unit/bus/test_proto_msgpack.py"
    )


STRUCTS = _proto_structs()


def test_the_proto_package_has_the_shared_and_bus_messages():
    names = {t.__name__ for t in STRUCTS}
    assert {"Header", "ErrorReply", "NDArray", "RequestFrame", "BrokerStats", "EchoRequest"} <= names


@pytest.mark.parametrize("struct_type", STRUCTS, ids=lambda t: f"{t.__module__}.{t.__qualname__}")
def test_plain_msgpack_reads_every_proto_message(struct_type):
    instance = example(msgspec.inspect.type_info(struct_type))
    assert isinstance(instance, struct_type)
    wire = msgspec.msgpack.encode(instance)
    plain = msgpack.unpackb(wire, raw=False, strict_map_key=False, timestamp=3)
    config = struct_type.__struct_config__
    if config.array_like:
        assert isinstance(plain, list)
    else:
        assert isinstance(plain, dict)
        if config.tag is not None:
            assert plain[config.tag_field] == config.tag
        assert {f.encode_name for f in msgspec.structs.fields(struct_type)} <= set(plain)
    repacked = msgpack.packb(plain, use_bin_type=True, datetime=True)
    assert msgspec.msgpack.decode(repacked, type=struct_type) == instance


@pytest.mark.parametrize("envelope_type", Envelope.__args__, ids=lambda t: t.__name__)
def test_every_bus_envelope_is_a_msgpack_array_led_by_its_command_name(envelope_type):
    instance = example(msgspec.inspect.type_info(envelope_type))
    plain = msgpack.unpackb(msgspec.msgpack.encode(instance), raw=False)
    assert isinstance(plain, list) and plain[0] == envelope_type.__struct_config__.tag
    assert plain[0].isupper()
    assert msgspec.msgpack.decode(msgpack.packb(plain), type=Envelope) == instance


def test_envelopes_with_a_body_frame_are_the_documented_ones():
    assert {t.__name__ for t in WITH_BODY} == {"RequestFrame", "JobFrame", "ReplyFrame", "ErrorFrame"}


def test_the_envelope_example_is_exact():
    # Bytes written out by hand from the msgpack spec, so the layout in PROTOCOL.md cannot drift.
    from proto.bus import RequestFrame

    wire = msgspec.msgpack.encode(RequestFrame("nlp", "j1", "k", 0, 30000, "doc", 2))
    expected = b"\x98\xa7REQUEST\xa3nlp\xa2j1\xa1k\x00\xcd\x75\x30\xa3doc\x02"
    assert wire == expected


class _Unused(enum.Enum):  # keeps the enum branch of ``example`` importable and tested
    A = 1


def test_the_example_builder_covers_enums_and_optionals():
    class Probe(msgspec.Struct):
        kind: _Unused
        maybe: int | None = None

    probe = example(msgspec.inspect.type_info(Probe))
    assert probe == Probe(kind=_Unused.A, maybe=1)


def _protocol_md_example() -> bytes:
    """The hex bytes of the envelope example in proto/PROTOCOL.md (leading hex tokens of each line)."""
    text = (Path(proto.__file__).with_name("PROTOCOL.md")).read_text()
    block = text.split("Example, byte for byte", 1)[1].split("```", 2)[1]
    out = bytearray()
    for line in block.splitlines():
        for token in line.split():
            if len(token) % 2 or not all(c in "0123456789abcdef" for c in token):
                break
            out += bytes.fromhex(token)
    return bytes(out)


def test_the_example_in_protocol_md_decodes_with_plain_msgpack_and_msgspec():
    from proto.bus import RequestFrame

    example_bytes = _protocol_md_example()
    assert msgpack.unpackb(example_bytes) == ["REQUEST", "nlp", "j1", "k", 0, 30000, "doc", 2]
    assert msgspec.msgpack.decode(example_bytes, type=Envelope) == RequestFrame(
        "nlp", "j1", "k", 0, 30000, "doc", 2
    )
