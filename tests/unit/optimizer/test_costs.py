"""The paper's eq. 1 and eq. 2 on hand-built geometry, and the body model against wana.domain.skeleton."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from services.optimizer.body import body_spheres, joint_positions
from services.optimizer.costs import (
    LayoutBatch,
    SceneGeometry,
    box_hits,
    collision_cost,
    contact_cost,
    contact_points_world,
    world_boxes,
)
from wana.domain.skeleton import N_JOINTS, forward_kinematics


def _grid_boxes(n: int, size: float = 0.1) -> np.ndarray:
    """n boxes in a row along x, each `size` wide, starting at x = 0."""
    return np.array([[[i * size, 0.0, 0.0], [(i + 1) * size, size, size]] for i in range(n)])


def test_fast_forward_kinematics_matches_the_skeleton_reference():
    rng = np.random.default_rng(3)
    rot = Rotation.random(5 * N_JOINTS, random_state=4).as_quat().reshape(5, N_JOINTS, 4)
    root = rng.normal(size=(5, 3))
    ref, _ = forward_kinematics(rot, root)
    np.testing.assert_allclose(joint_positions(rot, root), ref, atol=1e-10)


def test_body_spheres_cover_the_rest_skeleton_from_feet_to_head():
    sp = body_spheres()
    rest = joint_positions(np.tile([0, 0, 0, 1.0], (1, N_JOINTS, 1)), np.array([[0.0, 0.95, 0.0]]))
    c = sp.centres(rest)[0]
    top = (c[:, 1] + sp.radius).max()
    bottom = (c[:, 1] - sp.radius).min()
    assert 1.70 <= top <= 1.85 and -0.1 <= bottom <= 0.05
    # Consecutive spheres of a bone overlap: no gap a thin box could slip through.
    for b in np.unique(sp.bone):
        idx = np.flatnonzero(sp.bone == b)
        gaps = np.linalg.norm(np.diff(c[idx], axis=0), axis=1)
        assert (gaps <= sp.radius[idx[0]] * 1.01).all()


def test_collision_cost_is_the_share_of_hit_boxes_averaged_over_hit_objects():
    geom = SceneGeometry.from_arrays(
        [("a", _grid_boxes(4), {}), ("b", _grid_boxes(2), {}), ("c", _grid_boxes(3), {})]
    )
    hit = np.zeros((2, 9), dtype=bool)
    hit[0, [0]] = True  # a: 1/4
    hit[0, [4, 5]] = True  # b: 2/2; c untouched -> (0.25 + 1) / 2
    assert collision_cost(hit, geom)[0] == pytest.approx(0.625)
    assert collision_cost(hit, geom)[1] == 0.0  # nothing hit


def test_box_hits_respect_yaw_radius_and_tolerance():
    # One 1 m x 0.2 m plank rotated 90 degrees: it now runs along z.
    geom = SceneGeometry.from_arrays([("plank", np.array([[[-0.5, 0.0, -0.1], [0.5, 0.4, 0.1]]]), {})])
    layout = LayoutBatch(position=np.zeros((1, 1, 3)), yaw=np.array([[np.pi / 2]]), scale=np.ones((1, 1, 3)))
    bc, bh, by = world_boxes(geom, layout)
    radii = np.array([0.05])
    spheres = np.array([[[[0.0, 0.2, 0.4]], [[0.4, 0.2, 0.0]], [[0.14, 0.2, 0.0]]]])  # (1, 3 frames, 1, 3)
    hits = box_hits(spheres, radii, bc, bh, by)[0, :, 0]
    assert hits.tolist() == [True, False, True]  # 0.04 from the long side: hit; 0.3 away: miss
    tol = np.full((1, 3, 1), 0.02)
    assert box_hits(spheres, radii, bc, bh, by, tol)[0, :, 0].tolist() == [True, False, False]


def test_contact_cost_is_the_mean_distance_to_the_mean_joint_position():
    geom = SceneGeometry.from_arrays(
        [("desk", _grid_boxes(1), {"kb": (np.array([0.1, 0.7, 0.0]), "LeftHand")})]
    )
    layout = LayoutBatch(
        position=np.array([[[1.0, 0.0, 0.0]]]), yaw=np.array([[np.pi]]), scale=np.array([[[1.0, 1.1, 1.0]]])
    )
    world = contact_points_world(geom, layout, np.array([0]))
    np.testing.assert_allclose(world[0, 0], [0.9, 0.77, 0.0], atol=1e-12)  # yaw pi flips x; height scales
    joint = np.array([[[0.9, 0.77, 0.3]]])
    assert contact_cost(world, joint)[0] == pytest.approx(0.3)
