"""Props at their target: a seated drinker out of reach of the cup fetches it and sits back down, the cup
reaches the lips, a tool already in the hand is the one used on what the sentence names ("hammers a nail"),
and of two alike props the nearer is taken."""

from __future__ import annotations

import numpy as np

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.ik import global_transforms
from services.motion.planning import plan_actions
from services.motion.synthesis import synthesise
from wana.arrays import from_wire
from wana.domain.actions import get_clip
from wana.domain.skeleton import JOINT_INDEX

ROOM = Room(room_type="kitchen", width=7, depth=7, height=3)
TABLE = PlacedObject(id="table", category="dining_table", position=(0.0, 0.0, 0.0), yaw=0.0)
CHAIR = PlacedObject(id="chair", category="chair", position=(-1.5, 0.0, 1.8), yaw=0.0)
FAR_CUP = PlacedObject(id="cup", category="cup", position=(0.5, 0.76, 0.0), yaw=0.0, support="table")


def _sit_then_drink() -> CharacterNode:
    return CharacterNode(
        name="Eve",
        actions=[
            ActionNode(verb="sit", action="sit", target="chair"),
            ActionNode(verb="drink", action="drink", target="cup"),
        ],
    )


def test_a_seated_drinker_out_of_reach_gets_up_fetches_the_cup_and_sits_back_down(monkeypatch):
    import services.motion.planning as planning

    monkeypatch.setattr(planning, "FETCH_WHEN_SEATED", True)
    scene = Scene(room=ROOM, objects=[TABLE, CHAIR, FAR_CUP])
    plan = plan_actions(_sit_then_drink(), scene, (-1.5, 3.0, np.pi))
    drink = [s for s in plan.segments if s.action_index == 1]
    actions = [s.action for s in drink]
    assert actions[0] == "stand" and actions[-2:] == ["sit", "drink"], actions
    assert "press_switch" in actions  # the reach that takes the cup
    sit_again = drink[-2]
    assert sit_again.target_id == "chair" and sit_again.prop == "cup"  # carried back to the seat
    assert drink[-1].prop == "cup"


def test_the_cup_reaches_the_lips_while_drinking():
    scene = Scene(room=ROOM, objects=[TABLE, PlacedObject(id="cup", category="cup", position=(0.0, 0.76, 0.5),
                                                          yaw=0.0, support="table")])  # fmt: skip
    eve = CharacterNode(name="Eve", actions=[ActionNode(verb="drink", action="drink", target="cup")])
    plan = plan_actions(eve, scene, (0.0, 2.0, np.pi))
    motion, _, _ = synthesise(plan)
    seg = next(s for s in motion.segments if s.action == "drink")
    clip = get_clip("drink")
    n = seg.end_frame - seg.start_frame
    a = seg.start_frame + round(clip.interaction.window[0] / clip.duration_s * n)
    b = seg.start_frame + round(clip.interaction.window[1] / clip.duration_s * n)
    pos, rot = global_transforms(
        from_wire(motion.rotations).astype(float), from_wire(motion.root_position).astype(float)
    )
    from scipy.spatial.transform import Rotation

    head = JOINT_INDEX["Head"]
    centre = pos[a:b, head] + Rotation.from_quat(rot[a:b, head]).apply([0.0, 0.10, 0.0])
    wrist = pos[a:b, JOINT_INDEX["RightHand"]]
    at_lips = np.linalg.norm(wrist - centre, axis=1) <= 0.2
    assert at_lips.mean() >= 0.6, at_lips.mean()
    assert any(t.object_id == "cup" and t.start_frame <= a and t.end_frame >= b for t in motion.props)


def test_a_hammer_in_the_hand_is_the_tool_used_on_the_nail_it_names():
    bench = PlacedObject(id="workbench", category="workbench", position=(0.0, 0.0, 0.0), yaw=0.0)
    hammer = PlacedObject(
        id="hammer", category="hammer", position=(0.2, 0.9, 0.0), yaw=0.0, support="workbench"
    )
    nail = PlacedObject(id="nail", category="nail", position=(-0.2, 0.9, 0.0), yaw=0.0, support="workbench")
    scene = Scene(room=ROOM, objects=[bench, hammer, nail])
    tom = CharacterNode(
        name="Tom",
        actions=[
            ActionNode(verb="pick up", action="pick_up", target="hammer"),
            ActionNode(verb="hammer", action="hammer", target="nail"),
        ],
    )
    plan = plan_actions(tom, scene, (0.0, 1.5, np.pi))
    hammering = [s for s in plan.segments if s.action_index == 1]
    assert [s.action for s in hammering] == ["hammer"]  # no set-down, no reach for the nail
    assert hammering[0].prop == "hammer" and hammering[0].prop_span == "whole"


def test_of_two_mugs_on_the_table_the_nearer_one_is_taken():
    near = PlacedObject(id="mug/2", category="mug", position=(0.0, 0.76, 0.6), yaw=0.0, support="table")
    far = PlacedObject(id="mug", category="mug", position=(0.0, 0.76, -0.6), yaw=0.0, support="table")
    scene = Scene(room=ROOM, objects=[TABLE, far, near])
    eve = CharacterNode(name="Eve", actions=[ActionNode(verb="drink", action="drink", target="mug")])
    plan = plan_actions(eve, scene, (0.0, 2.0, np.pi))
    assert plan.segments[-1].prop == "mug/2"
