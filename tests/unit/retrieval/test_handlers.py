"""The handlers called in-process, as the orchestrator's embedded default does."""

from __future__ import annotations

import pytest

from proto.common import Header
from proto.retrieval import ActionMatchReply, ActionMatchRequest, ActionQuery, ComposeReply, ComposeRequest
from proto.ssg import ObjectNode, RelationNode
from services.retrieval.handlers import CONTRACT
from wana.bus.service import InvalidInput, call_in_process


def test_compose_reply_answers_the_request_header():
    req = ComposeRequest(
        header=Header(doc_id="doc", revision=2),
        objects=[
            ObjectNode(id="sofa", category="sofa", word="couch"),
            ObjectNode(id="tv", category="television", word="tv"),
        ],
        relations=[RelationNode(subject="sofa", relation="facing", object="tv")],
    )
    reply = call_in_process(CONTRACT, req)
    assert isinstance(reply, ComposeReply)
    assert reply.header.parent_id == req.header.msg_id and reply.header.doc_id == "doc"
    assert reply.relations[0].held and reply.overlaps == 0


def test_refused_requests_raise_invalid_input():
    with pytest.raises(InvalidInput):
        call_in_process(
            CONTRACT, ActionMatchRequest(header=Header(), queries=[ActionQuery(verb="sit")], top_k=0)
        )
    many = [ObjectNode(id=f"o{i}", category="chair", word="chair") for i in range(201)]
    with pytest.raises(InvalidInput):
        call_in_process(CONTRACT, ComposeRequest(header=Header(), objects=many))


def test_action_match_returns_one_result_per_query():
    reply = call_in_process(
        CONTRACT,
        ActionMatchRequest(header=Header(), queries=[ActionQuery(verb="wave"), ActionQuery(verb="qwerty")]),
    )
    assert isinstance(reply, ActionMatchReply)
    assert [r.query.verb for r in reply.results] == ["wave", "qwerty"]
    assert reply.results[1].clips == [] and reply.results[1].diagnostic
