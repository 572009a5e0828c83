"""The motion worker on a real socket answers its contract."""

from __future__ import annotations

import msgpack
import msgspec
import pytest

from proto.common import Header
from proto.motion import SynthesizeRequest
from proto.scene import Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.handlers import CONTRACT
from tests.contract.harness import check_contract, service_fixture

motion = service_fixture("motion")


@pytest.mark.contract
def test_synthesize_request_gets_a_motion(motion):
    req = SynthesizeRequest(
        header=Header(doc_id="d", revision=3),
        scene=Scene(room=Room(room_type="office", width=5, depth=5, height=3)),
        character=CharacterNode(
            name="Tom", actions=[ActionNode(verb="walk", action="walk"), ActionNode(verb="bow", action="bow")]
        ),
    )
    raw = motion.request("motion", msgspec.msgpack.encode(req))
    reply = check_contract(CONTRACT, req, raw)
    assert reply.header.parent_id == req.header.msg_id and reply.header.revision == 3
    assert [s.action for s in reply.motion.segments] == ["walk", "bow"]
    assert msgpack.unpackb(raw)["status"] == "ok"


@pytest.mark.contract
def test_garbage_gets_an_error_reply_and_the_worker_keeps_serving(motion):
    raw = motion.request("motion", b"\x92garbage")
    assert msgpack.unpackb(raw)["code"] == "E001"
    idle = SynthesizeRequest(
        header=Header(),
        scene=Scene(room=Room(room_type="office", width=5, depth=5, height=3)),
        character=CharacterNode(name="Tom"),
    )
    ok = motion.request("motion", msgspec.msgpack.encode(idle))
    assert msgpack.unpackb(ok)["status"] == "ok"
