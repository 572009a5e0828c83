"""The committed VAD table (``assets/social/vad.tsv``) and word lookup with inflection fallbacks.

Values are valence, arousal, dominance in [-1, 1] (Glasgow Norms, scaled; see the table's header).
A missing dimension ("nan", VADER-only words) reads as 0, the neutral value.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

from wana.domain.paths import asset_path

TABLE = asset_path("social", "vad.tsv")
NEUTRAL: tuple[float, float, float] = (0.0, 0.0, 0.0)

STOPWORDS = frozenset(
    "a an the to at on in with of for up down out off into onto from by one oneself someone someone's "
    "be do make give get take have go put set the's".split()
)


@dataclass(frozen=True)
class ActionEntry:
    """One action row: its VAD and whether it can be proposed as a reaction, and touches the other."""

    name: str
    vad: tuple[float, float, float]
    response: bool
    contact: bool


def content_words(phrase: str) -> list[str]:
    """Lower-case content words of a phrase ("shake someone's hand" -> ["shake", "hand"])."""
    out = []
    for raw in phrase.lower().replace("-", " ").replace("!", " ").split():
        w = raw.removesuffix("'s").strip("'.,")
        if w and w.isalpha() and w not in STOPWORDS:
            out.append(w)
    return out


def word_variants(word: str) -> list[str]:
    """Spellings to try for a word, most specific first: itself, British/US, and de-inflected forms.

    The NLP stage can pass stems such as "criticiz" (from "criticizes"), so "+e" is tried too.
    """
    w = word.lower().strip()
    out = [w]

    def add(x: str) -> None:
        if len(x) >= 2 and x not in out:
            out.append(x)

    if "is" in w:
        add(w.replace("ise", "ize").replace("isi", "izi"))
    add(w + "e")
    for suffix, repl in (
        ("ies", "y"),
        ("es", ""),
        ("s", ""),
        ("ing", ""),
        ("ing", "e"),
        ("ed", ""),
        ("ed", "e"),
        ("d", ""),
        ("ied", "y"),
    ):
        if w.endswith(suffix) and len(w) - len(suffix) >= 3:
            add(w[: -len(suffix)] + repl)
    for x in list(out):
        if "is" in x:
            add(x.replace("ise", "ize"))
    return out


@functools.lru_cache(maxsize=1)
def load_table(
    path: str = str(TABLE),
) -> tuple[dict[str, tuple[float, float, float]], dict[str, ActionEntry]]:
    """(word -> VAD, action name -> ActionEntry) from the committed table.

    Raises:
        FileNotFoundError: the table is missing (rebuild it with ``python -m tools.authoring.build_vad``).
    """
    words: dict[str, tuple[float, float, float]] = {}
    actions: dict[str, ActionEntry] = {}
    with open(path, encoding="utf-8") as fh:
        header: list[str] | None = None
        for line in fh:
            if line.startswith("#") or not line.strip():
                continue
            cells = line.rstrip("\n").split("\t")
            if header is None:
                header = cells
                continue
            row = dict(zip(header, cells, strict=True))
            v, a, d = (
                0.0 if math.isnan(float(row[c])) else float(row[c])
                for c in ("valence", "arousal", "dominance")
            )
            vad = (v, a, d)
            if row["kind"] == "action":
                actions[row["key"]] = ActionEntry(
                    row["key"], vad, row["response"] == "1", row["contact"] == "1"
                )  # type: ignore[arg-type]
            else:
                words[row["key"]] = vad  # type: ignore[assignment]
    return words, actions


def word_vad(word: str) -> tuple[float, float, float] | None:
    """VAD of a word (any inflection the table can resolve), or None when the table does not know it."""
    words, actions = load_table()
    for w in word_variants(word):
        if w in words:
            return words[w]
    for w in word_variants(word):
        if w in actions:
            return actions[w].vad
    if len(word) >= 5:  # a stem the variants missed ("criticiz"): the unique table word it starts
        hits = sorted(w for w in words if w.startswith(word.lower()) and len(w) - len(word) <= 3)
        if len(hits) >= 1:
            return words[hits[0]]
    return None


def action_vad(action: str, verb: str = "") -> tuple[float, float, float] | None:
    """VAD of an action: its library row, else its verb's word VAD, else None."""
    _, actions = load_table()
    if action in actions:
        return actions[action].vad
    return word_vad(verb) if verb else None


def response_candidates() -> list[ActionEntry]:
    """Actions that may be proposed as a character's reaction, sorted by name (idle first)."""
    _, actions = load_table()
    found = sorted((a for a in actions.values() if a.response), key=lambda a: (a.name != "idle", a.name))
    return found


def contact_action(action: str) -> bool:
    """Whether the action's clip touches the other person (its distance is arm's length)."""
    entry = load_table()[1].get(action)
    return bool(entry and entry.contact)
