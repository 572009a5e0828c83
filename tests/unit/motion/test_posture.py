"""Posture-aware planning and joins: no replayed sit-down, no get-up from standing, the seat an action needs,
and pieces that meet at their boundaries without a pose pop (the story checks' own pop test)."""

from __future__ import annotations

import msgspec
import numpy as np

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.planning import pick_seat, plan_actions
from services.motion.synthesis import SegmentState, rest_frame, synthesise, synthesise_segment
from wana.arrays import from_wire
from wana.fidelity import body_checks
from wana.fidelity.bodies import body_of

SCENE = Scene(
    room=Room(room_type="office", width=8, depth=8, height=3),
    objects=[
        PlacedObject(id="desk", category="desk", position=(1.0, 0.0, 0.3), yaw=0.0),
        PlacedObject(id="chair", category="office_chair", position=(1.0, 0.0, 1.05), yaw=np.pi),
        PlacedObject(id="sofa", category="sofa", position=(-2.5, 0.0, 2.5), yaw=0.0),
        PlacedObject(id="bed", category="bed", position=(2.5, 0.0, -2.5), yaw=0.0),
    ],
)


def _eve(*acts: tuple[str, str]) -> CharacterNode:
    return CharacterNode(name="Eve", actions=[ActionNode(verb=a, action=a, target=t) for a, t in acts])


def _plan(*acts: tuple[str, str], posture: str = "stand", start=(0.0, -3.0, 0.0)):
    return plan_actions(_eve(*acts), SCENE, start, posture=posture)


def test_sits_while_seated_keeps_sitting():
    plan = _plan(("sit", "chair"), ("sit", ""), ("sit", "chair"))
    sits = [s for s in plan.segments if s.action == "sit"]
    assert [s.kind for s in sits] == ["action", "wait", "wait"]
    motion, _, _ = synthesise(plan)
    hips = from_wire(motion.root_position)
    seated = motion.segments[-2].start_frame  # the two holds: the hips stay on the seat
    assert np.ptp(hips[seated:, 1]) < 0.01
    assert np.linalg.norm(np.diff(hips, axis=0), axis=1).max() * motion.fps < 6.0


def test_stands_while_standing_is_a_hold_and_walking_while_seated_stands_first():
    plan = _plan(("stand", ""))
    assert [(s.kind, s.action) for s in plan.segments] == [("wait", "stand")]
    seated = _plan(("jump", ""), posture="sit")
    assert [s.action for s in seated.segments] == ["stand", "jump"]


def test_seat_resolution_named_nearest_and_none():
    pos = np.array([0.0, 0.0])
    named = pick_seat(SCENE, "seat", SCENE.objects[2], pos, {}, "Eve")
    assert named is not None and named[0].id == "sofa"
    at_desk = pick_seat(SCENE, "seat", SCENE.objects[0], pos, {}, "Eve")  # "sits at the desk": its chair
    assert at_desk is not None and at_desk[0].id == "chair"
    taken = pick_seat(SCENE, "seat", SCENE.objects[0], pos, {"Tom": (at_desk[1][0], at_desk[1][2])}, "Eve")
    assert taken is None or taken[0].id != "chair" or taken[1] != at_desk[1]
    empty = Scene(room=SCENE.room, objects=[SCENE.objects[0]])
    assert pick_seat(empty, "seat", None, pos, {}, "Eve") is None
    plan = plan_actions(_eve(("sit", "")), empty, (0.0, -3.0, 0.0))
    assert all(s.action != "sit" for s in plan.segments)  # never sits on nothing ...
    assert any("stands instead" in d for d in plan.diagnostics)  # ... and says so


def test_sofa_slots_are_free_for_a_second_character():
    pos = np.array([-2.5, 1.5])
    first = pick_seat(SCENE, "seat", SCENE.objects[2], pos, {}, "Eve")
    assert first is not None
    second = pick_seat(SCENE, "seat", SCENE.objects[2], pos, {"Eve": (first[1][0], first[1][2])}, "Tom")
    assert second is not None and np.hypot(second[1][0] - first[1][0], second[1][2] - first[1][2]) > 0.4


