"""Walks go round the characters standing in the way (SynthesizeRequest.bodies, routing.scene_route)."""

from __future__ import annotations

import numpy as np

from proto.common import Header
from proto.motion import SynthesizeRequest
from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.handlers import CONTRACT
from services.motion.routing import BODY_M, RADIUS, scene_route
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
