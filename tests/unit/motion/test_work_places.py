"""Where an action at an object is done when the sentence names none, and where a seated character's hands
work on a table top: "Zoe washes her hands" at the sink, "She takes notes" at the long table she sits at,
"She uses the computer" with both hands in front of it; and a held action naming one of two alike props
sees both (the planner takes the nearer)."""

from __future__ import annotations

import numpy as np

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.planning import SEAT_BACK, plan_actions, slid_to_place
from services.orchestrator.stages.motion import _with_props
from services.orchestrator.views import scene_view
from wana.assets.catalog import asset_for, to_world, world_support_surfaces

ROOM = Room(room_type="bathroom", width=5, depth=5, height=3)


def _actions(plan, name: str):
    return [s for s in plan.segments if s.kind == "action" and s.action == name]


def test_washing_ones_hands_walks_to_the_sink_and_the_hands_go_to_its_wash_point():
    """solo-bathroom-07: the hands hung at her sides 0.21 m from the sink (no object named: no targets)."""
    sink = PlacedObject(
        id="bathroom_sink", category="bathroom_sink", position=(-1.5, 0.0, 0.0), yaw=np.pi / 2
    )
    scene = Scene(room=ROOM, objects=[sink])
    zoe = CharacterNode(name="Zoe", actions=[ActionNode(verb="wash", action="wash_hands", target="hand")])
    plan = plan_actions(zoe, scene, (1.0, 1.0, 0.0))
    (wash,) = _actions(plan, "wash_hands")
    assert wash.target_id == "bathroom_sink"
    cp = asset_for(sink).contact_points["wash"]
    point = to_world(sink, np.asarray(cp.position, float))
    assert np.linalg.norm(np.asarray(dict(wash.targets)[cp.joint]) - point) < 1e-6
    assert plan.segments[0].kind == "locomotion"  # walked up to it first


def test_an_action_naming_nothing_is_not_done_at_something_far_away():
    sink = PlacedObject(id="bathroom_sink", category="bathroom_sink", position=(-2.3, 0.0, -2.3), yaw=0.0)
    scene = Scene(room=ROOM, objects=[sink])
    zoe = CharacterNode(name="Zoe", actions=[ActionNode(verb="wash", action="wash_hands", target="hand")])
    plan = plan_actions(zoe, scene, (2.0, 2.0, 0.0))  # 4 m from it: the clip plays where she stands
    (wash,) = _actions(plan, "wash_hands")
    assert wash.targets == () and not wash.target_id.startswith("bathroom")


def test_washing_ones_hands_with_only_a_shower_is_not_done_standing_in_the_shower():
    """solo-bathroom-23 (dev): "He turns on the shower and washes his hands" walked into the shower cubicle
    (chest 13 cm inside it); one stands inside a shower to use it, so a sentence naming none is not there."""
    shower = PlacedObject(id="shower", category="shower", position=(-1.5, 0.0, 0.0), yaw=np.pi / 2)
    zoe = CharacterNode(name="Zoe", actions=[ActionNode(verb="wash", action="wash_hands", target="hand")])
    plan = plan_actions(zoe, Scene(room=ROOM, objects=[shower]), (1.0, 1.0, 0.0))
    (wash,) = _actions(plan, "wash_hands")
    assert wash.target_id != "shower" and all(s.kind != "locomotion" for s in plan.segments)


def _meeting() -> tuple[Scene, PlacedObject, PlacedObject]:
    table = PlacedObject(
        id="conference_table", category="conference_table", position=(0.0, 0.0, 0.0), yaw=0.0
    )
    b = asset_for(table).collision_boxes
    lo = np.asarray(b, float).reshape(-1, 2, 3)[:, 0].min(axis=0)
    # a chair at the far end of one long side, facing the table (its front toward -z: yaw pi)
    chair = PlacedObject(
        id="chair", category="chair", position=(float(lo[0]) + 0.4, 0.0, float(-lo[2]) + 0.35), yaw=np.pi
    )
    return (
        Scene(room=Room(room_type="meeting_room", width=8, depth=6, height=3), objects=[table, chair]),
        table,
        chair,
    )


