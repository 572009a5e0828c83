"""Command lines: camera, weather/light, wait, faster/slower.

>>> parse_command("camera left").value
'left'
>>> parse_command("Wait 2 seconds.").seconds
2.0
>>> parse_command("Tom waits") is None
True
"""

from __future__ import annotations

import re

from proto.common import Span
from proto.ssg import Command

NUMBER_WORDS = {
    "a": 1.0,
    "an": 1.0,
    "one": 1.0,
    "two": 2.0,
    "three": 3.0,
    "four": 4.0,
    "five": 5.0,
    "six": 6.0,
    "seven": 7.0,
    "eight": 8.0,
    "nine": 9.0,
    "ten": 10.0,
    "eleven": 11.0,
    "twelve": 12.0,
    "fifteen": 15.0,
    "twenty": 20.0,
    "thirty": 30.0,
    "sixty": 60.0,
    "half": 0.5,
    "half a": 0.5,
    "a few": 3.0,
    "few": 3.0,
    "several": 3.0,
    "a couple of": 2.0,
    "couple of": 2.0,
}
UNIT_SECONDS = {
    "s": 1.0,
    "sec": 1.0,
    "secs": 1.0,
    "second": 1.0,
    "seconds": 1.0,
    "min": 60.0,
    "mins": 60.0,
    "minute": 60.0,
    "minutes": 60.0,
    "ms": 0.001,
    "hour": 3600.0,
    "hours": 3600.0,
}

CAMERA_VALUES = {
    "front": "front",
    "back": "back",
    "behind": "back",
    "rear": "back",
    "left": "left",
    "right": "right",
    "top": "top",
    "above": "top",
    "overhead": "top",
    "bird": "top",
    "up": "top",
    "follow": "follow",
    "follows": "follow",
    "following": "follow",
    "track": "follow",
    "close": "close",
    "closeup": "close",
    "close-up": "close",
    "zoom": "close",
    "near": "close",
    "wide": "wide",
    "establishing": "wide",
    "overview": "wide",
    "long": "wide",
    "over-the-shoulder": "over_shoulder",
    "ots": "over_shoulder",
    "shoulder": "over_shoulder",
}
# What a diagnostic on an unknown camera word lists (the render service's COMMAND_MODES, in words).
KNOWN_CAMERA_WORDS = "front, back, left, right, top, wide, close, follow, over the shoulder"
WEATHER_VALUES = {
    "sunny": "sunny",
    "sun": "sunny",
    "day": "sunny",
    "daylight": "sunny",
    "bright": "sunny",
    "night": "night",
    "nighttime": "night",
    "dark": "night",
    "evening": "night",
    # a time of day said as a line of its own ("morning", "Midnight.")
    "morning": "sunny",
    "afternoon": "sunny",
    "noon": "sunny",
    "midday": "sunny",
    "daytime": "sunny",
    "dawn": "sunny",
    "sunrise": "sunny",
    "dusk": "night",
    "twilight": "night",
    "sunset": "night",
    "midnight": "night",
    "rainy": "rainy",
    "rain": "rainy",
    "raining": "rainy",
    "rains": "rainy",
    "foggy": "foggy",
    "fog": "foggy",
    "misty": "foggy",
    "mist": "foggy",
    "snowy": "snowy",
    "snow": "snowy",
    "snowing": "snowy",
    "snows": "snowy",
    "pour": "rainy",
    "pours": "rainy",
    "pouring": "rainy",
    "drizzle": "rainy",
    "drizzles": "rainy",
    "drizzling": "rainy",
}
SPEED_VALUES = {
    "faster": "faster",
    "speed up": "faster",
    "quicker": "faster",
    "slower": "slower",
    "slow down": "slower",
}

