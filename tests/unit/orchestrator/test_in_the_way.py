"""Which standing characters a walk goes round (slotting.in_the_way -> SynthesizeRequest.bodies)."""

from __future__ import annotations

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode
from services.orchestrator.slotting import in_the_way

ROOM = Room(room_type="office", width=8, depth=8, height=3)
PETE = (0.0, 0.0)


def test_only_the_characters_near_a_walk_to_an_object_are_in_its_way():
    scene = Scene(room=ROOM, objects=[PlacedObject(id="desk", category="desk", position=(3.0, 0.0, 0.0))])
    walk = ActionNode(verb="walk", action="walk", destination="desk")
    standing = {"Pete": PETE, "Ann": (0.0, 3.5)}
    assert in_the_way(scene, walk, (-3.0, 0.0), standing) == [PETE]
    assert in_the_way(scene, ActionNode(verb="wave", action="wave"), (-3.0, 0.0), standing) == []
