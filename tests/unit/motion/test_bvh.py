"""BVH round trips and retargeting."""

from __future__ import annotations

import numpy as np
import pytest

from services.motion.retarget import retarget_clip
from wana.domain import quat
from wana.domain.bvh import BvhError, canonical_motion, parse_bvh, read_bvh, write_bvh, write_clip
from wana.domain.skeleton import JOINT_INDEX, forward_kinematics


def _random_motion(t: int = 20, seed: int = 0):
    rng = np.random.default_rng(seed)
    rot = quat.normalize(rng.normal(size=(t, 24, 4)) * 0.3 + np.array([0, 0, 0, 1.0]))
    root = rng.normal(size=(t, 3))
    return root, rot


def test_write_then_read_reproduces_the_motion(tmp_path):
    root, rot = _random_motion()
    write_bvh(tmp_path / "a.bvh", root, rot, fps=30)
    clip = read_bvh(tmp_path / "a.bvh")
    assert clip.fps == pytest.approx(30, rel=1e-6)
    r2, q2 = canonical_motion(clip)
    assert np.abs(r2 - root).max() < 1e-5
    assert np.abs(np.abs(np.sum(q2 * rot, axis=-1)) - 1).max() < 1e-8


def test_round_trip_reproduces_every_channel(tmp_path):
    root, rot = _random_motion(seed=1)
    write_bvh(tmp_path / "a.bvh.gz", root, rot, scale=100.0)
    first = read_bvh(tmp_path / "a.bvh.gz")
    write_clip(tmp_path / "b.bvh", first)
    second = read_bvh(tmp_path / "b.bvh")
    assert second.joint_names == first.joint_names and second.channels == first.channels
    assert np.abs(second.motion - first.motion).max() <= 1e-4


def test_malformed_bvh_names_the_problem():
    with pytest.raises(BvhError, match="HIERARCHY"):
        parse_bvh("nope")
    text = "HIERARCHY\nROOT Hips\n{\nOFFSET 0 0 0\nCHANNELS 3 Xposition Yposition Zposition\n}\nMOTION\nFrames: 2\nFrame Time: 0.1\n0 0 0\n"
    with pytest.raises(BvhError, match="Frames"):
        parse_bvh(text)


def test_retarget_of_a_canonical_file_in_centimetres_recovers_positions(tmp_path):
    from wana.domain.actions import get_clip

    rot, offs, _ = get_clip("wave").sample()
    root = offs + np.array([0.0, 0.95, 0.0])
    write_bvh(tmp_path / "w.bvh", root, rot, scale=100.0)
    r2, q2 = retarget_clip(read_bvh(tmp_path / "w.bvh"), fps=30)
    p1, _ = forward_kinematics(rot, root)
    p2, _ = forward_kinematics(q2, r2)
    hand = JOINT_INDEX["RightHand"]
    rel1 = p1[:, hand] - p1[:, 0]
    rel2 = p2[: len(p1), hand] - p2[: len(p1), 0]
    assert np.abs(rel1 - rel2).max() < 0.03


@pytest.mark.data
def test_retarget_cmu_iclone_walk(shared_data):
    clip = read_bvh(shared_data / "cmu_mocap_iclone" / "bvh" / "007_02.bvh.gz")
    assert len(clip.joint_names) == 100 and clip.fps == pytest.approx(60, rel=1e-3)
    root, rot = retarget_clip(clip)
    assert len(root) == pytest.approx(clip.n_frames / 2, abs=2)
    pos, _ = forward_kinematics(rot, root)
    head, foot = pos[:, JOINT_INDEX["Head"], 1], pos[:, JOINT_INDEX["LeftFoot"], 1]
    assert 1.35 < head.mean() < 1.75 and foot.min() > -0.05 and foot.min() < 0.2
    travel = np.linalg.norm(root[-1, [0, 2]] - root[0, [0, 2]])
    assert travel > 1.0  # the subject walks a few metres