def test_pieces_join_without_pops_even_when_synthesised_apart():
    plan = _plan(
        ("walk", "desk"), ("wave", ""), ("sit", "chair"), ("type", "desk"), ("stand", ""), ("sleep", "bed")
    )
    motion, pieces, states = synthesise(plan)
    body = body_of(motion)
    boundaries = [s.start_frame for s in motion.segments if s.start_frame > 0]
    assert len(boundaries) >= 6
    assert not body_checks.pops(body, boundaries).failing.any()
    assert not body_checks.speeds(body, motion.fps).failing.any()
    # Each piece ends in exactly the rest pose the next one starts from (what lets holds sit between them).
    state = plan.start_state()
    for k in range(len(plan.segments)):
        piece, end = synthesise_segment(plan, k, state)
        rot, hips = rest_frame(end)
        assert np.allclose(piece.root[-1], hips, atol=1e-6)
        assert np.allclose(np.abs(np.sum(piece.rotations[-1] * rot, axis=-1)), 1.0, atol=1e-6)
        state = end
    assert isinstance(state, SegmentState)


def test_sits_next_to_a_person_takes_a_free_seat_near_them_not_the_floor_beside_them():
    eve = CharacterNode(name="Eve", actions=[ActionNode(verb="sit", action="sit", target="Zoe")])
    zoe_on_sofa = pick_seat(SCENE, "seat", SCENE.objects[2], np.array([-2.5, 1.5]), {}, "Zoe")
    assert zoe_on_sofa is not None
    zoe = (zoe_on_sofa[1][0], zoe_on_sofa[1][2])
    plan = plan_actions(eve, SCENE, (0.0, -3.0, 0.0), others={"Zoe": zoe})
    sit = next(s for s in plan.segments if s.action == "sit")
    assert sit.target_id == "sofa"  # the seat next to her, the other slot of her sofa
    hips = dict(sit.targets)["Hips"]
    assert 0.2 < np.hypot(hips[0] - zoe[0], hips[2] - zoe[1]) < 1.5


def test_a_turn_while_seated_holds_the_seat():
    plan = _plan(("sit", "chair"), ("turn_around", ""))
    assert [(s.kind, s.action) for s in plan.segments][-1] == ("wait", "turn_around")
    motion, _, _ = synthesise(plan)
    hips = from_wire(motion.root_position)
    sat = next(s for s in motion.segments if s.action == "sit").end_frame
    assert np.linalg.norm(hips[sat:] - hips[sat - 1], axis=1).max() < 0.01


def test_seat_points_keep_the_thighs_on_the_seat():
    """The Hips point sits SIT_HIPS_M above a seat's top, so the thighs (6 cm spheres 5 cm under the Hips)
    rest on it instead of sinking 7-11 cm into it."""
    from wana.assets.catalog import make_object

    for category in ("chair", "dining_chair", "armchair", "sofa", "stool", "bench"):
        obj = make_object(category)
        hips = obj.contact_points["sit"].position
        seat = max(s.height for s in obj.support_surfaces)  # the seat: these seats' only support surface
        assert 0.08 <= hips[1] - seat <= 0.12, (category, hips[1], seat)


def _chair_only(*extra: PlacedObject) -> Scene:
    chair = PlacedObject(id="chair", category="chair", position=(0.0, 0.0, 0.0), yaw=np.pi)
    return Scene(room=Room(room_type="office", width=8, depth=8, height=3), objects=[chair, *extra])


def test_the_sit_approach_stands_clear_of_the_seat_front_unless_a_table_is_there():
    from services.motion.planning import LEG_CLEAR_M, SEAT_BACK, seat_approach, seat_slots
    from wana.assets.catalog import world_bounds

    free = _chair_only()
    chair = free.objects[0]
    hips = seat_slots(chair, "seat")[0]
    front = float(-world_bounds(chair)[0, 2])  # the chair faces -Z: its front edge is its lowest z
    back = seat_approach(free, chair, hips)
    assert back > SEAT_BACK
    assert abs((hips[2] - back) - (-front - LEG_CLEAR_M)) < 0.02  # the hips LEG_CLEAR_M in front of the edge
    table = PlacedObject(id="table", category="dining_table", position=(0.0, 0.0, -0.75), yaw=0.0)
    tucked = _chair_only(table)
    assert seat_approach(tucked, tucked.objects[0], hips) == SEAT_BACK


