"""Relation-first matching (Algorithm 1) against the object-first LDS baseline, on hand-made databases."""

from __future__ import annotations

import pytest

from services.retrieval.lds import match_object_first
from services.retrieval.matching import match_relation_first


@pytest.fixture
def office_db(hand):
    record = hand.record
    return hand.db(
        # Exact categories, but nothing related.
        record("plain", "office", ["desk:desk", "chair:office_chair", "plant:plant"], []),
        # Near categories that stand in the stated relation.
        record(
            "related",
            "office",
            ["table:table", "seat:chair", "lamp:desk_lamp"],
            ["seat in_front_of table", "lamp on table"],
        ),
    )


def test_a_stated_relation_pulls_the_match_to_a_scene_that_has_it(office_db, hand):
    obj, rel = hand.obj, hand.rel
    objects = [obj("c:office_chair"), obj("d:desk")]
    relations = [rel("c in_front_of d")]
    ours = match_relation_first(objects, relations, office_db)
    lds = match_object_first(objects, relations, office_db)
    assert {m.scene for m in ours.nodes.values()} == {1}
    assert all(m.via == "relation" for m in ours.nodes.values())
    assert ours.relation_scores == [1.0]
    # The baseline takes the exact categories of the unrelated scene and loses the relation.
    assert {m.scene for m in lds.nodes.values()} == {0}
    assert lds.relation_scores == [0.0]
    assert ours.score > lds.score


def test_a_relation_stated_from_the_anchor_side_matches_its_inverse(office_db, hand):
    obj, rel = hand.obj, hand.rel
    objects = [obj("d:desk"), obj("c:office_chair")]
    ours = match_relation_first(objects, [rel("d behind c")], office_db)
    assert ours.relation_scores == [1.0]
    assert office_db.objects[ours.nodes["d"].db_object].node.id == "table"


def test_objects_no_relation_covers_are_matched_as_single_nodes(office_db, hand):
    obj, rel = hand.obj, hand.rel
    objects = [obj("c:office_chair"), obj("d:desk"), obj("p:plant"), obj("x:not_a_category")]
    ours = match_relation_first(objects, [rel("c in_front_of d")], office_db)
    assert ours.nodes["p"].via == "object"
    assert ours.nodes["p"].score == 1.0
    assert "x" not in ours.nodes  # nothing in the database resembles it


def test_relations_sharing_an_object_map_it_to_one_database_object(hand):
    obj, rel, record, make_db = hand.obj, hand.rel, hand.record, hand.db
    db = make_db(
        record(
            "s",
            "office",
            ["t1:desk", "t2:desk", "c:office_chair", "l:laptop"],
            ["c in_front_of t1", "l on t1", "l near t2"],
        ),
    )
    objects = [obj("chair:office_chair"), obj("desk:desk"), obj("laptop:laptop")]
    ours = match_relation_first(objects, [rel("chair in_front_of desk"), rel("laptop on desk")], db)
    assert len(ours.pieces) == 1
    assert ours.pieces[0].mapping["desk"] == db.object_index[(0, "t1")]
    assert ours.relation_scores == [1.0, 1.0]
    assert ours.score == pytest.approx(1.0)


def test_attribute_agreement_picks_the_matching_variant(hand):
    obj, record, make_db = hand.obj, hand.record, hand.db
    db = make_db(
        record("blue", "office", ["c:chair:colour=blue"], []),
        record("red", "office", ["c:chair:colour=red"], []),
    )
    ours = match_relation_first([obj("c:chair:colour=red")], [], db)
    assert ours.nodes["c"].scene == 1
    assert ours.nodes["c"].score == pytest.approx(1.0)
    blue = match_relation_first([obj("c:chair:colour=blue,material=wooden")], [], db)
    assert blue.nodes["c"].scene == 0
    assert blue.nodes["c"].score < 1.0  # the material is left open in the database


def test_relations_naming_unknown_objects_are_ignored(office_db, hand):
    obj, rel = hand.obj, hand.rel
    objects = [obj("c:office_chair")]
    ours = match_relation_first(objects, [rel("c near ghost"), rel("c on c")], office_db)
    assert ours.relation_scores == [0.0, 0.0]
    assert ours.score == pytest.approx(ours.nodes["c"].score)  # only the object node counts


def test_matching_is_deterministic(office_db, hand):
    obj, rel = hand.obj, hand.rel
    objects = [obj("c:office_chair"), obj("d:desk"), obj("l:desk_lamp")]
    relations = [rel("c in_front_of d"), rel("l on d")]
    a = match_relation_first(objects, relations, office_db)
    b = match_relation_first(objects, relations, office_db)
    assert a == b
