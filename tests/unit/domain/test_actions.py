"""The action library: size, required actions, valid data, clips that really move."""

from __future__ import annotations

import numpy as np
import pytest

from wana.domain.actions import action_names, clip_from_dict, get_clip, load_library, synonym_index

REQUIRED = (
    "sit stand type play_piano call_with_phone drink sing_with_microphone listen_with_headphones "
    "write_on_blackboard punch_bag saw hammer look_at think wave push_button read turn_left turn_right "
    "wave_hands high_five shake_hands hug bow apologize criticize quarrel clap point"
).split()


def test_library_has_at_least_150_actions_including_the_papers_examples():
    names = action_names()
    assert len(names) >= 150
    assert [r for r in REQUIRED if r not in names] == []


def test_every_clip_has_metadata_and_moves_the_body():
    for name, clip in load_library().items():
        assert clip.tags and clip.duration_s > 0 and clip.body_parts, name
        rot, root, yaw = clip.sample()
        assert rot.shape[1:] == (24, 4) and np.all(np.isfinite(rot)), name
        assert np.allclose(np.linalg.norm(rot, axis=-1), 1.0, atol=1e-6), name
        # the body moves: some joint rotates by more than 2 degrees (idle breathing is subtle), or the root travels / turns
        d = np.abs(np.sum(rot[:, None] * rot[None, :1], axis=-1)).min()
        moved = (
            2 * np.degrees(np.arccos(min(1.0, d))) > 2
            or np.ptp(root, axis=0).max() > 0.02
            or np.ptp(yaw) > 0.1
        )
        assert moved, f"{name} does not move"


def test_interaction_clips_name_their_contact_joints():
    lib = load_library()
    assert lib["sit"].interaction.object == "seat" and lib["sit"].contact_joints == ("Hips",)
    assert set(lib["type"].contact_joints) == {"LeftHandMiddle1", "RightHandMiddle1"}
    assert lib["wave"].interaction is None


def test_synonyms_resolve_to_actions():
    idx = synonym_index()
    assert idx["take a seat"] == "sit"
    assert get_clip("applaud").name == "clap"
    with pytest.raises(KeyError):
        get_clip("levitate_wildly")


def test_bad_clip_data_is_refused_with_a_clear_message():
    with pytest.raises(ValueError, match="unknown joint"):
        clip_from_dict({"name": "x", "duration_s": 1, "keys": [{"t": 0, "pose": {"Tail": [0, 0, 0]}}]})
    with pytest.raises(ValueError, match="missing field"):
        clip_from_dict({"name": "x"})


def test_looping_clip_repeats_and_holds_its_period():
    clip = get_clip("type")
    rot, _, _ = clip.sample(30, clip.duration_s * 3)
    n = int(round(clip.duration_s * 30))
    assert np.allclose(np.abs(np.sum(rot[0] * rot[n], axis=-1)), 1.0, atol=1e-6)


def test_euler_angles_become_the_quaternions_scipy_gives_bit_for_bit():
    """quat.from_euler composes the elementary turns itself (the library's 16,000 keys loaded in 1.5 s through
    scipy, 0.2 s now): the same bits, signs included, for every order and the +-180 degree edges."""
    from scipy.spatial.transform import Rotation

    from wana.domain import quat

    rng = np.random.default_rng(3)
    angles = np.concatenate([rng.uniform(-180, 180, (500, 3)), [[180, 0, -180], [0, 0, 0], [-180, 90, 180]]])
    for order in ("ZXY", "ZYX", "XYZ", "YXZ", "XZY", "YZX"):
        want = Rotation.from_euler(order, angles, degrees=True).as_quat()
        assert np.array_equal(quat.from_euler(order, angles), want), order
        assert np.array_equal(quat.from_euler(order, angles[7]), want[7])
