"""Social verbs, emotions and relations reach the SSG as the social model reads them.

Each sentence goes through the committed pipeline; the expected action names are the motion
library's clips tagged "social" (assets/actions), written here by hand.
"""

from __future__ import annotations

import pytest

from services.nlp.lemmatizer import verb_lemma_candidates
from services.nlp.parse import parse_document, parse_sentence


def acts(graphs):
    return sorted((c.name, a.action, a.target) for g in graphs for c in g.characters for a in c.actions)


def social(graphs):
    return sorted((s.kind, s.label, tuple(sorted(s.subjects))) for g in graphs for s in g.social)


def codes(graphs):
    return [d.code for g in graphs for d in g.diagnostics]


@pytest.mark.parametrize(
    ("text", "action", "label"),
    [
        ("Tom criticizes Mary.", "criticize", "criticize"),
        ("Tom criticized Mary.", "criticize", "criticize"),
        ("Tom is criticizing Mary.", "criticize", "criticize"),
        ("Tom scolds Mary.", "criticize", "scold"),
        ("Tom hugs Mary.", "hug", "hug"),
        ("Tom is hugging Mary.", "hug", "hug"),
        ("Tom quarrels with Mary.", "quarrel", "quarrel"),
        ("Tom quarreled with Mary.", "quarrel", "quarrel"),
        ("Tom is quarrelling with Mary.", "quarrel", "quarrel"),
        ("Tom argued with Mary.", "argue", "argue"),
        ("Tom apologizes to Mary.", "apologize", "apologize"),
        ("Tom is apologizing to Mary.", "apologize", "apologize"),
        ("Tom bows to Mary.", "bow", "bow"),
        ("Tom comforts Mary.", "comfort", "comfort"),
        ("Tom is comforting Mary.", "comfort", "comfort"),
        ("Tom greets Mary.", "wave", "greet"),
        ("Tom congratulates Mary.", "shake_hands", "congratulate"),
        ("Tom thanks Mary.", "bow", "thank"),
        ("Tom thanked Mary.", "bow", "thank"),
        ("Tom shakes hands with Mary.", "shake_hands", "shake_hands"),
        ("Tom shook hands with Mary.", "shake_hands", "shake_hands"),
        ("Tom is shaking hands with Mary.", "shake_hands", "shake_hands"),
        ("Tom high-fives Mary.", "high_five", "high-five"),
        ("Tom high-fived Mary.", "high_five", "high-five"),
        ("Tom gives Mary a hug.", "hug", "hug"),
        ("Tom gives Mary a high five.", "high_five", "high_five"),
        ("Tom has a quarrel with Mary.", "quarrel", "quarrel"),
        ("Tom introduces himself to Mary.", "introduce", "introduce"),
        ("Tom whispers to Mary.", "whisper", "whisper"),
        ("Tom kisses Mary.", "kiss_cheek", "kiss"),
        ("Tom pushes Mary.", "push_person", "push"),
        ("Tom threatens Mary.", "threaten", "threaten"),
    ],
)
def test_social_act_aimed_at_a_character_gives_action_target_and_social_node(text, action, label):
    graphs = [parse_sentence(text)]
    assert acts(graphs) == [("Tom", action, "Mary")]
    assert social(graphs) == [("emotion", label, ("Mary", "Tom"))]
    assert "W102" not in codes(graphs) and "W101" not in codes(graphs)


@pytest.mark.parametrize(
    ("text", "action"),
    [
        ("Tom waves at Mary.", "wave"),
        ("Tom waved to Mary.", "wave"),
        ("Tom waves his hands at Mary.", "wave_hands"),
        ("Tom points at Mary.", "point"),
        ("Tom claps for Mary.", "clap"),
        ("Tom beckons to Mary.", "beckon"),
    ],
)
def test_gesture_aimed_at_a_character_targets_it_without_a_social_node(text, action):
    graphs = [parse_sentence(text)]
    assert acts(graphs) == [("Tom", action, "Mary")]
    assert social(graphs) == []


