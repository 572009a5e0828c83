"""The semantic scene graph (SSG), after Zhang et al., Write-An-Animation (PG 2021).

Object nodes with category and attributes; relation nodes between two objects; character
nodes with ordered action nodes; commands; per-sentence diagnostics with character spans.
"""

from __future__ import annotations

from typing import Literal

import msgspec

from proto.common import Span

# Relations the NLP stage emits and the retrieval stage keeps true.
RELATIONS = (
    "on",
    "near",
    "in_front_of",
    "behind",
    "left_of",
    "right_of",
    "under",
    "above",
    "next_to",
    "facing",
    "in",
    "around",
    "hanging_above",
)

SentenceKind = Literal["scene", "action", "command", "empty"]
Severity = Literal["error", "warning", "info"]


class Diagnostic(msgspec.Struct, frozen=True, kw_only=True):
    code: str  # e.g. "W101 unknown object word"; codes listed in services/nlp/errors.py
    message: str
    span: Span  # characters in the document text
    severity: Severity = "warning"


class ObjectNode(msgspec.Struct, frozen=True, kw_only=True):
    id: str  # unique in the document, e.g. "desk" or "chair#2"
    category: str  # catalog category, e.g. "office_chair"
    word: str  # the word(s) the user wrote, e.g. "modernchair"
    attributes: dict[str, str] = {}  # colour, material, style, size, state -> value
    count: int = 1  # "two chairs" -> 2
    span: Span = Span(0, 0)


class RelationNode(msgspec.Struct, frozen=True, kw_only=True):
    subject: str  # ObjectNode.id
    relation: str  # one of RELATIONS
    object: str  # ObjectNode.id (the anchor)
    span: Span = Span(0, 0)
    each: bool = False  # "a chair at each desk": one subject per copy of a counted anchor, copy k at anchor k


class ActionNode(msgspec.Struct, frozen=True, kw_only=True):
    verb: str  # lemma as written, e.g. "sit"
    action: str  # action-library name, e.g. "sit" or "call_with_phone"; "" when unknown
    manner: str = ""  # "slowly", "madly"
    target: str = ""  # ObjectNode.id or character name the action is aimed at
    instrument: str = ""  # ObjectNode.id used as instrument ("with the microphone")
    destination: str = ""  # ObjectNode.id or place word ("to the house")
    duration_s: float = 0.0  # 0 = the clip's natural length
    span: Span = Span(0, 0)


class CharacterNode(msgspec.Struct, frozen=True, kw_only=True):
    name: str  # canonical name ("Eve"); pronouns already resolved when resolved=True
    actions: list[ActionNode] = []
    mention: str = ""  # what the sentence said ("He", "Eve")


class SocialNode(msgspec.Struct, frozen=True, kw_only=True):
    """A relation or emotion between characters: "They are friends", "Tom apologizes to Mary"."""

    kind: Literal["relation", "emotion"]
    subjects: list[str]  # character names
    label: str  # "friends", "boss", "angry", ...
    span: Span = Span(0, 0)


class Command(msgspec.Struct, frozen=True, kw_only=True):
    kind: Literal["camera", "weather", "wait", "speed"]
    value: str  # camera: front|back|left|right|top|follow|close; weather: sunny|night|rainy|foggy|snowy;
    # speed: faster|slower; wait: "" (see seconds)
    seconds: float = 0.0  # wait duration
    target: str = ""  # character a camera command refers to, "" = current
    span: Span = Span(0, 0)


class SentenceGraph(msgspec.Struct, frozen=True, kw_only=True):
    """The SSG fragment of one sentence."""

    sentence_id: str
    text: str
    kind: SentenceKind
    objects: list[ObjectNode] = []
    relations: list[RelationNode] = []
    characters: list[CharacterNode] = []
    social: list[SocialNode] = []
    commands: list[Command] = []
    diagnostics: list[Diagnostic] = []
    room_type: str = ""  # "office", "working shop" when the sentence names a kind of room
