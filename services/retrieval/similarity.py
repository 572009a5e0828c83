"""How alike two SSG nodes are: categories (synonyms, hypernyms), attributes, relations.

Scores are in [0, 1]. Category similarity comes from the asset vocabulary (1 for the same category,
lower by hypernym distance); attribute agreement scales it; relation similarity is a small table
(the same word 1, near-synonyms such as "near"/"next to" lower, unrelated 0).
"""

from __future__ import annotations

from functools import lru_cache

from proto.ssg import RELATIONS, ObjectNode
from wana.assets import vocabulary

# A relation read from the anchor's side: "A in front of B" is "B behind A".
INVERSE_RELATION: dict[str, str] = {
    "in_front_of": "behind",
    "behind": "in_front_of",
    "left_of": "right_of",
    "right_of": "left_of",
    "under": "above",
    "above": "under",
    "near": "near",
    "next_to": "next_to",
}

# Partial agreement between different relation words (symmetric); everything else is 0.
_RELATED: dict[frozenset[str], float] = {
    frozenset({"near", "next_to"}): 0.8,
    frozenset({"above", "hanging_above"}): 0.8,
    frozenset({"on", "in"}): 0.5,
    frozenset({"on", "above"}): 0.4,
    frozenset({"in_front_of", "facing"}): 0.6,
    frozenset({"near", "around"}): 0.6,
    frozenset({"next_to", "left_of"}): 0.6,
    frozenset({"next_to", "right_of"}): 0.6,
    frozenset({"near", "left_of"}): 0.5,
    frozenset({"near", "right_of"}): 0.5,
    frozenset({"near", "in_front_of"}): 0.5,
    frozenset({"near", "behind"}): 0.5,
    frozenset({"near", "facing"}): 0.5,
}

ATTRIBUTE_WEIGHT = 0.25  # share of a node's score that attribute agreement decides


def relation_similarity(a: str, b: str) -> float:
    """Agreement of two relation words in [0, 1] (1 when equal)."""
    if a == b:
        return 1.0
    return _RELATED.get(frozenset({a, b}), 0.0)


def relation_table() -> tuple[tuple[str, ...], list[list[float]]]:
    """All relation words and their (K, K) similarity table, for vectorised scoring."""
    names = tuple(RELATIONS)
    return names, [[relation_similarity(a, b) for b in names] for a in names]


@lru_cache(maxsize=65536)
def category_similarity(a: str, b: str) -> float:
    """Vocabulary similarity of two catalog categories, cached; 0 for unknown words."""
    if a == b:
        return 1.0
    try:
        return float(vocabulary.category_similarity(a, b))
    except (KeyError, ValueError):
        return 0.0


def attribute_agreement(query: dict[str, str], candidate: dict[str, str]) -> float:
    """Share of the query's attribute knobs the candidate agrees with (1 when the query states none).

    A knob the candidate leaves open counts half: it could be given that value.
    """
    if not query:
        return 1.0
    total = 0.0
    for knob, value in query.items():
        have = candidate.get(knob)
        if have is None:
            total += 0.5
        elif have == value:
            total += 1.0
    return total / len(query)


def node_similarity(query: ObjectNode, candidate: ObjectNode) -> float:
    """Similarity of a query object node to a scene-database object node, in [0, 1]."""
    c = category_similarity(query.category, candidate.category)
    if c <= 0.0:
        return 0.0
    a = attribute_agreement(query.attributes, candidate.attributes)
    return c * (1.0 - ATTRIBUTE_WEIGHT + ATTRIBUTE_WEIGHT * a)
