"""Annealing proposals stay inside the room and do not push objects into each other."""

import numpy as np

from proto.scene import PlacedObject, Room, Scene
from services.optimizer.annealing import LayoutModel

ROOM = Room(room_type="office", width=4.0, depth=4.0, height=2.7)


def model() -> LayoutModel:
    scene = Scene(
        room=ROOM,
        objects=[
            PlacedObject(id="desk", category="desk", position=(1.2, 0.0, 0.0)),
            PlacedObject(id="chair", category="chair", position=(-0.5, 0.0, 0.0)),
        ],
    )
    return LayoutModel(scene, ["desk", "chair"])


def test_a_proposal_that_pushes_an_object_through_a_wall_is_refused():
    m = model()
    states = np.repeat(m.identity()[None], 3, axis=0)
    states[1, 0, 0] = 1.0  # desk 1 m further +x: past the wall at x = 2
    states[2, 0, 0] = 0.05  # a small nudge stays inside
    assert m.inside_room(m.layouts(states)).tolist() == [True, False, True]


def test_a_proposal_that_pushes_one_object_into_another_is_refused():
    m = model()
    states = np.repeat(m.identity()[None], 2, axis=0)
    states[1, 1, 0] = 1.6  # chair moved onto the desk
    assert m.no_new_overlaps(m.layouts(states)).tolist() == [True, False]
