"""The door, entrances, exits and starting spots (services/orchestrator/staging.py)."""

from __future__ import annotations

import numpy as np
import pytest

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode
from services.orchestrator.staging import (
    APART_M,
    doorway,
    first_spot,
    is_entrance,
    is_exit,
    kept_clear,
    presence,
    route,
    spot_near,
    with_door,
)
from wana.domain.object_geometry import scene_footprints
from wana.domain.routes import occupancy_grid

ROOM = Room(room_type="living_room", width=5.0, depth=4.0, height=2.8)


def act(verb: str, action: str = "walk", target: str = "") -> ActionNode:
    return ActionNode(verb=verb, action=action, target=target)


@pytest.mark.parametrize("verb", ["walk in", "enter", "come in", "run in", "walk into"])
def test_entrance_verbs(verb):
    assert is_entrance(act(verb)) and not is_exit(act(verb))


@pytest.mark.parametrize("verb", ["leave", "go out", "walk out", "run out", "exit"])
def test_exit_verbs(verb):
    assert is_exit(act(verb)) and not is_entrance(act(verb))


def test_walking_to_the_door_is_neither_an_entrance_nor_an_exit():
    walk = act("walk", target="door")
    assert not is_entrance(walk) and not is_exit(walk)


def test_an_empty_room_gets_a_door_on_a_wall_facing_into_the_room():
    scene = with_door(Scene(room=ROOM))
    door = doorway(scene)
    assert door is not None
    (placed,) = [o for o in scene.objects if o.category == "door"]
    x, z = placed.position[0], placed.position[2]
    assert min(ROOM.width / 2 - abs(x), ROOM.depth / 2 - abs(z)) < 0.1  # against a wall
    inside = np.array(door.inside(1.0))
    assert abs(inside[0]) < ROOM.width / 2 and abs(inside[1]) < ROOM.depth / 2
    front = np.array([np.sin(placed.yaw), np.cos(placed.yaw)])
    assert front @ door.inward > 0.99  # the door's front faces the room


def test_a_room_that_has_a_door_keeps_it_and_gets_no_second():
    door = PlacedObject(id="door", category="door", position=(2.4, 0.0, 0.0), yaw=-np.pi / 2)
    scene = Scene(room=ROOM, objects=[door])
    assert with_door(scene) is scene
    assert np.allclose(doorway(scene).inward, (-1.0, 0.0))


def test_the_added_door_leaves_its_way_in_free_of_furniture():
    sofa = PlacedObject(id="sofa", category="sofa", position=(-2.0, 0.0, 0.0), yaw=np.pi / 2)
    scene = with_door(Scene(room=ROOM, objects=[sofa]))
    door = doorway(scene)
    grid = occupancy_grid(ROOM, scene_footprints(scene), radius=0.25)
    assert all(grid.is_free_xz(np.array(door.inside(d))) for d in (0.5, 1.0))


def test_a_door_whose_way_in_is_blocked_gets_a_second_one_that_entrances_use():
    door = PlacedObject(id="ctx_door", category="door", position=(2.4, 0.0, 0.0), yaw=-np.pi / 2)
    toilet = PlacedObject(id="toilet", category="toilet", position=(1.9, 0.0, 0.0), yaw=-np.pi / 2)
    scene = with_door(Scene(room=ROOM, objects=[door, toilet]))  # the toilet stands in the door's way in
    doors = [o for o in scene.objects if o.category == "door"]
    assert len(doors) == 2
    way = doorway(scene)
    assert not np.allclose(way.centre, (2.4, 0.0))
    grid = occupancy_grid(ROOM, scene_footprints(scene), radius=0.25)
    assert all(grid.is_free_xz(np.array(way.inside(d))) for d in (0.5, 1.0))
    assert with_door(scene) is scene  # and no third


def test_a_hidden_character_waits_outside_the_room_and_each_at_its_own_place():
    door = doorway(with_door(Scene(room=ROOM)))
    places = [np.array(door.outside(i)) for i in range(3)]
    for p in places:
        assert abs(p[0]) > ROOM.width / 2 or abs(p[1]) > ROOM.depth / 2
    assert min(np.linalg.norm(a - b) for i, a in enumerate(places) for b in places[i + 1 :]) >= 0.6


def test_starting_spots_are_free_apart_and_near_what_each_first_acts_on():
    desk = PlacedObject(id="desk", category="desk", position=(1.5, 0.0, 1.2), yaw=np.pi)
    scene = Scene(room=ROOM, objects=[desk])
    taken: list[tuple[float, float]] = []
    spots = []
    for _ in range(3):
        s = first_spot(scene, act("type", "type", target="desk"), taken)
        taken.append((s[0], s[1]))
        spots.append(np.array(s[:2]))
    grid = occupancy_grid(ROOM, scene_footprints(scene), radius=0.25)
    assert all(grid.is_free_xz(p) for p in spots)
    assert min(np.linalg.norm(a - b) for i, a in enumerate(spots) for b in spots[i + 1 :]) >= APART_M - 1e-6
    assert all(np.linalg.norm(p - np.array([1.5, 1.2])) < 2.1 for p in spots)
    xs, zs = [p[0] for p in spots], [p[1] for p in spots]
    assert np.ptp(xs) > 0.2 and np.ptp(zs) > 0.2  # not a line-up along one wall


