"""Split glued compounds ("oilpainting", "modernchair", "horsesculpture", "boxingbag") into words.

A split is accepted when its last part, or the whole phrase, names a catalog category and every
other part is a known word (an attribute word, a category word or an English word of the
treebank vocabulary). Fewer parts win; among equals, parts known to the catalog win.

    >>> split_glued("horsesculpture")
    ['horse', 'sculpture']
    >>> split_glued("oilpainting")
    ['oil', 'painting']
"""

from __future__ import annotations

import functools
import json

from services.nlp import lexicon
from wana.assets import vocabulary

MIN_PART = 2


@functools.lru_cache(maxsize=1)
def _catalog_words() -> frozenset[str]:
    words: set[str] = set()
    for name, info in vocabulary.CATEGORIES.items():
        words.update(name.split("_"))
        for syn in info.synonyms:
            words.update(syn.split())
    for attr in vocabulary.ATTRIBUTE_WORDS:
        words.update(attr.split())
    return frozenset(w for w in words if len(w) >= MIN_PART)


@functools.lru_cache(maxsize=1)
def _english_words() -> frozenset[str]:
    from services.nlp.pipeline import MODEL_DIR

    path = MODEL_DIR / "wana_lemmatizer" / "tables.json"
    try:
        forms = json.loads(path.read_text(encoding="utf-8"))["by_form"]
    except (OSError, ValueError, KeyError):
        return frozenset()
    return frozenset(w for w in forms if w.isalpha() and len(w) >= 3)


def _splits(word: str, max_parts: int) -> list[list[str]]:
    if max_parts == 1:
        return [[word]]
    out = [[word]]
    for i in range(MIN_PART, len(word) - MIN_PART + 1):
        head = word[:i]
        if head in _catalog_words() or head in _english_words():
            out += [[head, *rest] for rest in _splits(word[i:], max_parts - 1)]
    return out


@functools.lru_cache(maxsize=4096)
def split_glued(word: str) -> list[str] | None:
    """Parts of a glued compound whose last part (or whole) is a category, or None."""
    w = word.lower()
    if not w.isalpha() or len(w) < 2 * MIN_PART + 1:
        return None
    best: tuple[tuple[int, int], list[str]] | None = None
    for parts in _splits(w, 3):
        if len(parts) < 2:
            continue
        if not all(p in _catalog_words() or p in _english_words() for p in parts):
            continue
        if lexicon.category_of(" ".join(parts)) is None and lexicon.category_of(parts[-1]) is None:
            continue
        unknown_to_catalog = sum(p not in _catalog_words() for p in parts)
        key = (len(parts), unknown_to_catalog)
        if best is None or key < best[0]:
            best = (key, parts)
    return best[1] if best else None
