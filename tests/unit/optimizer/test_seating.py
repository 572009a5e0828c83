"""Seated interactions: the seat is found under a seated draft, joins the interaction, and the
optimiser brings the work within reach of the seat (real catalog, real motion service)."""

from __future__ import annotations

import numpy as np
import pytest

from proto.optimizer import Interaction
from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode
from services.motion.seated import seated_action_fn
from services.optimizer.body import motion_joint_positions
from services.optimizer.costs import LayoutBatch, SceneGeometry, contact_points_world
from services.optimizer.layout_model import LayoutModel
from services.optimizer.seating import seat_under, seated_interaction
from services.optimizer.verify import optimise_and_verify
from wana.domain.skeleton import JOINT_INDEX

ROOM = Room(room_type="office", width=5.0, depth=5.0, height=3.0)
TYPE = Interaction(character="Eve", action="type", targets=["laptop"])


def _office(chair_z: float, laptop_z: float = -1.0) -> Scene:
    """A desk at z = -0.9 (facing +z), a laptop on it, an office chair facing the desk at chair_z."""
    return Scene(
        room=ROOM,
        objects=[
            PlacedObject(id="desk", category="desk", position=(0.0, 0.0, -0.9)),
            PlacedObject(id="chair", category="office_chair", position=(0.0, 0.0, chair_z), yaw=float(np.pi)),
            PlacedObject(id="laptop", category="laptop", position=(0.0, 0.75, laptop_z), support="desk"),
        ],
    )


@pytest.fixture(scope="module")
def far(typing_draft):
    scene = _office(0.1)
    return scene, typing_draft(scene)


def test_the_seat_under_a_seated_draft_is_found_even_after_it_moved(far):
    scene, draft = far
    geom = SceneGeometry.from_scene(scene)
    assert seat_under(scene, draft, TYPE, geom).object_id == "chair"
    moved = _office(0.1 - 0.3)  # the chair moved 30 cm since the draft was made
    assert seat_under(moved, draft, TYPE, SceneGeometry.from_scene(moved)).object_id == "chair"
    inter = seated_interaction(TYPE, seat_under(scene, draft, TYPE, geom), geom)
    assert inter.targets == ["chair", "laptop"]
    assert [(p.object_id, p.joint) for p in inter.contacts] == [
        ("chair", "Hips"),
        ("laptop", "RightHandMiddle1"),
        ("laptop", "LeftHandMiddle1"),
    ]


def test_a_standing_draft_has_no_seat():
    scene = _office(0.1)
    full = seated_action_fn("Eve", "chair", ActionNode(verb="type", action="type", target="laptop"))(scene)
    assert seat_under(scene, full, TYPE, SceneGeometry.from_scene(scene)) is None  # it sits down first


def test_a_laptop_may_slide_on_its_desk_but_not_off_it():
    model = LayoutModel(_office(0.1), ["laptop"])
    states = np.repeat(model.identity()[None], 3, axis=0)
    states[1, 0, 1] = 0.2  # toward the desk's front edge: still on it
    states[2, 0, 1] = 0.6  # past the edge
    assert model.on_supports(model.layouts(states)).tolist() == [True, True, False]


@pytest.mark.slow
def test_optimising_a_seated_typing_draft_brings_the_keys_within_reach_of_the_seat(far):
    scene, draft = far
    res = optimise_and_verify(scene, TYPE, draft)
    assert res.made == "motion_service"
    positions = motion_joint_positions(res.motion)
    geom = SceneGeometry.from_scene(res.scene)
    typing = next(s for s in res.motion.segments if s.action == "type")
    for joint in ("RightHandMiddle1", "LeftHandMiddle1"):
        keys = contact_points_world(
            geom,
            LayoutBatch.from_scenes([res.scene]),
            np.array([geom.contact_index("laptop", "type", joint)]),
        )[0, 0]
        hand = positions[typing.start_frame : typing.end_frame, JOINT_INDEX[joint]]
        assert np.median(np.linalg.norm(hand - keys, axis=1)) < 0.05, joint
    model = LayoutModel(res.scene, [])
    assert model.on_supports(LayoutBatch.from_scenes([res.scene]))[0]
    assert max(res.after.contact_distances) < max(res.search.before.contact_distances)
