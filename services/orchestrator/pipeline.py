"""The incremental pipeline over one document: parse -> resolve -> scene -> social -> optimise -> motion.

Query nodes (DESIGN §3), each keyed by the content hash of its inputs (what it reads: views.py):
- `parse:<sentence id>`   the sentence's whitespace-normalised text  -> its SSG fragment (sentence offsets)
- `resolve`               the parse results in order                 -> names and pronouns resolved
- `scene`                 every scene sentence's objects + relations -> the composed room
- `social`                characters, actions and social nodes       -> faces, distances, response timing
- `draft:<name>:<k>`      actions, layout before optimising action k -> the motion the optimiser starts from
- `optimise:<name>:<k>`   layout, draft motion, action k             -> layout (+ motion) around action k
- `segment:<name>:<k>`    action k, the final layout, end state k-1  -> frames of action k + its end state
- `face:<name>`           the social plan, every character's timing  -> the character's face track
Each stage is a module of services/orchestrator/stages/. A stage whose service this process may not reach
(StageUnavailable, e.g. a gateway started with --services) or that fails is named in `unavailable`, with
an E011 diagnostic on the first sentence; nothing is faked.
The document's compute budget (services/orchestrator/budget.py) cuts what is over it before the stages
see it: sentences past the count or size limits and those the parse time did not reach get an empty graph
and a W501 diagnostic, waits are shortened; after the time budget, service calls fail with E006.
"""

from __future__ import annotations

from collections.abc import Callable

import msgspec

from proto.common import ErrorCode, Span
from proto.social import SocialPlan
from proto.ssg import Diagnostic, SentenceGraph
from services.orchestrator.backend import Backend, StageFailed, StageUnavailable
from services.orchestrator.budget import Budget, Meter, over_budget
from services.orchestrator.document import Document, Sentence
from services.orchestrator.queries import QueryEngine
from services.orchestrator.result import PipelineResult, SentenceView
from services.orchestrator.stages import StageContext
from services.orchestrator.stages.motion import animate
from services.orchestrator.stages.parse import parse_all, resolve
from services.orchestrator.stages.scene import scene
from services.orchestrator.stages.social import faces, social_plan
from services.orchestrator.views import map_span
from wana.blas import single_threaded

__all__ = ["STAGES", "Pipeline", "PipelineResult", "SentenceView"]

STAGES = ("parse", "scene", "motion")

Progress = Callable[[str, int, int], None]  # (stage, done, total)


def _shift(span: Span, by: int) -> Span:
    return Span(span.start + by, span.end + by)


def _stage_diag(stage: str, why: str, span: Span) -> Diagnostic:
    message = f"the {stage} stage is not available yet: {why}"
    return Diagnostic(code=ErrorCode.UNAVAILABLE, message=message, span=span, severity="info")


