"""The voxel-grid collider agrees with the brute-force box test, and its coarse mode never misses a hit."""

from __future__ import annotations

import numpy as np

from services.optimizer.collisions import BodyCollider, voxel_grid
from services.optimizer.costs import LayoutBatch, SceneGeometry, box_hits, world_boxes


def _grid_object(dims=(6, 4, 5), size=(0.1, 0.15, 0.08), keep=0.6, seed=0) -> np.ndarray:
    rng = np.random.default_rng(seed)
    idx = np.argwhere(rng.random(dims) < keep)
    lo = np.array([-0.3, 0.0, -0.2]) + idx * np.array(size)
    return np.stack([lo, lo + np.array(size)], axis=1)


def test_voxel_grid_recognises_cells_and_rejects_free_boxes():
    boxes = _grid_object()
    grid = voxel_grid(boxes[:, 0], boxes[:, 1])
    assert grid is not None and (grid.cell_box >= 0).sum() == len(boxes)
    free = np.array([[[0, 0, 0], [0.1, 0.1, 0.1]], [[0.05, 0, 0], [0.2, 0.1, 0.1]]])
    assert voxel_grid(free[:, 0], free[:, 1]) is None


def test_exact_hits_match_the_brute_force_test_under_yaw_and_scale():
    rng = np.random.default_rng(1)
    grid_boxes = _grid_object()
    loose = np.array(
        [[[-0.2, 0.0, -0.2], [0.25, 0.3, 0.1]], [[0.0, 0.5, 0.0], [0.1, 0.9, 0.35]]]
    )  # not a grid
    geom = SceneGeometry.from_arrays([("a", grid_boxes, {}), ("b", loose, {})])
    k_, n_ = 3, 400
    layout = LayoutBatch(
        position=rng.uniform(-0.2, 0.2, (k_, 2, 3)) * [1, 0, 1],
        yaw=rng.uniform(-np.pi, np.pi, (k_, 2)),
        scale=rng.uniform(0.8, 1.25, (k_, 2, 3)),
    )
    centres = rng.uniform([-0.7, -0.1, -0.7], [0.7, 1.0, 0.7], (k_, n_, 3))
    radii = rng.uniform(0.03, 0.12, n_)
    reach = np.repeat(np.broadcast_to(radii, (k_, n_))[..., None], 2, axis=2)
    collider = BodyCollider(geom)
    assert collider.grids[0] is not None and collider.grids[1] is None
    ours = np.zeros((k_, len(geom.box_owner)), dtype=bool)
    for ks, b in collider.hits(centres, reach, layout):
        ours[ks[:, 0], b] = True
    bc, bh, by = world_boxes(geom, layout)
    brute = box_hits(centres[:, None], radii, bc, bh, by)[:, 0]  # every sphere as one pose
    assert brute.sum() > 20
    np.testing.assert_array_equal(ours, brute)
    coarse = np.zeros_like(ours)
    for ks, b in collider.hits(centres, reach, layout, coarse=True):
        coarse[ks[:, 0], b] = True
    assert np.all(coarse[:, geom.box_owner == 0] >= brute[:, geom.box_owner == 0])  # never misses
    assert coarse.sum() < 3 * brute.sum()  # and is not everything
