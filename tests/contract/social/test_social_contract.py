"""The social worker on a real socket answers its contract (real broker, real worker process)."""

from __future__ import annotations

import msgpack
import msgspec
import numpy as np
import pytest

from proto.common import Header
from proto.motion_data import Segment
from proto.social import ExpressionTrackRequest, SocialPlanRequest
from services.social.handlers import CONTRACT
from services.social.sketch import sketch_graphs
from tests.contract.harness import check_contract, service_fixture
from wana.arrays import from_wire
from wana.assets.characters import EXPRESSIONS

social = service_fixture("social")

STORY = (
    "rel Mary Tom boss; emo Tom nervous; act Mary criticize Tom; act Tom apologize Mary; act Mary shake_head"
)


@pytest.mark.contract
def test_social_plan_request_gets_a_plan_with_faces_distances_and_timing(social):
    req = SocialPlanRequest(header=Header(doc_id="doc", revision=4), graphs=sketch_graphs(STORY), seed=1)
    raw = social.request("social", msgspec.msgpack.encode(req))
    reply = check_contract(CONTRACT, req, raw)
    plan = reply.plan
    assert reply.header.revision == 4 and msgpack.unpackb(raw)["type"] == "social_plan_reply"
    assert [c.name for c in plan.characters] == ["Mary", "Tom"]
    assert {(p.character, p.relation) for p in plan.pairs} == {("Mary", "boss"), ("Tom", "employee")}
    assert any(r.responder == "Tom" and r.response_index == 0 for r in plan.responses)
    assert plan.energy_final < plan.energy_initial and plan.seed == 1
    assert plan.expression_names == list(EXPRESSIONS)


@pytest.mark.contract
def test_expression_track_request_gets_a_face_track(social):
    plan = check_contract(
        CONTRACT,
        r := SocialPlanRequest(header=Header(), graphs=sketch_graphs(STORY)),
        social.request("social", msgspec.msgpack.encode(r)),
    ).plan
    segments = [Segment(index=0, action="apologize", start_frame=30, end_frame=130, action_index=0)]
    req = ExpressionTrackRequest(header=Header(), plan=plan, character="Tom", segments=segments, frames=150)
    reply = check_contract(CONTRACT, req, social.request("social", msgspec.msgpack.encode(req)))
    track = from_wire(reply.expression)
    assert track.shape == (150, len(EXPRESSIONS)) and track.dtype == np.float32
    assert 0.0 <= track.min() and track.max() <= 1.0


@pytest.mark.contract
def test_bad_input_gets_an_invalid_input_error_and_the_worker_keeps_serving(social):
    req = ExpressionTrackRequest(
        header=Header(),
        plan=check_contract(
            CONTRACT,
            r := SocialPlanRequest(header=Header(), graphs=sketch_graphs("act Tom wave Mary")),
            social.request("social", msgspec.msgpack.encode(r)),
        ).plan,
        character="Nobody",
        segments=[],
    )
    err = check_contract(
        CONTRACT, req, social.request("social", msgspec.msgpack.encode(req)), expect="error", code="E010"
    )
    assert "Nobody" in err.message
    many = "; ".join(f"act P{i} wave P{i + 1}" for i in range(9))
    req2 = SocialPlanRequest(header=Header(), graphs=sketch_graphs(many))
    check_contract(
        CONTRACT, req2, social.request("social", msgspec.msgpack.encode(req2)), expect="error", code="E010"
    )
    garbage = social.request("social", b"\x93not a request")
    assert msgpack.unpackb(garbage)["code"] == "E001"
    ok = SocialPlanRequest(header=Header(), graphs=sketch_graphs("act Tom hug Mary"))
    assert check_contract(CONTRACT, ok, social.request("social", msgspec.msgpack.encode(ok))).plan.proposals
