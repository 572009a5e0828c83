"""The optimizer worker on a real socket answers its contract (real broker, real worker process)."""

from __future__ import annotations

import msgpack
import msgspec
import numpy as np
import pytest

from proto.common import ErrorReply, Header
from proto.motion_data import Motion, Segment
from proto.optimizer import (
    ContactPair,
    CostRequest,
    Interaction,
    OptimiseRequest,
    OptimiseSettings,
)
from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.optimizer.handlers import CONTRACT
from tests.contract.harness import check_contract, service_fixture
from wana.arrays import to_wire
from wana.domain.skeleton import JOINT_NAMES, N_JOINTS

optimizer = service_fixture("optimizer", "wana.compose:optimizer_worker")  # as `wana worker optimizer`

ROOM = Room(room_type="office", width=5.0, depth=5.0, height=3.0)
DESK_SCENE = Scene(room=ROOM, objects=[PlacedObject(id="desk", category="desk", position=(0.0, 0.0, 0.0))])


def _standing(x: float, z: float, frames: int = 20) -> Motion:
    rot = np.zeros((frames, N_JOINTS, 4), dtype=np.float32)
    rot[..., 3] = 1.0
    root = np.tile(np.array([x, 0.95, z], dtype=np.float32), (frames, 1))
    return Motion(
        character="Eve",
        joint_names=list(JOINT_NAMES),
        root_position=to_wire(root),
        rotations=to_wire(rot),
        segments=[Segment(index=0, action="idle", start_frame=0, end_frame=frames)],
    )


@pytest.mark.contract
def test_cost_request_counts_the_desk_boxes_a_body_stands_in(optimizer):
    inside = CostRequest(
        header=Header(),
        scene=DESK_SCENE,
        motion=_standing(0.0, 0.0),
        interaction=Interaction(character="Eve", action="idle"),
    )
    clear = msgspec.structs.replace(inside, motion=_standing(1.5, 1.5))
    hit = check_contract(
        CONTRACT, inside, optimizer.request("optimizer", msgspec.msgpack.encode(inside))
    ).report
    miss = check_contract(
        CONTRACT, clear, optimizer.request("optimizer", msgspec.msgpack.encode(clear))
    ).report
    assert (
        hit.collided_boxes > 0
        and 0 < hit.collision_cost <= 1
        and hit.cost == pytest.approx(hit.collision_cost)
    )
    assert miss.collided_boxes == 0 and miss.cost == 0.0


@pytest.mark.contract
def test_optimise_request_moves_the_desk_off_the_body_and_returns_its_curve(optimizer):
    req = OptimiseRequest(
        header=Header(doc_id="doc", revision=5),
        scene=DESK_SCENE,
        motion=_standing(0.0, 0.42),
        interaction=Interaction(character="Eve", action="idle", movable=["desk"]),
        settings=OptimiseSettings(steps=60, seed=3),
    )
    raw = optimizer.request("optimizer", msgspec.msgpack.encode(req), deadline_s=120)
    reply = check_contract(CONTRACT, req, raw)
    assert reply.before.collided_boxes > 0
    assert reply.after.cost < reply.before.cost
    assert len(reply.cost_curve) == len(reply.best_curve) == reply.steps_run + 1 and reply.movable == ["desk"]
    # All 60 steps, or fewer because the search cost reached 0 (nothing could beat it after that).
    assert reply.steps_run == 60 or (reply.steps_run < 60 and reply.best_curve[-1] < 1e-4)
    assert reply.scene.objects[0].position != DESK_SCENE.objects[0].position
    assert reply.scene.objects[0].position[1] == 0.0 and reply.resynthesis == "anchored"
    again = check_contract(
        CONTRACT, req, optimizer.request("optimizer", msgspec.msgpack.encode(req), deadline_s=120)
    )
    assert again.scene == reply.scene and again.cost_curve == reply.cost_curve  # fixed seed, same answer


@pytest.mark.contract
def test_bad_requests_get_error_replies_and_the_worker_keeps_serving(optimizer):
    assert msgpack.unpackb(optimizer.request("optimizer", b"\x92garbage"))["code"] == "E001"
    bad = CostRequest(
        header=Header(),
        scene=DESK_SCENE,
        motion=_standing(0.0, 0.0),
        interaction=Interaction(character="Eve", action="sit", targets=["chair"]),
    )
    check_contract(
        CONTRACT,
        bad,
        optimizer.request("optimizer", msgspec.msgpack.encode(bad)),
        expect="error",
        code="E010",
    )
    wrong_point = msgspec.structs.replace(
        bad,
        interaction=Interaction(
            character="Eve",
            action="sit",
            targets=["desk"],
            contacts=[ContactPair(object_id="desk", point="nope")],
        ),
    )
    check_contract(
        CONTRACT,
        wrong_point,
        optimizer.request("optimizer", msgspec.msgpack.encode(wrong_point)),
        expect="error",
        code="E010",
    )
    hybrid = OptimiseRequest(
        header=Header(),
        scene=DESK_SCENE,
        motion=_standing(0.0, 0.0),
        interaction=Interaction(character="Eve", action="idle"),
        resynthesis="hybrid",
    )
    check_contract(
        CONTRACT,
        hybrid,
        optimizer.request("optimizer", msgspec.msgpack.encode(hybrid)),
        expect="error",
        code="E010",
    )
    ok = CostRequest(
        header=Header(),
        scene=DESK_SCENE,
        motion=_standing(2.0, 2.0),
        interaction=Interaction(character="Eve", action="idle"),
    )
    check_contract(CONTRACT, ok, optimizer.request("optimizer", msgspec.msgpack.encode(ok)))


def _motion_service_request() -> OptimiseRequest:
    """Eve walks to the chair; the desk may move; motion re-synthesised by the motion service."""
    scene = Scene(
        room=ROOM,
        objects=[
            PlacedObject(id="desk", category="desk", position=(0.0, 0.0, 0.0)),
            PlacedObject(id="chair", category="chair", position=(1.2, 0.0, 1.2)),
        ],
    )
    eve = CharacterNode(name="Eve", actions=[ActionNode(verb="walk", action="walk", destination="chair")])
    return OptimiseRequest(
        header=Header(doc_id="doc", revision=6),
        scene=scene,
        motion=_standing(-1.5, -1.5),
        interaction=Interaction(character="Eve", action="walk", movable=["desk"]),
        settings=OptimiseSettings(steps=2, proposals=1, seed=1),
        resynthesis="motion_service",
        character=eve,
        start=(-1.5, -1.5, 0.0),
    )


@pytest.mark.contract
def test_motion_service_resynthesis_runs_in_the_worker_through_the_composed_motion(optimizer):
    """The worker process re-synthesises with the motion service's code that `wana worker` wires in."""
    req = _motion_service_request()
    raw = optimizer.request("optimizer", msgspec.msgpack.encode(req), deadline_s=120)
    reply = check_contract(CONTRACT, req, raw)  # an ErrorReply here: the worker could not re-synthesise
    assert reply.resynthesis == "motion_service" and reply.steps_run == 2
    assert len(reply.cost_curve) == 3


@pytest.mark.contract
def test_a_worker_started_without_the_composition_root_answers_motion_service_with_an_error():
    """Started as services.optimizer.worker:main alone it has no motion synthesis, and says so."""
    from tests.contract.harness import running_service

    with running_service("optimizer") as bare:
        raw = bare.request("optimizer", msgspec.msgpack.encode(_motion_service_request()), deadline_s=60)
    reply = msgspec.msgpack.decode(raw, type=ErrorReply)
    assert reply.status == "error" and "wana worker optimizer" in reply.message
