"""Pure request -> reply handlers of the NLP service (no zmq); the orchestrator may call them in-process."""

from __future__ import annotations

from proto.common import reply_header
from proto.nlp import (
    ParseBatchReply,
    ParseBatchRequest,
    ParseDocumentReply,
    ParseDocumentRequest,
    ParseReply,
    ParseRequest,
    ResolveReply,
    ResolveRequest,
    SentenceSpan,
)
from services.nlp.parse import parse_document_with_spans, parse_sentence, parse_sentences
from services.nlp.pipeline import MODEL_VERSION
from services.nlp.resolve import resolve
from wana.bus.service import Contract, InvalidInput

MAX_SENTENCE_CHARS = 100_000  # a longer "sentence" is refused; up to this it is parsed (its start) with W108
MAX_DOCUMENT_CHARS = 1_000_000
MAX_BATCH = 2_000


def _check_sentence(text: str, offset: int) -> None:
    if offset < 0:
        raise InvalidInput(f"offset must be >= 0, got {offset}")
    if len(text) > MAX_SENTENCE_CHARS:
        raise InvalidInput(
            f"sentence of {len(text)} characters; split documents with services.nlp.segment first "
            f"(limit {MAX_SENTENCE_CHARS})"
        )


def handle_parse(req: ParseRequest) -> ParseReply:
    """One sentence -> its unresolved SentenceGraph."""
    _check_sentence(req.text, req.offset)
    graph = parse_sentence(req.text, req.sentence_id, req.offset, req.kind_hint)
    return ParseReply(header=reply_header(req), graph=graph, model_version=MODEL_VERSION)


def handle_parse_batch(req: ParseBatchRequest) -> ParseBatchReply:
    """Several sentences -> their graphs, in order."""
    if len(req.sentences) > MAX_BATCH:
        raise InvalidInput(f"{len(req.sentences)} sentences in one batch (limit {MAX_BATCH})")
    for s in req.sentences:
        _check_sentence(s.text, s.offset)
    graphs = parse_sentences([(s.text, s.sentence_id, s.offset, s.kind_hint) for s in req.sentences])
    return ParseBatchReply(header=reply_header(req), graphs=graphs, model_version=MODEL_VERSION)


def handle_resolve(req: ResolveRequest) -> ResolveReply:
    """Resolve names and pronouns across the graphs of a document."""
    if req.offsets and len(req.offsets) != len(req.graphs):
        raise InvalidInput(f"{len(req.offsets)} offsets for {len(req.graphs)} graphs")
    return ResolveReply(header=reply_header(req), graphs=resolve(list(req.graphs), list(req.offsets) or None))


def handle_parse_document(req: ParseDocumentRequest) -> ParseDocumentReply:
    """Split, parse and resolve a whole text."""
    if len(req.text) > MAX_DOCUMENT_CHARS:
        raise InvalidInput(f"document of {len(req.text)} characters (limit {MAX_DOCUMENT_CHARS})")
    pieces, graphs = parse_document_with_spans(req.text)
    return ParseDocumentReply(
        header=reply_header(req),
        sentences=[SentenceSpan(s, e, k) for s, e, k in pieces],
        graphs=graphs,
        model_version=MODEL_VERSION,
    )


CONTRACT: Contract = {
    ParseRequest: handle_parse,
    ParseBatchRequest: handle_parse_batch,
    ResolveRequest: handle_resolve,
    ParseDocumentRequest: handle_parse_document,
}
