"""Relation labels -> r = (dominance, intimacy), both in [-1, 1], directed from the first subject.

Dominance > 0: the first subject has power over the second ("Mary is Tom's boss" -> Mary over Tom).
Intimacy: -1 hostile, 0 neutral acquaintance, +1 intimate. The values are hand-set, ordered after
interpersonal-circumplex studies (e.g. Wiggins 1979) and Hall's proxemics; the model samples around them.
"""

from __future__ import annotations

# label -> (dominance of subjects[0] over subjects[1], intimacy)
RELATIONS: dict[str, tuple[float, float]] = {
    "friends": (0.0, 0.7),
    "best friends": (0.0, 0.85),
    "couple": (0.0, 0.95),
    "lovers": (0.0, 0.95),
    "partners": (0.0, 0.8),
    "wife": (0.0, 0.9),
    "husband": (0.0, 0.9),
    "boyfriend": (0.0, 0.9),
    "girlfriend": (0.0, 0.9),
    "fiance": (0.0, 0.9),
    "fiancee": (0.0, 0.9),
    "family": (0.0, 0.75),
    "relatives": (0.0, 0.55),
    "siblings": (0.0, 0.75),
    "sister": (0.0, 0.75),
    "brother": (0.0, 0.75),
    "cousins": (0.0, 0.55),
    "mother": (0.5, 0.8),
    "father": (0.5, 0.8),
    "parent": (0.5, 0.8),
    "son": (-0.5, 0.8),
    "daughter": (-0.5, 0.8),
    "child": (-0.5, 0.8),
    "boss": (0.7, 0.05),
    "manager": (0.6, 0.05),
    "employer": (0.7, 0.0),
    "employee": (-0.7, 0.05),
    "assistant": (-0.5, 0.15),
    "teacher": (0.5, 0.25),
    "coach": (0.5, 0.3),
    "student": (-0.5, 0.25),
    "colleagues": (0.0, 0.25),
    "classmates": (0.0, 0.35),
    "teammates": (0.0, 0.45),
    "roommates": (0.0, 0.4),
    "neighbors": (0.0, 0.2),
    "acquaintances": (0.0, 0.1),
    "strangers": (0.0, -0.2),
    "rivals": (0.0, -0.5),
    "enemies": (0.0, -0.85),
}
# Words the NLP may emit for the labels above (plural/singular, spelling).
ALIASES: dict[str, str] = {
    "friend": "friends",
    "lover": "lovers",
    "partner": "partners",
    "sibling": "siblings",
    "cousin": "cousins",
    "parents": "parent",
    "children": "child",
    "colleague": "colleagues",
    "classmate": "classmates",
    "teammate": "teammates",
    "roommate": "roommates",
    "neighbor": "neighbors",
    "neighbour": "neighbors",
    "neighbours": "neighbors",
    "acquaintance": "acquaintances",
    "stranger": "strangers",
    "rival": "rivals",
    "enemy": "enemies",
}
DEFAULT_RELATION = "acquaintances"  # when the text names none
SYMMETRIC = frozenset(k for k, (d, _) in RELATIONS.items() if d == 0.0)


def relation_of(label: str) -> tuple[float, float] | None:
    """(dominance of the first subject over the second, intimacy) of a label, or None when unknown."""
    key = label.lower().strip()
    key = ALIASES.get(key, key)
    return RELATIONS.get(key)


def canonical_label(label: str) -> str:
    key = label.lower().strip()
    return ALIASES.get(key, key)


_INVERSE = {
    "boss": "employee",
    "manager": "employee",
    "employer": "employee",
    "employee": "boss",
    "assistant": "boss",
    "teacher": "student",
    "coach": "student",
    "student": "teacher",
    "mother": "child",
    "father": "child",
    "parent": "child",
    "son": "parent",
    "daughter": "parent",
    "child": "parent",
    "wife": "husband",
    "husband": "wife",
    "boyfriend": "girlfriend",
    "girlfriend": "boyfriend",
    "fiance": "fiancee",
    "fiancee": "fiance",
}


def inverse_label(label: str) -> str:
    """The relation seen from the other side ("boss" -> "employee"); symmetric labels stay."""
    key = canonical_label(label)
    return _INVERSE.get(key, key)