def test_getting_up_ends_with_the_legs_out_of_the_chair_and_walks_away_clear_of_it():
    from wana.domain.actions import get_clip
    from wana.fidelity.world import World

    scene = _chair_only()
    rise = round(get_clip("stand").duration_s * 30)  # frames of the get-up a walk from the seat begins with
    for then in (["stand", "walk"], ["walk"]):  # "stands up and walks", and a walk that gets up first
        acts = [ActionNode(verb="sit", action="sit", target="chair")]
        acts += [ActionNode(verb=a, action=a) for a in then]
        plan = plan_actions(CharacterNode(name="Eve", actions=acts), scene, (-3.0, -0.34, np.pi / 2))
        stand = [s for s in plan.segments if s.action == "stand"]
        assert all(dict(s.targets)["Hips"][2] < -0.3 for s in stand)  # onto the spot in front of the seat
        motion, _, _ = synthesise(plan)
        assert motion.fps == 30
        inside = body_checks.penetration(body_of(motion), World(scene), {}).failing
        away = [g for g in motion.segments if g.action == "walk"][-1]
        up_end = away.start_frame + (0 if stand else rise)  # the first frame standing
        hips = from_wire(motion.root_position)
        assert hips[up_end - 1, 2] < -0.3  # standing up ends clear of the seat's front edge (z -0.24)
        assert not inside[up_end : away.end_frame].any()  # and walks away without a leg in the chair


def test_falling_asleep_in_the_bed_one_lies_in_keeps_lying_when_planned_on_its_own():
    """Seen on a sheet: "Tom lies down on the bed. He falls asleep." stood Tom up on the bed and laid him
    down again: the second sentence is planned apart, from the end state, whose root lies 0.6 m from the
    bed's lie point (not within a seat's 0.35 m), so he did not count as lying there."""
    lying = _plan(("lie_down", "bed"))
    _, _, states = synthesise(lying)
    end = states[-1]
    assert end.posture == "lie"
    asleep = _plan(("sleep", "bed"), posture="lie", start=(end.x, end.z, end.yaw))
    assert [(s.kind, s.action) for s in asleep.segments] == [("wait", "sleep")]


def test_a_chair_tucked_in_at_a_table_is_sat_on_and_left_from_beside_it():
    """At a table the chair's front edge touches the table's: standing up in front of it stands in both, so
    the character gets up beside the chair, sliding off the seat, and walks away without a leg in the chair
    or the table; a plan resumed seated (the next sentence) knows the seat it is on and does the same."""
    from wana.assets.catalog import world_bounds
    from wana.fidelity.world import World

    table = PlacedObject(id="table", category="dining_table", position=(0.0, 0.0, -0.75), yaw=0.0)
    scene = _chair_only(table)
    chair = scene.objects[0]
    half_w = float(world_bounds(chair)[1, 0])
    acts = [
        ActionNode(verb=a, action=a, target="chair" if a == "sit" else "") for a in ("sit", "stand", "walk")
    ]
    plan = plan_actions(CharacterNode(name="Eve", actions=acts), scene, (-3.0, 1.5, np.pi / 2))
    (stand,) = [s for s in plan.segments if s.action == "stand"]
    rise = dict(stand.targets)["Hips"]
    assert abs(rise[0]) > half_w + 0.15  # beside the seat, not before it
    motion, _, states = synthesise(plan)
    inside = body_checks.penetration(body_of(motion), World(scene), {})
    up = next(g for g in motion.segments if g.action == "stand")
    assert not inside.failing[up.end_frame :].any(), set(inside.what[inside.failing])  # away clear of both
    seated = states[next(i for i, s in enumerate(plan.segments) if s.action == "sit")]
    resumed = plan_actions(
        CharacterNode(name="Eve", actions=acts[1:]), scene, (seated.x, seated.z, seated.yaw), posture="sit"
    )
    (again,) = [s for s in resumed.segments if s.action == "stand"]
    assert np.allclose(dict(again.targets)["Hips"], rise, atol=0.02)


