"""Props in hand: a handheld action walks to its small object, and the object's grip point sits on the holding
joint in every held frame, in the motion service's output and in the story's assembled motion."""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np

from proto.motion_data import Motion
from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.ik import global_transforms
from services.motion.planning import plan_actions
from services.motion.synthesis import synthesise
from services.orchestrator.backend import InProcessBackend
from services.orchestrator.session import Orchestrator
from wana.arrays import from_wire
from wana.domain import quat
from wana.domain.skeleton import JOINT_INDEX

SCENE = Scene(
    room=Room(room_type="kitchen", width=6, depth=6, height=3),
    objects=[
        PlacedObject(id="table", category="dining_table", position=(1.5, 0.0, 1.0), yaw=0.0),
        PlacedObject(id="cup", category="cup", position=(1.5, 0.76, 1.0), yaw=0.4, support="table"),
        PlacedObject(id="phone", category="phone", position=(-2.0, 0.76, -2.0), yaw=0.0),
    ],
)


def _grip_errors(motion: Motion) -> list[float]:
    """Per held frame: metres between the prop's grip point (world) and its joint."""
    pos, _ = global_transforms(
        from_wire(motion.rotations).astype(float), from_wire(motion.root_position).astype(float)
    )
    out = []
    for track in motion.props:
        origin = from_wire(track.position).astype(float)
        rot = from_wire(track.rotation).astype(float)
        grip = origin + quat.rotate(rot, np.broadcast_to(np.asarray(track.grip), origin.shape))
        hand = pos[track.start_frame : track.end_frame, JOINT_INDEX[track.joint]]
        assert len(hand) == len(grip) == track.end_frame - track.start_frame > 0
        out += np.linalg.norm(grip - hand, axis=1).tolist()
    return out


def test_drinking_walks_to_the_cup_reaches_for_it_and_holds_it_in_the_hand():
    eve = CharacterNode(name="Eve", actions=[ActionNode(verb="drink", action="drink", target="cup")])
    plan = plan_actions(eve, SCENE, (-1.0, -1.0, 0.0))
    assert [s.action for s in plan.segments if s.kind == "action"] == ["press_switch", "drink"]  # a reach
    assert plan.segments[0].kind == "locomotion"
    assert plan.segments[-1].prop == "cup" and plan.segments[-2].prop == "cup"
    motion, _, _ = synthesise(plan)
    assert {p.object_id for p in motion.props} == {"cup"}
    errors = _grip_errors(motion)
    assert len(errors) > 30 and max(errors) < 0.01
    origin = np.concatenate([from_wire(t.position) for t in motion.props])
    assert np.ptp(origin[:, 1]) > 0.1  # it travels with the hand (to the mouth), not left on the table


def test_the_nearest_prop_made_for_the_action_is_used_when_none_is_named():
    tom = CharacterNode(name="Tom", actions=[ActionNode(verb="call", action="call_with_phone")])
    plan = plan_actions(tom, SCENE, (-1.0, -1.0, 0.0))
    assert plan.segments[-1].prop == "phone"
    motion, _, _ = synthesise(plan)
    assert max(_grip_errors(motion)) < 0.01


def test_texting_fetches_the_phone_its_clip_is_named_for_though_the_phone_has_no_text_point():
    """solo-cafe-15, solo-home_office-02: the phone's one held point is "call"; "texts" and "answers the phone"
    (text_on_phone, pick_up_phone_answer) found nothing made for them and played with an empty hand."""
    for action in ("text_on_phone", "pick_up_phone_answer"):
        tom = CharacterNode(name="Tom", actions=[ActionNode(verb="text", action=action)])
        plan = plan_actions(tom, SCENE, (-1.0, -1.0, 0.0))
        assert plan.segments[-1].prop == "phone", action


def test_the_story_motion_keeps_the_prop_in_the_hand_after_timing():
    text = "In the kitchen there is a table$. A cup is on the table$.\nEve waves.\nEve drinks from the cup.\n"
    with tempfile.TemporaryDirectory() as tmp:
        orchestrator = Orchestrator(Path(tmp) / "s.db", InProcessBackend(), seed=0)
        try:
            result = orchestrator.create(text, doc_id="props").compute()
        finally:
            orchestrator.close()
    motion = result.motions["Eve"]
    assert motion.props and motion.props[0].object_id in {o.id for o in result.scene.objects}
    reach = next(s for s in motion.segments if s.action == "press_switch")  # the reach for the cup
    drink = next(s for s in motion.segments if s.action == "drink")
    first = min(motion.props, key=lambda t: t.start_frame)
    assert reach.start_frame < first.start_frame < reach.end_frame  # taken during the reach, not before
    held = np.zeros(len(from_wire(motion.root_position)), bool)
    for t in motion.props:
        held[t.start_frame : t.end_frame] = True
    assert held[first.start_frame : drink.end_frame].all()  # and held on through the drink
    assert max(_grip_errors(motion)) < 0.01


