"""Hiding spots: beside a door with the back to its wall (not out in front of it, in full view), behind a
sofa standing free, beside it when its back is against a wall; two hiders get two spots; the planner walks
there before the hide clip."""

from __future__ import annotations

import numpy as np

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.planning import plan_actions
from wana.assets.catalog import object_to_world
from wana.domain.hiding import hiding_spots

ROOM = Room(room_type="office", width=5.0, depth=4.0, height=2.7)
DOOR = PlacedObject(id="door", category="door", position=(0.0, 0.0, -1.95), yaw=0.0)  # on the back wall
SOFA = PlacedObject(id="sofa", category="sofa", position=(0.5, 0.0, 0.3), yaw=0.0)


def _local(placed: PlacedObject, xz: tuple[float, float]) -> np.ndarray:
    m = object_to_world(placed)
    return np.linalg.inv(m[:3, :3]) @ (np.array([xz[0], 0.0, xz[1]]) - m[:3, 3])


def test_spots_by_a_door_are_beside_it_against_its_wall():
    spots = hiding_spots(DOOR, Scene(room=ROOM, objects=[DOOR]), need=2)
    assert len(spots) >= 2
    sides = {np.sign(_local(DOOR, s)[0]) for s in spots[:2]}
    assert sides == {-1.0, 1.0}  # one each side of the door
    for s in spots:
        local = _local(DOOR, s)
        assert 0.0 < local[2] < 0.45  # back to the wall, not out in the room in front of the door
        assert abs(local[0]) > 0.4  # past the door's edge


def test_behind_a_free_standing_sofa_first():
    (first, *_) = hiding_spots(SOFA, Scene(room=ROOM, objects=[SOFA]))
    assert _local(SOFA, first)[2] < -0.4


def test_hiding_behind_the_door_walks_beside_it_first():
    eve = CharacterNode(name="Eve", actions=[ActionNode(verb="hide", action="hide", target="door")])
    plan = plan_actions(eve, Scene(room=ROOM, objects=[DOOR]), (1.5, 1.0, 0.0))
    assert [s.kind for s in plan.segments][-1] == "action" and plan.segments[-1].action == "hide"
    walk = [s for s in plan.segments if s.kind == "locomotion"]
    assert walk, "Eve hides where she stood, 3 m in front of the door"
