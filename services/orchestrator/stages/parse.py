"""The parse stage: one `parse:<sentence id>` node per sentence, then `resolve` over all of them.

The sentences whose node must run are parsed together, up to `PARSE_BATCH` in one ParseBatchRequest (the
NLP service parses a batch through one spaCy `pipe`: about 1 ms a sentence against 2.4 ms one by one); the
memo stays per sentence, so an edit re-parses only the sentences it changed.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from functools import partial

from proto.common import Span
from proto.nlp import ParseBatchRequest, ParseRequest, ResolveRequest, SentenceInput
from proto.ssg import Diagnostic, SentenceGraph
from services.orchestrator.backend import StageFailed
from services.orchestrator.document import Sentence
from services.orchestrator.stages import StageContext

PARSE_BATCH = 64  # sentences in one request: the compute budget's parse clock is checked between batches


def parse_sentence(ctx: StageContext, sentence_id: str, text: str) -> SentenceGraph:
    """One sentence's graph (spans relative to the whitespace-normalised text), unresolved."""
    request = ParseRequest(header=ctx.header(), sentence_id=sentence_id, text=text, offset=0)
    return ctx.backend.call(request).graph


def parse_batch(ctx: StageContext, sentences: Sequence[Sentence]) -> dict[str, SentenceGraph]:
    """Sentence id -> graph of several sentences in one round trip; {} when the batch failed (each
    sentence is then parsed on its own, so that only the one the parser fails on fails)."""
    inputs = [SentenceInput(sentence_id=s.id, text=s.key_text, offset=0) for s in sentences]
    try:
        reply = ctx.backend.call(ParseBatchRequest(header=ctx.header(), sentences=inputs))
    except StageFailed:
        return {}
    return {s.id: g for s, g in zip(sentences, reply.graphs, strict=True)}


def _parsed(ctx: StageContext, ready: dict[str, SentenceGraph], sentence_id: str, text: str) -> SentenceGraph:
    """The batch's graph of a sentence, else its own parse."""
    graph = ready.pop(sentence_id, None)
    return graph if graph is not None else parse_sentence(ctx, sentence_id, text)


def parse_all(
    ctx: StageContext,
    sentences: Sequence[Sentence],
    tick: Callable[[str, int, int], None],
    time_left: Callable[[], bool] = lambda: True,
) -> list[SentenceGraph]:
    """The graphs of the sentences in order, stopping before the first sentence reached once `time_left()`
    is false (the result is then a prefix); a sentence the parser fails on gets an empty graph with the error.

    A failed parse is not memoised, so the next compute tries it again.
    """
    keys = [f"parse:{s.id}" for s in sentences]
    stale = [
        i for i, (k, s) in enumerate(zip(keys, sentences, strict=True)) if not ctx.engine.fresh(k, s.key_text)
    ]
    ready: dict[str, SentenceGraph] = {}
    batched = 0  # stale sentences sent so far (stale[:batched])
    out: list[SentenceGraph] = []
    for i, s in enumerate(sentences):
        if not time_left():
            break
        text = s.key_text
        if batched < len(stale) and stale[batched] <= i:
            tick("parse", i, len(sentences))
            chunk = [sentences[j] for j in stale[batched : batched + PARSE_BATCH]]
            batched += len(chunk)
            if len(chunk) > 1:
                ready.update(parse_batch(ctx, chunk))
        try:
            out.append(ctx.engine.query(keys[i], text, partial(_parsed, ctx, ready, s.id, text)))
        except StageFailed as exc:
            failed = Diagnostic(
                code=exc.code,
                message=f"this sentence could not be parsed: {exc}",
                span=Span(0, len(text)),
                severity="error",
            )
            out.append(SentenceGraph(sentence_id=s.id, text=text, kind="empty", diagnostics=[failed]))
    tick("parse", len(out), len(sentences))
    return out


def resolve(ctx: StageContext, graphs: list[SentenceGraph]) -> list[SentenceGraph]:
    """Names and pronouns resolved across the document (the `resolve` node, keyed by the parses' hashes)."""

    def run() -> list[SentenceGraph]:
        return list(ctx.backend.call(ResolveRequest(header=ctx.header(), graphs=graphs)).graphs)

    inputs = [ctx.engine.hash_of(f"parse:{g.sentence_id}", g) for g in graphs]
    return ctx.engine.query("resolve", inputs, run)
