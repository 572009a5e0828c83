"""The fast paths of composition give the same answers as the plain tests they replace.

Each fast path (broadcast box tests, collision index, batched room test, cached world boxes, per-scene
bounds, broad-phase overlap check, memoised relation predicate) is compared with a plain reference
written here or kept in services.retrieval.geometry, on random inputs with a fixed seed.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import RelationNode
from services.retrieval.collide import ObstacleIndex
from services.retrieval.compose import MemoHolds, outer_bounds, overlapping_pairs
from services.retrieval.database import default_db
from services.retrieval.geometry import (
    OVERLAP_EPS,
    boxes_at,
    boxes_overlap,
    first_overlapping,
    footprint,
    footprint_boxes_at,
    inside_room,
)
from services.retrieval.matching import scene_bounds
from services.retrieval.placement import Placed
from services.retrieval.trials import inside_room_many
from wana.assets.catalog import world_collision_boxes
from wana.assets.relations import relation_holds

SEED = 20240501
YAWS = (0.0, math.pi / 2.0, math.pi, -math.pi / 2.0, 0.3, -2.1)


def random_boxes(rng: np.random.Generator, n: int, spread: float = 1.0) -> np.ndarray:
    lo = rng.uniform(-spread, spread, size=(n, 3))
    return np.stack([lo, lo + rng.uniform(0.005, 0.6, size=(n, 3))], axis=1)


def pair_overlaps(a: np.ndarray, b: np.ndarray, eps: float = OVERLAP_EPS) -> bool:
    """Reference: two boxes interpenetrate by more than eps on every axis."""
    return all(a[0, k] < b[1, k] - eps and b[0, k] < a[1, k] - eps for k in range(3))


def test_broadcast_box_test_agrees_with_pairwise_reference_on_random_boxes():
    rng = np.random.default_rng(SEED)
    hits = 0
    for _ in range(300):
        a = random_boxes(rng, int(rng.integers(1, 6)))
        groups = [random_boxes(rng, int(rng.integers(1, 6))) for _ in range(int(rng.integers(1, 5)))]
        owner = np.repeat(np.arange(len(groups)), [len(g) for g in groups])
        expected = next(
            (k for k, g in enumerate(groups) if any(pair_overlaps(x, y) for x in a for y in g)), -1
        )
        assert first_overlapping(a, np.concatenate(groups), owner) == expected
        for g in groups:
            assert boxes_overlap(a, g) == any(pair_overlaps(x, y) for x in a for y in g)
        hits += expected >= 0
    assert 30 < hits < 270  # both outcomes were exercised


def test_cached_world_boxes_equal_boxes_at_bit_for_bit():
    fp = footprint("office_chair", {}, 7)
    rng = np.random.default_rng(SEED)
    for yaw in YAWS:
        pos = rng.uniform(-2.0, 2.0, size=3)
        assert np.array_equal(footprint_boxes_at(fp, pos, yaw), boxes_at(fp.boxes, pos, yaw))


def random_poses(rng: np.random.Generator, n: int, pid: str, fp, support: str = "") -> list[Placed]:
    return [
        Placed(
            pid, fp, np.array([rng.uniform(-2, 2), 0.0, rng.uniform(-2, 2)]), float(rng.choice(YAWS)), support
        )
        for _ in range(n)
    ]


def reference_collider(p: Placed, others: list[Placed]) -> str | None:
    """The first placed object whose collision boxes p's interpenetrate (support relations aside)."""
    for q in others:
        if q.id == p.support or q.support == p.id:
            continue
        if any(pair_overlaps(x, y) for x in p.boxes for y in q.boxes):
            return q.id
    return None


def test_collision_index_agrees_with_reference_one_by_one_and_in_batches():
    rng = np.random.default_rng(SEED)
    kinds = [footprint(c, {}, 1) for c in ("desk", "office_chair", "plant", "bookshelf", "sofa")]
    placed = []
    for k in range(8):
        placed += random_poses(rng, 1, f"obj{k}", kinds[k % len(kinds)])
    placed.append(Placed("mug", footprint("mug", {}, 1), placed[0].position + [0, 0.75, 0], 0.0, "obj0"))
    index = ObstacleIndex(placed)
    # Resting on the bookshelf (a seat's sitter place is another matter: test_sitter_room.py).
    poses = random_poses(rng, 60, "new", footprint("office_chair", {}, 3), support="obj3")
    expected = [reference_collider(p, placed) for p in poses]
    assert [index.first_collider(p) for p in poses] == expected
    assert index.first_colliders(poses) == expected
    assert index.first_colliders(poses[:1]) == expected[:1]
    assert sum(e is not None for e in expected) > 5 and sum(e is None for e in expected) > 5
    assert all(e != "obj3" for e in expected)  # what it rests on never counts


