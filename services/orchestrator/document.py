"""A document: text split into sentences with stable ids, edited by text diffs.

A sentence ends after `.`, `!`, `?` or `$` (the `$` marks a scene sentence and stays part of it), or at a
newline; a line such as `camera left` is a sentence of its own. The period of a title ("Dr. Jones",
"Mrs. Brown") ends nothing, as the parser's own segmenter (services/nlp/segment.py) has it: a titled name
is one character, in one sentence. Whitespace between sentences belongs to
no sentence. An edit re-splits only the region it touches; the sentences outside it keep their ids (their
offsets shift) and inside it an unchanged sentence text keeps its old id.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

import msgspec

# A sentence: a run of non-space text up to and including a terminator, or up to a newline / the end.
_SENTENCE = re.compile(r"[^\s][^\n.!?$]*(?:[.!?$]+|(?=\n)|$)")
_SPACE = re.compile(r"\s+")
# Titles and abbreviations whose period, followed by a space, does not end a sentence (services/nlp/segment.py).
TITLES = frozenset(
    {"mr", "mrs", "ms", "dr", "st", "prof", "jr", "sr", "vs", "etc", "mt", "no", "capt", "gen"}
)
_WORD_BEFORE = re.compile(r"([A-Za-z]+)\.$")

MAX_DOCUMENT_CHARS = 1_000_000


class TextChange(msgspec.Struct, frozen=True, kw_only=True):
    """Replace document characters [start, end) by text (offsets in the base version)."""

    start: int
    end: int
    text: str


class StaleEdit(Exception):
    """An edit was made against a version that is not the current one."""

    def __init__(self, base_version: int, current_version: int) -> None:
        super().__init__(
            f"edit is based on version {base_version} but the document is at version {current_version}; "
            f"rebase the change onto version {current_version} and send it again"
        )
        self.base_version = base_version
        self.current_version = current_version


class BadEdit(ValueError):
    """An edit whose ranges do not fit the document."""


@dataclass(frozen=True)
class Sentence:
    id: str
    start: int  # document offset, inclusive
    end: int  # document offset, exclusive
    text: str

    @property
    def key_text(self) -> str:
        """The text with runs of whitespace collapsed: what derived values depend on."""
        return normalise(self.text)


def normalise(text: str) -> str:
    return _SPACE.sub(" ", text).strip()


def split_spans(text: str, base: int = 0) -> list[tuple[int, int]]:
    """Sentence spans [start, end) of text, shifted by base."""
    spans: list[tuple[int, int]] = []
    glue = False  # the previous piece ended at a title's period: this piece continues its sentence
    for m in _SENTENCE.finditer(text):
        s, e = m.start(), m.end()
        while e > s and text[e - 1].isspace():
            e -= 1
        if e <= s:
            continue
        if glue and spans:
            s = spans.pop()[0] - base
        spans.append((s + base, e + base))
        glue = _ends_in_title(text, s, e)
    return spans


def _ends_in_title(text: str, start: int, end: int) -> bool:
    """Whether text[start:end] ends with a title's period ("Dr.") before a name on the same line ("Dr. Jones").

    Title and name are capitalised ("He sees a dr. He sits." stays two sentences).
    """
    word = _WORD_BEFORE.search(text, max(start, end - 6), end)
    follows = text[end : end + 2]
    return (
        word is not None
        and word.group(1)[0].isupper()
        and word.group(1).lower() in TITLES
        and follows[:1] == " "
        and follows[1:2].isupper()
    )


@dataclass
class Document:
    doc_id: str
    text: str = ""
    version: int = 0
    sentences: list[Sentence] = field(default_factory=list)
    next_id: int = 1

    @classmethod
    def from_text(cls, doc_id: str, text: str, version: int = 0) -> Document:
        doc = cls(doc_id=doc_id)
        doc.text = text
        doc.version = version
        doc.sentences = [doc._new_sentence(s, e) for s, e in split_spans(text)]
        return doc

    def _new_sentence(self, start: int, end: int) -> Sentence:
        sid = f"s{self.next_id}"
        self.next_id += 1
        return Sentence(sid, start, end, self.text[start:end])

    def apply(self, base_version: int, changes: list[TextChange]) -> list[str]:
        """Apply text changes made against base_version; returns the ids of sentences whose text changed.

        Changes are given in base-version offsets, must not overlap, and are applied together.

        Raises:
            StaleEdit: base_version is not the current version.
            BadEdit: a range lies outside the document, ranges overlap, or the result is too large.
        """
        if base_version != self.version:
            raise StaleEdit(base_version, self.version)
        ordered = sorted(changes, key=lambda c: (c.start, c.end))
        prev_end = -1
        for c in ordered:
            if not (0 <= c.start <= c.end <= len(self.text)):
                raise BadEdit(
                    f"range [{c.start}, {c.end}) is outside the document of {len(self.text)} characters"
                )
            if c.start < prev_end:
                raise BadEdit(f"ranges overlap at offset {c.start}")
            prev_end = c.end
        new_len = len(self.text) + sum(len(c.text) - (c.end - c.start) for c in ordered)
        if new_len > MAX_DOCUMENT_CHARS:
            raise BadEdit(f"the document would have {new_len} characters; the limit is {MAX_DOCUMENT_CHARS}")
        changed: list[str] = []
        # Apply from the last change backwards so earlier offsets stay valid.
        for c in reversed(ordered):
            changed.extend(self._apply_one(c))
        self.version += 1
        current = {s.id for s in self.sentences}
        return [sid for sid in dict.fromkeys(changed) if sid in current]

    def _apply_one(self, change: TextChange) -> list[str]:
        old = self.text
        self.text = old[: change.start] + change.text + old[change.end :]
        delta = len(change.text) - (change.end - change.start)
        # Touched: sentences overlapping or adjacent to the range (an edit at a boundary can merge them).
        first = 0
        while first < len(self.sentences) and self.sentences[first].end < change.start:
            first += 1
        last = first
        while last < len(self.sentences) and self.sentences[last].start <= change.end:
            last += 1
        # Widen by one on each side: a removed terminator merges a sentence with its neighbour.
        first = max(0, first - 1)
        last = min(len(self.sentences), last + 1)
        region_start = self.sentences[first].start if first < len(self.sentences) else change.start
        region_start = min(region_start, change.start)
        region_end_old = self.sentences[last - 1].end if last > first else change.end
        region_end_old = max(region_end_old, change.end)
        region_end = region_end_old + delta
        # Extend to the end of the line run so that a sentence is never cut mid-way.
        fresh_spans = split_spans(self.text[region_start:region_end], region_start)
        old_region = self.sentences[first:last]
        by_text: dict[str, list[Sentence]] = {}
        for s in old_region:
            by_text.setdefault(s.key_text, []).append(s)
        # First keep the ids of sentences whose text is unchanged; then the remaining old sentences hand
        # their ids, in order, to the remaining new ones (an edit inside a sentence keeps its id).
        slots: list[str | None] = []
        for start, end in fresh_spans:
            reuse = by_text.get(normalise(self.text[start:end]))
            slots.append(reuse.pop(0).id if reuse else None)
        kept = {sid for sid in slots if sid is not None}
        spare = [s.id for s in old_region if s.id not in kept]
        fresh: list[Sentence] = []
        changed: list[str] = []
        for (start, end), sid in zip(fresh_spans, slots, strict=True):
            if sid is None:
                if spare:
                    sid = spare.pop(0)
                    fresh.append(Sentence(sid, start, end, self.text[start:end]))
                else:
                    sent = self._new_sentence(start, end)
                    sid = sent.id
                    fresh.append(sent)
                changed.append(sid)
            else:
                fresh.append(Sentence(sid, start, end, self.text[start:end]))
        after = [Sentence(s.id, s.start + delta, s.end + delta, s.text) for s in self.sentences[last:]]
        self.sentences = self.sentences[:first] + fresh + after
        return changed

    def sentence(self, sid: str) -> Sentence:
        for s in self.sentences:
            if s.id == sid:
                return s
        raise KeyError(sid)
