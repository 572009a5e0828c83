"""Simulated annealing on hand-built geometry with real motions (no catalog needed)."""

from __future__ import annotations

import numpy as np
import pytest

from proto.motion_data import Motion, Segment
from proto.optimizer import ContactPair, Interaction, OptimiseSettings
from proto.scene import PlacedObject, Room, Scene
from services.optimizer.annealing import LayoutModel, optimise_interaction, truncated_normal
from services.optimizer.costs import SceneGeometry
from wana.arrays import to_wire
from wana.domain.skeleton import JOINT_NAMES, N_JOINTS

ROOM = Room(room_type="office", width=5.0, depth=5.0, height=3.0)
HAND_T_POSE = np.array([0.81, 1.41, 0.0])  # LeftHandMiddle1 of the T-pose at hips (0, 0.95, 0)


def _motion(root: np.ndarray, segments: list[Segment]) -> Motion:
    rot = np.zeros((len(root), N_JOINTS, 4), dtype=np.float32)
    rot[..., 3] = 1.0
    return Motion(
        character="Eve",
        joint_names=list(JOINT_NAMES),
        root_position=to_wire(root.astype(np.float32)),
        rotations=to_wire(rot),
        segments=segments,
    )


def _voxels(size: tuple[float, float, float], n: int = 4) -> np.ndarray:
    """An object made of n x n x n small boxes centred on x, z, base at y = 0."""
    sx, sy, sz = size
    edges = [
        np.linspace(-sx / 2, sx / 2, n + 1),
        np.linspace(0, sy, n + 1),
        np.linspace(-sz / 2, sz / 2, n + 1),
    ]
    out = []
    for i in range(n):
        for j in range(n):
            for k in range(n):
                out.append(
                    [
                        [edges[0][i], edges[1][j], edges[2][k]],
                        [edges[0][i + 1], edges[1][j + 1], edges[2][k + 1]],
                    ]
                )
    return np.array(out)


def test_truncated_normal_stays_within_three_sigma():
    x = truncated_normal(np.random.default_rng(0), 0.02, (20000,))
    assert np.abs(x).max() <= 0.06 and 0.017 < x.std() < 0.02


def test_annealing_brings_a_contact_point_to_the_hand():
    geom = SceneGeometry.from_arrays(
        [("shelf", _voxels((0.3, 1.2, 0.3)), {"grip": (np.array([0.0, 1.4, 0.0]), "LeftHandMiddle1")})]
    )
    scene = Scene(room=ROOM, objects=[PlacedObject(id="shelf", category="shelf", position=(0.95, 0.0, 0.08))])
    motion = _motion(
        np.tile([0.0, 0.95, 0.0], (30, 1)), [Segment(index=0, action="reach", start_frame=0, end_frame=30)]
    )
    inter = Interaction(
        character="Eve",
        action="reach",
        contacts=[ContactPair(object_id="shelf", point="grip")],
        targets=["shelf"],
    )
    res = optimise_interaction(scene, lambda s: motion, inter, geometry=geom, seed=1)
    assert res.before.contact_cost > 0.15
    assert res.after.contact_cost < 0.04
    assert res.after.cost <= min(res.cost_curve) + 1e-12 and res.after.cost == res.best_curve[-1]
    assert len(res.cost_curve) == res.steps_run + 1 == 101
    assert res.scene.objects[0].position[1] == 0.0  # vertical position fixed
    assert res.after.contact_pairs[0].joint == "LeftHandMiddle1"


def test_annealing_moves_an_obstacle_off_the_walked_path_and_is_deterministic():
    geom = SceneGeometry.from_arrays([("crate", _voxels((0.4, 0.5, 0.4)), {})])
    scene = Scene(room=ROOM, objects=[PlacedObject(id="crate", category="box", position=(0.0, 0.0, 0.2))])
    x = np.linspace(-1.5, 1.5, 90)
    root = np.stack([x, np.full_like(x, 0.95), np.zeros_like(x)], axis=1)
    motion = _motion(root, [Segment(index=0, action="walk", start_frame=0, end_frame=90)])
    inter = Interaction(character="Eve", action="walk", movable=["crate"])
    res = optimise_interaction(scene, lambda s: motion, inter, geometry=geom, seed=7)
    assert res.before.locomotion_collided_boxes > 0
    assert res.after.collided_boxes == 0 and res.after.collision_cost == 0.0
    again = optimise_interaction(scene, lambda s: motion, inter, geometry=geom, seed=7)
    assert again.scene == res.scene and again.cost_curve == res.cost_curve


def test_zero_budget_returns_the_input_layout():
    geom = SceneGeometry.from_arrays([("crate", _voxels((0.4, 0.5, 0.4), 2), {})])
    scene = Scene(room=ROOM, objects=[PlacedObject(id="crate", category="box", position=(0.0, 0.0, 0.2))])
    motion = _motion(np.tile([0.0, 0.95, 0.0], (10, 1)), [])
    res = optimise_interaction(
        scene,
        lambda s: motion,
        Interaction(character="Eve", action="idle", movable=["crate"]),
        geometry=geom,
        budget_s=0.0,
    )
    assert res.steps_run == 0 and res.scene == scene and len(res.cost_curve) == 1
    assert res.after == res.before


def test_supported_objects_follow_their_support_and_rise_with_its_vertical_scale():
    scene = Scene(
        room=ROOM,
        objects=[
            PlacedObject(id="desk", category="desk", position=(1.0, 0.0, 0.0), yaw=np.pi / 2),
            PlacedObject(id="laptop", category="laptop", position=(1.1, 0.75, 0.2), support="desk"),
        ],
    )
    model = LayoutModel(scene, ["desk"])
    state = np.array([[[0.1, -0.2, 1.0, 1.2]]])  # move desk, scale its height by 1.2
    lay = model.layouts(state)
    np.testing.assert_allclose(lay.position[0, 0], [1.1, 0.0, -0.2])
    np.testing.assert_allclose(lay.position[0, 1], [1.2, 0.9, 0.0], atol=1e-12)
    np.testing.assert_allclose(lay.scale[0, 0], [1.0, 1.2, 1.0])


def test_bad_interaction_target_is_a_clear_error():
    geom = SceneGeometry.from_arrays([("crate", _voxels((0.4, 0.5, 0.4), 2), {})])
    scene = Scene(room=ROOM, objects=[PlacedObject(id="crate", category="box")])
    motion = _motion(np.tile([0.0, 0.95, 0.0], (10, 1)), [])
    with pytest.raises(ValueError, match="not an object of the scene"):
        optimise_interaction(
            scene,
            lambda s: motion,
            Interaction(character="Eve", action="sit", targets=["chair"]),
            geometry=geom,
            settings=OptimiseSettings(),
        )
