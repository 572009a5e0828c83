"""Place commands and captions on frames, from the document's sentences and the motions' segments.

A sentence's actions start at the earliest ``Segment.start_frame`` that carries its id. A command
sentence ("camera left", "night") takes effect where the next sentence with motion starts (or, at
the end of the story, where the last earlier motion ends). A camera command without a target
follows the character of the closest earlier action sentence (the "current" character); ``close``
and ``follow`` the character of the next one (what the command cuts to), when there is one.

The inputs are accepted in the shapes the orchestrator has at hand: motions as a list or a
name -> Motion dict; commands as ``Command``, ``(sentence_id, Command)`` or ``TimedCommand``;
sentences as objects with ``id``/``sentence_id`` and ``text`` attributes, dicts, ``(id, text)``
pairs or plain strings.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from proto.motion_data import Motion
from proto.render import Caption, TimedCommand
from proto.ssg import Command
from services.render.camera import CAMERA_MODES, CameraKey
from services.render.weather import WEATHERS, WeatherKey

MIN_FRAMES = 30  # a scene without motion still gets one second of video
COMMAND_HOLD_FRAMES = 45  # the last command stays on screen at least 1.5 s (the final pose is held)


@dataclass(frozen=True)
class SentenceRef:
    id: str
    text: str


def as_motion_list(motions: Iterable[Motion] | Mapping[str, Motion] | None) -> list[Motion]:
    if motions is None:
        return []
    if isinstance(motions, Mapping):
        return [motions[k] for k in sorted(motions)]
    return list(motions)


def as_sentences(sentences: Iterable[Any] | None) -> list[SentenceRef]:
    out: list[SentenceRef] = []
    for i, s in enumerate(sentences or []):
        if isinstance(s, str):
            out.append(SentenceRef(id=f"s{i}", text=s))
        elif isinstance(s, tuple) and len(s) == 2:
            out.append(SentenceRef(id=str(s[0]), text=str(s[1])))
        elif isinstance(s, Mapping):
            out.append(
                SentenceRef(id=str(s.get("id", s.get("sentence_id", f"s{i}"))), text=str(s.get("text", "")))
            )
        else:
            sid = getattr(s, "id", None) or getattr(s, "sentence_id", None) or f"s{i}"
            out.append(SentenceRef(id=str(sid), text=str(getattr(s, "text", ""))))
    return out


def n_frames_of(motions: list[Motion]) -> int:
    from wana.arrays import from_wire

    longest = max((from_wire(m.root_position).shape[0] for m in motions), default=0)
    return longest if longest > 0 else MIN_FRAMES


def video_frames(motions: list[Motion], commands: Iterable[TimedCommand] = ()) -> int:
    """The video's length: the longest motion, held on its final pose until the last camera or weather
    command has been in force for COMMAND_HOLD_FRAMES (a command at the end of a story lands on the last
    motion frame and would otherwise never be seen)."""
    n = n_frames_of(motions)
    starts = [max(0, tc.frame) for tc in commands if tc.command.kind in ("camera", "weather")]
    return max(n, max(starts) + COMMAND_HOLD_FRAMES) if starts else n


def _sentence_spans(motions: list[Motion]) -> dict[str, tuple[int, int, str]]:
    """sentence id -> (first start frame, last end frame, character of the first segment)."""
    spans: dict[str, tuple[int, int, str]] = {}
    for m in motions:
        for seg in m.segments:
            if not seg.sentence_id:
                continue
            old = spans.get(seg.sentence_id)
            if old is None:
                spans[seg.sentence_id] = (seg.start_frame, seg.end_frame, m.character)
            else:
                first = (seg.start_frame, m.character) if seg.start_frame < old[0] else (old[0], old[2])
                spans[seg.sentence_id] = (first[0], max(old[1], seg.end_frame), first[1])
    return spans


def character_named(said: str, names: Sequence[str]) -> str:
    """The character a command's subject means, as the motions name it: "camera close on Mom" is the
    character "mom", "follow Okafor" is "Professor Okafor" when no one else is called so; ``said`` itself
    when no character or more than one matches."""
    if said in names:
        return said
    low = said.lower().removeprefix("the ")
    same = [n for n in names if n.lower() == low]
    if len(same) == 1:
        return same[0]
    words = low.split()
    part = [n for n in names if (w := n.lower().split())[-len(words) :] == words or w[: len(words)] == words]
    return part[0] if len(part) == 1 else said


def place_commands(
    commands: Iterable[Any] | None,
    sentences: Iterable[Any] | None,
    motions: Iterable[Motion] | Mapping[str, Motion] | None,
) -> list[TimedCommand]:
    """Camera and weather commands with the frame each takes effect, in frame order (stable).

    Camera commands without a target get the current character filled in.
    """
    mlist = as_motion_list(motions)
    sents = as_sentences(sentences)
    order = {s.id: i for i, s in enumerate(sents)}
    spans = _sentence_spans(mlist)
    default_char = mlist[0].character if mlist else ""
    names = [m.character for m in mlist]
    out: list[tuple[int, int, TimedCommand]] = []
    for n, item in enumerate(commands or []):
        if isinstance(item, TimedCommand):
            out.append((item.frame, n, item))
            continue
        sid, cmd = (str(item[0]), item[1]) if isinstance(item, tuple) else ("", item)
        if not isinstance(cmd, Command) or cmd.kind not in ("camera", "weather"):
            continue
        frame, current = 0, default_char
        pos = order.get(sid)
        if pos is not None:
            later = [spans[s.id] for s in sents[pos + 1 :] if s.id in spans]
            earlier = [spans[s.id] for s in sents[:pos] if s.id in spans]
            if later:
                frame = later[0][0]
            elif earlier:
                frame = max(e[1] for e in earlier)
            if earlier:
                current = earlier[-1][2]
            elif later:
                current = later[0][2]
            if (
                later
                and cmd.kind == "camera"
                and MODE_ALIASES.get(cmd.value, cmd.value) in ("close", "follow")
            ):
                current = later[0][2]  # a close-up or a follow is on who acts next (the scene it cuts to)
        if cmd.kind == "camera" and cmd.target and (who := character_named(cmd.target, names)) != cmd.target:
            cmd = Command(kind=cmd.kind, value=cmd.value, seconds=cmd.seconds, target=who, span=cmd.span)
        implied = cmd.kind == "camera" and not cmd.target and bool(current)
        if implied:
            cmd = Command(kind=cmd.kind, value=cmd.value, seconds=cmd.seconds, target=current, span=cmd.span)
        out.append(
            (frame, n, TimedCommand(frame=frame, command=cmd, sentence_id=sid, implied_target=implied))
        )
    out.sort(key=lambda t: (t[0], t[1]))
    return [t[2] for t in out]


def make_captions(
    sentences: Iterable[Any] | None, motions: Iterable[Motion] | Mapping[str, Motion] | None
) -> list[Caption]:
    """One caption per sentence that has motion, over the frames of its segments."""
    spans = _sentence_spans(as_motion_list(motions))
    caps = [
        Caption(start_frame=spans[s.id][0], end_frame=spans[s.id][1], text=s.text.strip(), sentence_id=s.id)
        for s in as_sentences(sentences)
        if s.id in spans and s.text.strip()
    ]
    return sorted(caps, key=lambda c: c.start_frame)


def caption_at(captions: list[Caption], frame: int) -> str:
    """The caption of the latest-starting sentence that covers the frame ("" when none)."""
    best: Caption | None = None
    for c in captions:
        if c.start_frame <= frame < c.end_frame and (best is None or c.start_frame >= best.start_frame):
            best = c
    return best.text if best else ""


COMMAND_MODES = ("front", "back", "left", "right", "top", "wide", "close", "follow", "over_shoulder")
MODE_ALIASES = {
    "closeup": "close",
    "close-up": "close",
    "close_up": "close",
    "overview": "wide",
    "establishing": "wide",
    "over-the-shoulder": "over_shoulder",
    "over_the_shoulder": "over_shoulder",
    "shoulder": "over_shoulder",
    "ots": "over_shoulder",
}


def camera_mode(value: str) -> str:
    """The camera mode a command's value names ("close-up" -> "close").

    Raises:
        ValueError: a word that names no camera the render service has (the message lists them).
    """
    mode = MODE_ALIASES.get(value, value)
    if mode not in COMMAND_MODES or mode not in CAMERA_MODES:
        raise ValueError(f"unknown camera command {value!r}; choose one of {', '.join(COMMAND_MODES)}")
    return mode


def camera_keys(commands: list[TimedCommand]) -> list[CameraKey]:
    """The commands' own keys (no director): each from its frame until the next."""
    keys = []
    for tc in commands:
        c = tc.command
        if c.kind == "camera":
            keys.append(CameraKey(frame=max(0, tc.frame), mode=camera_mode(c.value), character=c.target))
    return sorted(keys, key=lambda k: k.frame)


def weather_keys(commands: list[TimedCommand]) -> list[WeatherKey]:
    keys = []
    for tc in commands:
        c = tc.command
        if c.kind == "weather":
            if c.value not in WEATHERS:
                raise ValueError(f"unknown weather {c.value!r}; choose one of {', '.join(WEATHERS)}")
            keys.append(WeatherKey(frame=max(0, tc.frame), weather=c.value))
    return sorted(keys, key=lambda k: k.frame)


def chunk_ranges(n_frames: int, n_chunks: int) -> list[tuple[int, int]]:
    """Split [0, n_frames) into n_chunks contiguous ranges of near-equal length (empty ones dropped)."""
    if n_frames < 0 or n_chunks < 1:
        raise ValueError("n_frames must be >= 0 and n_chunks >= 1")
    edges = np.linspace(0, n_frames, n_chunks + 1).round().astype(int)
    return [(int(a), int(b)) for a, b in zip(edges[:-1], edges[1:], strict=True) if b > a]
