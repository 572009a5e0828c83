"""Relation predicates on hand-made placements (the retrieval stage reuses them)."""

from __future__ import annotations

import numpy as np
import pytest

from proto.scene import PlacedObject
from proto.ssg import RELATIONS, RelationNode
from wana.assets import catalog
from wana.assets.relations import PREDICATES, relation_holds, relations_between

DESK = PlacedObject(id="desk", category="desk", position=(0.0, 0.0, 0.0))
DESK_TOP = catalog.make_object("desk").support_surfaces[0].height


def _at(cat: str, x: float, z: float, y: float = 0.0, yaw: float = 0.0, support: str = "") -> PlacedObject:
    return PlacedObject(id=cat, category=cat, position=(x, y, z), yaw=yaw, support=support)


def test_every_ssg_relation_has_a_predicate():
    assert set(PREDICATES) == set(RELATIONS)
    with pytest.raises(ValueError, match="unknown relation"):
        relation_holds("inside_out", DESK, DESK)


def test_on_needs_the_surface_height_and_footprint():
    laptop = _at("laptop", 0.1, 0.0, DESK_TOP, support="desk")
    assert relation_holds("on", laptop, DESK)
    assert relation_holds(RelationNode(subject="laptop", relation="on", object="desk"), laptop, DESK)
    assert not relation_holds("on", _at("laptop", 0.1, 0.0, DESK_TOP + 0.2), DESK)  # floating
    assert not relation_holds("on", _at("laptop", 2.0, 0.0, DESK_TOP), DESK)  # beside the desk


def test_front_behind_left_right_use_the_anchors_own_frame():
    d = catalog.make_object("desk").dims
    front = _at("office_chair", 0.0, d[2] / 2 + 0.5, yaw=np.pi)
    assert relation_holds("in_front_of", front, DESK) and relation_holds("facing", front, DESK)
    assert not relation_holds("behind", _at("filing_cabinet", 0.0, d[2] / 2 + 0.5), DESK)
    # one sits *behind* a desk: for a seat facing it at its working side "behind" holds too, not turned away
    assert relation_holds("behind", front, DESK)
    assert not relation_holds("behind", _at("office_chair", 0.0, d[2] / 2 + 0.5), DESK)
    assert relation_holds("behind", _at("office_chair", 0.0, -d[2] / 2 - 0.5), DESK)
    left = _at("filing_cabinet", d[0] / 2 + 0.4, 0.0)
    assert relation_holds("left_of", left, DESK) and not relation_holds("right_of", left, DESK)
    # turn the desk to face +X: its left side is now -Z
    turned = PlacedObject(id="desk", category="desk", position=(0.0, 0.0, 0.0), yaw=np.pi / 2)
    assert relation_holds("left_of", _at("filing_cabinet", 0.0, -(d[0] / 2 + 0.4)), turned)
    assert relation_holds("in_front_of", _at("office_chair", d[2] / 2 + 0.5, 0.0), turned)


def test_near_next_to_and_distance():
    d = catalog.make_object("desk").dims
    assert relation_holds("near", _at("plant", d[0] / 2 + 0.8, 0.0), DESK)
    assert not relation_holds("near", _at("plant", d[0] / 2 + 1.6, 0.0), DESK)
    assert relation_holds("next_to", _at("plant", d[0] / 2 + 0.3, 0.0), DESK)
    assert not relation_holds("next_to", _at("plant", d[0] / 2 + 0.7, 0.0), DESK)


def test_under_above_and_facing():
    assert relation_holds("under", _at("trash_can", 0.0, 0.0), DESK)
    lamp_high = _at("painting", 0.0, 0.0, y=1.2)
    assert relation_holds("above", lamp_high, DESK) and relation_holds("hanging_above", lamp_high, DESK)
    chair_away = _at("chair", 0.0, 1.2, yaw=0.0)  # in front of the desk but looking away
    assert not relation_holds("facing", chair_away, DESK)
    assert "in_front_of" in relations_between(chair_away, DESK)


def test_under_a_window_is_against_its_wall_below_it_and_within_its_width():
    # A window on the back wall (z = 0) facing into the room (+Z), its bottom at 0.9 m.
    window = PlacedObject(id="window", category="window", position=(0.0, 0.9, 0.0))
    d = catalog.make_object("desk").dims
    w = catalog.make_object("window").dims
    against = _at("desk", 0.0, w[2] / 2 + d[2] / 2 + 0.01)
    assert relation_holds("under", against, window)
    assert not relation_holds("under", _at("desk", 0.0, w[2] / 2 + d[2] / 2 + 1.0), window)  # out in the room
    beside = _at("desk", w[0] / 2 + d[0], w[2] / 2 + d[2] / 2 + 0.01)
    assert not relation_holds("under", beside, window)
    wardrobe = catalog.make_object("wardrobe").dims
    too_tall = _at("wardrobe", 0.0, w[2] / 2 + wardrobe[2] / 2 + 0.01)
    assert not relation_holds("under", too_tall, window)


def test_a_subject_copy_of_an_each_relation_goes_with_its_own_anchor_copy():
    from proto.ssg import RelationNode
    from wana.assets.relations import anchor_copy

    each = RelationNode(subject="chair", relation="near", object="desk", each=True)
    assert [anchor_copy(c, each, 2) for c in ("chair", "chair/2", "chair/3")] == ["desk", "desk/2", "desk"]
    plain = RelationNode(subject="chair", relation="near", object="desk")
    assert anchor_copy("chair/2", plain, 2) == "desk"
