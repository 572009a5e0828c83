"""The handlers called in-process (as the orchestrator's embedded default does)."""

from __future__ import annotations

import numpy as np
import pytest

from proto.common import Header
from proto.motion_data import Motion, Segment
from proto.optimizer import CostRequest, Interaction, OptimiseRequest, OptimiseSettings
from proto.scene import PlacedObject, Room, Scene
from services.optimizer.handlers import CONTRACT
from wana.arrays import to_wire
from wana.bus.service import InvalidInput, call_in_process
from wana.domain.skeleton import JOINT_NAMES, N_JOINTS

pytest.importorskip("wana.assets.catalog", reason="needs the asset catalog")

ROOM = Room(room_type="office", width=5.0, depth=5.0, height=3.0)
SCENE = Scene(room=ROOM, objects=[PlacedObject(id="desk", category="desk")])


def _standing(x: float, z: float) -> Motion:
    rot = np.zeros((10, N_JOINTS, 4), dtype=np.float32)
    rot[..., 3] = 1.0
    return Motion(
        character="Eve",
        joint_names=list(JOINT_NAMES),
        rotations=to_wire(rot),
        root_position=to_wire(np.tile(np.float32([x, 0.95, z]), (10, 1))),
        segments=[Segment(index=0, action="idle", start_frame=0, end_frame=10)],
    )


def test_reply_headers_answer_the_request():
    req = CostRequest(
        header=Header(doc_id="d", revision=4),
        scene=SCENE,
        motion=_standing(2.0, 2.0),
        interaction=Interaction(character="Eve", action="idle"),
    )
    reply = call_in_process(CONTRACT, req)
    assert (
        reply.header.parent_id == req.header.msg_id
        and reply.header.doc_id == "d"
        and reply.header.revision == 4
    )
    assert reply.report.collided_boxes == 0  # standing 2.8 m from the desk


def test_bad_input_is_refused_with_a_reason():
    with pytest.raises(InvalidInput, match="unique"):
        call_in_process(
            CONTRACT,
            CostRequest(
                header=Header(),
                scene=Scene(room=ROOM, objects=SCENE.objects * 2),
                motion=_standing(0, 0),
                interaction=Interaction(character="Eve", action="idle"),
            ),
        )
    with pytest.raises(InvalidInput, match="positive"):
        call_in_process(
            CONTRACT,
            CostRequest(
                header=Header(),
                scene=Scene(room=Room(room_type="x", width=0, depth=1, height=1)),
                motion=_standing(0, 0),
                interaction=Interaction(character="Eve", action="idle"),
            ),
        )
    with pytest.raises(InvalidInput, match="proposals"):
        call_in_process(
            CONTRACT,
            OptimiseRequest(
                header=Header(),
                scene=SCENE,
                motion=_standing(0, 0),
                interaction=Interaction(character="Eve", action="idle"),
                settings=OptimiseSettings(proposals=0),
            ),
        )


def test_a_budget_of_one_millisecond_still_returns_a_valid_answer():
    req = OptimiseRequest(
        header=Header(),
        scene=SCENE,
        motion=_standing(0.0, 0.4),
        interaction=Interaction(character="Eve", action="idle", movable=["desk"]),
        settings=OptimiseSettings(budget_s=0.001),
    )
    reply = call_in_process(CONTRACT, req)
    assert reply.steps_run < 100 and len(reply.cost_curve) == reply.steps_run + 1
    assert reply.after.cost <= reply.before.cost
