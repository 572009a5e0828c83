"""proto/PROTOCOL.md's message catalogue is generated from proto/*.py and keeps the hand-written part."""

from __future__ import annotations

import importlib
import pkgutil

import msgspec

import proto
from wana.bus import protocol_doc


def test_the_catalogue_names_every_struct_of_every_proto_module():
    text = protocol_doc.catalogue()
    for info in pkgutil.iter_modules(proto.__path__):
        module = importlib.import_module(f"proto.{info.name}")
        for value in vars(module).values():
            if (
                isinstance(value, type)
                and issubclass(value, msgspec.Struct)
                and value.__module__ == module.__name__
            ):
                assert f"#### `{value.__name__}`" in text, f"{info.name}.{value.__name__} missing"


def test_the_catalogue_shows_tags_defaults_and_field_comments():
    text = protocol_doc.catalogue()
    assert '#### `ErrorReply` (map, tag `type: "error_reply"`)' in text
    assert '#### `RequestFrame` (array, first element `"REQUEST"`)' in text
    assert "| `code` | `str` | required | key of ERROR_CODES |" in text
    assert "| `revision` | `int` | `0` | document revision the work was computed for |" in text


def test_updating_replaces_only_the_text_between_the_markers():
    old = f"# Title\n\nhand-written\n\n{protocol_doc.BEGIN}\nstale\n{protocol_doc.END}\n\ntail\n"
    new = protocol_doc.updated_document(old)
    assert new.startswith("# Title\n\nhand-written\n\n")
    assert new.endswith(f"{protocol_doc.END}\n\ntail\n")
    assert "stale" not in new and "#### `Header`" in new
    assert protocol_doc.updated_document(new) == new


def test_the_protocol_document_has_its_catalogue_markers():
    text = protocol_doc.PROTOCOL_MD.read_text()
    assert text.index(protocol_doc.BEGIN) < text.index(protocol_doc.END)
    assert "## 7. Messages" in text
