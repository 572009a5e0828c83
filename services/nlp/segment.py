"""Split a document into sentences with character spans and a kind hint.

A sentence ends at ``.``, ``!``, ``?``, ``$`` or a newline. A ``.`` between digits ("1.5") or after a
common abbreviation ("Mr.") does not end one. Consecutive terminators stay together ("$." "?!").
The kind hint is "scene" for a sentence ending in ``$``, "command" for a command line ("camera
left", "wait 2 seconds", "night"), else "action".

    >>> split_sentences("A desk is near a window$. Eve sits.\\ncamera left")
    [(0, 25, 'scene'), (26, 35, 'action'), (36, 47, 'command')]
"""

from __future__ import annotations

import re

from services.nlp.commands import looks_like_command, parse_command

_ABBREV = {"mr", "mrs", "ms", "dr", "st", "prof", "jr", "sr", "vs", "etc", "e.g", "i.e", "mt", "no"}
_TERMINATORS = ".!?$"
_CLOSERS = "\"')]}»”’"


_QUOTE = re.compile(r'"[^"\n]*"|\u201c[^\u201d\n]*\u201d')


def quote_spans(text: str) -> list[tuple[int, int]]:
    """(start, end) of each double-quoted stretch, quotes included; an unclosed quote is none."""
    return [m.span() for m in _QUOTE.finditer(text)]


def _sentence_ends(line: str) -> list[int]:
    """End positions (exclusive) of sentences inside one line; none inside quoted speech."""
    ends: list[int] = []
    quotes = quote_spans(line)
    i, n = 0, len(line)
    while i < n:
        ch = line[i]
        inside = next((e for s, e in quotes if s < i < e - 1), None)
        if inside is not None and ch in _TERMINATORS:
            # 'says "I drank it. Sorry."': the speech is one piece of the sentence; it ends the
            # sentence when its last terminator is followed by a new sentence ('"Sorry." Mary nods')
            # but not by the rest of this one ('"Stop!" shouts Tom.')
            rest = line[inside:].lstrip()
            last = line[i + 1 : inside - 1].strip(_TERMINATORS) == ""
            if last and (not rest or rest[0].isupper()):
                ends.append(inside)
            i = inside if last else i + 1
            continue
        if ch in _TERMINATORS:
            if ch == "." and 0 < i < n - 1 and line[i - 1].isdigit() and line[i + 1].isdigit():
                i += 1
                continue
            if ch == ".":
                m = re.search(r"([A-Za-z.]+)$", line[max(0, i - 12) : i])
                if m and m.group(1).lower().rstrip(".") in _ABBREV and i + 1 < n and line[i + 1] == " ":
                    i += 1
                    continue
            j = i + 1
            while j < n and (line[j] in _TERMINATORS or line[j] in _CLOSERS):
                j += 1
            if ch != "$" and j < n and not line[j].isspace():
                i = j  # "e.g.x", "3.x", "a.b": no break without following space
                continue
            ends.append(j)
            i = j
        else:
            i += 1
    return ends


def kind_hint(sentence: str) -> str:
    """ "scene", "command" or "action" for one sentence's text."""
    stripped = sentence.rstrip()
    if "$" in stripped[-3:]:
        return "scene"
    if parse_command(stripped) is not None or looks_like_command(stripped):
        return "command"
    return "action"


def split_sentences(text: str) -> list[tuple[int, int, str]]:
    """Sentences of a document as ``(start, end, kind_hint)``; ``text[start:end]`` has no outer spaces.

    Blank stretches produce no sentence.
    """
    out: list[tuple[int, int, str]] = []
    pos = 0
    for line in text.splitlines(keepends=True):
        body = line.rstrip("\r\n")
        starts = 0
        for end in _sentence_ends(body) + [len(body)]:
            piece = body[starts:end]
            lead = len(piece) - len(piece.lstrip())
            trail = len(piece.rstrip())
            if trail > lead:
                s, e = pos + starts + lead, pos + starts + trail
                out.append((s, e, kind_hint(text[s:e])))
            starts = end
        pos += len(line)
    return out
