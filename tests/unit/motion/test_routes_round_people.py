"""Walks go round the characters standing in the way (SynthesizeRequest.bodies, routing.scene_route)."""

from __future__ import annotations

import numpy as np

from proto.common import Header
from proto.motion import SynthesizeRequest
from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.handlers import CONTRACT
from services.motion.routing import BODY_M, PASS_BY_M, RADIUS, scene_route
from wana.arrays import from_wire
from wana.bus.service import call_in_process

ROOM = Room(room_type="office", width=8, depth=8, height=3)
EMPTY = Scene(room=ROOM, objects=[])
PETE = (0.0, 0.0)  # stands in the middle of the room, on the straight line below


def _distance_to_polyline(points: np.ndarray, p: tuple[float, float]) -> float:
    best = np.inf
    for a, b in zip(points[:-1], points[1:], strict=True):
        ab = b - a
        t = np.clip(np.dot(np.asarray(p) - a, ab) / max(float(ab @ ab), 1e-12), 0.0, 1.0)
        best = min(best, float(np.linalg.norm(a + t * ab - np.asarray(p))))
    return best


def test_a_route_goes_round_someone_standing_on_the_straight_line():
    straight, _ = scene_route(EMPTY, (-3.0, 0.0), (3.0, 0.0))
    assert _distance_to_polyline(straight, PETE) < 0.05  # alone, the straight line goes through him
    around, why = scene_route(EMPTY, (-3.0, 0.0), (3.0, 0.0), bodies=[PETE])
    assert why == ""
    assert _distance_to_polyline(around, PETE) >= RADIUS + BODY_M - 0.05
    assert np.allclose(around[-1], (3.0, 0.0))


def test_someone_at_the_goal_is_walked_up_to_not_round():
    route, _ = scene_route(EMPTY, (-3.0, 0.0), (0.5, 0.0), bodies=[PETE])  # Pete stands right at the goal
    assert np.allclose(route[-1], (0.5, 0.0))


def test_a_walk_synthesised_with_bodies_never_passes_through_them():
    req = SynthesizeRequest(
        header=Header(),
        character=CharacterNode(
            name="Sam", actions=[ActionNode(verb="walk", action="walk", destination="desk")]
        ),
        scene=Scene(
            room=ROOM, objects=[PlacedObject(id="desk", category="desk", position=(3.0, 0.0, 0.0), yaw=0.0)]
        ),
        start=(-3.0, 0.0, np.pi / 2),
        bodies=[PETE],
    )
    reply = call_in_process(CONTRACT, req)
    hips = from_wire(reply.motion.root_position)[:, [0, 2]]
    assert float(np.linalg.norm(hips - np.asarray(PETE), axis=1).min()) > 0.4


ARMCHAIR = Scene(
    room=Room(room_type="living_room", width=6, depth=5, height=2.8),
    objects=[PlacedObject(id="armchair", category="armchair", position=(-0.62, 0.0, -0.49), yaw=-np.pi / 2)],
)


def test_walking_up_to_someone_behind_the_armchair_stops_short_of_them_not_inside_them():
    from services.motion.routing import reachable_short_of, scene_grid

    tom, ben = (-0.89, -0.49), (0.21, -0.35)  # Tom gets up from the armchair, Ben stands behind it
    stop = reachable_short_of(ARMCHAIR, tom, ben, 0.45)
    assert stop is not None  # the point short of Ben on the straight line is inside the armchair
    assert abs(np.hypot(stop[0] - ben[0], stop[1] - ben[1]) - 0.45) < 1e-6
    assert scene_grid(ARMCHAIR).is_free_xz(np.asarray(stop))
    route, why = scene_route(ARMCHAIR, tom, stop)
    assert why == "" and np.hypot(route[-1][0] - ben[0], route[-1][1] - ben[1]) > 0.4


def test_with_nothing_between_them_the_straight_stop_stands():
    from services.motion.routing import reachable_short_of

    assert reachable_short_of(EMPTY, (-2.0, 0.0), (0.0, 0.0), 0.45) is None


def test_someone_standing_beside_the_goal_is_walked_round_not_through():
    # Ada stands 0.5 m past the goal on the straight line: the walk ends beside her, never through her
    ada = (0.5, 0.0)
    route, why = scene_route(EMPTY, (-3.0, 0.0), (1.0, 0.3), bodies=[ada])
    assert why == ""
    assert np.allclose(route[-1], (1.0, 0.3))
    assert _distance_to_polyline(route, ada) >= 0.3


def test_the_one_stood_beside_when_setting_off_is_not_walked_round():
    route, _ = scene_route(EMPTY, (0.0, 0.4), (3.0, 0.0), bodies=[PETE])
    assert np.allclose(route[0], (0.0, 0.4)) and np.allclose(route[-1], (3.0, 0.0))


def test_someone_in_the_mouth_of_a_nook_is_passed_shoulder_by_shoulder_not_walked_through():
    # two long cabinets from the west wall leave a way 1 m wide for the hips into the nook between them; Pete
    # stands in it: the full disc round him closes the way, a closer pass (PASS_BY_M) does not
    walls = [
        PlacedObject(id=n, category="cabinet", position=(-2.5, 0.0, z), yaw=0.0, scale=(6.0, 1.0, 1.0))
        for n, z in (("north", 1.0), ("south", -1.0))
    ]
    scene = Scene(room=ROOM, objects=walls)
    pete = (-1.0, 0.0)
    route, why = scene_route(scene, (2.0, 0.0), (-2.6, 0.0), bodies=[pete])
    assert why == ""
    assert np.allclose(route[-1], (-2.6, 0.0))
    assert RADIUS + BODY_M > _distance_to_polyline(route, pete) >= min(PASS_BY_M) - 0.05
