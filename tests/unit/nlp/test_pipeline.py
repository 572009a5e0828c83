"""The committed spaCy pipeline: components, lemmas, and accuracy on the domain and EWT test splits."""

from __future__ import annotations

import pytest

from services.nlp.lemmatizer import LookupLemmatizer, build_lemma_tables, rule_lemma
from services.nlp.pipeline import MODEL_DIR, evaluate_treebank, get_nlp


def test_pipeline_loads_once_with_its_trained_components():
    nlp = get_nlp()
    assert get_nlp() is nlp
    for name in ("tok2vec", "tagger", "morphologizer", "wana_lemmatizer", "parser"):
        assert name in nlp.pipe_names
    size = sum(p.stat().st_size for p in MODEL_DIR.rglob("*") if p.is_file())
    assert size <= 30e6


def test_tagging_lemmas_and_tree_of_a_domain_sentence():
    doc = get_nlp()("Eve sits on the chairs and types on the laptop.")
    assert [t.pos_ for t in doc] == [
        "PROPN",
        "VERB",
        "ADP",
        "DET",
        "NOUN",
        "CCONJ",
        "VERB",
        "ADP",
        "DET",
        "NOUN",
        "PUNCT",
    ]
    assert [t.lemma_ for t in doc][:7] == ["Eve", "sit", "on", "the", "chair", "and", "type"]
    assert doc[0].head == doc[1] and doc[0].dep_ == "nsubj"
    assert doc[6].head == doc[1] and doc[6].dep_ == "conj"


def test_lookup_tables_prefer_the_frequent_lemma_and_rules_cover_unknown_words(tmp_path):
    conllu = tmp_path / "t.conllu"
    conllu.write_text(
        "1\tsaw\tsee\tVERB\tVBD\t_\t0\troot\t_\t_\n"
        "1\tsaw\tsee\tVERB\tVBD\t_\t0\troot\t_\t_\n"
        "1\tsaw\tsaw\tNOUN\tNN\t_\t0\troot\t_\t_\n"
    )
    tables = build_lemma_tables([conllu])
    lem = LookupLemmatizer(tables=tables)
    assert lem.lemma("Saw", "VERB") == "see" and lem.lemma("saw", "NOUN") == "saw"
    assert rule_lemma("frobnicates", "VERB") == "frobnicate" and rule_lemma("zorblaxes", "NOUN") == "zorblax"
    assert rule_lemma("Eve", "PROPN") == "Eve"


def test_domain_test_split_parses_well(repo_root):
    scores = evaluate_treebank(repo_root / "corpus" / "domain" / "domain-test.conllu")
    assert scores["pos"] >= 0.95 and scores["uas"] >= 0.90 and scores["las"] >= 0.85


@pytest.mark.data
def test_ewt_test_slice_parses_reasonably(shared_data):
    scores = evaluate_treebank(shared_data / "ud_english_ewt" / "en_ewt-ud-test.conllu", limit=150)
    assert scores["pos"] >= 0.85 and scores["uas"] >= 0.65
