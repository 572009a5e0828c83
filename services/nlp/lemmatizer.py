"""wana's lookup lemmatizer: (form, UPOS) -> lemma tables built from the treebanks, plus suffix rules.

spaCy's rule lemmatizer needs the spacy-lookups-data package; this component needs nothing but the
tables that ``scripts/train_nlp.py`` builds from the UD lemmas of EWT-train and the domain corpus and
stores inside the pipeline folder. Unknown words fall back to English inflection rules by POS.

Registered as the spaCy factory ``wana_lemmatizer`` (requires ``token.pos``, assigns ``token.lemma``).
"""

from __future__ import annotations

import json
from collections import Counter, defaultdict
from collections.abc import Iterable
from pathlib import Path

from spacy.language import Language
from spacy.tokens import Doc

LemmaTables = dict[str, dict[str, str]]
_VOWELS = set("aeiou")


def build_lemma_tables(conllu_paths: Iterable[Path]) -> LemmaTables:
    """Count (lower form, UPOS) -> lemma in CoNLL-U files and keep the most frequent lemma of each.

    Returns:
        {"by_pos": {"lower|UPOS": lemma}, "by_form": {"lower": lemma}}; ties break alphabetically.
    """
    by_pos: dict[str, Counter[str]] = defaultdict(Counter)
    by_form: dict[str, Counter[str]] = defaultdict(Counter)
    for path in conllu_paths:
        with open(path, encoding="utf-8") as fh:
            for line in fh:
                if not line or line[0] == "#" or line == "\n":
                    continue
                cols = line.rstrip("\n").split("\t")
                if len(cols) < 4 or not cols[0].isdigit() or cols[2] == "_":
                    continue
                form, lemma, upos = cols[1].lower(), cols[2], cols[3]
                by_pos[f"{form}|{upos}"][lemma] += 1
                by_form[form][lemma] += 1

    def best(c: Counter[str]) -> str:
        return sorted(c.items(), key=lambda kv: (-kv[1], kv[0]))[0][0]

    return {
        "by_pos": {k: best(v) for k, v in sorted(by_pos.items())},
        "by_form": {k: best(v) for k, v in sorted(by_form.items())},
    }


def _noun_rule(w: str) -> str:
    if len(w) > 4 and w.endswith("ies"):
        return w[:-3] + "y"
    if len(w) > 4 and w.endswith(("ches", "shes", "sses", "xes", "zes")):
        return w[:-2]
    if len(w) > 3 and w.endswith("s") and not w.endswith(("ss", "us", "is")):
        return w[:-1]
    return w


def _verb_rule(w: str) -> str:
    if len(w) > 4 and w.endswith("ies"):
        return w[:-3] + "y"
    if len(w) > 4 and w.endswith(("ches", "shes", "sses", "xes", "zes", "oes")):
        return w[:-2]
    if len(w) > 3 and w.endswith("s") and not w.endswith("ss"):
        return w[:-1]
    for suffix in ("ing", "ed"):
        if len(w) > len(suffix) + 2 and w.endswith(suffix):
            stem = w[: -len(suffix)]
            if len(stem) > 2 and stem[-1] == stem[-2] and stem[-1] not in "lsz":
                return stem[:-1]  # "stopped" -> "stop"
            if (
                stem[-1] not in _VOWELS
                and stem[-2] in _VOWELS
                and stem[-3] not in _VOWELS
                and stem[-1] not in "wxy"
            ):
                return stem + "e"  # "smiled" -> "smile"; a heuristic, the tables cover common verbs
            return stem
    return w


def rule_lemma(form: str, pos: str) -> str:
    """Lemma of a word the tables do not know, from its POS and English inflection."""
    if pos == "PROPN":
        return form
    w = form.lower()
    if pos == "NOUN":
        return _noun_rule(w)
    if pos in ("VERB", "AUX"):
        return _verb_rule(w)
    return w


class LookupLemmatizer:
    """Sets ``token.lemma_`` from (lower form, UPOS), then lower form, then :func:`rule_lemma`."""

    def __init__(self, name: str = "wana_lemmatizer", tables: LemmaTables | None = None) -> None:
        self.name = name
        self.tables: LemmaTables = tables or {"by_pos": {}, "by_form": {}}

    def lemma(self, form: str, pos: str) -> str:
        lower = form.lower()
        hit = self.tables["by_pos"].get(f"{lower}|{pos}")
        if hit is not None:
            return hit
        if pos not in ("NOUN", "VERB", "PROPN", "ADJ"):
            hit = self.tables["by_form"].get(lower)
            if hit is not None:
                return hit
        return rule_lemma(form, pos)

    def __call__(self, doc: Doc) -> Doc:
        for token in doc:
            token.lemma_ = self.lemma(token.text, token.pos_)
        return doc

    def to_disk(self, path: str | Path, exclude: Iterable[str] = ()) -> None:
        path = Path(path)
        path.mkdir(parents=True, exist_ok=True)
        (path / "tables.json").write_text(
            json.dumps(self.tables, ensure_ascii=False, separators=(",", ":")), encoding="utf-8"
        )

    def from_disk(self, path: str | Path, exclude: Iterable[str] = ()) -> LookupLemmatizer:
        self.tables = json.loads((Path(path) / "tables.json").read_text(encoding="utf-8"))
        return self


@Language.factory("wana_lemmatizer", requires=["token.pos"], assigns=["token.lemma"])
def make_wana_lemmatizer(nlp: Language, name: str) -> LookupLemmatizer:
    return LookupLemmatizer(name)
