"""Seat and stand slots on catalog furniture, and the book of who holds which."""

from __future__ import annotations

import math

import numpy as np

from proto.scene import PlacedObject
from wana.assets.catalog import asset_for, to_world
from wana.domain.slots import SlotBook, seat_slots, stand_slots


def placed(category: str, yaw: float = 0.0) -> PlacedObject:
    return PlacedObject(id=category, category=category, position=(1.0, 0.0, -0.5), yaw=yaw)


def test_a_sofa_has_three_seat_slots_a_loveseat_two_and_a_chair_one():
    assert seat_slots(placed("sofa")) == ["sit", "sit_0", "sit_2"]
    assert len(seat_slots(placed("loveseat"))) == 2
    assert seat_slots(placed("chair")) == ["sit"]
    assert seat_slots(placed("desk")) == []


def test_a_sofas_seat_slots_are_a_body_width_apart_along_its_seat():
    sofa = placed("sofa", yaw=0.7)
    points = asset_for(sofa).contact_points
    world = np.array([to_world(sofa, np.asarray(points[n].position, float)) for n in seat_slots(sofa)])
    gaps = [np.linalg.norm(world[i] - world[j]) for i in range(3) for j in range(i + 1, 3)]
    assert min(gaps) > 0.45


def test_stand_slots_lie_in_front_of_the_object_and_apart():
    counter = placed("kitchen_counter", yaw=np.pi / 2)  # its front faces +x
    spots = np.array(stand_slots(counter))
    assert len(spots) >= 2
    assert np.all(spots[:, 0] > counter.position[0] + 0.3)
    assert min(np.linalg.norm(a - b) for i, a in enumerate(spots) for b in spots[i + 1 :]) >= 0.6


def test_a_table_has_stand_slots_on_both_sides():
    table = placed("dining_table")
    z = np.array(stand_slots(table))[:, 1]
    assert (z > table.position[2]).any() and (z < table.position[2]).any()


def test_the_book_gives_two_characters_two_slots_and_a_slot_back_when_one_leaves():
    book = SlotBook()
    slots = ["sit", "sit_0", "sit_2"]
    assert book.take("sofa", slots, "Eve") == "sit"
    assert book.take("sofa", slots, "Tom") == "sit_0"
    assert book.take("sofa", slots, "Eve") == "sit"  # asking again keeps one's own
    assert book.take("sofa", slots, "Ada") == "sit_2"
    assert book.take("sofa", slots, "Ben") is None
    book.release("Tom")
    assert book.take("sofa", slots, "Ben") == "sit_0"


def test_taking_a_new_slot_gives_back_the_old_one():
    book = SlotBook()
    book.take("chair", ["sit"], "Eve")
    book.take("sofa", ["sit"], "Eve")
    assert book.holder("chair", "sit") == "" and book.holder("sofa", "sit") == "Eve"


def test_a_second_row_of_stand_slots_lies_behind_the_first():
    window = placed("window")
    one, two = stand_slots(window), stand_slots(window, rows=2)
    assert two[: len(one)] == one and len(two) == 2 * len(one)
    behind = np.array(two[len(one) :])[:, 1]
    assert np.all(behind > max(z for _, z in one) + 0.5)  # the window faces +z: the second row is further out


def test_a_slot_something_rests_on_is_not_offered():
    sofa = placed("sofa")
    middle = to_world(sofa, np.asarray(asset_for(sofa).contact_points["sit"].position, float))
    laptop = PlacedObject(
        id="laptop", category="laptop", position=(float(middle[0]), 0.45, float(middle[2])), support="sofa"
    )
    elsewhere = PlacedObject(id="mug", category="mug", position=(float(middle[0]), 0.0, 2.0))
    assert seat_slots(sofa, "sit", [laptop, elsewhere]) == ["sit_0", "sit_2"]
    assert seat_slots(sofa, "sit", [elsewhere]) == ["sit", "sit_0", "sit_2"]


def test_a_park_bench_seats_two_apart_and_a_piano_bench_one():
    bench = placed("bench")
    assert seat_slots(bench) == ["sit", "sit_0", "sit_2"]  # one alone sits in the middle
    ends = [
        to_world(bench, np.asarray(asset_for(bench).contact_points[n].position, float))
        for n in ("sit_0", "sit_2")
    ]
    assert np.linalg.norm(ends[0] - ends[1]) >= 0.7  # two side by side: their elbows apart
    assert seat_slots(placed("piano_bench")) == ["sit"]


def test_a_front_row_holds_as_many_as_asked_side_by_side():
    painting = placed("painting")
    assert len(stand_slots(painting)) == 1
    two = stand_slots(painting, across=2)
    assert len(two) == 2 and abs(two[0][1] - two[1][1]) < 1e-6  # one row, side by side
    assert math.dist(*two) >= 0.6