class Pipeline:
    def __init__(
        self, backend: Backend, *, doc_id: str = "", seed: int = 0, budget: Budget | None = None
    ) -> None:
        self.backend = backend
        self.doc_id = doc_id
        self.seed = seed
        self.budget = budget or Budget()
        single_threaded()  # the services' small products: one BLAS thread (wana/blas.py)

    def run(
        self,
        doc: Document,
        engine: QueryEngine,
        *,
        stages: tuple[str, ...] | None = None,
        progress: Progress | None = None,
    ) -> PipelineResult:
        stages = stages or STAGES
        result = PipelineResult(doc_id=doc.doc_id, version=doc.version)
        tick: Progress = progress or (lambda stage, done, total: None)
        sentences = list(doc.sentences)
        meter = Meter(self.budget)
        ctx = StageContext(meter.backend(self.backend), engine, self.doc_id, doc.version, self.seed)
        cut = meter.sentences_to_parse(sentences)

        try:
            ordered = self._parse(ctx, meter, sentences, cut, tick)
            # Only the sentences within the budget go on: the later stages never see the cut ones.
            kept = [i for i, s in enumerate(sentences) if s.id not in cut]
            resolved = list(ordered)
            try:
                for i, g in zip(kept, resolve(ctx, [ordered[i] for i in kept]), strict=True):
                    resolved[i] = g
            except StageFailed as exc:
                result.unavailable["resolve"] = str(exc)
        except StageUnavailable as exc:
            result.unavailable["parse"] = str(exc)
            self._finish(result, engine, sentences)
            return result
        resolved = self._cut_waits(meter, resolved, cut)
        live_graphs = [resolved[i] for i in kept]
        live_sentences = [sentences[i] for i in kept]
        result.cut = cut
        # Spans from the parser are relative to the whitespace-normalised sentence text; map them back.
        for s, g in zip(sentences, resolved, strict=True):
            result.graphs[s.id] = g
            result.sentences.append(SentenceView(s.id, s.start, s.end, s.text, g.kind))
            result.diagnostics[s.id] = [
                msgspec.structs.replace(d, span=_shift(map_span(d.span, s.text), s.start))
                for d in g.diagnostics
            ]
            result.commands.extend((s.id, c) for c in g.commands)

        if "scene" in stages:
            try:
                tick("scene", 0, 1)
                result.scene, result.scene_report = scene(ctx, live_graphs)
                tick("scene", 1, 1)
            except (StageUnavailable, StageFailed) as exc:
                result.unavailable["scene"] = str(exc)

        if "motion" in stages and result.scene is not None:
            try:
                self._motion(ctx, result, live_graphs, live_sentences, tick)
            except (StageUnavailable, StageFailed) as exc:
                result.unavailable["motion"] = str(exc)
        self._finish(result, engine, sentences)
        return result

    @staticmethod
    def _parse(
        ctx: StageContext,
        meter: Meter,
        sentences: list[Sentence],
        cut: dict[str, str],
        tick: Progress,
    ) -> list[SentenceGraph]:
        """Every sentence's graph in order: parsed while the parse time lasts, else an empty graph whose
        W501 says why it was cut (recorded in ``cut``)."""
        todo = [s for s in sentences if s.id not in cut]
        tick("parse", 0, len(todo))
        parsed = parse_all(ctx, todo, tick, meter.parse_time_left)  # batched; stops when the time is up
        graphs = {s.id: g for s, g in zip(todo, parsed, strict=False)}
        for late in todo[len(parsed) :]:
            cut[late.id] = meter.out_of_parse_time()
        for s in sentences:
            if s.id in cut:
                why = over_budget(cut[s.id], Span(0, len(s.key_text)))
                graphs[s.id] = SentenceGraph(sentence_id=s.id, text="", kind="empty", diagnostics=[why])
        return [graphs[s.id] for s in sentences]

    @staticmethod
    def _cut_waits(meter: Meter, graphs: list[SentenceGraph], cut: dict[str, str]) -> list[SentenceGraph]:
        """The graphs with their waits cut to the budget, each cut named by a W501 on its sentence."""
        out, used = [], 0.0
        for g in graphs:
            g, used, notes = meter.cut_waits(g, used)
            if notes:
                span = Span(0, len(g.text))
                g = msgspec.structs.replace(
                    g, diagnostics=[*g.diagnostics, *(over_budget(n, span) for n in notes)]
                )
                cut.setdefault(g.sentence_id, "; ".join(notes))
            out.append(g)
        return out

    def _motion(
        self,
        ctx: StageContext,
        result: PipelineResult,
        resolved: list[SentenceGraph],
        sentences: list[Sentence],
        tick: Progress,
    ) -> None:
        assert result.scene is not None
        plan: SocialPlan | None = None
        try:
            plan = social_plan(ctx, resolved)
        except (StageUnavailable, StageFailed) as exc:
            result.unavailable["social"] = str(exc)
        done = animate(ctx, result.scene, resolved, sentences, result.commands, plan, tick)
        result.scene = done.scene
        result.motions = done.motions
        result.optimisations = done.optimisations
        for sid, diagnostic in done.diagnostics:
            result.diagnostics.setdefault(sid, []).append(diagnostic)
        if plan is not None:
            try:
                result.motions = faces(ctx, plan, result.motions)
            except (StageUnavailable, StageFailed) as exc:
                result.unavailable["social"] = str(exc)

    def _finish(self, result: PipelineResult, engine: QueryEngine, sentences: list[Sentence]) -> None:
        result.ran = engine.ran()
        result.reused = engine.reused()
        if sentences and result.unavailable:
            span = Span(sentences[0].start, sentences[0].end)
            first = sentences[0].id
            for stage, why in result.unavailable.items():
                result.diagnostics.setdefault(first, []).append(_stage_diag(stage, why, span))
