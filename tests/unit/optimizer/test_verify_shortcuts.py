"""The verifier runs the annealing only when its layouts would be tried: not for a layout that already
hits nothing and meets its contacts, nor when a reach layout verifies (real catalog, motion service)."""

from __future__ import annotations

import numpy as np
import pytest

from proto.optimizer import Interaction
from proto.scene import PlacedObject, Room, Scene
from services.optimizer.verify import CONTACT_OK_M, optimise_and_verify

ROOM = Room(room_type="office", width=4.71, depth=4.095, height=2.7)
PI = float(np.pi)
TYPE = Interaction(character="Eve", action="type", targets=["laptop"])


def _office(desk_z: float, laptop_z: float, chair_z: float = 0.7807) -> Scene:
    """The office example: a desk against the window wall, a laptop on it, a chair in front of it."""
    return Scene(
        room=ROOM,
        objects=[
            PlacedObject(
                id="desk", category="desk", seed=891, position=(-0.3017, 0.0, desk_z), yaw=-PI,
                scale=(1.0194, 1.0237, 1.0194),
            ),
            PlacedObject(
                id="laptop", category="laptop", seed=927, position=(-0.4484, 0.7406, laptop_z), yaw=-PI,
                support="desk",
            ),
            PlacedObject(
                id="chair", category="chair", seed=474, position=(-0.3942, 0.0, chair_z),
                scale=(0.9027, 0.9761, 0.9027),
            ),
        ],
    )  # fmt: skip


@pytest.fixture(scope="module")
def out_of_reach(typing_draft):
    """The desk pushed back to the wall (the walk to the chair needed it): the laptop is out of reach."""
    scene = _office(1.6955, 1.6862)
    return scene, optimise_and_verify(scene, TYPE, typing_draft(scene))


def test_a_laptop_out_of_reach_is_reached_with_no_box_hit_and_no_annealing(out_of_reach):
    scene, res = out_of_reach
    assert res.search.before.contact_cost > CONTACT_OK_M
    assert res.made == "motion_service" and res.scene != scene
    assert res.after.contact_cost <= CONTACT_OK_M and max(res.after.contact_distances[1:]) < CONTACT_OK_M
    assert res.after.collided_boxes == 0  # no leg inside the desk's drawer pedestal
    assert res.search.steps_run == 0 and res.search.cost_curve == [res.search.before.cost]


def test_a_layout_that_already_meets_both_criteria_comes_back_as_it_is_without_annealing(typing_draft):
    # The laptop at the desk's front edge and the chair pulled in: no box hit, every contact on its point.
    scene = _office(1.6955, 1.4843, chair_z=0.82)
    res = optimise_and_verify(scene, TYPE, typing_draft(scene))
    assert res.made == "input" and res.scene is scene and res.search.steps_run == 0
    assert res.after.collided_boxes == 0 and max(res.after.contact_distances) <= 0.01


def test_a_contact_missed_by_a_few_centimetres_is_still_optimised(typing_draft):
    # The same with the chair where the story put it: the hips slide 3 cm forward on the seat.
    scene = _office(1.6955, 1.4843)
    res = optimise_and_verify(scene, TYPE, typing_draft(scene))
    assert max(res.search.before.contact_distances) > 0.02
    assert res.search.steps_run > 0 or res.made == "motion_service"