def test_a_spot_near_a_point_faces_it():
    x, z, yaw = spot_near(Scene(room=ROOM), (0.0, 0.0), [])
    assert np.allclose([np.sin(yaw), np.cos(yaw)], -np.array([x, z]) / np.hypot(x, z), atol=1e-3)


def test_a_start_the_optimiser_slid_a_table_onto_moves_to_the_nearest_free_spot_and_keeps_its_facing():
    table = PlacedObject(id="table", category="table", position=(0.0, 0.0, 0.0), yaw=0.0)
    scene = Scene(room=ROOM, objects=[table])
    starts = {"Lily": (0.05, 0.1, 1.0), "Max": (1.9, 1.5, 0.5), "Eve": (0.0, 0.0, 0.2)}
    got = kept_clear(scene, starts, hidden=["Eve"])
    grid = occupancy_grid(ROOM, scene_footprints(scene), radius=0.3)
    assert got["Max"] == starts["Max"] and got["Eve"] == starts["Eve"]  # free, and waiting outside
    assert grid.is_free_xz(np.array(got["Lily"][:2])) and got["Lily"][2] == 1.0
    assert np.linalg.norm(np.array(got["Lily"][:2]) - np.array(got["Max"][:2])) >= APART_M - 1e-6
    assert np.linalg.norm(np.array(got["Lily"][:2]) - np.array([0.05, 0.1])) < 1.0  # beside the table


def test_a_start_boxed_in_by_furniture_steps_out_past_the_tables_not_through_them():
    tables = [
        PlacedObject(id="table", category="table", position=(1.3, 0.0, 1.2), yaw=0.0),
        PlacedObject(id="table#2", category="table", position=(2.1, 0.0, 0.55), yaw=np.pi / 2),
    ]
    scene = Scene(room=ROOM, objects=tables)
    way = np.array(route(scene, (2.3, 1.75), (-2.0, -1.5)))
    solid = occupancy_grid(ROOM, scene_footprints(scene), radius=0.0)
    t = np.linspace(0.0, 1.0, 50)[:, None]
    along = np.concatenate([a + t * (b - a) for a, b in zip(way[:-1], way[1:], strict=True)])
    assert len(way) > 2 and solid.is_free_xz(along).all()  # the straight line crosses the first table


def test_presence_starts_at_the_first_action_and_ends_after_an_exit():
    actions = [act("walk in"), act("wave", "wave"), act("leave"), act("come in")]
    on = presence(100, [10, 30, 50, 80], [20, 20, 20, 10], actions, on_at_zero=False)
    assert not on[:10].any() and on[10:70].all() and not on[70:80].any() and on[80:].all()


def test_a_character_on_stage_from_the_start_is_present_from_frame_zero():
    on = presence(40, [15], [10], [act("wave", "wave")], on_at_zero=True)
    assert on.all()


@pytest.mark.parametrize(
    "node",
    [
        ActionNode(verb="walk", action="walk"),  # "Mary and John walk in": the parser drops "in"
        ActionNode(verb="walk", action="walk", destination="workshop"),  # "Sam walks into the workshop"
        ActionNode(verb="walk", action="walk", destination="room"),
    ],
)
def test_a_walk_onto_the_stage_or_into_the_room_itself_is_an_entrance(node):
    assert is_entrance(node)


def test_walking_to_a_sofa_is_no_entrance():
    assert not is_entrance(ActionNode(verb="walk", action="walk", destination="sofa"))


def test_those_who_come_in_side_by_side_head_in_on_their_own_sides_apart():
    door = doorway(with_door(Scene(room=ROOM)))
    starts = [door.inside(beside=b) for b in range(3)]
    goals = [np.array(door.way_in(s)) for s in starts]
    for s, g in zip(starts, goals, strict=True):
        assert np.sign(door.side_of(s)) == np.sign(door.side_of(tuple(g)))  # no one crosses to the other side
    assert min(np.linalg.norm(a - b) for i, a in enumerate(goals) for b in goals[i + 1 :]) >= APART_M - 1e-6


def test_a_door_the_text_did_not_name_is_reported_on_the_first_entrance():
    from proto.ssg import CharacterNode
    from services.orchestrator.document import Sentence
    from services.orchestrator.stages.motion import _door_added

    sentences = [Sentence("s1", 0, 12, "Tom waves."), Sentence("s2", 13, 30, "Ms Lee enters.")]
    characters = {
        "Tom": (CharacterNode(name="Tom", actions=[act("wave", "wave")]), ["s1"]),
        "Ms Lee": (CharacterNode(name="Ms Lee", actions=[act("enter")]), ["s2"]),
    }
    added = with_door(Scene(room=ROOM))
    ((sid, note),) = _door_added(added, characters, sentences, {"Ms Lee"})
    assert sid == "s2" and "door" in note.message and "Ms Lee" in note.message
    named = PlacedObject(id="door", category="door", position=(2.4, 0.0, 0.0), yaw=-np.pi / 2)
    assert _door_added(Scene(room=ROOM, objects=[named]), characters, sentences, {"Ms Lee"}) == []
