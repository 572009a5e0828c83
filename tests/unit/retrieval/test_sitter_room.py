"""A seat keeps the space of its sitter's torso free: a chair may slide under a table up to the knees, not the chest."""

from __future__ import annotations

import math

import numpy as np

from services.retrieval.collide import ObstacleIndex
from services.retrieval.geometry import footprint, sitter_boxes
from services.retrieval.placement import Placed
from wana.assets.catalog import make_object


def test_each_seat_slot_has_a_sitter_box_above_it_and_a_table_none():
    chair = make_object("chair")
    boxes = sitter_boxes(chair)
    hips = np.asarray(chair.contact_points["sit"].position)
    assert boxes.shape == (1, 2, 3)
    assert boxes[0, 0, 1] > hips[1] and boxes[0, 1, 1] > hips[1] + 0.5  # above the seat, up to the head
    assert len(sitter_boxes(make_object("sofa"))) == 3  # one per slot
    assert len(sitter_boxes(make_object("dining_table"))) == 0
    fp = footprint("chair", {}, 0)
    assert fp.height == float(fp.bounds[1, 1] - fp.bounds[0, 1]) < 1.0  # the chair itself is no taller


def _chair_facing_table(tuck: float) -> str | None:
    """The first collider of a chair facing a table's +Z edge, its front edge ``tuck`` metres under the top."""
    table_fp = footprint("dining_table", {}, 0)
    table = Placed("table", table_fp, np.zeros(3), 0.0)
    chair_fp = footprint("chair", {}, 0)
    half = float(make_object("chair").dims[2]) / 2
    z = float(table_fp.bounds[1, 2]) + half - tuck
    chair = Placed("chair", chair_fp, np.array([0.0, 0.0, z]), math.pi)  # facing -Z, toward the table
    return ObstacleIndex([table]).first_collider(chair)


def test_a_chair_tucked_chest_deep_under_a_table_collides_but_one_at_its_edge_does_not():
    assert _chair_facing_table(-0.05) is None  # 5 cm in front of the edge
    assert _chair_facing_table(0.04) is None  # the front of the seat just under the top: knees under it
    assert _chair_facing_table(0.25) == "table"  # the seat under the top: the chest would be in the table


def test_what_rests_on_a_bench_for_one_keeps_off_its_sitters_place():
    bench_fp = footprint("bench", {"size": "small"}, 0)
    assert bench_fp.sitters == 1
    bench = Placed("bench", bench_fp, np.zeros(3), 0.0)
    top = float(bench_fp.surfaces[0].height)
    box_fp = footprint("box", {"size": "small"}, 0)
    index = ObstacleIndex([bench])
    middle = Placed("box", box_fp, np.array([0.0, top, 0.0]), 0.0, support="bench")
    end = Placed("box", box_fp, np.array([0.45, top, 0.0]), 0.0, support="bench")
    assert index.first_collider(middle) == "bench"
    assert index.first_collider(end) is None
    assert index.first_colliders([middle, end]) == ["bench", None]
    # a park bench that seats two is a sofa: what rests on it takes a place, the sitters the others
    wide = Placed("bench", footprint("bench", {}, 0), np.zeros(3), 0.0)
    assert wide.fp.sitters == 3
    wide_top = float(wide.fp.surfaces[0].height)
    on_wide = Placed("box", box_fp, np.array([0.0, wide_top, 0.0]), 0.0, support="bench")
    assert ObstacleIndex([wide]).first_collider(on_wide) is None


def test_a_bench_in_front_of_a_painting_faces_it_with_room_for_the_legs():
    from services.retrieval.placement import relation_candidates

    painting_fp = footprint("painting", {}, 0)
    assert painting_fp.mount == "wall"
    painting = Placed("painting", painting_fp, np.array([0.0, 1.3, 0.0]), 0.0)  # on the wall z = 0, facing +Z
    bench_fp = footprint("bench", {}, 0)
    assert bench_fp.sitters
    front = float(painting_fp.bounds[1, 2])
    seen = 0
    for position, yaw, _ in relation_candidates(
        "in_front_of", bench_fp, painting, np.random.default_rng(3), room_height=2.8
    ):
        if abs(math.remainder(yaw - math.pi, 2 * math.pi)) > 1e-6:
            continue  # its back to the painting
        seen += 1
        half = float(make_object("bench").dims[2]) / 2
        assert position[2] - half - front >= 0.55  # the seat's front this far from the wall: shins and feet
    assert seen
