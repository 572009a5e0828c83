"""The retrieval worker on a real socket answers its contract (and survives bad frames)."""

from __future__ import annotations

import msgpack
import msgspec
import pytest

from proto.common import Header
from proto.retrieval import ActionMatchRequest, ActionQuery, ComposeRequest
from proto.ssg import ObjectNode, RelationNode
from services.retrieval.handlers import CONTRACT
from tests.contract.harness import check_contract, service_fixture

retrieval = service_fixture("retrieval")

OBJECTS = [
    ObjectNode(id="desk", category="desk", word="desk"),
    ObjectNode(id="laptop", category="laptop", word="laptop"),
    ObjectNode(id="chair", category="office_chair", word="chair"),
]
RELATIONS = [
    RelationNode(subject="laptop", relation="on", object="desk"),
    RelationNode(subject="chair", relation="in_front_of", object="desk"),
]


def call(bus, request, **kw):
    raw = bus.request("retrieval", msgspec.msgpack.encode(request), deadline_s=60.0)
    return raw, check_contract(CONTRACT, request, raw, **kw)


@pytest.mark.contract
def test_compose_request_gets_a_scene_that_keeps_the_relations(retrieval):
    req = ComposeRequest(
        header=Header(doc_id="d1", revision=5),
        objects=OBJECTS,
        relations=RELATIONS,
        room_type="office",
        seed=2,
    )
    raw, reply = call(retrieval, req)
    assert reply.header.parent_id == req.header.msg_id and reply.header.revision == 5
    assert reply.scene.room.room_type == "office"
    assert [p.id for p in reply.scene.objects if p.from_text] == ["desk", "laptop", "chair"]
    assert [c.held for c in reply.relations] == [True, True] and reply.overlaps == 0
    assert [m.object_id for m in reply.matches] == ["desk", "laptop", "chair"]
    plain = msgpack.unpackb(raw)
    assert plain["type"] == "compose_reply" and plain["status"] == "ok"
    # The previous scene goes back in: nothing moves.
    again_req = ComposeRequest(
        header=Header(),
        objects=OBJECTS,
        relations=RELATIONS,
        room_type="office",
        seed=2,
        previous=reply.scene,
    )
    _, again = call(retrieval, again_req)
    assert again.scene == reply.scene


@pytest.mark.contract
def test_action_match_request_gets_clips_or_a_diagnostic(retrieval):
    req = ActionMatchRequest(
        header=Header(), queries=[ActionQuery(verb="sit", object="sofa"), ActionQuery(verb="xyzzy")], top_k=2
    )
    raw, reply = call(retrieval, req)
    sit, unknown = reply.results
    assert sit.query.verb == "sit" and len(sit.clips) <= 2
    assert unknown.clips == [] and "xyzzy" in unknown.diagnostic
    assert msgpack.unpackb(raw)["type"] == "action_match_reply"


@pytest.mark.contract
def test_refused_input_gets_an_e010_error_reply(retrieval):
    req = ActionMatchRequest(header=Header(), queries=[ActionQuery(verb="sit")], top_k=0)
    _, reply = call(retrieval, req, expect="error", code="E010")
    assert "top_k" in reply.message


@pytest.mark.contract
def test_garbage_gets_an_error_reply_and_the_worker_keeps_serving(retrieval):
    raw = retrieval.request("retrieval", b"\xc1 not msgpack")
    assert msgpack.unpackb(raw)["code"] == "E001"
    req = ActionMatchRequest(header=Header(), queries=[ActionQuery(verb="wave")])
    _, reply = call(retrieval, req)
    assert reply.status == "ok"