def test_taking_notes_seated_writes_on_the_table_in_front_of_the_chair_not_at_its_one_catalog_point():
    """solo-meeting_room-18: "She sits down. She takes notes." at a long conference table: no object named
    (nothing to write on), and the table's one "write" point was metres from her chair."""
    scene, table, chair = _meeting()
    patel = CharacterNode(
        name="Dr. Patel",
        actions=[
            ActionNode(verb="sit", action="sit", target="chair"),
            ActionNode(verb="take", action="write"),
        ],
    )
    plan = plan_actions(patel, scene, (float(chair.position[0]), 2.5, np.pi))
    (write,) = _actions(plan, "write")
    assert write.target_id == "conference_table"
    hand = dict(write.targets)["RightHandMiddle1"]
    hips = np.array([chair.position[0], chair.position[2]])
    assert np.hypot(hand[0] - hips[0], hand[2] - hips[1]) < 0.75  # within a seated arm's reach
    cp = asset_for(table).contact_points["write"]
    assert abs(hand[1] - to_world(table, np.asarray(cp.position, float))[1]) < 1e-6  # on the top


def test_sliding_leaves_hands_already_at_the_place_in_front_and_objects_without_a_top():
    scene, table, _ = _meeting()
    yaw = np.pi
    pos = np.array([0.0, 0.6])  # in front of the table's long side, facing it
    ahead = pos + np.array([np.sin(yaw), np.cos(yaw)]) * (0.4 - SEAT_BACK)  # on the top
    targets = {"RightHandMiddle1": (float(ahead[0]), 0.78, float(ahead[1]))}
    assert slid_to_place(table, targets, pos, yaw) == targets
    far = {"RightHandMiddle1": (1.5, 0.78, 0.0)}
    moved = slid_to_place(table, far, pos, yaw)["RightHandMiddle1"]
    assert np.allclose(moved, (ahead[0], 0.78, ahead[1]))
    board = PlacedObject(id="whiteboard", category="whiteboard", position=(0.0, 0.0, 0.0))
    assert slid_to_place(board, far, pos, yaw) == far


def test_using_the_computer_types_with_both_hands_in_front_of_it():
    """solo-home_office-20: the computer's only point was its power button (right hand): the typing clip's
    left hand had nowhere to go. Its catalog entry now has a two-handed "type" point before it, on the desk."""
    computer = PlacedObject(id="computer", category="computer", position=(0.0, 0.76, 0.0), yaw=0.0)
    points = asset_for(computer).contact_points
    assert "type" in points and "LeftHandMiddle1" in points["type"].extra
    right = to_world(computer, np.asarray(points["type"].position, float))
    left = to_world(computer, np.asarray(points["type"].extra["LeftHandMiddle1"], float))
    assert abs(right[1] - 0.76) < 0.05 and abs(left[1] - 0.76) < 0.05  # on the desk top it stands on
    assert right[2] > 0.2 and left[2] > 0.2  # in front of it, where the user sits
    assert right[0] > left[0]  # the user faces -z: the right hand at +x


def test_a_held_action_naming_one_of_two_mugs_sees_both():
    """duo-cafe-04: "She drinks from her mug" named "mug"; the motion view held only that one, 1.05 m from
    Ms Lee, not mug/2 in her reach (0.83 m), so the planner's nearest-alike rule could not take it."""
    table = PlacedObject(id="cafe_table", category="cafe_table", position=(0.0, 0.0, 0.0))
    mugs = [
        PlacedObject(id=i, category="mug", position=(x, 0.75, 0.0), support="cafe_table")
        for i, x in (("mug", 0.2), ("mug/2", -0.2))
    ]
    cup = PlacedObject(id="cup", category="cup", position=(0.0, 0.75, 0.2), support="cafe_table")
    scene = Scene(room=ROOM, objects=[table, *mugs, cup])
    drink = ActionNode(verb="drink", action="drink", target="mug")
    view = _with_props(scene, scene_view(scene, drink), drink)
    assert {o.id for o in view.objects} == {"cafe_table", "mug", "mug/2"}  # not the cup: another kind
    anyone = ActionNode(verb="drink", action="drink")
    assert {o.id for o in _with_props(scene, scene_view(scene, anyone), anyone).objects} == {
        "cafe_table",
        "mug",
        "mug/2",
        "cup",
    }


