"""Procedural characters: skinning data, proportions, face blendshapes and the glTF round trip."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from scipy.spatial.transform import Rotation

from wana.assets.characters import EXPRESSIONS, character_names, make_character, pose_vertices
from wana.assets.gltf import export_character_glb, load_character_glb, read_glb
from wana.domain.skeleton import JOINT_INDEX, N_JOINTS, identity_pose


def test_at_least_ten_characters_with_different_heights_and_clothes():
    names = character_names()
    assert len(names) >= 10
    chars = [make_character(n) for n in names]
    heights = {round(c.height, 2) for c in chars}
    assert len(heights) >= 8
    for c in chars:
        top = c.vertices[:, 1].max()
        assert abs(top - c.height) < 0.06, c.name
        assert abs(c.vertices[:, 1].min()) < 1e-3  # feet on the floor
    shirts = {tuple(c.colours[np.argmax(c.joints[:, 0] == JOINT_INDEX["Spine1"])]) for c in chars}
    assert len(shirts) >= 8


def test_skin_weights_are_normalised_and_name_real_joints():
    c = make_character("Tom")
    assert c.joints.shape == c.weights.shape == (len(c.vertices), 4)
    assert np.allclose(c.weights.sum(axis=1), 1.0, atol=1e-5)
    assert c.joints.max() < N_JOINTS
    assert len(np.unique(c.joints[:, 0])) == N_JOINTS  # every bone drives some vertices


def test_rest_pose_skinning_is_identity_and_a_raised_arm_moves_the_hand():
    c = make_character("Mary")
    root = c.rest_joint_positions()[None, 0]
    rest = pose_vertices(c, identity_pose(1), root)[0]
    assert np.allclose(rest, c.vertices, atol=1e-5)
    pose = identity_pose(1)
    pose[0, JOINT_INDEX["LeftArm"]] = Rotation.from_euler("z", 80, degrees=True).as_quat()
    moved = pose_vertices(c, pose, root)[0]
    hand = c.joints[:, 0] == JOINT_INDEX["LeftHand"]
    legs = c.joints[:, 0] == JOINT_INDEX["RightLeg"]
    assert moved[hand, 1].mean() > rest[hand, 1].mean() + 0.3
    assert np.allclose(moved[legs], rest[legs], atol=1e-6)


def test_face_blendshapes_move_only_the_face():
    c = make_character("Eve")
    assert len(EXPRESSIONS) >= 6 and set(EXPRESSIONS) <= set(c.blendshapes)
    head = c.joints[:, 0] == JOINT_INDEX["Head"]
    for name in EXPRESSIONS:
        d = np.linalg.norm(c.blendshapes[name], axis=1)
        assert d.max() > 0.002, name
        assert np.all(d[~head] == 0.0), name
    smile, frown = c.blendshapes["smile"], c.blendshapes["frown"]
    moved = np.linalg.norm(smile, axis=1) > 0
    assert smile[moved, 1].mean() > 0 > frown[moved, 1].mean()


def test_expression_weights_blend_linearly():
    c = make_character("Leo")
    root = c.rest_joint_positions()[None, 0]
    half = pose_vertices(c, identity_pose(1), root, {"smile": 0.5})[0]
    assert np.allclose(half, c.vertices + 0.5 * c.blendshapes["smile"], atol=1e-5)


@pytest.mark.parametrize("name", ["Eve", "Max"])
def test_gltf_export_reimports_unchanged(tmp_path, name):
    c = make_character(name)
    path = export_character_glb(c, tmp_path / f"{name}.glb")
    back = load_character_glb(path)
    assert back.name == c.name and back.height == c.height
    for field in ("offsets", "vertices", "faces", "colours", "joints", "weights"):
        a, b = getattr(c, field), getattr(back, field)
        assert a.dtype == b.dtype and np.array_equal(a, b), field
    assert set(back.blendshapes) == set(c.blendshapes)
    for k in c.blendshapes:
        assert np.array_equal(back.blendshapes[k], c.blendshapes[k])
    gltf, _ = read_glb(path)
    assert len(gltf["skins"][0]["joints"]) == N_JOINTS
    loaded = trimesh.load(path, force="mesh")  # an independent reader parses the same geometry
    assert len(loaded.faces) == len(c.faces)


def test_unknown_character_and_bad_files_are_clear_errors(tmp_path):
    with pytest.raises(KeyError, match="unknown character"):
        make_character("Nobody")
    bad = tmp_path / "x.glb"
    bad.write_bytes(b"not a glb file at all")
    with pytest.raises(ValueError, match="glTF"):
        load_character_glb(bad)
