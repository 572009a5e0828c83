"""Per-document compute budgets: how much time and how much story one compute may spend.

A hostile (or just enormous) story must not hold a worker for ever: "wait 99999999 seconds", 10,000
sentences or one sentence of a megabyte each finish within a bounded time. What goes over a budget is cut,
a W501 diagnostic on the sentence names what was cut and which budget (and the option that raises it),
and the rest of the document still animates.

- ``max_sentences``: sentences after the first N are not parsed nor animated.
- ``max_sentence_chars``: a longer sentence is not parsed (a parser's cost grows with its length).
- ``max_wait_s`` / ``max_duration_s``: each ``wait`` is cut to the former, and all of them together to
  the latter, so that the time line (frames held in memory, the video) stays bounded.
- ``max_seconds``: the wall time of one compute. Sentences are parsed only during the first half of it
  (the rest is not parsed and so not animated); a service call after the whole of it fails with E006,
  which names the stage it cut.

The budget is applied in services/orchestrator/pipeline.py; `wana animate --max-seconds ...` and the
gateway's WANA_MAX_* settings set it.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import TypeVar

import msgspec

from proto.common import ErrorCode, Request, Span
from proto.ssg import Command, Diagnostic, SentenceGraph
from services.orchestrator.backend import Backend, StageFailed
from services.orchestrator.document import Sentence
from services.orchestrator.registry import service_of

R = TypeVar("R")

BUDGET_CODE = "W501"  # proto.common.ERROR_CODES: over the document's compute budget, this part was cut
PARSE_SHARE = 0.5  # share of max_seconds the parse stage may use before the remaining sentences are cut


@dataclass(frozen=True)
class Budget:
    """What one compute of one document may spend. Defaults fit any story a person writes by hand."""

    max_seconds: float = 600.0  # wall time of one compute
    max_sentences: int = 1000  # the social plan works window by window (services/social/windows.py)
    max_sentence_chars: int = 2000
    max_wait_s: float = 60.0  # one `wait` command
    max_duration_s: float = 600.0  # all `wait` commands of the document together

    def check(self) -> None:
        """Raises ValueError for a budget that is not a positive number."""
        for name in ("max_seconds", "max_sentences", "max_sentence_chars", "max_wait_s", "max_duration_s"):
            value = getattr(self, name)
            if not (isinstance(value, int | float) and math.isfinite(value) and value > 0):
                raise ValueError(f"{name} must be a positive number, not {value!r}")


def over_budget(message: str, span: Span) -> Diagnostic:
    return Diagnostic(code=BUDGET_CODE, message=message, span=span, severity="warning")


@dataclass
class Meter:
    """One compute's spending against a Budget: the clock, and the backend that stops at the deadline."""

    budget: Budget
    started: float = field(default_factory=time.monotonic)

    def elapsed(self) -> float:
        return time.monotonic() - self.started

    def parse_time_left(self) -> bool:
        return self.elapsed() < self.budget.max_seconds * PARSE_SHARE

    def sentences_to_parse(self, sentences: list[Sentence]) -> dict[str, str]:
        """Sentence id -> why it is cut before parsing (too many sentences, too long a sentence)."""
        b = self.budget
        cut: dict[str, str] = {}
        for i, s in enumerate(sentences):
            if i >= b.max_sentences:
                cut[s.id] = (
                    f"the document has {len(sentences)} sentences; only the first {b.max_sentences} are "
                    f"animated (compute budget: --max-sentences / WANA_MAX_SENTENCES)"
                )
            elif len(s.key_text) > b.max_sentence_chars:
                cut[s.id] = (
                    f"this sentence is {len(s.key_text)} characters long; sentences over "
                    f"{b.max_sentence_chars} are not animated "
                    f"(compute budget: --max-sentence-chars / WANA_MAX_SENTENCE_CHARS)"
                )
        return cut

    def out_of_parse_time(self) -> str:
        return (
            f"the compute budget of {self.budget.max_seconds:g} s ran out while parsing: this sentence "
            f"and those after it are not animated (--max-seconds / WANA_MAX_SECONDS)"
        )

    def cut_waits(self, graph: SentenceGraph, used_s: float) -> tuple[SentenceGraph, float, list[str]]:
        """The graph with its `wait` commands cut to the budget; the wait seconds used so far after it and
        a message per cut."""
        b = self.budget
        commands: list[Command] = []
        notes: list[str] = []
        for c in graph.commands:
            if c.kind == "wait":
                asked = 0.0 if math.isnan(c.seconds) else c.seconds
                seconds = min(max(asked, 0.0), b.max_wait_s, max(b.max_duration_s - used_s, 0.0))
                if seconds != c.seconds:
                    why = (
                        f"wait {asked:.10g} s is cut to {seconds:.10g} s (compute budget: at most "
                        f"{b.max_wait_s:g} s a wait, --max-wait-s, and {b.max_duration_s:g} s of waits "
                        f"in all, --max-duration-s)"
                    )
                    notes.append(why)
                    c = msgspec.structs.replace(c, seconds=seconds)
                used_s += seconds
            commands.append(c)
        if notes:
            graph = msgspec.structs.replace(graph, commands=commands)
        return graph, used_s, notes

    def backend(self, backend: Backend) -> Backend:
        return MeteredBackend(backend, self)


class MeteredBackend:
    """A backend whose calls after the compute budget's deadline fail at once with E006."""

    def __init__(self, backend: Backend, meter: Meter) -> None:
        self.inner = backend
        self.meter = meter

    def call(self, request: Request[R]) -> R:
        if self.meter.elapsed() >= self.meter.budget.max_seconds:
            service = service_of(type(request))
            raise StageFailed(
                service,
                ErrorCode.DEADLINE,
                f"the compute budget of {self.meter.budget.max_seconds:g} s is spent, so the {service} "
                f"stage was cut (--max-seconds / WANA_MAX_SECONDS)",
            )
        return self.inner.call(request)
