"""A* routes on the occupancy grid: real grids from boxes, checked against geometry, not against itself."""

from __future__ import annotations

import numpy as np
import pytest

from proto.scene import Room
from wana.domain.routes import (
    Footprints,
    NoRouteError,
    astar,
    occupancy_grid,
    plan_route_on_grid,
    point_rect_distance,
)

ROOM = Room(room_type="office", width=4.0, depth=4.0, height=3.0)


def _box(x0, x1, z0, z1, y0=0.0, y1=0.8):
    return [[x0, y0, z0], [x1, y1, z1]]


def _min_clearance(route: np.ndarray, fp: Footprints) -> float:
    """Smallest distance from any point along the route to any footprint."""
    pts = []
    for a, b in zip(route[:-1], route[1:], strict=True):
        t = np.linspace(0, 1, 200)[:, None]
        pts.append(a * (1 - t) + b * t)
    return float(point_rect_distance(np.concatenate(pts), fp).min())


def test_straight_route_in_an_empty_room_is_the_segment_itself():
    grid = occupancy_grid(ROOM, Footprints.from_aabbs(np.zeros((0, 2, 3))), radius=0.25, cell=0.05)
    route = plan_route_on_grid(grid, np.array([-1.0, -1.0]), np.array([1.2, 0.7]))
    np.testing.assert_allclose(route, [[-1.0, -1.0], [1.2, 0.7]])


def test_route_goes_around_a_wall_with_the_character_radius_as_clearance():
    # A wall across the room with a gap at x > 1.0.
    fp = Footprints.from_aabbs(np.array([_box(-2.0, 1.0, -0.1, 0.1)]))
    grid = occupancy_grid(ROOM, fp, radius=0.25, cell=0.05)
    route = plan_route_on_grid(grid, np.array([-1.0, -1.5]), np.array([-1.0, 1.5]))
    assert route[0].tolist() == [-1.0, -1.5] and route[-1].tolist() == [-1.0, 1.5]
    assert _min_clearance(route, fp) >= 0.25 - 0.05 * 0.75  # radius up to sub-cell discretisation
    assert route[:, 0].max() > 1.0 + 0.2  # it went through the gap
    length = np.linalg.norm(np.diff(route, axis=0), axis=1).sum()
    # Shortest path hugs the gap corner: two straight legs via (1.25, 0) are a lower bound.
    lower = np.linalg.norm([2.25, 1.5]) * 2
    assert lower - 1e-6 <= length <= lower * 1.08
    assert len(route) <= 6  # smoothing removed the staircase


def test_enclosed_goal_raises_a_clear_error():
    ring = np.array(
        [
            _box(0.0, 1.5, 0.0, 0.1),
            _box(0.0, 1.5, 1.4, 1.5),
            _box(0.0, 0.1, 0.0, 1.5),
            _box(1.4, 1.5, 0.0, 1.5),
        ]
    )
    grid = occupancy_grid(ROOM, Footprints.from_aabbs(ring), radius=0.1, cell=0.05)
    with pytest.raises(NoRouteError, match="enclosed"):
        plan_route_on_grid(grid, np.array([-1.5, -1.5]), np.array([0.75, 0.75]))


def test_blocked_goal_snaps_to_the_nearest_free_cell():
    fp = Footprints.from_aabbs(np.array([_box(-0.5, 0.5, -0.5, 0.5)]))
    grid = occupancy_grid(ROOM, fp, radius=0.25, cell=0.05)
    route = plan_route_on_grid(grid, np.array([-1.5, 0.0]), np.array([-0.1, 0.0]))
    end = route[-1]
    d = point_rect_distance(end[None], fp)[0, 0]
    assert 0.25 <= d <= 0.25 + 0.05 * 1.5  # just outside the grown footprint
    assert end[0] < -0.7  # the near side, towards the start