def test_eating_from_the_plate_with_a_plate_at_each_place_eats_from_the_nearest():
    """duo-dining_room-11 "They eat dinner": two plates, one at each place; Tom ate from the first plate,
    across the table (his hand 0.84 m from it), not from his own."""
    from services.motion.planning import straight_route
    from wana.assets.catalog import world_support_surfaces

    table = PlacedObject(id="dining_table", category="dining_table", position=(0.0, 0.0, 0.0))
    top = max(h for h, _ in world_support_surfaces(table))
    far = PlacedObject(id="plate", category="plate", position=(0.0, top, -0.35), support="dining_table")
    near = PlacedObject(id="plate/2", category="plate", position=(0.0, top, 0.35), support="dining_table")
    scene = Scene(room=Room(room_type="dining_room", width=6, depth=6, height=3), objects=[table, far, near])
    node = CharacterNode(name="Tom", actions=[ActionNode(verb="eat", action="eat", target="plate")])
    plan = plan_actions(node, scene, (0.0, 1.2, np.pi), straight_route)
    (eat,) = [s for s in plan.segments if s.action == "eat"]
    assert eat.target_id == "plate/2"
    (hand,) = np.array(list(dict(eat.targets).values()))
    assert np.hypot(hand[0] - near.position[0], hand[2] - near.position[2]) < 0.2


def test_making_a_coffee_at_the_counter_puts_the_right_hand_on_the_cup_and_stands_by_it():
    """bakery s4: "Hana makes a coffee" (cook, the cup) played at the counter's own cook point, the right
    hand 0.40 m from the cup at the counter's other end; the hands go to the cup, the body beside it."""
    counter = PlacedObject(id="kitchen_counter", category="kitchen_counter", position=(0.0, 0.0, -1.0))
    top = max(h for h, _ in world_support_surfaces(counter))
    cup = PlacedObject(id="cup", category="cup", position=(0.6, top, -0.85), support="kitchen_counter")
    scene = Scene(room=Room(room_type="kitchen", width=5, depth=5, height=3), objects=[counter, cup])
    hana = CharacterNode(name="Hana", actions=[ActionNode(verb="make", action="cook", target="cup")])
    plan = plan_actions(hana, scene, (0.0, 0.5, np.pi))
    (cook,) = _actions(plan, "cook")
    hands = dict(cook.targets)
    right = np.asarray(hands.get("RightHandMiddle1", hands.get("RightHand")))
    grip = to_world(cup, np.asarray(asset_for(cup).contact_points["pick_up"].position, float))
    assert np.hypot(right[0] - grip[0], right[2] - grip[2]) < 1e-6 and right[1] >= grip[1] - 1e-6
    walk = [s for s in plan.segments if s.kind == "locomotion"]
    end = np.asarray(walk[-1].waypoints[-1])
    assert np.hypot(end[0] - grip[0], end[1] - grip[2]) < 0.75  # within an arm's reach of the cup


def test_eating_seated_with_nothing_named_eats_at_the_plate_in_front_of_the_chair():
    """kitchen2 s7: "Lucy walks in and sits at the table ... Lucy eats." at a table with no "eat" point of its
    own and a plate in front of her: the hand went nowhere (0.19 m above the table); now at the plate."""
    scene, table, chair = _meeting()
    top = max(h for h, _ in world_support_surfaces(table))
    plate = PlacedObject(
        id="plate", category="plate", position=(chair.position[0], top, chair.position[2] - 0.55),
        support="conference_table",
    )  # fmt: skip
    scene = Scene(room=scene.room, objects=[*scene.objects, plate])
    lucy = CharacterNode(
        name="Lucy",
        actions=[ActionNode(verb="sit", action="sit", target="chair"), ActionNode(verb="eat", action="eat")],
    )
    plan = plan_actions(lucy, scene, (float(chair.position[0]), 2.5, np.pi))
    (eat,) = _actions(plan, "eat")
    assert eat.target_id == "plate"
    cp = asset_for(plate).contact_points["eat"]
    point = to_world(plate, np.asarray(cp.position, float))
    assert np.linalg.norm(np.asarray(dict(eat.targets)[cp.joint]) - point) < 1e-6