_NUM = r"(\d+(?:\.\d+)?|half a|a couple of|couple of|a few|[a-z]+)"
_WAIT = re.compile(rf"^(?:wait|pause)(?:\s+for)?(?:\s+{_NUM}(?:\s*([a-z]+))?)?$")
_CAMERA = re.compile(
    r"^camera\s*:?\s+(?:view\s+)?(?:from\s+(?:the\s+)?)?([a-z-]+)(?:\s+(?:on\s+|to\s+)?([A-Za-z][\w'.-]*(?:\s+(?!and\b)[A-Za-z][\w'.-]*){0,2}))?$",
    re.IGNORECASE,
)
_OVER_SHOULDER = re.compile(
    r"^camera\s*:?\s+over\s+(?:the\s+shoulder(?:\s+of\s+([A-Za-z][\w'-]*))?|([A-Za-z][\w-]*)'s?\s+shoulder)$",
    re.IGNORECASE,
)
_FOLLOW = re.compile(
    r"^follow\s+([A-Z][\w'.-]*(?:\s+[A-Z][\w'.-]*){0,2})$"
)  # "Follow Anna." (an imperative, not "Tom follows Anna")
_WEATHER = re.compile(r"^(?:(?:weather|light|lighting|time)\s*:?\s+|it\s+is\s+|it's\s+)?([a-z]+)$")
# "It starts to pour outside.", "It is raining.", "It snows": the weather, said as a sentence
_WEATHER_SENTENCE = re.compile(
    r"^(?:then\s+|suddenly\s+|outside\s+)?it\s+(?:(?:starts|begins|started|began)\s+(?:to\s+)?|is\s+|was\s+|'s\s+)?"
    r"(rain|rains|raining|pour|pours|pouring|drizzle|drizzles|drizzling|snow|snows|snowing)"
    r"(?:\s+(?:outside|again|heavily|hard|softly|gently))*$"
)

# A stage direction for the light: "lights dim to evening", "The lights go down", "lights up".
_LIGHTS = re.compile(
    r"^(?:the\s+)?(?:lights?|lighting)\s+(dim|dims|go down|goes down|fade|fades|fade out|darken|darkens|"
    r"go up|goes up|come up|comes up|up|brighten|brightens)(?:\s+(?:to|into)\s+(?:the\s+)?([a-z]+))?$"
)
_LIGHTS_DOWN = frozenset(
    {"dim", "dims", "go down", "goes down", "fade", "fades", "fade out", "darken", "darkens"}
)


def _clean(text: str) -> str:
    return re.sub(r"\s+", " ", text.strip().rstrip(".!?$;").strip())


def _number(word: str) -> float | None:
    try:
        return float(word)
    except ValueError:
        return NUMBER_WORDS.get(word)


def parse_command(text: str, offset: int = 0) -> Command | None:
    """The command a sentence states, or None when it is not a command line.

    Args:
        text: one sentence (its terminator may be included).
        offset: character position of ``text`` in the document, for the span.
    """
    clean = _clean(text)
    if not clean or len(clean) > 60:
        return None
    lower = clean.lower()
    lead = len(text) - len(text.lstrip())
    span = Span(offset + lead, offset + lead + len(clean))
    if m := _OVER_SHOULDER.match(clean):
        return Command(kind="camera", value="over_shoulder", target=m.group(1) or m.group(2) or "", span=span)
    if (m := _FOLLOW.match(clean[:1].lower() + clean[1:])) and m.group(1).lower() not in (
        "the",
        "me",
        "him",
        "her",
    ):
        return Command(kind="camera", value="follow", target=m.group(1), span=span)
    if m := _CAMERA.match(clean):
        value = CAMERA_VALUES.get(m.group(1).lower())
        if value is None:
            return None
        target = m.group(2) or ""
        if target.lower() in ("the", "view", "shot", "angle"):
            target = ""
        elif target.lower().startswith("the "):  # "camera close on the teacher": the character "teacher"
            target = target[4:]
        return Command(kind="camera", value=value, target=target, span=span)
    if lower in SPEED_VALUES:
        return Command(kind="speed", value=SPEED_VALUES[lower], span=span)
    if m := _WAIT.match(lower):
        seconds = 1.0
        if m.group(1):
            n = _number(m.group(1))
            if n is None:
                return None
            unit = m.group(2) or "seconds"
            if unit not in UNIT_SECONDS:
                return None
            seconds = n * UNIT_SECONDS[unit]
        return Command(kind="wait", value="", seconds=seconds, span=span)
    if m := _WEATHER_SENTENCE.match(lower.replace("it's", "it 's")):
        return Command(kind="weather", value=WEATHER_VALUES[m.group(1)], span=span)
    if m := _LIGHTS.match(lower):
        value = WEATHER_VALUES.get(m.group(2) or "", "night" if m.group(1) in _LIGHTS_DOWN else "sunny")
        return Command(kind="weather", value=value, span=span)
    if m := _WEATHER.match(lower):
        value = WEATHER_VALUES.get(m.group(1))
        if value is not None:
            return Command(kind="weather", value=value, span=span)
    return None


def unknown_camera_detail(text: str) -> str:
    """The W104 detail of a line that starts like a camera command but names no known camera."""
    return f"'{text.strip()[:60]}'; the camera words are {KNOWN_CAMERA_WORDS}"


def looks_like_command(text: str) -> bool:
    """True when a line starts like a command (``camera ...``) even if its value is unknown (W104)."""
    return _clean(text).lower().startswith("camera")
