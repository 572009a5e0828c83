"""A scene may hold objects the asset catalog lacks (a wall button): planning walks and sits around them."""

from __future__ import annotations

import pytest

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.planning import plan_actions
from wana.domain.object_geometry import object_shape

BUTTON = PlacedObject(id="lift_button", category="elevator_button", position=(3.0, 1.1, 0.0), yaw=-1.57)


def test_getting_up_from_a_chair_beside_an_object_the_catalog_lacks_is_planned():
    with pytest.raises(KeyError):
        object_shape(BUTTON)  # the catalog has no such category
    scene = Scene(
        room=Room(room_type="office", width=8, depth=8, height=3),
        objects=[
            PlacedObject(id="desk", category="desk", position=(0.0, 0.0, 0.0), yaw=0.0),
            PlacedObject(id="chair", category="office_chair", position=(0.0, 0.0, 0.75), yaw=3.14159),
            BUTTON,
        ],
    )
    actions = [ActionNode(verb="sit", action="sit", target="chair"), ActionNode(verb="stand", action="stand")]
    plan = plan_actions(CharacterNode(name="c", actions=actions), scene, (1.5, 0.0, 1.5))
    assert [s.action for s in plan.segments][-1] == "stand"
