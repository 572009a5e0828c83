"""Causes of the action misses on the fresh gold split (issue 17), each tried on sentences written
here, not the gold ones: an animal named "it", an animal whose word is also a catalog thing, a time
phrase with no comma, a noun the tagger read as an adverb, words said as a verb's object, a body part
that is where the hands go, a thing thrown "at" someone, two objects of a giving verb, and the things a
relative clause or a verbless sentence names.

Every sentence goes through the committed pipeline; expected values are written here by hand.
"""

from __future__ import annotations

import pytest

from services.nlp.parse import parse_document


def acts(text):
    return [
        (c.name, a.action, a.target or a.destination)
        for g in parse_document(text)
        for c in g.characters
        for a in c.actions
    ]


def objects(text):
    return sorted(o.category for g in parse_document(text) for o in g.objects)


def codes(text):
    return [d.code for g in parse_document(text) for d in g.diagnostics]


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        # "it" that acts is the animal last named
        (
            "The puppy runs to the door. It jumps onto the rug.",
            [("puppy", "run", "door"), ("puppy", "jump", "rug")],
        ),
        ("The kitten runs to the basket. It picks up a sock.", None),
        # an animal whose word is a catalog thing acts as the subject of an action verb
        ("The grey mouse runs to the bed.", [("mouse", "run", "bed")]),
        # a time phrase with no comma before the name
        ("That evening Omar walks to the window.", [("Omar", "walk", "window")]),
        ("One afternoon Priya skips to the gate.", [("Priya", "skip", "gate")]),
        # "the well": a determiner and a preposition make the word a noun
        ("Hugo runs to the well.", [("Hugo", "run", "well")]),
        # what is said is no target
        ("The kids wave goodbye.", [("kid", "wave", "")]),
        # the face is what the hands cover
        ("Lena hides her face in her hands.", [("Lena", "cover_face", "face")]),
        # a thing no catalog holds, thrown at someone: the target is who it is thrown at
        ("The witch casts a curse at the knight.", [("witch", "throw", "knight")]),
    ],
)
def test_fresh_action_causes(text, expected):
    got = acts(text)
    if expected is None:  # the second sentence's actor is the animal, whatever the clip
        assert [name for name, _, _ in got] == ["kitten", "kitten"]
    else:
        assert got == expected


def test_it_that_names_no_animal_is_a_thing_and_no_warning():
    text = "Eve pushes the cart. It rolls to the wall."
    assert [name for name, _, _ in acts(text)] == ["Eve"]
    assert "W105" not in codes(text)


def test_a_mouse_in_a_scene_sentence_stays_a_thing():
    assert objects("A mouse lies beside the laptop$.") == ["laptop", "mouse"]
    assert objects("The computer mouse falls off the desk.") == ["desk", "mouse"]


def test_a_giving_verb_keeps_both_objects():
    text = "Grandma hands the boy a cup."
    assert acts(text) == [("grandma", "present", "boy")]
    assert objects(text) == ["cup"]


def test_a_relative_clause_names_a_thing_in_the_room():
    assert "door" in objects("The boy who stands by the door waves.")


def test_a_thing_that_does_something_is_still_in_the_story():
    assert objects("At dawn, the clock ticks loudly.") == ["clock"]


def test_a_social_act_with_nobody_to_aim_at_has_no_social_node():
    graphs = parse_document("Mia takes his hand.")
    assert [s for g in graphs for s in g.social] == []


def test_what_one_puts_on_is_worn_not_a_thing_in_the_room():
    assert objects("Aunt Rosa puts on her glasses.") == []
    assert objects("Pavel takes off his glasses and smiles.") == []
    assert objects("Pavel puts the glass on the shelf.") == ["glass", "shelf"]


def test_a_book_opened_is_read():
    assert acts("Pavel opens the book.") == [("Pavel", "read", "book")]
    assert acts("Pavel opens the drawer.") == [("Pavel", "open_drawer", "drawer")]


def test_a_blown_thing_no_phrase_names_has_no_clip():
    text = "The referee blows the whistle."
    assert [a for _, a, _ in acts(text)] == [""]
    assert "W102" in codes(text)
    assert acts("Nadia blows out the candles.") == [("Nadia", "greet_bow", "candle")]


def test_a_character_in_a_scene_relative_clause_acts_at_the_antecedent():
    text = "There is a bench on which an old farmer sits$."
    assert acts(text) == [("farmer", "sit", "bench")]
    assert objects(text) == ["bench"]
    assert acts("There is a shelf under which a basket stands$.") == []


