"""'Did you mean ...' for words the parser does not know: the closest words of the object catalog, the
action library (its names, its synonyms and the verb table) and the command set, by edit distance;
a synonym found is shown with what it stands for ("couch (sofa)").
"""

from __future__ import annotations

import difflib
import functools

import numpy as np

from services.nlp import lexicon, verbs
from services.nlp.commands import CAMERA_VALUES, SPEED_VALUES, WEATHER_VALUES
from wana.assets import vocabulary

_CUTOFF = 0.75  # difflib ratio: "sist" ~ "sit" (0.86), "chiar" ~ "chair" (0.8); "lamp" !~ "map"


@functools.lru_cache(maxsize=1)
def _object_words() -> dict[str, str]:
    """Word -> the category it names (itself for a category name)."""
    words: dict[str, str] = {}
    for name, info in vocabulary.CATEGORIES.items():
        words.setdefault(name.replace("_", " "), name)
        for syn in info.synonyms:
            words.setdefault(syn, name)
    return words


@functools.lru_cache(maxsize=1)
def _verb_words() -> dict[str, str]:
    """One-word verb -> the action it maps to."""
    out: dict[str, str] = {}
    for name in lexicon.action_names():
        if "_" not in name:
            out.setdefault(name, name)
    for word in lexicon.verb_words() | {w for w in verbs.VERB_ACTIONS if " " not in w}:
        action = lexicon.action_for(word)
        if action:
            out.setdefault(word, action)
    return out


@functools.lru_cache(maxsize=1)
def _command_words() -> dict[str, str]:
    out = {f"camera {v}": f"camera {v}" for v in set(CAMERA_VALUES.values())}
    out.update({w: w for w in WEATHER_VALUES})
    out.update({w: w for w in SPEED_VALUES})
    out["wait"] = "wait"
    return out


def edit_distance(a: str, b: str) -> int:
    """Damerau-Levenshtein distance (adjacent swaps cost one: "chiar" -> "chair" is 1)."""
    prev2: list[int] = []
    prev = list(range(len(b) + 1))
    for i, ca in enumerate(a, 1):
        cur = [i] + [0] * len(b)
        for j, cb in enumerate(b, 1):
            cur[j] = min(prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (ca != cb))
            if i > 1 and j > 1 and ca == b[j - 2] and a[i - 2] == cb:
                cur[j] = min(cur[j], prev2[j - 2] + 1)
        prev2, prev = prev, cur
    return prev[-1]


class _Shortlist:
    """A vocabulary's words with their letter counts, to skip the words difflib would reject unread.

    ``difflib.get_close_matches`` keeps a word only if its ``quick_ratio`` (twice the letters the two
    words share, counted as multisets, over their total length) reaches the cutoff, and ``ratio`` never
    exceeds it; so the words below that bound, computed here for the whole vocabulary in a few numpy
    operations, are exactly those it would drop, and the matches (scored and ordered by difflib, ties
    by word) are the same. Scoring all 2,000 words one by one in difflib cost milliseconds per unknown
    word (``bench/nlp.py`` reports ``suggest_p50_ms``).
    """

    def __init__(self, words: list[str]) -> None:
        self.words = words
        chars = sorted({ch for w in words for ch in w})
        self.column = {ch: i for i, ch in enumerate(chars)}
        self.counts = np.zeros((len(words), len(chars)), dtype=np.int16)
        for row, w in enumerate(words):
            for ch in w:
                self.counts[row, self.column[ch]] += 1
        self.lengths = np.array([len(w) for w in words], dtype=np.int32)

    def candidates(self, word: str, cutoff: float) -> list[str]:
        query = np.zeros(len(self.column), dtype=np.int16)
        for ch in word:
            col = self.column.get(ch)
            if col is not None:  # a letter no vocabulary word has matches nothing
                query[col] += 1
        shared = np.minimum(self.counts, query).sum(axis=1)
        bound = 2.0 * shared / (self.lengths + len(word))
        return [self.words[i] for i in np.flatnonzero(bound >= cutoff)]


@functools.lru_cache(maxsize=4)
def _shortlist(kind: str) -> _Shortlist:
    table = {"object": _object_words, "action": _verb_words, "command": _command_words}[kind]()
    return _Shortlist(list(table))


def _close_matches(word: str, kind: str, n: int) -> list[str]:
    """``difflib.get_close_matches(word, vocabulary, n, _CUTOFF)``, reading only the words that can pass."""
    return difflib.get_close_matches(word, _shortlist(kind).candidates(word, _CUTOFF), n=n, cutoff=_CUTOFF)


def _shown(word: str, meaning: str) -> str:
    meaning = meaning.replace("_", " ")
    return f"'{word}'" if meaning == word else f"'{word}' ({meaning})"


@functools.lru_cache(maxsize=4096)
def suggestions(word: str, kind: str, limit: int = 3) -> tuple[str, ...]:
    """Closest known words to ``word`` as shown strings.

    Args:
        word: the unknown word as written ("sist", "chiar").
        kind: "object", "action" or "command": which vocabularies to search first (the other two
            follow, so a verb written where an object was expected is still found).
        limit: at most this many suggestions.
    """
    lower = word.lower().strip()
    if len(lower) < 3:
        return ()
    order = {"object": ("object", "action", "command"), "action": ("action", "object", "command")}.get(
        kind, ("command", "action", "object")
    )
    tables = {"object": _object_words(), "action": _verb_words(), "command": _command_words()}
    found: list[str] = []
    for name in order:
        table = tables[name]
        close = _close_matches(lower, name, limit * 3)
        close.sort(key=lambda h: (edit_distance(lower, h), h[:1] != lower[:1]))
        best = edit_distance(lower, close[0]) if close else 0
        for hit in close:
            if edit_distance(lower, hit) > best:
                break  # only the nearest: "sist" -> "sit", not also "insist"
            if hit != lower:
                shown = _shown(hit, table[hit])
                if shown not in found:
                    found.append(shown)
        if found:
            break  # the first vocabulary that has a near word is the likely intent
    if not found and kind == "action" and lower.endswith("s") and len(lower) > 4:
        return suggestions(lower[:-1], kind, limit)  # "wlaks": "wlak" is one swap from "walk"
    return tuple(found[:limit])


def did_you_mean(word: str, kind: str) -> str:
    """ "; did you mean 'sit'?" or "" when nothing is close."""
    hits = suggestions(word, kind)
    if not hits:
        return ""
    return "; did you mean " + " or ".join(hits) + "?"
