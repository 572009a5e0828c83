"""An action at an object is not done from inside someone standing at it (planning's clear_of_bodies)."""

from __future__ import annotations

import numpy as np

from proto.common import Header
from proto.motion import SynthesizeRequest
from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.handlers import CONTRACT
from services.motion.planning import BODY_CLEAR_M
from wana.arrays import from_wire
from wana.bus.service import call_in_process

ROOM = Room(room_type="music_room", width=6, depth=6, height=3)
GUITAR = PlacedObject(id="bass_guitar", category="bass_guitar", position=(0.0, 0.0, 0.0), yaw=0.0)


def _end_hips(bodies: list[tuple[float, float]]) -> np.ndarray:
    req = SynthesizeRequest(
        header=Header(),
        character=CharacterNode(
            name="Leo", actions=[ActionNode(verb="pick up", action="pick_up", target="bass_guitar")]
        ),
        scene=Scene(room=ROOM, objects=[GUITAR]),
        start=(0.0, 2.0, np.pi),
        bodies=bodies,
    )
    reply = call_in_process(CONTRACT, req)
    return from_wire(reply.motion.root_position)[-1, [0, 2]]


def test_the_bass_guitar_is_not_picked_up_from_inside_the_drummer_standing_at_it():
    alone = _end_hips([])
    drummer = (float(alone[0]), float(alone[1]))  # stands right where Leo would pick it up from
    beside = _end_hips([drummer])
    assert float(np.linalg.norm(beside - np.asarray(drummer))) >= BODY_CLEAR_M - 0.05
    assert float(np.hypot(*beside)) <= float(np.hypot(*alone)) + 0.45  # still within reach of it


def test_nobody_near_leaves_the_spot_as_it_was():
    alone = _end_hips([])
    assert np.allclose(_end_hips([(2.5, -2.5)]), alone, atol=1e-3)
