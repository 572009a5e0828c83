"""Messages of the retrieval service: scene composition and action-to-clip retrieval.

ComposeRequest -> ComposeReply: the scene part of the SSG (objects, relations, room kind) becomes one
composed room of placed catalog objects, with the matching map of the paper's Algorithm 1 and a check
of every stated relation.

ActionMatchRequest -> ActionMatchReply: action words (verb, object, instrument, manner) become
template clips of the motion library, best first, each with a score.
"""

from __future__ import annotations

from typing import Literal

import msgspec

from proto.common import Header, Request, Status
from proto.scene import Scene
from proto.ssg import Diagnostic, ObjectNode, RelationNode

MatchKind = Literal["relation", "object", "none"]


class ComposeRequest(Request["ComposeReply"], frozen=True, kw_only=True, tag="compose_request"):
    """Compose one room from the scene sentences' objects and relations."""

    header: Header
    objects: list[ObjectNode] = []  # every scene object of the document, in document order
    relations: list[RelationNode] = []  # every stated relation, in document order
    room_type: str = ""  # "office", "working shop"; "" lets retrieval choose from the matches
    seed: int = 0  # composition seed; same request and seed -> same scene
    previous: Scene | None = None  # the last composed scene: unchanged objects keep their placements


class ObjectMatch(msgspec.Struct, frozen=True, kw_only=True):
    """One entry of the matching map: a query object and the scene-database object it matched."""

    object_id: str  # ObjectNode.id of the query
    scene_id: str = ""  # scene-database record id; "" when nothing matched
    db_object_id: str = ""  # ObjectNode.id inside that record
    db_category: str = ""
    score: float = 0.0  # 0..1 node similarity (category, attributes)
    via: MatchKind = "none"  # matched inside a relation subgraph, as a single node, or not at all


class RelationCheck(msgspec.Struct, frozen=True, kw_only=True):
    """A stated relation, whether the composed scene keeps it, and its matching score."""

    subject: str  # ObjectNode.id
    relation: str  # one of proto.ssg.RELATIONS
    object: str  # ObjectNode.id (the anchor)
    held: bool  # True when the relation holds geometrically in the composed scene
    match_score: float = 0.0  # 0..1: agreement with a scene-database relation between the matches


class ComposeReply(msgspec.Struct, frozen=True, kw_only=True, tag="compose_reply"):
    header: Header
    status: Status = "ok"
    scene: Scene
    matches: list[ObjectMatch] = []  # one per query object, in request order
    relations: list[RelationCheck] = []  # one per stated relation, in request order
    match_score: float = 0.0  # 0..1 score of the whole matching (paper Fig. 8)
    overlaps: int = 0  # object pairs whose collision boxes interpenetrate (target 0)
    diagnostics: list[Diagnostic] = []  # spans point at the sentence text of the concerned node


class ActionQuery(msgspec.Struct, frozen=True, kw_only=True):
    """Action words of one action node; object and instrument are catalog categories or words."""

    verb: str  # lemma, e.g. "sing"
    object: str = ""  # e.g. "piano" ("plays the piano")
    instrument: str = ""  # e.g. "microphone" ("with the microphone")
    manner: str = ""  # e.g. "slowly"


class ActionMatchRequest(Request["ActionMatchReply"], frozen=True, kw_only=True, tag="action_match_request"):
    header: Header
    queries: list[ActionQuery] = []
    top_k: int = 3  # clips returned per query, best first


class ClipMatch(msgspec.Struct, frozen=True, kw_only=True):
    clip: str  # action-library clip name, e.g. "sing_with_microphone"
    score: float  # 0..1
    matched_on: list[str] = []  # what agreed: "name", "synonym", "tag", "object", "instrument", "manner"


class ActionMatchResult(msgspec.Struct, frozen=True, kw_only=True):
    query: ActionQuery
    clips: list[ClipMatch] = []  # best first; empty when nothing fits (see diagnostic)
    diagnostic: str = ""  # why nothing (or only a weak clip) fits; "" when a clip fits well


class ActionMatchReply(msgspec.Struct, frozen=True, kw_only=True, tag="action_match_reply"):
    header: Header
    status: Status = "ok"
    results: list[ActionMatchResult] = []  # one per query, in request order
