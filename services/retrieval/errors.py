"""Diagnostic codes of the retrieval stage (one table, spaCy style). Each message names the object."""

from __future__ import annotations

DIAGNOSTIC_CODES: dict[str, str] = {
    "W501": "unknown object category: the object is left out of the scene",
    "W502": "unknown relation word: the relation is ignored",
    "W503": "the relation names an object the scene does not have",
    "W504": "the relation could not be kept in the composed scene",
    "W505": "no free spot: the object overlaps another one",
    "W506": "nothing in the scene database resembles the object",
    "W507": "two objects share one id: the later one is left out",
    "I508": "the room was enlarged to fit the objects",
    "I509": "context objects were added for the named kind of room",
}


def code(key: str) -> str:
    """'W501 unknown object category' style code string for proto.ssg.Diagnostic.code."""
    return f"{key} {DIAGNOSTIC_CODES[key].split(':')[0]}"
