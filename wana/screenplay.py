"""Fountain screenplays -> a wana story (the plain-text language of DESIGN.md §1).

Fountain (https://fountain.io) is the plain-text format screenwriters use. It is read by
``screenplain`` (the maintained parser behind screenplain.com, MIT, with its own test suite), and
each element becomes what wana already understands:

- scene heading ``INT. KITCHEN - NIGHT`` -> ``In the kitchen$.`` (the room kind, when the catalog
  knows it) and a light command (``night``; ``sunny`` for DAY/MORNING/AFTERNOON);
- action lines -> sentences as written, character names in capitals ("ADA enters") in the spelling
  of their cue ("Ada enters"), notes in parentheses dropped;
- a character cue with dialogue -> one ``Ada says "..."`` sentence per spoken sentence: a talking
  action, and the line itself is the sentence's caption in the render; a parenthetical adverb
  ``(angrily)`` is the manner ("Ada angrily says ..."), ``(to Tom)`` the one spoken to, ``(beat)`` a
  one-second wait;
- a transition (``CUT TO:``, ``DISSOLVE TO:``) -> ``camera close``: a cut to a close-up of whoever acts
  next, for that action, after which the director frames the scene again (a view command such as
  ``camera left`` would hold for the rest of the film).

It lives in the domain library because both the NLP service (``wana parse``) and the orchestrator
(``wana animate``) read Fountain, and services do not import each other.
"""

from __future__ import annotations

import io
import re

from wana.assets import vocabulary

_HEADING = re.compile(r"^\s*(?:\.(?=[A-Za-z])|(?:INT|EXT|EST|INT\.?/EXT|I/E)[. ])", re.IGNORECASE)
_CUE = re.compile(r"^[A-Z][A-Z0-9 .'\-]+(\s*\([^)]*\))?\s*\^?$")
_LIGHT = {
    "NIGHT": "night",
    "EVENING": "night",
    "DUSK": "night",
    "MIDNIGHT": "night",
    "LATE NIGHT": "night",
    "DAY": "sunny",
    "MORNING": "sunny",
    "AFTERNOON": "sunny",
    "DAWN": "sunny",
    "NOON": "sunny",
}
_CUT = "camera close"
_TITLE_DOT = re.compile(r"\b(Mr|Mrs|Ms|Dr|Prof|St|Jr|Sr|Capt|Sgt|Lt|Det)\.", re.IGNORECASE)
# A sentence ends at . ! ? (with closing quotes) unless the period ends a title ("Dr. Jones").
_SENTENCE = re.compile(r"(?:\b(?:Mr|Mrs|Ms|Dr|Prof|St|Jr|Sr|Capt|Sgt|Lt|Det)\.|[^.!?])+[.!?]*[\"')]*")


def looks_like_fountain(text: str, path: str = "") -> bool:
    """True for a ``.fountain`` file, or text with a scene heading or a title page and a character
    cue followed by dialogue."""
    if path.lower().endswith((".fountain", ".spmd")):
        return True
    lines = text.splitlines()
    if any(_HEADING.match(line) and line.strip().upper() == line.strip() for line in lines):
        return True
    title_page = bool(lines) and re.match(r"^(Title|Credit|Author|Draft date)\s*:", lines[0].strip() or "x")
    cue_then_line = any(
        _CUE.match(lines[i].strip()) and lines[i + 1].strip() and (i == 0 or not lines[i - 1].strip())
        for i in range(len(lines) - 1)
        if lines[i].strip() and not lines[i].strip().endswith(("$", ".", ":"))
    )
    return bool(title_page) or (cue_then_line and sum(1 for ln in lines if _CUE.match(ln.strip())) >= 2)


def _cue_name(cue: str) -> str:
    name = _no_title_dots(re.sub(r"\([^)]*\)", "", cue).replace("^", "").strip())
    return " ".join(w.capitalize() for w in name.split())