def test_the_renderer_poses_a_held_prop_on_the_hand_and_leaves_it_out_of_the_static_room():
    from services.render.scene_geometry import held_ids, object_meshes, prop_pose

    eve = CharacterNode(name="Eve", actions=[ActionNode(verb="drink", action="drink", target="cup")])
    motion, _, _ = synthesise(plan_actions(eve, SCENE, (-1.0, -1.0, 0.0)))
    assert held_ids([motion]) == {"cup"}
    assert "cup" not in {m.name for m in object_meshes(SCENE, held_ids([motion]))}
    track = motion.props[0]
    cup = SCENE.objects[1]
    pos, _ = global_transforms(
        from_wire(motion.rotations).astype(float), from_wire(motion.root_position).astype(float)
    )
    for f in (track.start_frame, (track.start_frame + track.end_frame) // 2, track.end_frame - 1):
        m = prop_pose(cup, [motion], f)
        grip = m[:3, :3] @ np.asarray(track.grip) + m[:3, 3]
        assert np.linalg.norm(grip - pos[f, JOINT_INDEX[track.joint]]) < 0.01
    assert np.allclose(prop_pose(cup, [motion], 0)[:3, 3], cup.position)  # before: where it was placed


def test_the_glb_animates_the_held_prop_as_a_node_of_its_own():
    import json
    import struct

    from services.render.gltf_export import scene_glb
    from services.render.scene_geometry import prop_track

    eve = CharacterNode(name="Eve", actions=[ActionNode(verb="drink", action="drink", target="cup")])
    motion, _, _ = synthesise(plan_actions(eve, SCENE, (-1.0, -1.0, 0.0)))
    glb = scene_glb(SCENE, [motion])
    (length,) = struct.unpack_from("<I", glb, 12)
    doc = json.loads(glb[20 : 20 + length])
    cup = [i for i, n in enumerate(doc["nodes"]) if n["name"] == "cup"]
    assert len(cup) == 1  # drawn once: not also in the static room
    paths = {c["target"]["path"] for c in doc["animations"][0]["channels"] if c["target"]["node"] == cup[0]}
    assert paths == {"translation", "rotation"}
    n = len(from_wire(motion.root_position))
    pos, rot = prop_track(SCENE.objects[1], [motion], n)
    track = motion.props[0]
    assert np.allclose(pos[0], SCENE.objects[1].position)  # on the table before it is picked up
    assert np.allclose(pos[track.start_frame], from_wire(track.position)[0])
    # the placed orientation as a quaternion agrees with the catalog's object-to-world yaw
    from wana.assets.catalog import yaw_matrix

    x, y, z, w = rot[0]
    m = np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )
    assert np.allclose(m, yaw_matrix(SCENE.objects[1].yaw), atol=1e-6)


def _prop_positions(motion: Motion, placed: PlacedObject) -> np.ndarray:
    from services.render.scene_geometry import prop_track

    return prop_track(placed, [motion], len(from_wire(motion.root_position)))[0]


def test_a_prop_leaves_the_table_at_the_grasp_and_stays_in_the_hand_through_a_later_walk():
    eve = CharacterNode(
        name="Eve",
        actions=[
            ActionNode(verb="pick up", action="pick_up", target="cup"),
            ActionNode(verb="walk", action="walk", destination="phone"),
        ],
    )
    plan = plan_actions(eve, SCENE, (-1.0, -1.0, 0.0))
    walk_after = [s for s in plan.segments if s.action_index == 1]
    assert walk_after and all(s.prop == "cup" and s.prop_span == "whole" for s in walk_after)
    motion, _, _ = synthesise(plan)
    assert max(_grip_errors(motion)) < 0.01
    pos = _prop_positions(motion, SCENE.objects[1])
    first = min(t.start_frame for t in motion.props)
    # reach, then attach: at the grasp the cup is still where it stood on the table (no jump into the hand)
    assert np.linalg.norm(pos[first] - np.asarray(SCENE.objects[1].position)) < 0.02
    assert np.max(np.linalg.norm(np.diff(pos, axis=0), axis=1)) < 0.3  # never jumps (10 m/s at 30 fps)
    assert np.linalg.norm(pos[-1, [0, 2]] - np.asarray(SCENE.objects[2].position)[[0, 2]]) < 1.0  # carried


