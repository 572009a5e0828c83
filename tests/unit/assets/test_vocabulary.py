"""The vocabulary maps words to categories and knobs and orders categories by hypernym distance."""

from __future__ import annotations

import pytest

from wana.assets import vocabulary as v


def test_the_table_has_at_least_120_categories_across_15_room_types():
    assert len(v.CATEGORIES) >= 120
    assert len(v.ROOM_TYPES) >= 15
    used_rooms = {r for c in v.CATEGORIES.values() for r in c.rooms}
    assert used_rooms == set(v.ROOM_TYPES)


@pytest.mark.parametrize(
    ("phrase", "category"),
    [
        ("couch", "sofa"),
        ("notebook computer", "laptop"),
        ("computer", "computer"),
        ("the big red couch", "sofa"),
        ("old wooden office chair", "office_chair"),
        ("punching bag", "boxing_bag"),
        ("bookshelves", "bookshelf"),
        ("knives", "knife"),
        ("chest of drawers", "dresser"),
        ("a cup of coffee", "cup"),
        ("Boxing-Bag", "boxing_bag"),
        ("office_chair", "office_chair"),
    ],
)
def test_lookup_resolves_synonyms_plurals_and_attribute_prefixes(phrase, category):
    assert v.lookup(phrase) == category


def test_lookup_returns_none_for_unknown_words():
    assert v.lookup("spaceship") is None
    assert v.lookup("") is None
    assert v.lookup("red") is None


def test_hypernyms_walk_up_to_the_top():
    assert v.hypernyms("office_chair") == ["chair", "seat", "furniture"]
    assert v.hypernyms("laptop")[0] == "computer"
    with pytest.raises(KeyError):
        v.hypernyms("no_such_thing")


def test_similarity_falls_with_hypernym_distance():
    s = v.category_similarity
    assert s("desk", "desk") == 1.0
    assert 1.0 > s("office_chair", "chair") > s("office_chair", "armchair") > s("office_chair", "sofa")
    assert s("office_chair", "sofa") > s("office_chair", "desk") > 0.0
    assert s("chair", "cup") == 0.0
    assert s("chair", "desk") == s("desk", "chair")


def test_attribute_words_name_their_knob():
    w = v.ATTRIBUTE_WORDS
    assert (w["red"], w["wooden"], w["modern"], w["small"], w["messy"]) == (
        "colour",
        "material",
        "style",
        "size",
        "state",
    )
    assert v.normalize_attribute("Tidy") == ("state", "organized")
    assert v.normalize_attribute("gray") == ("colour", "grey")
    assert v.normalize_attribute("spaceship") is None


def test_rooms_resolve_from_what_people_write():
    assert v.lookup_room("working shop") == "workshop"
    assert v.lookup_room("the living room") == "living_room"
    assert v.lookup_room("conference room") == "meeting_room"
    assert v.lookup_room("moon") is None


def test_every_category_declares_valid_knobs_and_mount():
    for info in v.CATEGORIES.values():
        assert set(info.knobs) <= set(v.KNOBS), info.name
        assert info.mount in v.MOUNTS
        assert info.rooms, info.name


@pytest.mark.parametrize(
    ("phrase", "category"),
    [
        ("carpet", "rug"),
        ("a box of chocolates", "chocolate_box"),
        ("birthday cake", "cake"),
        ("photo negative", "film_negative"),
        ("pills", "pill_bottle"),
        ("guitar stand", "instrument_stand"),
        ("microphone stand", "microphone"),
        ("drum kit", "drum_kit"),
        ("popcorn", "bowl"),
    ],
)
def test_things_stories_name_are_catalog_kinds(phrase, category):
    assert v.lookup(phrase) == category
