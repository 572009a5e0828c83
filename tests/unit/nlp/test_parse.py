"""Sentence -> SSG through the committed pipeline: scene, actions, commands, diagnostics, spans."""

from __future__ import annotations

import pytest

from services.nlp.parse import parse_document, parse_sentence, shift_spans


def rels(g):
    return {(r.subject, r.relation, r.object) for r in g.relations}


def acts(g):
    return [(c.name, a.action, a.target or a.destination) for c in g.characters for a in c.actions]


def test_scene_sentence_gives_objects_and_relation():
    g = parse_sentence("A laptop is on the desk$.")
    assert g.kind == "scene"
    assert {o.id: o.category for o in g.objects} == {"laptop": "laptop", "desk": "desk"}
    assert rels(g) == {("laptop", "on", "desk")}


def test_multiword_relations_room_type_and_counts():
    g = parse_sentence("In the office there are two chairs in front of the desk$.")
    assert g.room_type == "office"
    chair = next(o for o in g.objects if o.category == "chair")
    assert chair.count == 2
    assert rels(g) == {("chair", "in_front_of", "desk")}


def test_attributes_and_synonyms_map_to_catalog_values():
    g = parse_sentence("A big red couch is next to the TV$.")
    sofa = next(o for o in g.objects if o.category == "sofa")
    assert sofa.attributes == {"colour": "red", "size": "large"} and sofa.word == "couch"
    assert rels(g) == {("sofa", "next_to", "television")}


def test_glued_compound_splits_into_category_and_attribute():
    g = parse_sentence("There is a horsesculpture near the window$.")
    sculpture = next(o for o in g.objects if o.category == "sculpture")
    assert sculpture.attributes.get("kind") == "horse" and sculpture.word == "horsesculpture"


def test_action_sentence_gives_ordered_conjoined_actions_with_targets():
    g = parse_sentence("Eve sits on the chair and types on the laptop.")
    assert g.kind == "action"
    assert acts(g) == [("Eve", "sit", "chair"), ("Eve", "type", "laptop")]


def test_manner_destination_instrument_and_duration():
    (walk,) = parse_sentence("Tom walks slowly to the door.").characters[0].actions
    assert (walk.action, walk.manner, walk.destination) == ("walk", "slowly", "door")
    (sing,) = parse_sentence("Mary sings with the microphone for 5 seconds.").characters[0].actions
    assert (sing.action, sing.instrument, sing.duration_s) == ("sing_with_microphone", "microphone", 5.0)


def test_synonym_phrases_map_to_library_actions():
    assert acts(parse_sentence("Alice is chatting on the phone.")) == [("Alice", "call_with_phone", "phone")]
    assert acts(parse_sentence("Bob plays the piano.")) == [("Bob", "play_piano", "piano")]


def test_social_relation_and_emotion():
    g = parse_sentence("Mary is Tom's boss.")
    assert [(s.kind, s.label, s.subjects) for s in g.social] == [("relation", "boss", ["Mary", "Tom"])]
    g = parse_sentence("Tom is angry.")
    assert [(s.kind, s.label) for s in g.social] == [("emotion", "angry")]


def test_document_resolves_pronouns_across_sentences():
    gs = parse_document("Eve walks to the piano. She plays it.\nTom walks in. They are friends.")
    assert acts(gs[1]) == [("Eve", "play_piano", "piano")]
    assert sorted(gs[3].social[0].subjects) == ["Eve", "Tom"]


def test_command_lines_are_commands():
    (g,) = parse_document("camera follow Tom")
    assert g.kind == "command" and (g.commands[0].kind, g.commands[0].value, g.commands[0].target) == (
        "camera",
        "follow",
        "Tom",
    )


@pytest.mark.parametrize(
    "text,code",
    [
        ("Eve juggles the balls.", "W102"),
        ("A unicorn is on the desk$.", "W101"),
        ("Eve.", "W103"),
        ("camera sideways", "W104"),
        ("Der Mann geht schnell zum Tisch und setzt sich.", "W106"),
        ("\x00\x01\x02\x03garbage\xff", "E110"),
        ("", "I111"),
        ("He sits.", "W105"),
    ],
)
def test_bad_input_gives_a_diagnostic_with_a_span_not_an_exception(text, code):
    gs = parse_document(text)
    diags = [d for g in gs for d in g.diagnostics]
    assert code in [d.code for d in diags]
    d = next(d for d in diags if d.code == code)
    assert 0 <= d.span.start <= d.span.end <= max(len(text), 1)


def test_unknown_word_span_points_at_the_word_in_the_document():
    text = "Tom sits. Eve eats an apple."
    g = parse_document(text)[1]
    (d,) = [d for d in g.diagnostics if d.code == "W101"]
    assert text[d.span.start : d.span.end] == "apple"


def test_the_rest_of_the_document_still_parses_around_garbage():
    gs = parse_document("A desk is near a window$.\n\x00\x01\x02\x03\x04\nEve sits on the chair.")
    assert rels(gs[0]) == {("desk", "near", "window")} and acts(gs[2]) == [("Eve", "sit", "chair")]


def test_long_sentence_is_cut_with_w108():
    g = parse_sentence("Eve walks " + "very " * 400 + "slowly.")
    assert "W108" in [d.code for d in g.diagnostics]


def test_parse_is_deterministic_and_spans_shift_with_offset():
    a = parse_sentence("A chair is next to the desk$.", "s1", 0)
    b = parse_sentence("A chair is next to the desk$.", "s1", 40)
    assert shift_spans(a, 40) == b
    assert parse_sentence("A chair is next to the desk$.", "s1", 0) == a
