"""Action retrieval: action words (verb, object, instrument, manner) -> template clips of the library.

A clip is a candidate when the verb agrees with its name, a synonym or a tag. The object and the
instrument then raise clips that mention them (or one of their hypernyms: a grand piano is a piano is a
keyboard instrument) and lower clips made for another object ("play the piano" is not
"play_guitar"); a clip whose name or tags carry the manner ("walk_slowly") beats the plain one. When nothing fits, the result says
so and names the closest clips.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from proto.retrieval import ActionMatchResult, ActionQuery, ClipMatch
from wana.assets import vocabulary

WEAK_SCORE = 0.5  # below this the best clip is reported as a weak fit
_GENERIC_WORDS = {"with", "on", "at", "to", "the", "a", "an", "in", "of", "up", "down", "off", "and"}


@dataclass(frozen=True)
class ClipWords:
    """The words a clip answers to, prepared once per library."""

    name: str
    name_tokens: tuple[str, ...]
    synonyms: frozenset[str]  # lower-case phrases
    synonym_tokens: frozenset[str]
    tags: frozenset[str]
    object_words: frozenset[str]  # words naming objects the clip is made for (tokens after the verb, tags)


def _tokens(text: str) -> list[str]:
    return [t for t in re.split(r"[^a-z0-9]+", text.lower()) if t]


def _lemma(word: str) -> str:
    """Cheap verb normalisation for words the parser did not lemmatise ("plays" -> "play")."""
    w = word.lower().strip()
    for suffix, repl in (("ies", "y"), ("ing", ""), ("es", ""), ("s", "")):
        if w.endswith(suffix) and len(w) - len(suffix) >= 3:
            return w[: -len(suffix)] + repl
    return w


def prepare_clips(clips: Mapping[str, Any]) -> list[ClipWords]:
    """Index a library (name -> clip with ``tags`` and ``synonyms``) for matching."""
    prepared: list[ClipWords] = []
    all_verbs = {_tokens(n)[0] for n in clips if _tokens(n)}
    for name in sorted(clips):
        clip = clips[name]
        name_tokens = tuple(_tokens(name))
        synonyms = frozenset(s.lower().strip() for s in clip.synonyms)
        synonym_tokens = frozenset(t for s in synonyms for t in _tokens(s))
        tags = frozenset(t.lower() for t in clip.tags)
        interaction: Any = getattr(clip, "interaction", None)
        objects = {t for t in name_tokens[1:] if t not in _GENERIC_WORDS and t not in all_verbs}
        if interaction is not None and str(getattr(interaction, "object", "") or ""):
            objects.add(str(interaction.object).lower())
        prepared.append(ClipWords(name, name_tokens, synonyms, synonym_tokens, tags, frozenset(objects)))
    return prepared


def _object_words(word: str) -> tuple[set[str], set[str]]:
    """(exact words, hypernym words) for an object given as a category or a word."""
    if not word:
        return set(), set()
    category = word if word in vocabulary.CATEGORIES else vocabulary.lookup(word)
    exact = set(_tokens(word))
    broader: set[str] = set()
    if category:
        exact |= set(_tokens(category))
        exact.add(category)
        info = vocabulary.CATEGORIES.get(category)
        for syn in getattr(info, "synonyms", ()) or ():
            exact |= set(_tokens(syn))
        for h in vocabulary.hypernyms(category):
            broader |= set(_tokens(h))
            broader.add(h)
    return exact, broader - exact


def _verb_score(verb: str, obj: str, clip: ClipWords) -> tuple[float, str]:
    v = _lemma(verb)
    if not v:
        return 0.0, ""
    if clip.name == v:
        return 1.0, "name"
    phrase = f"{v} {obj}".strip()
    if phrase in clip.synonyms or v in clip.synonyms:
        return 0.95, "synonym"
    if clip.name_tokens and clip.name_tokens[0] == v:
        return 0.9, "name"
    if any(s.split()[0] == v for s in clip.synonyms if s):
        return 0.8, "synonym"
    if v in clip.tags:
        return 0.6, "tag"
    return 0.0, ""


def _role_agreement(word: str, clip: ClipWords) -> float | None:
    """How a clip fits an object or instrument: 1 names it, 0.7 a hypernym, 0.5 generic, 0 another object."""
    if not word:
        return None
    exact, broader = _object_words(word)
    words = clip.object_words | clip.tags | clip.synonym_tokens
    if exact & words:
        return 1.0
    named = set(clip.name_tokens[1:]) & clip.object_words
    if named:
        return 0.0  # the clip is made for another object ("play_guitar" for a piano)
    if broader & words:
        return 0.7
    return 0.0 if clip.object_words else 0.5


def match_action(query: ActionQuery, clips: list[ClipWords], *, top_k: int = 3) -> ActionMatchResult:
    """Rank the library's clips for one action.

    Args:
        query: verb (lemma), object / instrument (catalog category or word), manner.
        clips: the prepared library (``prepare_clips(load_library())``).
        top_k: clips returned, best first.

    Returns:
        The best clips with scores in [0, 1] and what agreed; a diagnostic when nothing (or only a
        weak clip) fits.
    """
    scored: list[ClipMatch] = []
    for clip in clips:
        verb_score, how = _verb_score(query.verb, query.object or query.instrument, clip)
        if verb_score <= 0.0:
            continue
        matched_on = [how]
        roles = [
            (r, _role_agreement(w, clip))
            for r, w in (("object", query.object), ("instrument", query.instrument))
        ]
        given = [(r, a) for r, a in roles if a is not None]
        fit = sum(a for _, a in given) / len(given) if given else 1.0
        matched_on += [r for r, a in given if a >= 0.7]
        score = verb_score * (0.6 + 0.4 * fit)
        if query.manner:
            manner = _lemma(query.manner)
            if manner in {_lemma(t) for t in clip.tags | set(clip.name_tokens) | clip.synonym_tokens}:
                score = min(1.0, score + 0.1)
                matched_on.append("manner")
            else:
                score *= 0.9  # a clip made for the manner beats the plain one
        scored.append(ClipMatch(clip=clip.name, score=round(score, 4), matched_on=matched_on))
    scored.sort(key=lambda m: (-m.score, m.clip))
    best = scored[: max(1, top_k)]
    diagnostic = ""
    if not scored:
        diagnostic = f"no action clip fits the verb {query.verb!r}" + _closest(query.verb, clips)
    elif best[0].score < WEAK_SCORE:
        diagnostic = f"only a weak fit for {_describe(query)}: {best[0].clip} ({best[0].score:.2f})"
    return ActionMatchResult(query=query, clips=best if scored else [], diagnostic=diagnostic)


def _describe(query: ActionQuery) -> str:
    parts = [query.verb, query.object, f"with {query.instrument}" if query.instrument else "", query.manner]
    return repr(" ".join(p for p in parts if p))


def _closest(verb: str, clips: Iterable[ClipWords]) -> str:
    names: dict[str, str] = {}
    for c in clips:
        names.setdefault(c.name, c.name)
        for s in c.synonyms:
            names.setdefault(s, c.name)
    close = difflib.get_close_matches(verb.lower(), list(names), n=3, cutoff=0.6)
    picks = list(dict.fromkeys(names[c] for c in close))
    return f"; closest clips: {', '.join(picks)}" if picks else "; the library has no similar clip"
