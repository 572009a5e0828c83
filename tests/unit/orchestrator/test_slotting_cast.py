"""Where several characters stand: their own stand slots at one object (services/orchestrator/slotting.py)."""

from __future__ import annotations

import math

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode
from services.orchestrator.slotting import Slotting

ROOM = Room(room_type="office", width=8, depth=8, height=3)
PETE = (0.0, 0.0)


COUNTER = Scene(
    room=ROOM, objects=[PlacedObject(id="counter", category="kitchen_counter", position=(0.0, 0.0, -1.5))]
)
EAT = ActionNode(verb="eat", action="eat", target="counter")


def test_two_eating_at_one_counter_each_get_their_own_stand_slot_apart():
    slotting = Slotting(COUNTER)
    for who in ("Ben", "Nora"):
        slotting.expect(who, EAT)
    ben, nora = slotting.claim("Ben", EAT), slotting.claim("Nora", EAT)
    assert ben.spot is not None and nora.spot is not None  # the first is told its slot too
    assert math.dist(ben.spot, nora.spot) >= 0.6


def test_one_at_a_counter_stands_where_the_planner_puts_it():
    slotting = Slotting(COUNTER)
    slotting.expect("Ben", EAT)
    assert slotting.claim("Ben", EAT).spot is None
