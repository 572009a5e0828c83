"""Routes around furniture, the contact point each clip aims at, seated end states and the typing pose."""

from __future__ import annotations

import numpy as np
import pytest

from proto.common import Header
from proto.motion import SynthesizeRequest
from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.handlers import handle_synthesize
from services.motion.ik import global_transforms
from services.motion.planning import _object_geometry, contact_targets, plan_actions, straight_route
from services.motion.routing import plan_scene_route
from services.motion.synthesis import synthesise
from wana.arrays import from_wire
from wana.assets.catalog import make_object, to_world, world_collision_boxes
from wana.domain.actions import get_clip
from wana.domain.skeleton import JOINT_INDEX

ROOM = Room(room_type="office", width=6, depth=6, height=3)
TABLE = PlacedObject(id="table", category="dining_table", position=(0.0, 0.0, 0.0))
DOOR = PlacedObject(id="door", category="door", position=(0.0, 0.0, 2.95), yaw=np.pi)


def _inside_footprints(xz: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """(N,) bool: points (N, 2) inside any box's (B, 2, 3) x/z footprint."""
    lo, hi = boxes[:, 0, [0, 2]], boxes[:, 1, [0, 2]]
    return ((xz[:, None] > lo[None]) & (xz[:, None] < hi[None])).all(-1).any(-1)


def _walk_to_door(route_fn=None) -> tuple[np.ndarray, np.ndarray]:  # noqa: ANN001
    scene = Scene(room=ROOM, objects=[TABLE, DOOR])
    eve = CharacterNode(name="Eve", actions=[ActionNode(verb="walk", action="walk", destination="door")])
    plan = plan_actions(eve, scene, (0.0, -2.5, 0.0), route_fn)
    motion, _, _ = synthesise(plan)
    return np.asarray(plan.segments[0].waypoints), from_wire(motion.root_position)[:, [0, 2]].astype(float)


def test_a_walk_past_a_table_goes_around_it_and_never_enters_its_boxes():
    boxes = world_collision_boxes(TABLE)
    waypoints, hips = _walk_to_door()
    assert len(waypoints) > 2  # it turned around the table
    assert not _inside_footprints(hips, boxes).any()
    assert np.linalg.norm(hips[-1] - waypoints[-1]) < 0.05
    _, straight = _walk_to_door(straight_route)
    assert _inside_footprints(straight, boxes).any()  # the straight line would have crossed it


def test_cached_routes_equal_the_optimizer_routes_and_follow_a_moved_object():
    from wana.domain.routes import plan_route

    chair = PlacedObject(id="chair", category="chair", position=(1.0, 0.0, 0.0))
    for chair_x in (1.0, -0.2, 1.0):  # the grid must follow the chair, and come back from the cache
        scene = Scene(
            room=ROOM,
            objects=[TABLE, DOOR, PlacedObject(id="chair", category="chair", position=(chair_x, 0.0, 1.2))],
        )
        for start, goal, ignore in (
            ((0.0, -2.5), (0.0, 2.3), frozenset()),
            ((2.0, -2.0), (-1.5, 2.0), frozenset({"table"})),
            ((-2.0, 0.0), (chair.position[0], 1.0), frozenset({"chair"})),
        ):
            mine = plan_scene_route(scene, start, goal, ignore=ignore)
            ref = plan_route(scene, np.asarray(start), np.asarray(goal), ignore=ignore)
            assert mine.shape == ref.shape and np.allclose(mine, ref)


def test_no_route_walks_straight_and_says_so():
    walls = [
        PlacedObject(id=f"shelf{i}", category="bookshelf", position=(x, 0.0, 0.0))
        for i, x in enumerate(np.arange(-2.6, 2.8, 0.6))
    ]
    scene = Scene(room=ROOM, objects=walls)
    eve = CharacterNode(name="Eve", actions=[ActionNode(verb="walk", action="walk", destination="door")])
    scene_door = Scene(room=ROOM, objects=[*walls, DOOR])
    reply = handle_synthesize(
        SynthesizeRequest(header=Header(), character=eve, scene=scene_door, start=(0.0, -2.5, 0.0))
    )
    assert any("no free walking route" in d for d in reply.diagnostics)
    assert reply.status == "ok" and scene.objects


@pytest.mark.parametrize(
    ("action", "category", "point"),
    [
        ("type", "laptop", "type"),
        ("type", "keyboard", "type"),
        ("play_piano", "piano", "play"),
        ("play_drums", "drum_kit", "play"),
        ("punch_bag", "boxing_bag", "punch"),
        ("write_on_blackboard", "blackboard", "write"),
        ("use_mouse", "mouse", "click"),
        ("open_door", "door", "open"),
        ("type", "desk", "write"),
    ],
)
def test_each_clip_aims_at_the_catalog_point_meant_for_it(action, category, point):
    placed = PlacedObject(id=category, category=category, position=(0.5, 0.0, 1.0), yaw=0.3)
    geo = _object_geometry(placed)
    assert geo is not None
    targets = contact_targets(get_clip(action), geo[1])
    cp = make_object(category).contact_points[point]
    expected = {cp.joint: cp.position, **cp.extra}
    assert set(targets) == set(expected)
    for joint, p in expected.items():
        assert np.allclose(targets[joint], to_world(placed, np.asarray(p, float)), atol=1e-9)


def _desk_chair_laptop(gap: float) -> Scene:
    """A desk facing +Z, a laptop 0.25 m behind its front edge, an office chair facing it ``gap`` m in front."""
    desk, chair = make_object("desk"), make_object("office_chair")
    front = float(desk.dims[2]) / 2
    return Scene(
        room=ROOM,
        objects=[
            PlacedObject(id="desk", category="desk", position=(0.0, 0.0, 0.0)),
            PlacedObject(
                id="laptop",
                category="laptop",
                position=(0.0, float(desk.dims[1]), front - 0.25),
                support="desk",
            ),
            PlacedObject(
                id="chair",
                category="office_chair",
                position=(0.0, 0.0, front + gap + float(chair.dims[2]) / 2),
                yaw=np.pi,
            ),
        ],
    )


def _seated_story(scene: Scene, *after: ActionNode):  # noqa: ANN202
    eve = CharacterNode(name="Eve", actions=[ActionNode(verb="sit", action="sit", target="chair"), *after])
    plan = plan_actions(eve, scene, (2.0, 2.0, np.pi))
    motion, pieces, states = synthesise(plan)
    pos, _ = global_transforms(
        from_wire(motion.rotations).astype(float), from_wire(motion.root_position).astype(float)
    )
    return plan, pieces, states, pos


def test_seated_actions_keep_the_hips_on_the_seat_even_when_the_walk_stopped_short():
    scene = _desk_chair_laptop(
        gap=-0.05
    )  # chair pushed in: the spot in front of the seat is inside the desk's clearance
    plan, pieces, states, pos = _seated_story(
        scene, ActionNode(verb="wave", action="wave"), ActionNode(verb="read", action="read")
    )
    seat = np.asarray(dict(plan.segments[1].targets)["Hips"])
    walk_end = np.asarray(plan.segments[0].waypoints[-1])
    chair = next(o for o in scene.objects if o.id == "chair")
    approach = seat[[0, 2]] + 0.22 * np.array([np.sin(chair.yaw), np.cos(chair.yaw)])
    assert np.linalg.norm(walk_end - approach) > 0.15  # the spot in front of the seat was not reached
    sit_end = states[1]
    f0 = len(pieces[0].root) + len(pieces[1].root)
    for piece, state in zip(pieces[2:], states[2:], strict=True):
        hips = pos[f0 : f0 + len(piece.root), JOINT_INDEX["Hips"]]
        assert state.posture == "sit" and (state.x, state.z) == (sit_end.x, sit_end.z)
        assert np.linalg.norm(hips[:, [0, 2]] - seat[[0, 2]], axis=1).max() < 0.05
        assert np.abs(hips[:, 1] - seat[1]).max() < 0.03
        f0 += len(piece.root)


def test_typing_at_a_laptop_puts_the_fingers_on_the_keys_with_bent_elbows():
    scene = _desk_chair_laptop(gap=0.15)
    plan, pieces, _, pos = _seated_story(
        scene, ActionNode(verb="type", action="type", target="laptop", duration_s=3.0)
    )
    laptop = next(o for o in scene.objects if o.id == "laptop")
    keys = make_object("laptop").contact_points["type"]
    f0 = sum(len(p.root) for p in pieces[:-1])
    frames, _ = pieces[-1].contact_frames["RightHandMiddle1"]
    assert len(frames) > 30
    for side, local in (("Right", keys.position), ("Left", keys.extra["LeftHandMiddle1"])):
        key = to_world(laptop, np.asarray(local, float))
        finger = pos[f0 + frames, JOINT_INDEX[f"{side}HandMiddle1"]]
        assert np.linalg.norm(finger - key, axis=1).max() < 0.03
        shoulder, elbow, wrist = (
            pos[f0 + frames, JOINT_INDEX[f"{side}{j}"]] for j in ("Arm", "ForeArm", "Hand")
        )
        u, v = shoulder - elbow, wrist - elbow
        angle = np.degrees(
            np.arccos(np.einsum("ij,ij->i", u, v) / np.linalg.norm(u, axis=1) / np.linalg.norm(v, axis=1))
        )
        assert angle.max() < 130.0 and angle.min() > 70.0  # bent, not stretched out, not folded
    neck = pos[f0 + frames, JOINT_INDEX["Neck"]] - pos[f0 + frames, JOINT_INDEX["Hips"]]
    lean = np.degrees(np.arctan2(np.linalg.norm(neck[:, [0, 2]], axis=1), neck[:, 1]))
    assert lean.max() < 45.0  # leaning in, not folded over the desk


def test_a_walk_to_the_far_side_of_a_table_goes_round_it_not_over_it():
    from services.motion.routing import _scene_route, passes_through, scene_route

    scene = Scene(room=ROOM, objects=[TABLE, DOOR])
    boxes = world_collision_boxes(TABLE)
    far = (0.0, float(boxes[:, 1, 2].max()) + 0.3)  # just past the table's +Z edge
    start = (0.0, float(boxes[:, 0, 2].min()) - 0.8)  # in front of its -Z edge
    ignore = frozenset({"table"})  # the object walked to does not block the end of the walk
    old, _ = _scene_route(scene, start, far, ignore)
    assert passes_through(scene, old, ignore)  # ignoring it, the straight line leads over the top
    way, why = scene_route(scene, start, far, ignore)
    assert why == "" and len(way) > 2
    assert np.allclose(way[-1], far)
    assert not passes_through(scene, way, ignore)
    pts = np.vstack([np.linspace(a, b, 20) for a, b in zip(way[:-1], way[1:], strict=True)])
    assert not _inside_footprints(pts, boxes).any()
