"""Did-you-mean: the shortlisted search finds exactly what difflib over the whole vocabulary finds."""

from __future__ import annotations

import difflib
import random

import pytest

from services.nlp import suggest


def _misspelled(word: str, rng: random.Random) -> str:
    chars = list(word)
    i = rng.randrange(len(chars))
    op = rng.choice("sdi")
    if op == "s" and len(chars) > 1:
        j = min(i + 1, len(chars) - 1)
        chars[i], chars[j] = chars[j], chars[i]
    elif op == "d" and len(chars) > 2:
        del chars[i]
    else:
        chars.insert(i, rng.choice("abcdefghijklmnopqrstuvwxyz é"))
    return "".join(chars)


@pytest.mark.parametrize(
    "kind,table",
    [("object", suggest._object_words), ("action", suggest._verb_words), ("command", suggest._command_words)],
)
def test_shortlist_matches_difflib_over_the_whole_vocabulary(kind, table):
    words = list(table())
    rng = random.Random(11)
    queries = [_misspelled(w, rng) for w in rng.sample(words, min(150, len(words)))]
    queries += ["zorblax", "chiar", "sist", "jmups", "café", "camera zom in", "ab", "x", "rainny"]
    for q in queries:
        want = difflib.get_close_matches(q, words, n=9, cutoff=suggest._CUTOFF)
        assert suggest._close_matches(q, kind, 9) == want, q


def test_suggestions_still_name_the_near_word():
    assert suggest.did_you_mean("chiar", "object") == "; did you mean 'chair'?"
    assert "'sit'" in suggest.did_you_mean("sist", "action")
    assert suggest.did_you_mean("zorblax", "object") == ""
