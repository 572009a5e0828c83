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


# Irregular pasts and participles of verbs wana's users write that the treebanks may lack.
IRREGULAR_VERBS = {
    "shook": "shake",
    "shaken": "shake",
    "threw": "throw",
    "thrown": "throw",
    "swung": "swing",
    "knelt": "kneel",
    "lit": "light",
    "sank": "sink",
    "swam": "swim",
    "spun": "spin",
    "fought": "fight",
    "caught": "catch",
    "taught": "teach",
    "bent": "bend",
    "fed": "feed",
    "hid": "hide",
    "hidden": "hide",
    "leapt": "leap",
    "crept": "creep",
    "wept": "weep",
    "slept": "sleep",
    "swept": "sweep",
    "stood": "stand",
    "sat": "sit",
    "lay": "lie",
    "rode": "ride",
    "drew": "draw",
    "drank": "drink",
    "ate": "eat",
    "sang": "sing",
    "ran": "run",
    "went": "go",
    "gave": "give",
    "took": "take",
    "hugged": "hug",
}


# Stem endings after which a dropped silent "e" comes back ("caus-ed" -> "cause").
SILENT_E_STEMS = ("iz", "is", "us", "as", "os", "at", "ur", "uc", "nc", "rc", "rg", "dg", "ag", "v", "u")


# Unstressed last syllables of longer verbs, which keep their form before "-ed"/"-ing" ("opened").
UNSTRESSED_ENDINGS = ("en", "er", "it", "on", "el", "al", "or", "ol", "ip")


def verb_lemma_candidates(w: str) -> list[str]:
    """Possible lemmas of an inflected verb form, the most likely spelling first.

    "criticizes" -> ["criticize", "criticiz"]; "quarrelled" -> ["quarrell", "quarrel", "quarrelle"];
    "smiled" -> ["smile", "smil"]; the caller keeps the first one a lexicon knows.
    """
    w = w.lower()
    if w in IRREGULAR_VERBS:
        return [IRREGULAR_VERBS[w]]
    out: list[str] = []

    def add(x: str) -> None:
        if len(x) >= 2 and x not in out:
            out.append(x)

    if len(w) > 4 and w.endswith("ies"):
        add(w[:-3] + "y")
    elif len(w) > 4 and w.endswith(("ches", "shes", "sses", "xes", "zzes")):
        add(w[:-2])
    elif len(w) > 3 and w.endswith("oes"):
        add(w[:-2])  # "goes" -> "go"
        add(w[:-1])  # "tiptoes" -> "tiptoe"
    elif len(w) > 3 and w.endswith("s") and not w.endswith("ss"):
        add(w[:-1])  # "criticizes" -> "criticize", "raises" -> "raise"
        if w.endswith("es"):
            add(w[:-2])
    if w.endswith("ying") and len(w) == 5:
        add(w[:-4] + "ie")  # "lying", "dying", "tying"
    if w.endswith("ied") and len(w) == 4:
        add(w[:-1])  # "tied", "died", "lied"
    if w.endswith("ed") and len(w) == 4:
        add(w[:-1])  # "used", "aged"
    for suffix in ("ing", "ed"):
        if len(w) > len(suffix) + 2 and w.endswith(suffix):
            stem = w[: -len(suffix)]
            if suffix == "ed" and stem.endswith("i") and len(stem) > 2:
                add(stem[:-1] + "y")  # "carried" -> "carry"
            if len(stem) > 2 and stem[-1] == stem[-2]:
                if stem[-1] in "lsz":
                    add(stem)  # "called", "kissed" (British "quarrelled" is tried next)
                    add(stem[:-1])
                else:
                    add(stem[:-1])  # "stopped" -> "stop"
                    add(stem)
            elif len(stem) >= 4 and stem.endswith(UNSTRESSED_ENDINGS):
                add(stem)  # "opened", "visited", "quarreled": no "e" came off
                add(stem + "e")
            elif (
                len(stem) > 2
                and stem[-1] not in _VOWELS
                and stem[-2] in _VOWELS
                and stem[-3] not in _VOWELS
                and stem[-1] not in "wxy"
            ):
                add(stem + "e")  # "smiled" -> "smile"; a heuristic, the known words decide
                add(stem)
            elif stem.endswith(SILENT_E_STEMS):
                add(stem + "e")  # "criticized", "caused", "danced", "managed", "solved"
                add(stem)
            else:
                add(stem)
                add(stem + "e")
            break
    add(w)
    return out


def _verb_rule(w: str, known: frozenset[str] | set[str] = frozenset()) -> str:
    candidates = verb_lemma_candidates(w)
    for c in candidates:
        if c in known:
            return c
    return candidates[0]


def rule_lemma(form: str, pos: str, known: frozenset[str] | set[str] = frozenset()) -> str:
    """Lemma of a word the tables do not know, from its POS and English inflection.

    Args:
        form: the word as written.
        pos: its UPOS.
        known: lemmas to prefer among a verb's possible spellings (treebank lemmas, action verbs).
    """
    if pos == "PROPN":
        return form
    w = form.lower()
    if pos == "NOUN":
        return _noun_rule(w)
    if pos in ("VERB", "AUX"):
        return _verb_rule(w, known)
    return w


def _action_verbs() -> frozenset[str]:
    try:
        from services.nlp.lexicon import verb_words

        return verb_words()
    except Exception:  # the lemmatizer must work without the action vocabulary (training, packaging)
        return frozenset()


class LookupLemmatizer:
    """Sets ``token.lemma_`` from (lower form, UPOS), then lower form, then :func:`rule_lemma`."""

    def __init__(self, name: str = "wana_lemmatizer", tables: LemmaTables | None = None) -> None:
        self.name = name
        self.tables: LemmaTables = tables or {"by_pos": {}, "by_form": {}}
        self._known: frozenset[str] | None = None

    @property
    def known(self) -> frozenset[str]:
        """Words a rule-made lemma may be: every treebank lemma and every action verb."""
        if self._known is None:
            lemmas = {v.lower() for v in self.tables["by_pos"].values()}
            self._known = frozenset(lemmas) | _action_verbs()
        return self._known

    def lemma(self, form: str, pos: str) -> str:
        lower = form.lower()
        hit = self.tables["by_pos"].get(f"{lower}|{pos}")
        if hit is not None:
            return hit
        if pos not in ("NOUN", "VERB", "PROPN", "ADJ"):
            hit = self.tables["by_form"].get(lower)
            if hit is not None:
                return hit
        return rule_lemma(form, pos, self.known)

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
        self._known = None
        return self


@Language.factory("wana_lemmatizer", requires=["token.pos"], assigns=["token.lemma"])
def make_wana_lemmatizer(nlp: Language, name: str) -> LookupLemmatizer:
    return LookupLemmatizer(name)