def test_put_down_on_a_named_surface_releases_the_prop_there():
    scene = Scene(
        room=SCENE.room,
        objects=[
            *SCENE.objects,
            PlacedObject(id="counter", category="kitchen_counter", position=(-1.5, 0.0, 1.5)),
        ],
    )
    eve = CharacterNode(
        name="Eve",
        actions=[
            ActionNode(verb="pick up", action="pick_up", target="cup"),
            ActionNode(verb="put", action="put_down", target="cup", destination="counter"),
        ],
    )
    plan = plan_actions(eve, scene, (-1.0, -1.0, 0.0))
    put = [s for s in plan.segments if s.action == "put_down"]
    assert len(put) == 1 and put[0].prop == "cup" and put[0].prop_span == "release"
    motion, _, _ = synthesise(plan)
    assert max(_grip_errors(motion)) < 0.01
    last = max(motion.props, key=lambda t: t.end_frame)
    end = from_wire(last.position)[-1]
    from wana.assets.catalog import world_support_surfaces

    (height, corners), *_ = sorted(world_support_surfaces(scene.objects[-1]), key=lambda s: -s[0])
    lo, hi = corners.min(axis=0), corners.max(axis=0)
    assert abs(end[1] - height) < 0.02  # standing on the counter's top ...
    assert np.all(end[[0, 2]] >= lo - 1e-6) and np.all(end[[0, 2]] <= hi + 1e-6)  # ... inside its rectangle


def test_taking_a_second_prop_sets_the_first_one_down_first():
    eve = CharacterNode(
        name="Eve",
        actions=[
            ActionNode(verb="pick up", action="pick_up", target="cup"),
            ActionNode(verb="call", action="call_with_phone", target="phone"),
        ],
    )
    plan = plan_actions(eve, SCENE, (-1.0, -1.0, 0.0))
    released = [i for i, s in enumerate(plan.segments) if s.prop == "cup" and s.prop_span == "release"]
    taken = [i for i, s in enumerate(plan.segments) if s.prop == "phone" and s.prop_span == "grasp"]
    assert released and taken and released[0] < taken[0]  # one hand, one prop
    assert all(s.prop != "cup" for s in plan.segments[released[0] + 1 :])
    motion, _, _ = synthesise(plan)
    assert max(_grip_errors(motion)) < 0.01


def test_putting_down_what_is_not_in_the_hand_takes_it_first_then_puts_it_there():
    """ "Dan puts the plate on the table" with empty hands: a reach for the plate, then the put with it in
    the hand (was a put_down of nothing, the hand 0.3 m from the plate, kitchen2 s6)."""
    scene = Scene(
        room=SCENE.room,
        objects=[
            *SCENE.objects,
            PlacedObject(id="counter", category="kitchen_counter", position=(-1.5, 0.0, 1.5)),
        ],
    )
    dan = CharacterNode(
        name="Dan", actions=[ActionNode(verb="put", action="put_down", target="cup", destination="counter")]
    )
    plan = plan_actions(dan, scene, (-1.0, -1.0, 0.0))
    spans = [(s.prop, s.prop_span) for s in plan.segments if s.kind == "action"]
    assert spans == [("cup", "grasp"), ("cup", "release")]
    assert plan.segments[-1].target_id == "counter"
    motion, _, _ = synthesise(plan)
    assert max(_grip_errors(motion)) < 0.01


def test_drinking_after_pouring_puts_the_bottle_down_for_a_glass():
    """ "John pours wine into the glasses. They drink.": from a glass, not from the bottle still in the hand
    (drinkware poured from is the last choice)."""
    scene = Scene(
        room=SCENE.room,
        objects=[
            SCENE.objects[0],
            PlacedObject(id="bottle", category="bottle", position=(1.3, 0.76, 0.8), support="table"),
            PlacedObject(id="glass", category="glass", position=(1.7, 0.76, 0.8), support="table"),
        ],
    )
    john = CharacterNode(name="John", actions=[ActionNode(verb="drink", action="drink")])
    plan = plan_actions(john, scene, (1.3, 0.2, 0.0), holding="bottle")
    spans = [(s.prop, s.prop_span) for s in plan.segments if s.kind == "action"]
    assert spans[0] == ("bottle", "release") and ("glass", "grasp") in spans
    assert plan.segments[-1].action == "drink" and plan.segments[-1].prop == "glass"