def _room_sentence(heading: str) -> tuple[str, str]:
    """("In the kitchen$.", "night") of a scene heading; "" for what it does not say."""
    body = re.sub(
        r"^\s*(?:\.|INT\.?/EXT\.?|I/E\.?|INT\.?|EXT\.?|EST\.?)\s*", "", heading, flags=re.IGNORECASE
    )
    body = re.sub(r"#[^#]*#\s*$", "", body).strip()  # a scene number
    place, _, when = body.rpartition(" - ") if " - " in body else (body, "", "")
    light = _LIGHT.get(when.strip().upper(), "")
    words = re.sub(r"[^a-z' ]", " ", place.lower()).split()
    room = ""
    for k in range(len(words)):  # the longest known ending: "ADA'S SMALL KITCHEN" -> kitchen
        found = vocabulary.lookup_room(" ".join(words[k:]))
        if found:
            room = found.replace("_", " ")
            break
    return (f"In the {room}$." if room else ""), light


def _spoken(name: str, text: str, manner: str, listener: str) -> list[str]:
    """``Ada angrily says "..." to Tom.`` per spoken sentence (quotes inside become single quotes)."""
    out: list[str] = []
    verb = f"{manner} says" if manner else "says"
    to = f" to {listener}" if listener else ""
    for m in _SENTENCE.finditer(text.replace('"', "'")):
        line = _no_title_dots(m.group(0).strip()).rstrip(".!?").strip()
        if line:
            # one line each, no terminator inside the quotes: every splitter keeps the line whole
            out.append(f'{name} {verb}{to} "{line}"')
    return out


def _no_title_dots(text: str) -> str:
    """ "Dr. Jones" -> "Dr Jones": a period after a title would end the sentence for a plain splitter."""
    return _TITLE_DOT.sub(r"\1", text)


# Lines that open or close the film ("FADE IN:", "FADE OUT.", "THE END"): screenplain reads them as
# action when they do not end in "TO:"; nothing to animate, and no sentence without a verb.
_BOOKENDS = re.compile(r"(?:FADE (?:IN|OUT)|FADE TO BLACK|BLACKOUT|THE END|END)\s*[.:!]?")


def to_story(text: str) -> str:
    """The wana story a Fountain screenplay tells, one sentence or command per line.

    Raises:
        ImportError: when ``screenplain`` is not installed.
    """
    from screenplain.parsers import fountain
    from screenplain.types import Action, Dialog, DualDialog, Slug, Transition

    play = fountain.parse(io.StringIO(text))
    dialogs: list[Dialog] = []
    for p in play:
        if isinstance(p, Dialog):
            dialogs.append(p)
        elif isinstance(p, DualDialog):
            dialogs += [p.left, p.right]
    names = {str(d.character): _cue_name(str(d.character)) for d in dialogs}
    caps = {re.sub(r"\([^)]*\)", "", k).replace("^", "").strip(): v for k, v in names.items()}
    caps_re = (
        re.compile(r"\b(" + "|".join(re.escape(k) for k in sorted(caps, key=len, reverse=True)) + r")\b")
        if caps
        else None
    )
    lines: list[str] = []

    def dialog(d: Dialog) -> None:
        name = _cue_name(str(d.character))
        manner = listener = ""
        for is_paren, rich in d.blocks:
            said = str(rich).strip()
            if is_paren:
                inner = said.strip("() ").strip()
                if m := re.fullmatch(r"to ([A-Z][\w.]*(?: [A-Z][\w.]*)?)", inner, re.IGNORECASE):
                    listener = _cue_name(m.group(1))
                elif re.fullmatch(r"[a-z]+ly", inner.lower()):
                    manner = inner.lower()
                elif inner.lower() in ("beat", "pause", "a beat", "long pause"):
                    lines.append("wait 2 seconds" if "long" in inner.lower() else "wait 1 second")
                continue
            lines.extend(_spoken(name, said, manner, listener))

    for p in play:
        if isinstance(p, Slug):
            room, light = _room_sentence(str(p.line))
            lines += [x for x in (room, light) if x]
        elif isinstance(p, Action):
            body = " ".join(str(line).strip() for line in p.lines)
            body = re.sub(r"\s*\([^)]*\)", "", body).strip()
            if _BOOKENDS.fullmatch(body):
                continue
            if caps_re is not None:
                body = caps_re.sub(lambda m: caps[m.group(1)], body)
            if body:
                lines += [_no_title_dots(s.strip()) for s in _SENTENCE.findall(body) if s.strip()]
        elif isinstance(p, Dialog):
            dialog(p)
        elif isinstance(p, DualDialog):
            dialog(p.left)
            dialog(p.right)
        elif isinstance(p, Transition):
            lines.append(_CUT)
    return "\n".join(lines) + ("\n" if lines else "")
