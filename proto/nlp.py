"""Messages of the NLP service: sentence -> semantic scene graph fragment; document-level resolution.

Spans in the graphs are character offsets in the document (the request's ``offset`` is added).
See services/nlp/__init__.py for the contract.
"""

from __future__ import annotations

from typing import Literal

import msgspec

from proto.common import Header, Request, Status
from proto.ssg import SentenceGraph

KindHint = Literal["", "scene", "action", "command"]


class ParseRequest(Request["ParseReply"], frozen=True, kw_only=True, tag="parse_request"):
    """Parse one sentence (the orchestrator splits documents with services.nlp.segment.split_sentences)."""

    header: Header
    sentence_id: str
    text: str  # the sentence with its terminator ("$" marks a scene sentence)
    offset: int = 0  # characters: position of `text` in the document; spans are shifted by it
    kind_hint: KindHint = ""  # from the splitter; "" = decide from the text


class ParseReply(msgspec.Struct, frozen=True, kw_only=True, tag="parse_reply"):
    header: Header
    status: Status = "ok"
    graph: SentenceGraph  # unresolved: pronouns as written, imperatives without a character
    model_version: str = ""  # trained pipeline version (part of the idempotency key)


class SentenceInput(msgspec.Struct, frozen=True, kw_only=True):
    sentence_id: str
    text: str
    offset: int = 0  # characters, document coordinates
    kind_hint: KindHint = ""


class ParseBatchRequest(Request["ParseBatchReply"], frozen=True, kw_only=True, tag="parse_batch_request"):
    """Parse several sentences in one round trip (each as ParseRequest would)."""

    header: Header
    sentences: list[SentenceInput]


class ParseBatchReply(msgspec.Struct, frozen=True, kw_only=True, tag="parse_batch_reply"):
    header: Header
    status: Status = "ok"
    graphs: list[SentenceGraph]  # one per input sentence, same order
    model_version: str = ""


class ResolveRequest(Request["ResolveReply"], frozen=True, kw_only=True, tag="resolve_request"):
    """Resolve names and pronouns across a document's sentence graphs (cheap; rerun after any edit)."""

    header: Header
    graphs: list[SentenceGraph]  # in document order
    offsets: list[int] = []  # document offset of each sentence (exact spans for pronoun diagnostics)


class ResolveReply(msgspec.Struct, frozen=True, kw_only=True, tag="resolve_reply"):
    header: Header
    status: Status = "ok"
    graphs: list[SentenceGraph]  # same order; characters canonical, "they" expanded


class ParseDocumentRequest(
    Request["ParseDocumentReply"], frozen=True, kw_only=True, tag="parse_document_request"
):
    """Split + parse + resolve a whole text (what `wana parse` does)."""

    header: Header
    text: str


class SentenceSpan(msgspec.Struct, frozen=True, array_like=True):
    start: int  # characters, document coordinates
    end: int
    kind_hint: str


class ParseDocumentReply(msgspec.Struct, frozen=True, kw_only=True, tag="parse_document_reply"):
    header: Header
    status: Status = "ok"
    sentences: list[SentenceSpan]  # where each graph's sentence lies in the text
    graphs: list[SentenceGraph]  # resolved, one per sentence
    model_version: str = ""
