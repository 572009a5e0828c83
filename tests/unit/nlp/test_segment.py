"""Sentence splitting: spans, terminators, command lines, kind hints."""

from __future__ import annotations

from services.nlp.segment import split_sentences


def texts(doc: str) -> list[tuple[str, str]]:
    return [(doc[s:e], k) for s, e, k in split_sentences(doc)]


def test_design_example_splits_into_its_sentences_with_kinds():
    doc = (
        "In the office there is a desk near a window$. A laptop is on the desk$.\n"
        "Eve walks to the chair. Eve sits on the chair and types on the laptop.\n"
        "camera left\n"
        "Tom walks in. Tom waves at Eve. They are colleagues."
    )
    assert texts(doc) == [
        ("In the office there is a desk near a window$.", "scene"),
        ("A laptop is on the desk$.", "scene"),
        ("Eve walks to the chair.", "action"),
        ("Eve sits on the chair and types on the laptop.", "action"),
        ("camera left", "command"),
        ("Tom walks in.", "action"),
        ("Tom waves at Eve.", "action"),
        ("They are colleagues.", "action"),
    ]


def test_dollar_ends_a_sentence_even_without_a_following_period():
    assert texts("A desk$ A chair is near it$") == [("A desk$", "scene"), ("A chair is near it$", "scene")]


def test_decimal_points_and_abbreviations_do_not_end_a_sentence():
    assert texts("Mr. Smith waits 1.5 seconds! Then he sits.") == [
        ("Mr. Smith waits 1.5 seconds!", "action"),
        ("Then he sits.", "action"),
    ]


def test_spans_index_the_document_and_skip_blank_lines():
    doc = "  Eve sits.  \n\n\n   camera top  \n"
    spans = split_sentences(doc)
    assert [(doc[s:e]) for s, e, _ in spans] == ["Eve sits.", "camera top"]
    assert spans[0][0] == 2 and spans[1][2] == "command"


def test_empty_and_whitespace_documents_have_no_sentences():
    assert split_sentences("") == []
    assert split_sentences(" \n\t \n") == []


def test_repeated_terminators_stay_with_their_sentence():
    assert texts("Really?! Yes...") == [("Really?!", "action"), ("Yes...", "action")]
