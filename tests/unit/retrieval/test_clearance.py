"""Context furniture stands against the walls, clear of the text objects' stand points and the walkway."""

from __future__ import annotations

import numpy as np
import pytest

from proto.ssg import ObjectNode, RelationNode
from services.retrieval.clearance import (
    STAND_RADIUS,
    against_wall,
    entrance,
    keep_clear_zones,
    stand_points,
    wall_of,
)
from services.retrieval.compose import compose_scene
from services.retrieval.geometry import footprint
from wana.assets.catalog import world_collision_boxes

OFFICE = [
    ObjectNode(id="desk", category="desk", word="desk"),
    ObjectNode(id="window", category="window", word="window"),
    ObjectNode(id="laptop", category="laptop", word="laptop"),
    ObjectNode(id="chair", category="chair", word="chair"),
]
OFFICE_RELATIONS = [
    RelationNode(subject="desk", relation="near", object="window"),
    RelationNode(subject="laptop", relation="on", object="desk"),
    RelationNode(subject="chair", relation="in_front_of", object="desk"),
]
TALL_STORAGE = ("bookshelf", "shelf", "wardrobe", "cabinet", "filing_cabinet", "locker", "display_case")


def _xz_box(p) -> np.ndarray:  # noqa: ANN001
    b = world_collision_boxes(p)
    return np.array([[b[:, 0, 0].min(), b[:, 0, 2].min()], [b[:, 1, 0].max(), b[:, 1, 2].max()]])


def _distance_to_box(point: np.ndarray, box: np.ndarray) -> float:
    gap = np.maximum(np.maximum(box[0] - point, point - box[1]), 0.0)
    return float(np.hypot(*gap))


@pytest.fixture(scope="module", params=[0, 1, 2])
def office(request):
    return compose_scene(OFFICE, OFFICE_RELATIONS, room_type="office", seed=request.param)


def test_an_office_gets_context_objects_and_keeps_every_relation_without_overlaps(office):
    scene, report = office
    assert len(report.context_objects) >= 3
    assert report.relations_held == 1.0 and report.overlaps == 0


def test_context_storage_stands_with_its_back_against_a_wall(office):
    scene, _ = office
    storage = [p for p in scene.objects if not p.from_text and p.category in TALL_STORAGE]
    assert storage, "the office scene lends no storage furniture"
    w, d = scene.room.width, scene.room.depth
    for p in storage:
        box = _xz_box(p)
        gaps = {
            "back": box[0, 1] + d / 2,
            "front": d / 2 - box[1, 1],
            "left": box[0, 0] + w / 2,
            "right": w / 2 - box[1, 0],
        }
        wall = min(gaps, key=gaps.get)
        assert gaps[wall] < 0.1, f"{p.id} stands {gaps[wall]:.2f} m from the nearest wall"
        # Its front (+Z in the object frame) points into the room, away from that wall.
        front = np.array([np.sin(p.yaw), np.cos(p.yaw)])
        inward = {"back": (0, 1), "front": (0, -1), "left": (1, 0), "right": (-1, 0)}[wall]
        assert front @ np.array(inward) > 0.99, f"{p.id} does not turn its back to the {wall} wall"


def test_context_floor_furniture_keeps_clear_of_stand_points_and_the_entrance(office):
    scene, _ = office
    text = [p for p in scene.objects if p.from_text]
    stands = stand_points(text)
    assert len(stands) == len(text)
    floor_context = [
        p
        for p in scene.objects
        if not p.from_text
        and not p.support
        and footprint(p.category, dict(p.attributes), p.seed).mount == "floor"
    ]
    assert floor_context
    door = entrance(scene.room.depth)
    for p in floor_context:
        box = _xz_box(p)
        for s in stands:
            assert _distance_to_box(s, box) >= STAND_RADIUS - 0.02, f"{p.id} stands in a stand point's way"
        assert _distance_to_box(door, box) > 0.5, f"{p.id} blocks the entrance"


def test_context_furniture_leaves_the_middle_of_the_room_free(office):
    scene, _ = office
    w, d = scene.room.width, scene.room.depth
    middle = np.array([[-w / 4, -d / 4], [w / 4, d / 4]])
    for p in scene.objects:
        if p.from_text or p.support:
            continue
        box = _xz_box(p)
        inside = np.all(box[0] < middle[1]) and np.all(middle[0] < box[1])
        assert not inside, f"{p.id} stands in the middle of the room"


def test_keep_clear_zones_block_a_box_on_a_walkway_and_not_one_beside_it(office):
    scene, _ = office
    text = [p for p in scene.objects if p.from_text and p.category == "desk"]
    zones = keep_clear_zones(text, scene.room.width, scene.room.depth)
    stand = stand_points(text)[0]
    door = entrance(scene.room.depth)
    mid = (stand + door) / 2.0
    on_path = np.array([[mid[0] - 0.1, 0.0, mid[1] - 0.1], [mid[0] + 0.1, 1.0, mid[1] + 0.1]])
    assert zones.blocks(on_path)
    corner = np.array(
        [
            [scene.room.width / 2 - 0.3, 0.0, -scene.room.depth / 2],
            [scene.room.width / 2, 1.0, -scene.room.depth / 2 + 0.3],
        ]
    )
    if np.linalg.norm(stand - corner[0, [0, 2]]) > 1.0:
        assert not zones.blocks(corner)


def test_which_furniture_goes_against_a_wall():
    assert against_wall(footprint("bookshelf", {}, 0), from_text=True)
    assert against_wall(footprint("trash_can", {}, 0), from_text=False)
    assert not against_wall(footprint("trash_can", {}, 0), from_text=True)
    assert not against_wall(footprint("coffee_table", {}, 0), from_text=False)
    assert not against_wall(footprint("window", {}, 0), from_text=False)  # wall-mounted: hangs, never stands


def test_a_named_bookshelf_without_relations_stands_against_a_wall():
    scene, report = compose_scene(
        [
            ObjectNode(id="shelf", category="bookshelf", word="bookshelf"),
            ObjectNode(id="sofa", category="sofa", word="sofa"),
        ],
        [],
        seed=4,
    )
    placed = {p.id: p for p in scene.objects}
    box = world_collision_boxes(placed["shelf"])
    aabb = np.stack([box[:, 0].min(axis=0), box[:, 1].max(axis=0)])
    assert wall_of(aabb, scene.room.width, scene.room.depth) != ""
    assert report.overlaps == 0


def test_context_placement_is_deterministic():
    a, _ = compose_scene(OFFICE, OFFICE_RELATIONS, room_type="office", seed=7)
    b, _ = compose_scene(OFFICE, OFFICE_RELATIONS, room_type="office", seed=7)
    assert a == b
