"""Scene grammar and the committed scene database."""

from __future__ import annotations

import time

import pytest

from proto.scene import PlacedObject, Scene
from proto.ssg import RelationNode
from wana.assets import vocabulary
from wana.assets.scenedb import get_scene, load_scenedb
from wana.assets.scenes import generate_scene
from wana.assets.validate import scene_problems


def test_database_has_150_scenes_in_15_room_types_and_loads_fast():
    load_scenedb()  # warm the file cache
    from wana.assets.scenedb import _load

    _load.cache_clear()
    t0 = time.perf_counter()
    records = load_scenedb()
    assert time.perf_counter() - t0 < 0.5
    assert len(records) >= 150
    assert len({r.room_type for r in records}) >= 15
    assert len({r.id for r in records}) == len(records)
    for r in records:
        assert r.room_type in vocabulary.ROOM_TYPES
        assert {o.id for o in r.objects} == {p.id for p in r.scene.objects}
        assert all(o.category in vocabulary.CATEGORIES for o in r.objects)


@pytest.mark.parametrize("scene_id", ["office-000", "kitchen-004", "gym-007", "classroom-002"])
def test_stored_scenes_are_valid(scene_id):
    rec = get_scene(scene_id)
    assert scene_problems(rec.scene, rec.relations) == []
    assert len(rec.relations) >= 3


def test_grammar_is_deterministic_and_valid():
    a = generate_scene("office", 11)
    b = generate_scene("office", 11)
    assert a.scene == b.scene and a.relations == b.relations
    assert scene_problems(a.scene, a.relations) == []
    cats = [o.category for o in a.objects]
    assert "desk" in cats or "standing_desk" in cats
    assert any(r.relation == "on" for r in a.relations)


def test_validation_catches_overlaps_escapes_floating_and_false_relations():
    rec = get_scene("office-000")
    desk = next(p for p in rec.scene.objects if p.category == "desk")
    intruder = PlacedObject(id="intruder", category="armchair", position=desk.position, yaw=desk.yaw)
    bad = Scene(room=rec.scene.room, objects=[*rec.scene.objects, intruder])
    assert any("interpenetrates" in p for p in scene_problems(bad))
    outside = PlacedObject(id="out", category="stool", position=(rec.scene.room.width, 0.0, 0.0))
    assert any("out of the room" in p for p in scene_problems(Scene(room=rec.scene.room, objects=[outside])))
    floating = PlacedObject(id="f", category="stool", position=(0.0, 0.5, 0.0))
    assert any("floats" in p for p in scene_problems(Scene(room=rec.scene.room, objects=[floating])))
    lie = RelationNode(subject=desk.id, relation="on", object=rec.scene.objects[-1].id)
    assert any("does not hold" in p for p in scene_problems(rec.scene, [lie]))


def test_unknown_room_and_scene_are_clear_errors():
    with pytest.raises(KeyError, match="no scene rules"):
        generate_scene("spaceship", 0)
    with pytest.raises(KeyError, match="no scene"):
        get_scene("nowhere-999")
