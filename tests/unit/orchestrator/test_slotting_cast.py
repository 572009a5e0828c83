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


STATUE = Scene(
    room=ROOM, objects=[PlacedObject(id="counter", category="kitchen_counter", position=(0.0, 0.0, 2.0))]
)
WALK_TO = ActionNode(verb="walk", action="walk", destination="counter")


def _crosses(a0, a1, b0, b1) -> bool:
    """True when the segments a0-a1 and b0-b1 cross."""

    def side(p, q, r):
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])

    return side(a0, a1, b0) * side(a0, a1, b1) < 0 and side(b0, b1, a0) * side(b0, b1, a1) < 0


def test_shortest_sharing_out_gives_each_walker_the_slot_on_its_own_side():
    from services.orchestrator.slotting import matched

    walkers = [(-1.0, 0.0), (1.0, 0.0)]
    slots = [(1.0, 2.0), (-1.0, 2.0)]
    assert matched(walkers, slots) == 1  # the left walker takes the left slot, not the first one
    assert matched(walkers, slots[:1]) is None  # fewer slots than walkers: nothing to share out


def test_two_walking_to_one_counter_together_do_not_cross_each_others_way():
    for left_first in (True, False):
        slotting = Slotting(STATUE)
        for who in ("Mary", "John"):
            slotting.expect(who, WALK_TO)
        here = (
            {"Mary": (-0.9, -1.0), "John": (0.9, -1.0)}
            if left_first
            else {"Mary": (0.9, -1.0), "John": (-0.9, -1.0)}
        )
        mary = slotting.claim("Mary", WALK_TO, here["Mary"], [here["John"]])
        john = slotting.claim("John", WALK_TO, here["John"])
        assert mary.spot is not None and john.spot is not None
        assert math.dist(mary.spot, john.spot) >= 0.6
        assert not _crosses(here["Mary"], mary.spot, here["John"], john.spot)


def test_a_stand_slot_where_someone_already_stands_is_passed_over():
    slotting = Slotting(COUNTER)
    slotting.expect("Ben", EAT)
    plain = slotting.claim("Ben", EAT)
    assert plain.spot is None  # alone: the planner's own spot
    slotting = Slotting(COUNTER)
    slotting.expect("Ben", EAT)
    from wana.domain.slots import stand_slots

    default = stand_slots(COUNTER.objects[0], rows=2)[0]
    moved = slotting.claim("Ben", EAT, crowd=[default])  # Nora stands on the planner's spot
    assert moved.spot is not None and math.dist(moved.spot, default) >= 0.75


# A long conference table (3 m along x) with its chairs at its two ends: far from its middle, at its edge.
LONG_TABLE = Scene(
    room=ROOM,
    objects=[
        PlacedObject(id="conference_table", category="conference_table", position=(0.0, 0.0, 0.0)),
        PlacedObject(id="chair", category="chair", position=(1.9, 0.0, 0.0), yaw=-math.pi / 2),
        PlacedObject(id="chair/2", category="chair", position=(-1.9, 0.0, 0.0), yaw=math.pi / 2),
        PlacedObject(id="stool", category="stool", position=(3.5, 0.0, 3.0)),
    ],
)
SIT_AT = ActionNode(verb="sit", action="sit", target="conference_table")


def test_two_sitting_at_a_long_table_each_get_a_chair_at_its_ends():
    slotting = Slotting(LONG_TABLE)
    for who in ("Walter", "Cheryl"):
        slotting.expect(who, SIT_AT)
    walter = slotting.claim("Walter", SIT_AT, here=(1.0, 1.5), company=[(-1.0, 1.5)])
    cheryl = slotting.claim("Cheryl", SIT_AT, here=(-1.0, 1.5))
    # each a chair at the table (0.4 m from its end, 1.9 m from its middle), not the stool far off
    assert {walter.action.target, cheryl.action.target} == {"chair", "chair/2"}


