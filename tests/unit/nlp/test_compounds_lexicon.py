"""Glued compounds and the word -> category / action tables."""

from __future__ import annotations

import pytest

from services.nlp import lexicon
from services.nlp.compounds import split_glued


@pytest.mark.parametrize(
    "word,parts",
    [
        ("oilpainting", ["oil", "painting"]),
        ("modernchair", ["modern", "chair"]),
        ("horsesculpture", ["horse", "sculpture"]),
        ("boxingbag", ["boxing", "bag"]),
        ("redsofa", ["red", "sofa"]),
    ],
)
def test_glued_compounds_split_against_the_catalog(word, parts):
    assert split_glued(word) == parts


@pytest.mark.parametrize("word", ["sofa", "xyzzyq", "table1", "ab"])
def test_words_that_are_not_glued_compounds_do_not_split(word):
    assert split_glued(word) is None


@pytest.mark.parametrize(
    "phrase,category",
    [
        ("couch", "sofa"),
        ("notebook computer", "laptop"),
        ("tv", "television"),
        ("fridge", "refrigerator"),
        ("punching bag", "boxing_bag"),
        ("soda", "soda_can"),
    ],
)
def test_synonyms_map_to_catalog_categories(phrase, category):
    assert lexicon.category_of(phrase) == category


@pytest.mark.parametrize("word", ["man", "teacher", "floor", "wall", "seconds"])
def test_people_and_places_are_not_objects(word):
    assert lexicon.category_of(word) is None


@pytest.mark.parametrize(
    "verb,kw,action",
    [
        ("chat", dict(obj_words=("phone",), prep="on"), "call_with_phone"),
        ("play", dict(obj_words=("piano", "keyboard_instrument")), "play_piano"),
        ("play", dict(obj_words=("drum_kit", "percussion", "drums")), "play_drums"),
        ("sing", dict(obj_words=("microphone",), prep="with"), "sing_with_microphone"),
        ("punch", dict(obj_words=("boxing_bag", "boxing_equipment", "bag")), "punch_bag"),
        ("turn", dict(direction="left"), "turn_left"),
        ("pick", dict(particle="up"), "pick_up"),
        ("push", dict(person_object=True), "push_person"),
        ("walk", dict(obj_words=("chair",), prep="to"), "walk"),
        ("sit", {}, "sit"),
        ("stand", {}, "stand"),
        ("sleep", {}, "sleep"),
    ],
)
def test_verbs_map_to_action_library_names(verb, kw, action):
    assert lexicon.action_for(verb, **kw) == action
    assert action in lexicon.action_names()


def test_unknown_verbs_map_to_no_action():
    assert lexicon.action_for("frobnicate") == ""
    assert lexicon.action_for("play", obj_words=("mirror",)) == ""
