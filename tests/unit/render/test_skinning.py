"""Linear-blend skinning against the character module's own reference implementation."""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from services.render.demo import hips_path, walk_motion
from services.render.skinning import Rig, character_for
from wana.assets.characters import make_character, pose_vertices
from wana.domain.skeleton import N_JOINTS, identity_pose


def test_skinned_vertices_match_the_reference_skinning_for_random_poses_and_expressions():
    ch = make_character("Eve")
    rng = np.random.default_rng(7)
    rot = Rotation.from_rotvec(rng.normal(0, 0.5, (4 * N_JOINTS, 3))).as_quat().reshape(4, N_JOINTS, 4)
    root = rng.uniform(-1, 1, (4, 3)) + [0, 1, 0]
    expr = rng.uniform(0, 1, (4, 8))
    rig = Rig(character=ch, root=root, rotations=rot, expression=expr)
    np.testing.assert_allclose(rig.vertices(range(4)), pose_vertices(ch, rot, root, expr), atol=1e-9)


def test_rest_pose_at_the_rest_hips_gives_the_rest_mesh():
    ch = make_character("Tom")
    rig = Rig(character=ch, root=ch.offsets[None, 0].astype(float), rotations=identity_pose(1))
    np.testing.assert_allclose(rig.vertices([0])[0], ch.vertices, atol=1e-5)


def test_a_walk_puts_the_hips_joint_where_the_motion_says():
    m = walk_motion("Eve", (-1.0, 0.5), (1.0, -0.5), 40)
    rig = Rig.from_motion(m)
    np.testing.assert_allclose(
        rig.joint_positions[:, 0], hips_path("Eve", (-1.0, 0.5), (1.0, -0.5), 40), atol=1e-5
    )
    track = rig.track()
    d = np.array([2.0, 0.0, -1.0]) / np.linalg.norm([2.0, 0.0, -1.0])
    assert np.all(track.facing @ d > 0.99)  # the walk faces its direction of travel


def test_unknown_character_names_borrow_a_built_in_look_deterministically():
    assert character_for("Zebulon").name == character_for("Zebulon").name
    assert character_for("eve").name == "Eve"