def test_three_walking_to_a_window_behind_a_sofa_each_get_a_spot_of_their_own():
    # the window's first row of stand slots is behind the sofa: the rows further out hold all three
    scene = Scene(
        room=ROOM,
        objects=[
            PlacedObject(id="window", category="window", position=(0.0, 0.9, 3.94), yaw=math.pi),
            PlacedObject(id="sofa", category="sofa", position=(0.0, 0.0, 3.3), yaw=math.pi),
        ],
    )
    to_window = ActionNode(verb="walk", action="walk", destination="window")
    slotting = Slotting(scene)
    for who in ("Ada", "Ben", "Eve"):
        slotting.expect(who, to_window)
    spots = [slotting.claim(who, to_window).spot for who in ("Ada", "Ben", "Eve")]
    assert all(s is not None for s in spots)
    assert min(math.dist(a, b) for i, a in enumerate(spots) for b in spots[i + 1 :]) >= 0.6  # type: ignore[arg-type]


# A dining table with three chairs around it: two on its near side, one on its far side.
DINING = Scene(
    room=ROOM,
    objects=[
        PlacedObject(id="dining_table", category="dining_table", position=(0.0, 0.0, 0.0)),
        PlacedObject(id="chair", category="chair", position=(-0.5, 0.0, 0.75), yaw=math.pi),
        PlacedObject(id="chair/2", category="chair", position=(-0.5, 0.0, -0.75)),
        PlacedObject(id="chair/3", category="chair", position=(0.4, 0.0, 0.75), yaw=math.pi),
    ],
)
SIT_AT_DINING = ActionNode(verb="sit", action="sit", target="dining_table")


def test_two_sitting_at_a_table_together_take_the_chairs_on_their_own_sides():
    # "Tom and Sam sit at the table": the first shares the chairs out with the second, the second takes
    # what that left it (the chair nearest to it), so their walks to the chairs do not cross
    for tom_near in (True, False):
        slotting = Slotting(DINING)
        for who in ("Tom", "Sam"):
            slotting.expect(who, SIT_AT_DINING)
        near, far = (-1.5, 1.2), (-1.5, -1.2)
        here = {"Tom": near, "Sam": far} if tom_near else {"Tom": far, "Sam": near}
        tom = slotting.claim("Tom", SIT_AT_DINING, here["Tom"], [here["Sam"]])
        sam = slotting.claim("Sam", SIT_AT_DINING, here["Sam"], joined=True)
        chairs = {o.id: (o.position[0], o.position[2]) for o in DINING.objects}
        assert tom.action.target != sam.action.target
        assert {tom.action.target, sam.action.target} == {"chair", "chair/2"}
        assert not _crosses(here["Tom"], chairs[tom.action.target], here["Sam"], chairs[sam.action.target])
        assert chairs[tom.action.target][1] * here["Tom"][1] > 0  # each the chair on its own side


def test_two_walking_to_one_painting_stand_side_by_side_in_its_front_row():
    scene = Scene(
        room=ROOM,
        objects=[PlacedObject(id="painting", category="painting", position=(0.0, 1.3, -3.9))],
    )
    to_it = ActionNode(verb="walk", action="walk", destination="painting")
    slotting = Slotting(scene)
    for who in ("Mary", "John"):
        slotting.expect(who, to_it)
    mary = slotting.claim("Mary", to_it, (-1.0, 1.0), [(1.0, 1.0)])
    john = slotting.claim("John", to_it, (1.0, 1.0), joined=True)
    assert mary.spot is not None and john.spot is not None
    assert abs(mary.spot[1] - john.spot[1]) < 1e-6  # one row, the front one (not one behind the other)
    assert math.dist(mary.spot, john.spot) >= 0.6


# A counter with a stool standing in front of its middle, and one who will sit on it.
STOOL_AT_COUNTER = Scene(
    room=ROOM,
    objects=[
        PlacedObject(id="counter", category="kitchen_counter", position=(0.0, 0.0, -1.5)),
        PlacedObject(id="stool", category="stool", position=(0.45, 0.0, -0.75)),
    ],
)


def test_one_at_a_counter_keeps_clear_of_the_stool_another_will_sit_on():
    sit = ActionNode(verb="sit", action="sit", target="stool")
    slotting = Slotting(STOOL_AT_COUNTER)
    slotting.expect("Hana", EAT)
    slotting.expect("Kofi", sit)
    hana = slotting.claim("Hana", EAT)
    assert hana.spot is not None and math.dist(hana.spot, (0.45, -0.75)) >= 0.75
    alone = Slotting(STOOL_AT_COUNTER)  # nobody sits there: the planner's own spot, as before
    alone.expect("Hana", EAT)
    assert alone.claim("Hana", EAT).spot is None
