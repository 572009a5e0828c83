"""Seats far enough apart: no two sitters' hips, or knees, in one another (services/orchestrator/slotting.py)."""

from __future__ import annotations

import math

import numpy as np

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode
from services.orchestrator.slotting import ELBOW_M, KNEE_M, KNEE_OUT_M, Slotting, seat_points
from wana.assets.catalog import asset_for, to_world

ROOM = Room(room_type="living_room", width=8, depth=8, height=3)
SIT_ON = ActionNode(verb="sit", action="sit", target="sofa")


def _sofa_with_a_lamp_on_its_end(*more: PlacedObject) -> Scene:
    sofa = PlacedObject(id="sofa", category="sofa", position=(0.0, 0.0, 0.0))
    end = to_world(sofa, np.asarray(asset_for(sofa).contact_points["sit_2"].position, float))
    lamp = PlacedObject(
        id="lamp", category="laptop", position=(float(end[0]), 0.45, float(end[2])), support="sofa"
    )
    return Scene(room=ROOM, objects=[sofa, lamp, *more])


def test_the_second_on_a_sofa_with_only_the_cushion_beside_the_first_free_takes_a_sofa_beside_it():
    second = PlacedObject(id="sofa/2", category="sofa", position=(2.6, 0.0, 0.0))
    slotting = Slotting(_sofa_with_a_lamp_on_its_end(second))
    jenny, forrest = slotting.claim("Jenny", SIT_ON), slotting.claim("Forrest", SIT_ON)
    assert jenny.action.target == "sofa" and jenny.seat == ""  # the middle cushion
    hips = seat_points(slotting.scene.objects[0], ["sit", "sit_0"])
    assert math.dist(*hips) < ELBOW_M  # the free end cushion is shoulder in shoulder with her
    assert forrest.action.target == "sofa/2"


def test_with_no_other_sofa_the_second_sits_on_the_cushion_beside_the_first():
    slotting = Slotting(_sofa_with_a_lamp_on_its_end())
    slotting.claim("Jenny", SIT_ON)
    forrest = slotting.claim("Forrest", SIT_ON)
    assert forrest.action.target == "sofa" and forrest.seat == "sit_0"


# Two chairs at a small table's corner (one along each side: hips apart, knees under the corner) and one
# across the table from them.
CORNER = Scene(
    room=ROOM,
    objects=[
        PlacedObject(id="table", category="dining_table", position=(0.0, 0.0, 0.3), scale=(0.6, 1.0, 0.6)),
        PlacedObject(id="left", category="chair", position=(-0.6, 0.0, 0.0), yaw=math.pi / 2),
        PlacedObject(id="front", category="chair", position=(0.0, 0.0, -0.6)),
        PlacedObject(id="across", category="chair", position=(0.0, 0.0, 1.2), yaw=math.pi),
    ],
)
SIT_AT = ActionNode(verb="sit", action="sit", target="table")


def test_a_chair_whose_knees_meet_a_sitters_at_a_corner_is_passed_over_for_a_free_one():
    chairs = {o.id: o for o in CORNER.objects}
    left, front = seat_points(chairs["left"], ["sit"])[0], seat_points(chairs["front"], ["sit"])[0]
    knees = [seat_points(chairs[c], ["sit"], KNEE_OUT_M)[0] for c in ("left", "front")]
    assert math.dist(left, front) >= ELBOW_M and math.dist(*knees) < KNEE_M  # hips apart, legs in legs
    slotting = Slotting(CORNER)
    eve, john = slotting.claim("Eve", SIT_AT), slotting.claim("John", SIT_AT)
    assert eve.action.target == "left"
    assert john.action.target == "across"


def _sitters(names: list[str]) -> tuple[list[tuple[float, float]], list[tuple[float, float]]]:
    """Hips and knees of ``names`` sitting on one three-seat sofa, all told before (Slotting.expect)."""
    sofa = PlacedObject(id="sofa", category="sofa", position=(0.0, 0.0, 0.0))
    slotting = Slotting(Scene(room=ROOM, objects=[sofa]))
    for name in names:
        slotting.expect(name, SIT_ON)
    seats = [slotting.claim(name, SIT_ON).seat or "sit" for name in names]
    assert len(set(seats)) == len(names)  # each a cushion of its own
    return seat_points(sofa, seats), seat_points(sofa, seats, KNEE_OUT_M)


def test_two_on_a_three_seat_sofa_take_its_ends_hips_and_knees_apart():
    hips, knees = _sitters(["Mary", "Zoe"])
    assert math.dist(*hips) >= ELBOW_M
    assert math.dist(*knees) >= KNEE_M


def test_three_on_a_three_seat_sofa_take_a_cushion_each():
    hips, _ = _sitters(["Mary", "Zoe", "Ann"])
    gaps = sorted(math.dist(a, b) for i, a in enumerate(hips) for b in hips[i + 1 :])
    assert gaps[0] >= 0.4  # neighbours a cushion apart, not on one another's lap
