"""Time phrases ("The next morning", "after a while", "that night", "meanwhile", "at the same time").

They are never objects or targets of a verb. A time of day that says how the room is lit becomes a
light command on its sentence ("that night" -> night, "the next morning" -> sunny); the others only
order the actions, which the sentence order already does.
"""

from __future__ import annotations

from spacy.tokens import Token

# Time nouns -> the light they set ("" = none).
TIME_NOUNS: dict[str, str] = {
    "morning": "sunny",
    "dawn": "sunny",
    "sunrise": "sunny",
    "daybreak": "sunny",
    "noon": "sunny",
    "midday": "sunny",
    "afternoon": "sunny",
    "day": "",
    "daytime": "sunny",
    "evening": "night",
    "dusk": "night",
    "sunset": "night",
    "twilight": "night",
    "night": "night",
    "nighttime": "night",
    "midnight": "night",
    "nightfall": "night",
    "sundown": "night",
    "bedtime": "night",
    "sunup": "sunny",
    "tonight": "night",
    "while": "",
    "moment": "",
    "instant": "",
    "time": "",
    "week": "",
    "weekend": "",
    "month": "",
    "year": "",
    "today": "",
    "tomorrow": "",
    "yesterday": "",
    "later": "",
    "meantime": "",
    "meanwhile": "",
    "minute": "",
    "minutes": "",
    "hour": "",
    "hours": "",
    "seconds": "",
    "second": "",
}
# Words that make a preceding noun a time ("the next morning", "that evening", "one day").
TIME_MODIFIERS = frozenset("next same following previous that this one every each early late last".split())
_TIME_PREPS = frozenset("after before during until till by at in on for since within".split())
# Meals are times only after these ("after lunch", "before dinner"); "eats lunch" is food on a plate.
MEALS = frozenset("breakfast brunch lunch lunchtime dinner dinnertime supper tea teatime".split())
_MEAL_PREPS = frozenset("after before during until till since".split())


def time_light(tok: Token) -> str | None:
    """For the head of a time phrase: the light it sets ("" for none); None when it is no time phrase.

    "morning" in "The next morning, ..." / "in the morning" -> "sunny"; "while" in "after a while"
    -> ""; "time" in "at the same time" -> ""; "the chair" -> None.
    """
    lower = tok.lower_
    lemma = tok.lemma_.lower()
    if lower in MEALS and {c.lower_ for c in tok.children if c.dep_ == "case"} & _MEAL_PREPS:
        return ""  # "After lunch, Coach Taylor blows the whistle": a time, no plate
    if lower not in TIME_NOUNS and lemma not in TIME_NOUNS:
        return None
    light = TIME_NOUNS.get(lower, TIME_NOUNS.get(lemma, ""))
    mods = {c.lower_ for c in tok.children if c.dep_ in ("amod", "det", "nummod")}
    preps = {c.lower_ for c in tok.children if c.dep_ == "case"}
    if lower in ("while", "meantime", "meanwhile", "tonight", "today", "tomorrow", "yesterday", "later"):
        return light
    if mods & TIME_MODIFIERS or preps & _TIME_PREPS or tok.dep_ in ("obl:tmod", "nmod:tmod", "obl:npmod"):
        return light
    return None