def test_a_seated_character_takes_a_box_beside_it_on_the_bench_without_getting_up():
    from services.motion.planning import seat_slots, straight_route
    from wana.assets.catalog import world_support_surfaces

    bench = PlacedObject(id="bench", category="bench", position=(0.0, 0.0, 0.0))
    hips = seat_slots(bench, "seat")[0]
    top = world_support_surfaces(bench)[0][0]
    box = PlacedObject(
        id="box", category="chocolate_box", position=(hips[0] + 0.35, top, 0.0), support="bench"
    )
    scene = Scene(room=Room(room_type="lobby", width=6, depth=6, height=3), objects=[bench, box])
    node = CharacterNode(name="Ann", actions=[
        ActionNode(verb="sit", action="sit", target="bench"),
        ActionNode(verb="pick", action="pick_up", target="box"),
    ])  # fmt: skip
    plan = plan_actions(node, scene, (hips[0], 1.5, np.pi), straight_route)
    after = [s for s in plan.segments if s.action_index == 1]
    assert [s.action for s in after] == ["pick_up"]  # no stand-up, no walk round the bench to bend over it
    assert after[0].upright and after[0].prop == "box" and after[0].prop_span == "grasp"
    far = msgspec.structs.replace(box, position=(hips[0] + 1.2, top, 0.0))  # out of reach: gets up for it
    plan = plan_actions(
        node, msgspec.structs.replace(scene, objects=[bench, far]), (hips[0], 1.5, np.pi), straight_route
    )
    assert plan.segments[[s.action_index for s in plan.segments].index(1)].action == "stand"


def test_a_seated_character_eats_from_a_bowl_in_reach_on_the_low_coffee_table_without_getting_up():
    """solo-living_room-08 "He eats a snack from the bowl" from the sofa: the bowl's grip on a coffee table
    (0.46 m) is below a table reach, so it was a floor-height pick-up, which needs standing: Ben got up and
    bent over the table. In arm's reach of the hips it is taken with the seated arm, then eaten from."""
    from services.motion.planning import seat_slots, straight_route
    from wana.assets.catalog import world_support_surfaces

    sofa = PlacedObject(id="sofa", category="sofa", position=(0.0, 0.0, 0.0))
    table = PlacedObject(id="coffee_table", category="coffee_table", position=(0.0, 0.0, 0.85))
    top = max(h for h, _ in world_support_surfaces(table))
    hips = seat_slots(sofa, "seat")[0]
    bowl = PlacedObject(
        id="bowl", category="bowl", position=(hips[0] + 0.1, top, 0.66), support="coffee_table"
    )
    scene = Scene(room=Room(room_type="living_room", width=6, depth=6, height=3), objects=[sofa, table, bowl])
    node = CharacterNode(name="Ben", actions=[
        ActionNode(verb="sit", action="sit", target="sofa"),
        ActionNode(verb="eat", action="eat_snack", target="snack"),
    ])  # fmt: skip
    plan = plan_actions(node, scene, (hips[0], 1.8, np.pi), straight_route)
    after = [s for s in plan.segments if s.action_index == 1]
    assert [s.action for s in after][-1] == "eat_snack" and "stand" not in [s.action for s in after]
    assert after[0].upright and after[0].prop == "bowl" and after[0].prop_span == "grasp"


def test_falling_asleep_in_a_chair_dozes_off_sitting_and_a_bed_is_walked_to():
    """ "Sits in the armchair ... falls asleep in the armchair": asleep where she sits (the head sinks, the
    hips stay on the seat), not lying down on a chair nor idling; "falls asleep on the bed" from the chair
    still gets up and lies down there."""
    plan = _plan(("sit", "sofa"), ("sleep", "sofa"))
    assert [(s.kind, s.action) for s in plan.segments][-2:] == [("action", "sit"), ("wait", "sleep")]
    motion, _, _ = synthesise(plan)
    hips = from_wire(motion.root_position)
    rot = from_wire(motion.rotations)
    doze = motion.segments[-1]
    assert np.ptp(hips[doze.start_frame : doze.end_frame, 1]) < 0.01
    head = list(motion.joint_names).index("Head")
    mid = (doze.start_frame + doze.end_frame) // 2
    assert abs(rot[mid, head, 0]) > abs(rot[doze.start_frame, head, 0]) + 0.05  # the head has sunk
    to_bed = _plan(("sit", "sofa"), ("sleep", "bed"))
    assert [s.action for s in to_bed.segments][-2:] == ["lie_down", "sleep"]


def test_standing_at_a_thing_across_the_room_walks_there_first():
    """ "Stands in front of the bed" while standing 4 m away: a walk to the bed, then the hold (was: the
    hold where she stood); next to it already, only the hold."""
    far = _plan(("stand", "bed"))
    assert [(s.kind, s.action) for s in far.segments][-1] == ("wait", "stand")
    assert any(s.kind == "locomotion" for s in far.segments)
    near = _plan(("stand", "bed"), start=(2.5, -1.2, 0.0))
    assert [(s.kind, s.action) for s in near.segments] == [("wait", "stand")]