def test_batched_room_test_agrees_with_inside_room():
    rng = np.random.default_rng(SEED)
    boxes = random_boxes(rng, 500, spread=3.0)
    got = inside_room_many(boxes, 5.0, 4.0, 2.8)
    assert got.tolist() == [inside_room(b, 5.0, 4.0, 2.8) for b in boxes]
    assert 0 < got.sum() < len(got)


def test_scene_bounds_equal_a_loop_over_edges():
    db = default_db()
    rng = np.random.default_rng(SEED)
    scores = rng.uniform(0.0, 1.0, size=(4, len(db.edge_scene))) * (rng.random((4, len(db.edge_scene))) < 0.3)
    expected = np.zeros((len(db), 4))
    for e, s in enumerate(db.edge_scene):
        expected[s] = np.maximum(expected[s], scores[:, e])
    assert np.array_equal(scene_bounds(scores, db), expected.sum(axis=1))


def reference_overlapping_pairs(scene: Scene) -> list[tuple[str, str]]:
    boxes = {p.id: world_collision_boxes(p) for p in scene.objects}
    objs = list(scene.objects)
    return [
        (a.id, b.id)
        for i, a in enumerate(objs)
        for b in objs[i + 1 :]
        if a.support != b.id and b.support != a.id and boxes_overlap(boxes[a.id], boxes[b.id])
    ]


def test_overlap_check_with_broad_phase_finds_the_same_pairs_as_all_pairs():
    rng = np.random.default_rng(SEED)
    cats = ["desk", "office_chair", "sofa", "coffee_table", "plant", "bookshelf", "bed", "lamp"]
    for trial in range(6):
        objects = [
            PlacedObject(
                id=f"o{k}",
                category=cats[int(rng.integers(len(cats)))],
                seed=int(rng.integers(5)),
                position=(float(rng.uniform(-1.5, 1.5)), 0.0, float(rng.uniform(-1.5, 1.5))),
                yaw=float(rng.choice(YAWS)),
                scale=(1.0, 1.0, 1.0) if trial % 2 else (1.2, 0.9, 0.8),
            )
            for k in range(9)
        ]
        scene = Scene(room=Room(room_type="office", width=4, depth=4, height=2.8), objects=objects)
        assert overlapping_pairs(scene) == reference_overlapping_pairs(scene)
        outer = outer_bounds(objects)
        for p, box in zip(objects, outer, strict=True):
            world = world_collision_boxes(p)
            assert np.all(box[0] <= world[:, 0]) and np.all(world[:, 1] <= box[1])


def test_memoised_predicate_answers_like_the_predicate_and_asks_once():
    calls = []

    def holds(rel: RelationNode, s: PlacedObject, a: PlacedObject) -> bool:
        calls.append(rel.relation)
        return relation_holds(rel, s, a)

    memo = MemoHolds(holds)
    desk = PlacedObject(id="desk", category="desk", position=(0.0, 0.0, 0.0))
    chair = PlacedObject(id="chair", category="office_chair", position=(0.0, 0.0, 1.0), yaw=math.pi)
    far = PlacedObject(id="chair", category="office_chair", position=(3.0, 0.0, 3.0))
    for rel in ("in_front_of", "behind", "near"):
        node = RelationNode(subject="chair", relation=rel, object="desk")
        for s in (chair, far):
            assert memo(node, s, desk) == relation_holds(node, s, desk)
            assert memo(node, s, desk) == relation_holds(node, s, desk)
    assert len(calls) == 6  # each question asked once


@pytest.mark.parametrize("relation", ["near", "on"])
def test_shared_memo_of_the_project_predicate_keeps_answers_apart_by_pose(relation):
    memo = MemoHolds(relation_holds)
    desk = PlacedObject(id="desk", category="desk", position=(0.0, 0.0, 0.0))
    node = RelationNode(subject="lamp", relation=relation, object="desk")
    top = float(footprint("desk", {}, 0).surfaces[0].height) if footprint("desk", {}, 0).surfaces else 0.75
    for pos in [(0.0, top, 0.0), (4.0, 0.0, 4.0), (0.1, top, 0.05)]:
        lamp = PlacedObject(id="lamp", category="desk_lamp", position=pos, support="desk")
        assert memo(node, lamp, desk) == relation_holds(node, lamp, desk)
