"""Props a seated character's action uses, put within its reach on the table it sits at (stages/reach.py):
the bottle at the far end of the dining table comes to the pourer's place with a glass to pour into, a
laptop across the table comes in front of the typist facing it, and what was in reach or used before
stays where it is."""

from __future__ import annotations

import numpy as np

from proto.motion import SegmentEndState
from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode, RelationNode
from services.orchestrator.stages.reach import within_reach
from wana.assets.catalog import world_support_surfaces

ROOM = Room(room_type="dining_room", width=6, depth=6, height=3)
TABLE = PlacedObject(id="dining_table", category="dining_table", position=(0.0, 0.0, 0.0), yaw=0.0)
TOP = max(h for h, _ in world_support_surfaces(TABLE))


def _on_table(id_: str, category: str, x: float, z: float) -> PlacedObject:
    return PlacedObject(id=id_, category=category, position=(x, TOP, z), support="dining_table")


# John sits at the table's -z side, facing +z (his position: SEAT_BACK in front of the hips, at his knees)
JOHN = SegmentEndState(x=0.0, z=-0.75, yaw=0.0, posture="sit")


def _run(scene: Scene, *actions: ActionNode, state: SegmentEndState = JOHN, stated=()):
    characters = {
        "John": (
            CharacterNode(name="John", actions=list(actions)),
            [f"s{k + 1}" for k in range(len(actions))],
        )
    }
    order = [("John", k) for k in range(len(actions))]
    return within_reach(scene, characters, order, [{"John": state}] * len(actions), stated)


def _dist(o: PlacedObject, state: SegmentEndState = JOHN) -> float:
    return float(np.hypot(o.position[0] - state.x, o.position[2] - state.z))


def test_the_bottle_at_the_far_end_comes_to_the_seated_pourer_with_a_glass_to_pour_into():
    bottle = _on_table("bottle", "bottle", 0.6, 0.35)
    glass = _on_table("glass", "glass", -0.5, 0.3)
    scene = Scene(room=ROOM, objects=[TABLE, bottle, glass])
    pour = ActionNode(verb="pour", action="pour", target="glass", destination="glass")
    out, notes = _run(
        scene, pour, stated=[RelationNode(subject="bottle", relation="on", object="dining_table")]
    )
    moved = {o.id: o for o in out.objects}
    assert (
        _dist(bottle) > 0.9 and _dist(moved["bottle"]) <= 0.9
    )  # out of reach before, in the arm's reach now
    assert _dist(moved["glass"]) <= 0.7  # and a glass to pour into at his place
    assert moved["bottle"].support == moved["glass"].support == "dining_table"
    assert abs(moved["bottle"].position[1] - TOP) < 1e-3
    gap = np.hypot(
        moved["bottle"].position[0] - moved["glass"].position[0],
        moved["bottle"].position[2] - moved["glass"].position[2],
    )
    assert gap > 0.05  # side by side, not one in the other
    assert [sid for sid, _ in notes] == ["s1", "s1"] and "bottle" in notes[0][1] and "John" in notes[0][1]


def test_a_laptop_across_the_table_comes_in_front_of_the_typist_facing_it():
    laptop = _on_table("laptop", "laptop", 0.3, 0.35)
    out, notes = _run(
        Scene(room=ROOM, objects=[TABLE, laptop]), ActionNode(verb="type", action="type", target="laptop")
    )
    moved = next(o for o in out.objects if o.id == "laptop")
    ahead = np.array([JOHN.x, JOHN.z + 0.25])
    assert np.hypot(moved.position[0] - ahead[0], moved.position[2] - ahead[1]) <= 0.4
    assert abs(np.cos(moved.yaw - np.pi)) > 0.99  # its front (+z) towards John, who faces +z
    assert len(notes) == 1


def test_what_is_in_reach_standing_or_used_before_stays_where_it_is():
    near = _on_table("bottle", "bottle", 0.1, -0.3)  # in reach of his place
    scene = Scene(room=ROOM, objects=[TABLE, near])
    pour = ActionNode(verb="pour", action="pour", target="bottle")
    assert _run(scene, pour) == (scene, [])
    far = _on_table("bottle", "bottle", 0.6, 0.35)
    scene = Scene(room=ROOM, objects=[TABLE, far])
    standing = SegmentEndState(x=0.0, z=-0.75, yaw=0.0)  # standing, the planner walks up to it
    assert _run(scene, pour, state=standing) == (scene, [])
    look = ActionNode(verb="look", action="look_at", target="bottle")  # an earlier action used it
    out, notes = _run(scene, look, pour)
    assert out == scene and notes == []