def test_a_relative_clause_of_a_thing_names_a_thing_too():
    assert objects("Mira picks up the cup which stands on the desk.") == ["cup", "desk"]


def test_a_tavern_is_a_place_not_an_unknown_object():
    assert "W101" not in codes("In the tavern there is a table$.")


def relations(text):
    graphs = parse_document(text)
    cat = {o.id: o.id for g in graphs for o in g.objects}
    return sorted((cat[r.subject], r.relation, cat[r.object]) for g in graphs for r in g.relations)


def test_it_in_a_scene_sentence_is_the_thing_the_last_one_named_first():
    assert relations("There is a wooden bench$. A basket stands beside it$.") == [
        ("basket", "next_to", "bench")
    ]
    assert relations("There is a sofa$. There is a second sofa in front of it$.") == [
        ("sofa#2", "in_front_of", "sofa")
    ]
    assert relations("A shelf hangs by the door$. On it there is a clock$.") == [
        ("clock", "on", "shelf"),
        ("shelf", "near", "door"),
    ]
    assert relations("A rug lies under it$.") == []  # nothing named before: no relation


def test_a_thing_the_parser_hung_as_a_compound_of_its_verb_is_its_subject():
    assert relations("A basket stands beside the bench$.") == [("basket", "next_to", "bench")]


def test_another_thing_is_new_when_resolve_gets_no_offsets():
    # the orchestrator parses sentences one by one (spans in document offsets) and resolves them
    # without the offsets: "another lamp" must still be a second lamp
    from services.nlp.parse import parse_sentences
    from services.nlp.resolve import resolve
    from services.nlp.segment import split_sentences

    text = "A lamp stands in the corner$. There is another lamp by the door$. Ivo looks at the lamp."
    pieces = split_sentences(text)
    graphs = parse_sentences([(text[s:e], f"s{i}", s, hint) for i, (s, e, hint) in enumerate(pieces)])
    ids = [o.id for g in resolve(graphs) for o in g.objects if o.category == "lamp"]
    assert ids[:2] == ["lamp", "lamp#2"]


def test_a_placement_verb_read_as_a_noun_keeps_its_subject_and_adjectives():
    graphs = parse_document("A big green blackboard hangs above the desk$.")
    assert [(o.category, o.attributes) for g in graphs for o in g.objects][0] == (
        "blackboard",
        {"colour": "green", "size": "large"},
    )
    assert relations("A blue punching bag hangs near the window$.") == [("boxing_bag", "near", "window")]


def test_a_thing_in_hand_thrown_at_someone_stays_the_target():
    # only an act that is no thing in hand (a spell, a glance) yields its target to the one it is aimed at
    assert acts("Rita tosses a pebble at Ivo.") == [("Rita", "throw", "pebble")]


def test_worn_catalog_things_named_in_full_stay_in_the_room():
    assert objects("Max puts on the boxing gloves.") == ["boxing_gloves"]


def test_a_giving_verb_read_as_a_noun_gives_to_the_person_after_it():
    assert acts("The nurse hands Omar the cup.") == [("nurse", "present", "Omar")]
    assert objects("The nurse hands Omar the cup.") == ["cup"]
    assert acts("The blacksmith hands you a hammer.") == [("blacksmith", "present", "hammer")]


def test_she_is_the_character_known_to_be_a_she_before_one_of_no_known_gender():
    assert acts("The waiter hands Ada the menu. She waves at him.") == [
        ("waiter", "present", "Ada"),
        ("Ada", "wave", "waiter"),
    ]


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        # getting out of a bed, a tub or a seat stands up where one is (no walk to it first)
        ("A bed is by the wall$. Nadia gets out of bed.", [("Nadia", "stand", "")]),
        ("A bathtub is here$. Omar climbs out of the bathtub.", [("Omar", "stand", "")]),
        ("A sofa is here$. Ines slides off the sofa.", [("Ines", "stand", "")]),
        # into a bed or a tub is lying there; onto a seat is sitting on it
        ("A bed is by the wall$. Nadia gets into bed.", [("Nadia", "lie_down", "bed")]),
        ("A bed is by the wall$. Nadia climbs into bed.", [("Nadia", "climb", "bed")]),
        ("An armchair is here$. Ines gets into the armchair.", [("Ines", "sit", "armchair")]),
        # a place that is no bed or seat keeps its verb
        ("A table is here$. Nadia climbs onto the table.", [("Nadia", "climb", "table")]),
    ],
)
def test_getting_into_and_out_of_places_changes_posture(text, expected):
    assert acts(text) == expected
