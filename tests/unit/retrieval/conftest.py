"""Small scene databases written by hand for the retrieval unit tests."""

from __future__ import annotations

from dataclasses import dataclass, field
from types import SimpleNamespace

import pytest

from proto.scene import Room, Scene
from proto.ssg import ObjectNode, RelationNode
from services.retrieval.database import SceneGraphDB


@dataclass
class Record:
    """A scene record with the attributes of wana.assets.scenedb.SceneRecord."""

    id: str
    room_type: str
    objects: list[ObjectNode]
    relations: list[RelationNode]
    scene: Scene = field(
        default_factory=lambda: Scene(room=Room(room_type="office", width=5, depth=4, height=2.8))
    )


def obj(spec: str) -> ObjectNode:
    """'id:category[:knob=value,...]' -> ObjectNode."""
    parts = spec.split(":")
    attrs = dict(kv.split("=") for kv in parts[2].split(",")) if len(parts) > 2 else {}
    return ObjectNode(id=parts[0], category=parts[1], word=parts[1].replace("_", " "), attributes=attrs)


def rel(spec: str) -> RelationNode:
    """'subject relation anchor' -> RelationNode."""
    s, r, o = spec.split()
    return RelationNode(subject=s, relation=r, object=o)


def record(rid: str, room: str, objects: list[str], relations: list[str]) -> Record:
    return Record(rid, room, [obj(o) for o in objects], [rel(r) for r in relations])


def make_db(*records: Record) -> SceneGraphDB:
    return SceneGraphDB(records)


@pytest.fixture
def hand() -> SimpleNamespace:
    """Builders for hand-written SSG nodes, records and databases (tests cannot import conftest)."""
    return SimpleNamespace(obj=obj, rel=rel, record=record, db=make_db)
