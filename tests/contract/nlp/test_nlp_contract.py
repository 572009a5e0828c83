"""The NLP worker on a real socket answers its contract (and survives bad frames)."""

from __future__ import annotations

import msgpack
import msgspec
import pytest

from proto.common import Header
from proto.nlp import ParseBatchRequest, ParseDocumentRequest, ParseRequest, ResolveRequest, SentenceInput
from services.nlp.handlers import CONTRACT
from tests.contract.harness import check_contract, service_fixture

nlp = service_fixture("nlp")


def call(bus, request, **kw):
    raw = bus.request("nlp", msgspec.msgpack.encode(request))
    return raw, check_contract(CONTRACT, request, raw, **kw)


@pytest.mark.contract
def test_parse_request_gets_a_scene_graph_with_document_spans(nlp):
    text = "A laptop is on the desk$."
    req = ParseRequest(header=Header(doc_id="d1", revision=4), sentence_id="s7", text=text, offset=50)
    raw, reply = call(nlp, req)
    assert reply.header.revision == 4 and reply.graph.sentence_id == "s7" and reply.graph.kind == "scene"
    assert {(r.subject, r.relation, r.object) for r in reply.graph.relations} == {("laptop", "on", "desk")}
    laptop = next(o for o in reply.graph.objects if o.id == "laptop")
    assert (laptop.span.start, laptop.span.end) == (50, 58)  # "A laptop" in document coordinates
    plain = msgpack.unpackb(raw)
    assert plain["type"] == "parse_reply" and plain["status"] == "ok"


@pytest.mark.contract
def test_batch_then_resolve_names_the_pronoun(nlp):
    sentences = [
        SentenceInput(sentence_id="a", text="Tom walks to the chair.", offset=0),
        SentenceInput(sentence_id="b", text="He sits on it.", offset=24),
    ]
    _, batch = call(nlp, ParseBatchRequest(header=Header(), sentences=sentences))
    assert [g.sentence_id for g in batch.graphs] == ["a", "b"]
    assert batch.graphs[1].characters[0].name == ""  # unresolved until the document-level pass
    _, resolved = call(nlp, ResolveRequest(header=Header(), graphs=batch.graphs, offsets=[0, 24]))
    (he,) = resolved.graphs[1].characters
    assert he.name == "Tom" and he.actions[0].action == "sit" and he.actions[0].target == "chair"


@pytest.mark.contract
def test_a_batch_answers_each_sentence_as_its_own_parse_request_would(nlp):
    """What the orchestrator's parse stage relies on when it batches a first compute and memoises per sentence."""
    texts = [
        "In the office there is a desk$.",
        "Eve walks to the desk.",
        "camera left",
        "Eve walks to the desk.",
    ]
    sentences = [SentenceInput(sentence_id=f"s{i}", text=t, offset=0) for i, t in enumerate(texts)]
    _, batch = call(nlp, ParseBatchRequest(header=Header(doc_id="d", revision=2), sentences=sentences))
    assert batch.header.revision == 2 and batch.model_version
    singles = [
        call(nlp, ParseRequest(header=Header(), sentence_id=s.sentence_id, text=s.text, offset=0))[1].graph
        for s in sentences
    ]
    assert list(batch.graphs) == singles
    assert [g.kind for g in batch.graphs] == ["scene", "action", "command", "action"]


@pytest.mark.contract
def test_parse_document_returns_one_graph_per_sentence(nlp):
    text = "There is a desk near a window$.\ncamera left\nEve walks to the desk."
    _, reply = call(nlp, ParseDocumentRequest(header=Header(), text=text))
    assert [g.kind for g in reply.graphs] == ["scene", "command", "action"]
    assert [text[s.start : s.end] for s in reply.sentences][1] == "camera left"
    assert reply.graphs[1].commands[0].value == "left"


@pytest.mark.contract
def test_garbage_input_is_a_diagnostic_not_a_crash(nlp):
    garbage = "\x00\x01\x02\xff\xfe" * 40
    _, reply = call(nlp, ParseRequest(header=Header(), sentence_id="g", text=garbage))
    assert [d.code for d in reply.graph.diagnostics] == ["E110"]


@pytest.mark.contract
def test_bad_frames_and_bad_input_get_error_replies_and_the_worker_keeps_serving(nlp):
    req = ParseRequest(header=Header(), sentence_id="x", text="Eve sits.")
    raw = nlp.request("nlp", b"\x93not a request")
    check_contract(CONTRACT, req, raw, expect="error", code="E001")
    bad = ParseRequest(header=Header(), sentence_id="x", text="Eve sits.", offset=-5)
    call(nlp, bad, expect="error", code="E010")
    mismatch = ResolveRequest(header=Header(), graphs=[], offsets=[1, 2])
    call(nlp, mismatch, expect="error", code="E010")
    _, ok = call(nlp, req)
    assert ok.graph.characters[0].name == "Eve"
