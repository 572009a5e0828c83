"""Catalog objects: frames, knobs, collision boxes, contact points and world placement."""

from __future__ import annotations

import numpy as np
import pytest

from proto.scene import PlacedObject
from wana.assets import catalog, vocabulary
from wana.assets.generators import REGISTRY
from wana.assets.generators.generic import block


def test_every_vocabulary_category_has_a_dedicated_generator():
    assert set(catalog.categories()) == set(vocabulary.CATEGORIES)
    assert [c for c, spec in REGISTRY.items() if spec.fn is block] == []
    assert len(catalog.categories()) >= 120


def test_there_are_at_least_2500_variants():
    assert catalog.count_variants() >= 2500


@pytest.mark.parametrize(
    "category", ["office_chair", "desk", "laptop", "boxing_bag", "bookshelf", "cup", "piano"]
)
def test_object_frame_is_base_centred_y_up(category):
    obj = catalog.make_object(category)
    lo, hi = obj.mesh.bounds
    assert abs(lo[1]) < 1e-9
    assert np.allclose((lo[[0, 2]] + hi[[0, 2]]) / 2, 0.0, atol=1e-9)
    assert np.allclose(obj.dims, hi - lo)
    assert np.allclose(obj.front, [0, 0, 1])
    assert obj.mesh.is_winding_consistent
    assert len(obj.mesh.visual.face_colors) == len(obj.mesh.faces)


def test_collision_boxes_are_many_small_boxes_inside_the_bounds():
    obj = catalog.make_object("office_chair")
    boxes = obj.collision_boxes
    assert boxes.ndim == 3 and boxes.shape[1:] == (2, 3)
    assert len(boxes) >= 20
    lo, hi = obj.mesh.bounds
    assert np.all(boxes[:, 0] >= lo - 1e-9) and np.all(boxes[:, 1] <= hi + 1e-9)
    # a chair's boxes cover far less than its bounding box (legs and air under the seat)
    vol = np.prod(boxes[:, 1] - boxes[:, 0], axis=1).sum()
    assert vol < 0.8 * np.prod(hi - lo)
    # every vertex of the mesh lies inside (or on) some collision box
    v = np.asarray(obj.mesh.vertices)[::7]
    inside = np.any(
        np.all((v[:, None] >= boxes[None, :, 0] - 1e-6) & (v[:, None] <= boxes[None, :, 1] + 1e-6), axis=2),
        axis=1,
    )
    assert inside.mean() > 0.97


def test_contact_points_name_canonical_joints():
    from wana.domain.skeleton import JOINT_NAMES

    expect = {
        "office_chair": ("sit", "Hips"),
        "laptop": ("type", "RightHandMiddle1"),
        "piano": ("play", None),
        "cup": ("drink", "RightHand"),
        "phone": ("call", "RightHand"),
        "microphone": ("sing", "RightHand"),
        "boxing_bag": ("punch", "RightHand"),
        "guitar": ("play", "RightHand"),
    }
    for cat, (act, joint) in expect.items():
        obj = catalog.make_object(cat)
        cp = obj.contact_points[act]
        assert joint is None or cp.joint == joint
        for name in (cp.joint, *cp.extra):
            assert name in JOINT_NAMES
        lo, hi = obj.mesh.bounds
        assert np.all(cp.position >= lo - 0.15) and np.all(cp.position <= hi + 0.15), cat
    for cat in catalog.categories():
        obj = catalog.make_object(cat)
        assert obj.contact_points, cat
        assert obj.stand_point[1] == 0.0


def test_seat_height_is_where_the_hips_go():
    chair = catalog.make_object("chair")
    sit = chair.contact_points["sit"].position
    assert 0.4 < sit[1] < 0.6
    seat = max(s.height for s in chair.support_surfaces)
    assert 0.08 <= sit[1] - seat <= 0.12  # the hips a thigh's thickness above the seat, not in it
    assert chair.stand_point[2] > chair.dims[2] / 2


def test_knobs_change_the_mesh_and_unknown_words_are_dropped():
    base = catalog.make_object("sofa")
    red = catalog.make_object("sofa", {"colour": "red"})
    big = catalog.make_object("sofa", {"size": "large"})
    assert catalog.mesh_digest(base) != catalog.mesh_digest(red)
    assert big.dims[0] > base.dims[0] * 1.2
    odd = catalog.make_object("sofa", {"colour": "sparkly", "mood": "happy"})
    assert odd.attributes == {}
    assert catalog.make_object("sofa", {"colour": "gray"}).attributes == {"colour": "grey"}
    assert catalog.make_object("laptop", {"state": "messy"}).attributes == {}  # laptops have no state knob


def test_variants_sampled_across_the_catalog_are_distinct():
    rng = np.random.default_rng(0)
    digests = set()
    n = 0
    for cat in catalog.categories()[::6]:
        variants = list(catalog.iter_variants(cat))
        for k in rng.choice(len(variants), size=min(4, len(variants)), replace=False):
            digests.add(catalog.mesh_digest(catalog.make_object(cat, dict(variants[k]))))
            n += 1
    assert len(digests) == n


def test_same_input_gives_the_same_object_and_seeds_vary_it():
    a = catalog.make_object("desk", {"state": "messy"}, seed=3)
    b = catalog._make_cached.__wrapped__("desk", (("state", "messy"),), 3)
    assert catalog.mesh_digest(a) == catalog.mesh_digest(b)
    assert catalog.mesh_digest(a) != catalog.mesh_digest(
        catalog.make_object("desk", {"state": "messy"}, seed=4)
    )


def test_unknown_category_is_a_clear_error():
    with pytest.raises(KeyError, match="unknown catalog category"):
        catalog.make_object("spaceship")


def test_support_surfaces_sit_on_tops():
    desk = catalog.make_object("desk")
    top = max(s.height for s in desk.support_surfaces)
    assert abs(top - 0.75) < 0.01


def test_world_boxes_follow_yaw_and_position():
    placed = PlacedObject(id="d", category="desk", position=(1.0, 0.0, 2.0), yaw=np.pi / 2)
    boxes = catalog.world_collision_boxes(placed)
    obj = catalog.make_object("desk")
    ext = boxes[:, 1].max(axis=0) - boxes[:, 0].min(axis=0)
    assert np.allclose(ext[[0, 2]], obj.dims[[2, 0]], atol=1e-6)  # width and depth swap after 90 degrees
    centre = (boxes[:, 1].max(axis=0) + boxes[:, 0].min(axis=0)) / 2
    assert np.allclose(centre[[0, 2]], [1.0, 2.0], atol=0.05)
    m = catalog.object_to_world(placed)
    assert np.allclose(m[:3, :3] @ [0, 0, 1], [1, 0, 0], atol=1e-9)  # front turns to +X


@pytest.mark.parametrize(
    ("category", "points", "height"),
    [
        ("vegetable", {"pick_up", "cut"}, (0.03, 0.12)),  # what one chops: cut where the knife comes down
        ("bread", {"pick_up", "cut"}, (0.06, 0.16)),
        ("jug", {"pick_up", "pour"}, (0.15, 0.3)),  # one pours water from it into a glass
        ("camera", {"pick_up", "take_photo"}, (0.05, 0.15)),  # held up to take a photo
    ],
)
def test_props_named_in_actions_are_held_where_the_action_works(category, points, height):
    obj = catalog.make_object(category)
    assert points <= set(obj.contact_points)
    assert height[0] < obj.mesh.bounds[1][1] < height[1]
