"""eval/motion.py's liveliness measures: frozen_share and the per-clip review lists."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest

from wana.domain import quat

REPO = Path(__file__).resolve().parents[3]


@pytest.fixture(scope="module")
def motion_eval():
    spec = importlib.util.spec_from_file_location("motion_eval", REPO / "eval" / "motion.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules["motion_eval"] = module
    spec.loader.exec_module(module)
    return module


def _spinning(frames: int, deg_per_frame: float) -> np.ndarray:
    """(T, 2, 4) global rotations: one joint still, one turning about Y."""
    g = np.zeros((frames, 2, 4))
    g[..., 3] = 1.0
    g[:, 1] = quat.yaw(np.radians(deg_per_frame) * np.arange(frames))
    return g


def test_a_frame_is_frozen_only_when_no_joint_turns_more_than_a_tenth_of_a_degree(motion_eval):
    assert motion_eval.frozen_share(_spinning(20, 0.0)) == 1.0
    assert motion_eval.frozen_share(_spinning(20, 0.05)) == 1.0
    assert motion_eval.frozen_share(_spinning(20, 0.2)) == 0.0
    half = _spinning(21, 0.2)
    half[11:] = half[10]  # turns for 10 frames, then holds for 10
    assert motion_eval.frozen_share(half) == pytest.approx(0.5)


def test_frames_off_stage_do_not_count(motion_eval):
    g = _spinning(21, 0.2)
    g[11:] = g[10]
    present = np.r_[np.ones(11), np.zeros(10)].astype(np.uint8)
    assert motion_eval.frozen_share(g, present) == 0.0


def test_the_clip_review_lists_twenty_clips_by_jerk_and_by_energy(motion_eval):
    review = motion_eval.clip_review()
    assert len(review["clips_highest_jerk"]) == 20 and len(review["clips_lowest_energy"]) == 20
    jerks = [j for _, j in review["clips_highest_jerk"]]
    assert jerks == sorted(jerks, reverse=True)
    rows = review["clips"]
    assert set(rows["wave"]) == {"jerk", "energy_deg_s", "frozen_share", "seconds"}
    assert rows["idle"]["energy_deg_s"] < rows["wave"]["energy_deg_s"]


def test_the_longest_frozen_run_is_measured_in_seconds_on_stage_only(motion_eval):
    g = _spinning(61, 0.2)
    g[31:] = g[30]  # turns for 30 frames, then holds for 30 (one second)
    assert motion_eval.longest_frozen_s(g) == pytest.approx(1.0)
    g[45:50] = _spinning(61, 0.2)[45:50]  # a short move in the hold splits it: 14 frames, then 11
    assert motion_eval.longest_frozen_s(g) == pytest.approx(14 / 30)
    present = np.r_[np.ones(40), np.zeros(21)].astype(np.uint8)  # off stage from frame 40
    assert motion_eval.longest_frozen_s(g, present) == pytest.approx(9 / 30)
    assert motion_eval.longest_frozen_s(_spinning(61, 0.2)) == 0.0
