"""The Daz-skeleton CMU takes retargeted onto ours: walking forward, feet on the floor, arms down, people apart."""

from __future__ import annotations

import numpy as np
import pytest

from services.motion.retarget import DAZ_MAP, guess_map, source_joints
from services.motion.train_locomotion import (
    HELD_OUT_SUBJECTS,
    SHARED,
    annotate,
    daz_clip,
    daz_heldout_rows,
    daz_training_rows,
)
from wana.domain import quat
from wana.domain.skeleton import JOINT_INDEX, REST_OFFSETS, forward_kinematics

DAZ = SHARED / "cmu_locomotion_daz"
needs_data = pytest.mark.skipif(
    not (DAZ / "labels.csv").is_file(), reason="../shared/data/cmu_locomotion_daz absent"
)


def test_the_daz_map_is_guessed_from_its_joint_names_and_reads_midpoints_and_end_sites():
    names = sorted({n for v in DAZ_MAP.values() for n in source_joints(v)}) + ["leftEye", "rButtock"]
    assert guess_map(names) == DAZ_MAP
    assert source_joints("hip|abdomen") == ["hip", "abdomen"]
    assert source_joints("lFoot@end") == ["lFoot"]


@needs_data
def test_held_out_subjects_never_reach_training():
    train = {int(r["subject"]) for r in daz_training_rows()}
    held = {int(r["subject"]) for r in daz_heldout_rows()}
    assert held == set(HELD_OUT_SUBJECTS)
    assert not train & held
    assert {8, 9, 10} <= train  # the new people


@needs_data
@pytest.mark.parametrize("take", ["02_01", "09_02", "12_02"])
def test_a_retargeted_take_walks_forward_on_the_floor_with_our_bone_lengths(take):
    root, rot = daz_clip(DAZ / "bvh" / f"{take}.bvh.gz")
    pos, glob = forward_kinematics(rot, root)
    j = JOINT_INDEX
    # Our bone lengths, whatever the subject's.
    thigh = np.linalg.norm(pos[:, j["LeftLeg"]] - pos[:, j["LeftUpLeg"]], axis=1)
    assert np.allclose(thigh, np.linalg.norm(REST_OFFSETS[j["LeftLeg"]]), atol=1e-6)
    # Planted feet on the floor (ankle 6 cm up), hips at walking height.
    _, _, heading, _, contacts, _ = annotate(root, rot)
    planted = pos[contacts[:, 0] > 0, j["LeftFoot"], 1]
    assert len(planted) and abs(np.median(planted) - 0.06) < 0.02
    assert 0.8 < np.median(root[:, 1]) < 0.97
    # The body faces where it goes and the toes point forward.
    travel = root[-1, [0, 2]] - root[0, [0, 2]]
    facing = quat.rotate(glob[:, j["Hips"]], np.array([0.0, 0.0, 1.0]))[:, [0, 2]].mean(0)
    assert travel @ facing / (np.linalg.norm(travel) * np.linalg.norm(facing)) > 0.9
    toe = (pos[:, j["LeftToeBase"]] - pos[:, j["LeftFoot"]])[:, [0, 2]].mean(0)
    assert travel @ toe > 0
    # No rest T-pose left at the start: the hands hang below the shoulders.
    assert pos[0, j["LeftHand"], 1] < pos[0, j["LeftArm"], 1] - 0.05
    # Knees bend forward, not backward: the knee is ahead of the hip-ankle line on average.
    knee = pos[:, j["LeftLeg"]] - 0.5 * (pos[:, j["LeftUpLeg"]] + pos[:, j["LeftFoot"]])
    fwd = np.stack([np.sin(heading), np.zeros_like(heading), np.cos(heading)], -1)
    assert np.mean(np.sum(knee * fwd, axis=1)) > 0.0