@pytest.mark.parametrize(
    ("text", "action", "label"),
    [
        ("Tom and Mary hug.", "hug", "hug"),
        ("Tom and Mary quarrel.", "quarrel", "quarrel"),
        ("Tom and Mary are arguing.", "argue", "argue"),
        ("Tom and Mary shake hands.", "shake_hands", "shake_hands"),
        ("Tom and Mary high-five.", "high_five", "high-five"),
        ("Tom and Mary hug each other.", "hug", "hug"),
    ],
)
def test_conjoined_subjects_of_a_reciprocal_act_target_each_other(text, action, label):
    graphs = [parse_sentence(text)]
    assert acts(graphs) == [("Mary", action, "Tom"), ("Tom", action, "Mary")]
    assert social(graphs) == [("emotion", label, ("Mary", "Tom"))]


def test_they_of_a_reciprocal_act_resolves_to_the_other_character():
    graphs = parse_document("Tom walks in. Mary sits. They quarrel.")
    assert acts(graphs[2:]) == [("Mary", "quarrel", "Tom"), ("Tom", "quarrel", "Mary")]
    assert social(graphs[2:]) == [("emotion", "quarrel", ("Mary", "Tom"))]


def test_they_wave_at_each_other_resolves_both_targets_without_social_node():
    graphs = parse_document("Tom sees Mary. They wave at each other.")
    assert acts(graphs[1:]) == [("Mary", "wave", "Tom"), ("Tom", "wave", "Mary")]
    assert social(graphs[1:]) == []


def test_a_crowd_doing_a_gesture_does_not_target_each_other():
    graphs = [parse_sentence("Tom and Mary wave.")]
    assert acts(graphs) == [("Mary", "wave", ""), ("Tom", "wave", "")]
    assert social(graphs) == []


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("Tom is angry.", [("emotion", "angry", ("Tom",))]),
        ("Mary feels sad.", [("emotion", "sad", ("Mary",))]),
        ("Tom and Mary are friends.", [("relation", "friends", ("Mary", "Tom"))]),
        ("Tom is Mary's boss.", [("relation", "boss", ("Mary", "Tom"))]),
        ("Tom is the boss of Mary.", [("relation", "boss", ("Mary", "Tom"))]),
        ("Tom and Mary are married.", [("relation", "couple", ("Mary", "Tom"))]),
        ("Tom is married to Mary.", [("relation", "couple", ("Mary", "Tom"))]),
    ],
)
def test_emotion_and_relation_sentences_give_social_nodes_and_no_action(text, expected):
    graphs = [parse_sentence(text)]
    assert social(graphs) == expected
    assert all(not a for _, a, _ in acts(graphs))
    assert codes(graphs) == []


def test_relation_word_order_keeps_the_first_subject_first():
    (g,) = [parse_sentence("Tom is the boss of Mary.")]
    assert g.social[0].subjects == ["Tom", "Mary"]


def test_they_are_colleagues_resolves_to_the_last_two_characters():
    graphs = parse_document("Tom walks in. Tom waves at Eve. They are colleagues.")
    assert social(graphs[2:]) == [("relation", "colleagues", ("Eve", "Tom"))]


def test_body_part_alone_stays_the_target_as_written():
    graphs = [parse_sentence("Tom washes his hands.")]
    assert acts(graphs) == [("Tom", "wash_hands", "hand")]


@pytest.mark.parametrize(
    ("form", "lemma"),
    [
        ("criticizes", "criticize"),
        ("criticized", "criticize"),
        ("apologizing", "apologize"),
        ("quarrelled", "quarrel"),
        ("quarreled", "quarrel"),
        ("argued", "argue"),
        ("smiled", "smile"),
        ("stopped", "stop"),
        ("carried", "carry"),
        ("shook", "shake"),
        ("lying", "lie"),
        ("used", "use"),
        ("opened", "open"),
    ],
)
def test_verb_lemma_candidates_include_the_lemma(form, lemma):
    assert lemma in verb_lemma_candidates(form)


def test_lemmatizer_prefers_a_known_verb_among_its_guesses():
    from services.nlp.lemmatizer import rule_lemma

    assert rule_lemma("quarreled", "VERB", frozenset({"quarrel"})) == "quarrel"
    assert rule_lemma("criticizes", "VERB") == "criticize"  # no tables: the first guess


@pytest.mark.parametrize("text", ["Tom is charming.", "Tom and Mary in the kitchen."])
def test_tree_repairs_leave_real_adjectives_and_verbless_sentences_alone(text):
    graphs = [parse_sentence(text)]
    assert acts(graphs) == []


def test_rare_inflected_verb_is_not_taken_for_a_foreign_language():
    assert "W106" not in codes([parse_sentence("Tom is congratulating Mary.")])
