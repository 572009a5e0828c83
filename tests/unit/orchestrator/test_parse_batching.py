"""The parse stage sends the sentences that need parsing in batches, and keeps a memo per sentence."""

from __future__ import annotations

from typing import Any

from proto.nlp import ParseBatchRequest, ParseRequest
from services.orchestrator.backend import InProcessBackend
from services.orchestrator.budget import Budget
from services.orchestrator.document import Document, TextChange
from services.orchestrator.pipeline import Pipeline
from services.orchestrator.queries import QueryEngine
from services.orchestrator.stages.parse import PARSE_BATCH

TEXT = (
    "In the office there is a desk$. A chair is near the desk$. Eve walks to the chair. Eve sits. Tom waves."
)


class Recording(InProcessBackend):
    """The in-process backend, writing down the parse requests it answers (how many sentences each)."""

    def __init__(self) -> None:
        self.parses: list[tuple[str, int]] = []

    def call(self, request: Any) -> Any:
        if isinstance(request, ParseBatchRequest):
            self.parses.append(("batch", len(request.sentences)))
        elif isinstance(request, ParseRequest):
            self.parses.append(("single", 1))
        return super().call(request)


def _parse(backend: InProcessBackend, doc: Document, engine: QueryEngine, budget: Budget | None = None):
    return Pipeline(backend, doc_id="d", budget=budget).run(doc, engine, stages=("parse",))


def test_a_first_parse_is_one_batch_and_an_edit_parses_only_the_changed_sentence():
    backend, engine = Recording(), QueryEngine()
    doc = Document.from_text("d", TEXT)
    engine.new_revision()
    first = _parse(backend, doc, engine)
    assert backend.parses == [("batch", 5)]
    assert [first.graphs[s.id].kind for s in doc.sentences] == [
        "scene",
        "scene",
        "action",
        "action",
        "action",
    ]
    # the graphs are those a sentence parsed on its own gets
    alone = _parse(InProcessBackend(), doc, QueryEngine())
    assert first.graphs == alone.graphs

    backend.parses.clear()
    at = doc.text.index("sits")
    changed = doc.apply(doc.version, [TextChange(start=at, end=at + 4, text="waves")])
    assert changed == [doc.sentences[3].id]
    engine.new_revision()
    again = _parse(backend, doc, engine)
    assert backend.parses == [("single", 1)]
    assert [k for k in again.ran if k.startswith("parse:")] == [f"parse:{doc.sentences[3].id}"]


def test_a_long_document_goes_in_bounded_batches():
    backend = Recording()
    n = PARSE_BATCH + 3
    doc = Document.from_text("d", " ".join(f"Eve waves {i} times." for i in range(n)))
    _parse(backend, doc, QueryEngine())
    assert backend.parses == [("batch", PARSE_BATCH), ("batch", 3)]


def test_a_sentence_the_service_refuses_fails_alone_and_the_rest_of_its_batch_is_parsed():
    from services.nlp.handlers import MAX_SENTENCE_CHARS

    backend = Recording()
    huge = "Eve " + "very " * (MAX_SENTENCE_CHARS // 5 + 1) + "slowly sits."
    doc = Document.from_text("d", f"Tom waves. {huge} Ann nods.")
    result = _parse(backend, doc, QueryEngine(), Budget(max_sentence_chars=10 * MAX_SENTENCE_CHARS))
    assert backend.parses == [("batch", 3), ("single", 1), ("single", 1), ("single", 1)]
    kinds = [result.graphs[s.id].kind for s in doc.sentences]
    assert kinds == ["action", "empty", "action"]
    assert "could not be parsed" in result.graphs[doc.sentences[1].id].diagnostics[0].message
