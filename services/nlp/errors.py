"""Numbered diagnostic codes of the NLP stage (spaCy-style: one table, one place).

W = warning (the sentence still yields a partial graph), E = error (the sentence yields nothing),
I = information. Each diagnostic carries the character span it is about, in document coordinates.
"""

from __future__ import annotations

from proto.common import Span
from proto.ssg import Diagnostic, Severity

DIAGNOSTICS: dict[str, tuple[Severity, str]] = {
    "W101": ("warning", "unknown object word"),
    "W102": ("warning", "unknown action word"),
    "W103": ("warning", "sentence has no verb"),
    "W104": ("warning", "unknown command"),
    "W105": ("warning", "pronoun or name with no character to refer to"),
    "W106": ("warning", "text does not look like English"),
    "W107": ("warning", "relation word without an object to relate"),
    "W108": ("warning", "sentence too long: only its beginning was parsed"),
    "W109": ("warning", "action without a character"),
    "E110": ("error", "binary or control characters: the sentence was skipped"),
    "I111": ("info", "empty sentence"),
    "E112": ("error", "the sentence could not be parsed"),
    "W113": ("warning", "verb with nothing to animate"),
    "I114": ("info", "placed by a part of the room, which the layout does not honour yet"),
    "W115": ("warning", "nothing in the sentence to animate"),
}

MAX_SENTENCE_CHARS = 1000  # longer sentences are cut here before parsing (W108)


def diagnostic(code: str, detail: str, start: int, end: int) -> Diagnostic:
    """A Diagnostic with the severity of ``code`` and a message "<summary>: <detail>".

    Args:
        code: a key of DIAGNOSTICS.
        detail: what exactly was wrong, e.g. the word.
        start, end: character range in the document text.
    """
    severity, summary = DIAGNOSTICS[code]
    message = f"{summary}: {detail}" if detail else summary
    return Diagnostic(code=code, message=message, span=Span(start, max(start, end)), severity=severity)