def test_high_boxes_do_not_block_and_rotated_boxes_block_only_their_footprint():
    lamp = _box(-2.0, 2.0, -0.1, 0.1, y0=1.9, y1=2.2)
    grid = occupancy_grid(ROOM, Footprints.from_aabbs(np.array([lamp])), radius=0.25, cell=0.05)
    assert not grid.blocked[10:-10, 10:-10].any()
    rot = Footprints(
        centre=np.array([[0.0, 0.0]]),
        half=np.array([[1.0, 0.05]]),
        yaw=np.array([np.pi / 4]),
        y_min=np.array([0.0]),
        y_max=np.array([1.0]),
        owner=("plank",),
    )
    grid = occupancy_grid(ROOM, rot, radius=0.0, cell=0.05)
    on_diag = grid.is_free_xz(
        np.array([[0.5, -0.5], [-0.5, 0.5]])
    )  # along the plank (yaw +45° maps +x to -z)
    off_diag = grid.is_free_xz(np.array([[0.5, 0.5], [-0.5, -0.5]]))
    assert not on_diag.any() and off_diag.all()


def test_astar_finds_the_optimal_octile_length_and_never_cuts_corners():
    blocked = np.zeros((20, 20), dtype=bool)
    blocked[5:15, 10] = True
    path = astar(blocked, (10, 2), (10, 17))
    steps = np.abs(np.diff(np.array(path), axis=0))
    cost = sum(np.sqrt(2) if (a and b) else 1.0 for a, b in steps)
    # Optimal by hand: round the wall's lower end through cell (15, 10): octile (5, 8) then (5, 7).
    assert cost == pytest.approx(10 * np.sqrt(2) + 5, abs=1e-9)
    for (r0, c0), (r1, c1) in zip(path[:-1], path[1:], strict=True):
        assert not blocked[r1, c1]
        if r0 != r1 and c0 != c1:
            assert not blocked[r0, c1] and not blocked[r1, c0]


def test_route_is_deterministic():
    fp = Footprints.from_aabbs(np.array([_box(-0.6, 0.6, -0.3, 0.3), _box(0.8, 1.2, 0.5, 1.0)]))
    grid = occupancy_grid(ROOM, fp, radius=0.25, cell=0.05)
    a = plan_route_on_grid(grid, np.array([-1.5, -1.5]), np.array([1.5, 1.5]))
    b = plan_route_on_grid(grid, np.array([-1.5, -1.5]), np.array([1.5, 1.5]))
    np.testing.assert_array_equal(a, b)


def test_a_rug_on_the_floor_is_walked_over():
    rug = _box(-2.0, 2.0, -0.5, 0.5, y0=0.0, y1=0.012)
    grid = occupancy_grid(ROOM, Footprints.from_aabbs(np.array([rug])), radius=0.25, cell=0.05)
    assert not grid.blocked[10:-10, 10:-10].any()
    step = _box(-2.0, 2.0, -0.5, 0.5, y0=0.0, y1=0.1)  # a low platform still blocks
    grid = occupancy_grid(ROOM, Footprints.from_aabbs(np.array([step])), radius=0.25, cell=0.05)
    assert grid.blocked[40, 10:-10].all()


def test_a_grid_is_the_union_of_its_objects_and_follows_a_moved_object():
    # Each object's cells are memoised (the furniture is the same from one route to the next): a grid of
    # furniture and a body is the furniture's grid with the body's cells added, and moving an object moves
    # its cells rather than reusing the old ones.
    table = Footprints.from_aabbs(np.array([_box(-0.5, 0.5, -0.3, 0.3)]), owner=["table"])
    body = Footprints.from_aabbs(np.array([_box(1.0, 1.4, 1.0, 1.4, y1=1.8)]), owner=["body:0"])
    furniture = occupancy_grid(ROOM, table)
    alone = occupancy_grid(ROOM, body)
    both = occupancy_grid(ROOM, table.concat(body))
    assert np.array_equal(both.blocked, furniture.blocked | alone.blocked)
    assert both.blocked.sum() > furniture.blocked.sum()
    moved = Footprints.from_aabbs(np.array([_box(0.5, 1.5, -0.3, 0.3)]), owner=["table"])
    shifted = occupancy_grid(ROOM, moved)
    assert not shifted.is_free_xz(np.array([[1.4, 0.0]]))[0]
    assert (
        shifted.is_free_xz(np.array([[-0.6, 0.0]]))[0]
        and not furniture.is_free_xz(np.array([[-0.6, 0.0]]))[0]
    )
