"""A walk to "a chair" of several goes to one the walker can reach (services/orchestrator/slotting.py)."""

from __future__ import annotations

import math

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode
from services.orchestrator.slotting import Slotting

ROOM = Room(room_type="meeting_room", width=4, depth=4, height=3)
WALK = ActionNode(verb="walk", action="walk", target="chair")


def _room_split_by_a_table() -> Scene:
    """A table from wall to wall, the first chair on its far side, the second on the walker's."""
    return Scene(
        room=ROOM,
        objects=[
            PlacedObject(
                id="table", category="dining_table", position=(0.0, 0.0, 0.0), scale=(3.0, 1.0, 1.0)
            ),
            PlacedObject(id="chair", category="chair", position=(0.0, 0.0, -1.3)),
            PlacedObject(id="chair/2", category="chair", position=(0.8, 0.0, 1.3), yaw=math.pi),
            PlacedObject(id="chair/3", category="chair", position=(-0.8, 0.0, 1.3), yaw=math.pi),
        ],
    )


def test_a_walk_to_a_chair_across_a_table_with_no_way_round_goes_to_the_nearest_one_on_this_side():
    claim = Slotting(_room_split_by_a_table()).claim("Ann", WALK, here=(-1.0, 1.7))
    assert claim.action.target == "chair/3"


def test_a_chair_that_can_be_walked_to_is_the_one_named():
    claim = Slotting(_room_split_by_a_table()).claim("Ann", WALK, here=(0.5, -1.7))
    assert claim.action.target == "chair"
    named = ActionNode(verb="walk", action="walk", target="chair/2")  # a copy named by its id stays
    assert Slotting(_room_split_by_a_table()).claim("Ann", named, here=(0.5, -1.7)).action.target == "chair/2"
