"""The optimiser's view of catalog objects agrees with the catalog, and plan_route works on real scenes."""

from __future__ import annotations

import numpy as np
import pytest

from proto.scene import PlacedObject, Room, Scene
from wana.domain.routes import NoRouteError, plan_route, point_rect_distance

catalog = pytest.importorskip("wana.assets.catalog", reason="needs the asset catalog")

from wana.domain.object_geometry import object_shape, scene_footprints, world_obbs  # noqa: E402

DESK = PlacedObject(id="desk", category="desk", position=(0.4, 0.0, -0.3), yaw=0.7, scale=(1.1, 0.9, 1.0))


def test_oriented_boxes_have_the_catalog_world_aabbs():
    centre, half = world_obbs(DESK)
    c, s = abs(np.cos(DESK.yaw)), abs(np.sin(DESK.yaw))
    ext = np.stack([c * half[:, 0] + s * half[:, 2], half[:, 1], s * half[:, 0] + c * half[:, 2]], axis=1)
    ours = np.stack([centre - ext, centre + ext], axis=1)
    np.testing.assert_allclose(ours, catalog.world_collision_boxes(DESK), atol=1e-9)


def test_contact_points_expand_every_joint_of_an_interaction():
    shape = object_shape(DESK)
    write = [j for n, j in zip(shape.contact_names, shape.contact_joints, strict=True) if n == "write"]
    assert sorted(write) == ["LeftHandMiddle1", "RightHandMiddle1"]


def test_plan_route_walks_around_a_desk_to_the_far_side():
    scene = Scene(
        room=Room(room_type="office", width=5.0, depth=5.0, height=3.0),
        objects=[PlacedObject(id="desk", category="desk", position=(0.0, 0.0, 0.0))],
    )
    route = plan_route(scene, np.array([0.0, -1.5]), np.array([0.0, 1.5]))
    fp = scene_footprints(scene)
    t = np.linspace(0, 1, 100)[:, None]
    pts = np.concatenate([a * (1 - t) + b * t for a, b in zip(route[:-1], route[1:], strict=True)])
    assert point_rect_distance(pts, fp).min() >= 0.25 - 0.04
    assert np.allclose(route[-1], [0.0, 1.5]) and len(route) >= 3
    # Ignoring the desk, the route is the straight line.
    assert len(plan_route(scene, np.array([0.0, -1.5]), np.array([0.0, 1.5]), ignore={"desk"})) == 2


def test_plan_route_reports_an_enclosed_goal():
    walls = [
        PlacedObject(id=f"w{i}", category="bookshelf", position=p, yaw=y, scale=(3.0, 1.0, 1.0))
        for i, (p, y) in enumerate(
            [
                ((0.0, 0.0, 1.0), 0.0),
                ((0.0, 0.0, -1.0), 0.0),
                ((1.0, 0.0, 0.0), np.pi / 2),
                ((-1.0, 0.0, 0.0), np.pi / 2),
            ]
        )
    ]
    scene = Scene(room=Room(room_type="office", width=6.0, depth=6.0, height=3.0), objects=walls)
    with pytest.raises(NoRouteError):
        plan_route(scene, np.array([2.5, 2.5]), np.array([0.0, 0.0]), radius=0.3)


def test_a_goal_in_front_of_a_chair_is_reached_by_a_last_step_into_its_clearance():
    scene = Scene(
        room=Room(room_type="office", width=5.0, depth=5.0, height=3.0),
        objects=[PlacedObject(id="chair", category="chair", position=(0.0, 0.0, 0.0))],
    )
    goal = np.array([0.0, 0.25])  # where one turns to sit: inside the chair's 0.25 m clearance
    route = plan_route(scene, np.array([0.0, 2.0]), goal)
    np.testing.assert_allclose(route[-1], goal)
    assert np.linalg.norm(route[-1] - route[-2]) <= 1.0
    snapped = plan_route(scene, np.array([0.0, 2.0]), goal, step_in=0.0)
    assert not np.allclose(snapped[-1], goal)
    assert point_rect_distance(snapped[-1][None], scene_footprints(scene))[0].min() >= 0.25 - 0.04
