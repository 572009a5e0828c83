"""The parse stage: one `parse:<sentence id>` node per sentence, then `resolve` over all of them."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from functools import partial

from proto.common import Span
from proto.nlp import ParseRequest, ResolveRequest
from proto.ssg import Diagnostic, SentenceGraph
from services.orchestrator.backend import StageFailed
from services.orchestrator.document import Sentence
from services.orchestrator.stages import StageContext


def parse_sentence(ctx: StageContext, sentence_id: str, text: str) -> SentenceGraph:
    """One sentence's graph (spans relative to the whitespace-normalised text), unresolved."""
    request = ParseRequest(header=ctx.header(), sentence_id=sentence_id, text=text, offset=0)
    return ctx.backend.call(request).graph


def parse_all(
    ctx: StageContext, sentences: Sequence[Sentence], tick: Callable[[str, int, int], None]
) -> list[SentenceGraph]:
    """Every sentence's graph, in order; a sentence the parser fails on gets an empty graph with the error.

    A failed parse is not memoised, so the next compute tries it again.
    """
    out: list[SentenceGraph] = []
    for i, s in enumerate(sentences):
        tick("parse", i, len(sentences))
        text = s.key_text
        try:
            out.append(ctx.engine.query(f"parse:{s.id}", text, partial(parse_sentence, ctx, s.id, text)))
        except StageFailed as exc:
            failed = Diagnostic(
                code=exc.code,
                message=f"this sentence could not be parsed: {exc}",
                span=Span(0, len(text)),
                severity="error",
            )
            out.append(SentenceGraph(sentence_id=s.id, text=text, kind="empty", diagnostics=[failed]))
    tick("parse", len(sentences), len(sentences))
    return out


def resolve(ctx: StageContext, graphs: list[SentenceGraph]) -> list[SentenceGraph]:
    """Names and pronouns resolved across the document (the `resolve` node, keyed by the parses' hashes)."""

    def run() -> list[SentenceGraph]:
        return list(ctx.backend.call(ResolveRequest(header=ctx.header(), graphs=graphs)).graphs)

    inputs = [ctx.engine.hash_of(f"parse:{g.sentence_id}", g) for g in graphs]
    return ctx.engine.query("resolve", inputs, run)
