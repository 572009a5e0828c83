"""The compute budget cuts a hostile story down to size, names what it cut, and the rest still animates."""

from __future__ import annotations

import time

import pytest

from proto.common import Header
from proto.motion_data import Motion
from proto.nlp import ParseRequest
from services.orchestrator.backend import InProcessBackend, StageFailed
from services.orchestrator.budget import BUDGET_CODE, Budget, Meter
from services.orchestrator.document import Document
from services.orchestrator.queries import QueryEngine
from services.orchestrator.session import Orchestrator
from wana.arrays import from_wire


def _diagnostics(result, sid: str) -> list[str]:
    return [d.message for d in result.diagnostics.get(sid, []) if d.code == BUDGET_CODE]


def _parse_only(text: str, budget: Budget):
    from services.orchestrator.pipeline import Pipeline

    doc = Document.from_text("d", text)
    result = Pipeline(InProcessBackend(), doc_id="d", budget=budget).run(
        doc, QueryEngine(), stages=("parse",)
    )
    return doc, result


@pytest.fixture(scope="module")
def orchestrator(tmp_path_factory):
    orch = Orchestrator(tmp_path_factory.mktemp("budget") / "s.db", InProcessBackend())
    yield orch
    orch.close()


def test_sentences_past_the_count_and_size_limits_are_cut_and_the_others_parsed():
    text = "Eve waves. " + "Eve " + "very " * 60 + "slowly sits. " + " ".join(["Tom waves."] * 6)
    doc, result = _parse_only(text, Budget(max_sentences=5, max_sentence_chars=100))
    ids = [s.id for s in doc.sentences]
    assert len(ids) == 8
    long_one, late = ids[1], ids[5:]
    assert set(result.cut) == {long_one, *late}
    assert "characters long" in _diagnostics(result, long_one)[0]
    assert all("only the first 5" in _diagnostics(result, sid)[0] for sid in late)
    assert [result.graphs[sid].kind for sid in (ids[0], *ids[2:5])] == ["action"] * 4
    assert all(result.graphs[sid].kind == "empty" for sid in result.cut)


def test_no_sentence_is_parsed_once_the_parse_share_of_the_time_budget_is_spent():
    doc, result = _parse_only("Eve waves. Tom sits.", Budget(max_seconds=1e-9))
    assert set(result.cut) == {s.id for s in doc.sentences}
    assert "ran out while parsing" in _diagnostics(result, doc.sentences[0].id)[0]


def test_a_call_after_the_deadline_fails_at_once_with_e006_naming_the_stage():
    meter = Meter(Budget(max_seconds=0.01))
    time.sleep(0.02)
    with pytest.raises(StageFailed) as err:
        meter.backend(InProcessBackend()).call(
            ParseRequest(header=Header(), sentence_id="s", text="Eve waves.")
        )
    assert err.value.code == "E006" and "nlp stage was cut" in str(err.value)


def test_waits_are_cut_to_one_wait_and_to_all_waits_together():
    from proto.ssg import Command, SentenceGraph

    meter = Meter(Budget(max_wait_s=60, max_duration_s=100))
    used = 0.0
    seconds = []
    for asked in (99999999.0, float("inf"), 30.0, float("nan"), -5.0, 2.0):
        graph = SentenceGraph(
            sentence_id="s", text="", kind="command", commands=[Command(kind="wait", value="", seconds=asked)]
        )
        graph, used, notes = meter.cut_waits(graph, used)
        seconds.append(graph.commands[0].seconds)
    assert seconds == [60.0, 40.0, 0.0, 0.0, 0.0, 0.0]


@pytest.mark.parametrize("bad", [0, -1, float("nan"), float("inf")])
def test_a_budget_that_is_not_a_positive_number_is_refused(bad):
    with pytest.raises(ValueError, match="max_seconds"):
        Budget(max_seconds=bad).check()


@pytest.mark.slow
def test_a_wait_of_a_hundred_million_seconds_animates_with_the_wait_cut(orchestrator):
    text = (
        "In the office there is a desk near a window$. A chair is in front of the desk$.\n"
        "Eve walks to the chair. wait 99999999 seconds. Eve sits on the chair."
    )
    started = time.monotonic()
    result = orchestrator.create(text).compute()
    assert time.monotonic() - started < 120
    assert not result.unavailable
    wait_id = next(s.id for s in result.sentences if "wait" in s.text)
    assert "cut to 60 s" in _diagnostics(result, wait_id)[0]
    motion: Motion = result.motions["Eve"]
    frames = from_wire(motion.root_position).shape[0]
    assert 60 * 30 <= frames < 120 * 30  # the 60 s wait is there, the hundred million seconds are not


def test_wana_animate_documents_and_reads_the_budget_options():
    from services.orchestrator.animate import budget_of, build_parser

    parser = build_parser()
    help_text = parser.format_help()
    for option in (
        "--max-seconds",
        "--max-sentences",
        "--max-sentence-chars",
        "--max-wait-s",
        "--max-duration-s",
    ):
        assert option in help_text
    args = parser.parse_args(["story.txt", "--max-seconds", "30", "--max-sentences", "12"])
    assert budget_of(args) == Budget(max_seconds=30, max_sentences=12)
    with pytest.raises(SystemExit, match="max_wait_s must be a positive number"):
        budget_of(parser.parse_args(["story.txt", "--max-wait-s", "0"]))


def test_the_gateway_reads_its_budget_from_the_environment(monkeypatch):
    from services.gateway.settings import Settings

    monkeypatch.setenv("WANA_MAX_SECONDS", "45")
    monkeypatch.setenv("WANA_MAX_SENTENCE_CHARS", "500")
    settings = Settings.from_env()
    assert settings.budget == Budget(max_seconds=45, max_sentence_chars=500)
    monkeypatch.setenv("WANA_MAX_SECONDS", "soon")
    with pytest.raises(ValueError, match="WANA_MAX_SECONDS must be a number"):
        Settings.from_env()
    with pytest.raises(ValueError, match="max_sentences"):
        Settings(max_sentences=0).check()
