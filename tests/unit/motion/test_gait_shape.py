"""The procedural gait's shape against the captured training walkers, and the network pose low-pass."""

from __future__ import annotations

import numpy as np
import pytest

from services.motion.gait import duty_factor, synthesize_gait
from services.motion.ik import global_transforms
from services.motion.locomotion import smooth_rotations
from services.motion.locomotion_features import to_local
from wana.domain import quat
from wana.domain.skeleton import JOINT_INDEX
from wana.domain.units import FPS


def _straight(speed: float, frames: int = 240):
    pos = np.stack([np.zeros(frames), np.arange(frames) * speed / FPS], -1)
    heading = np.zeros(frames)
    g = synthesize_gait(pos, heading, np.full(frames, speed))
    joints, _ = global_transforms(g["rotations"], g["root_position"])
    local = to_local(joints, pos, heading)[60:]  # past the first cycle
    return g, np.diff(local, axis=0) * FPS  # (T, J, 3) velocities in the heading frame


@pytest.mark.parametrize(("speed", "low", "high"), [(1.0, 0.47, 0.55), (2.5, 0.40, 0.46)])
def test_duty_factor_is_the_captured_walkers_stance(speed, low, high):
    assert low <= float(duty_factor(np.array(speed))) <= high


def test_procedural_contacts_last_the_duty_share():
    g, _ = _straight(1.0)
    assert g["contacts"][60:].mean() == pytest.approx(float(duty_factor(np.array(1.0))), abs=0.04)


@pytest.mark.parametrize(("speed", "most"), [(0.9, 0.1), (1.4, 0.19)])
def test_hips_bob_like_captured_walkers(speed, most):
    # the training takes' hips move 0.09 m/s vertically at 0.9 m/s and 0.15-0.2 at 1.6 (flat-footed
    # fixed-length legs needed 0.15 and 0.29)
    _, vel = _straight(speed)
    assert 0.03 < vel[:, JOINT_INDEX["Hips"], 1].std() < most


def test_hands_swing_sideways_and_rise_in_front():
    _, vel = _straight(1.4)
    for side in ("Left", "Right"):
        hand = vel[:, JOINT_INDEX[f"{side}Hand"]]
        assert hand[:, 0].std() > 0.1  # across the body, not a pendulum about one axis
        assert hand[:, 1].std() > 0.15


def test_smoothing_takes_out_jitter_and_keeps_a_steady_turn():
    rng = np.random.default_rng(0)
    t = 90
    angle = np.linspace(0, 1.5, t)
    steady = quat.from_axis_angle(np.array([0.0, 1.0, 0.0]), angle[:, None] * np.ones((1, 3)))
    noisy = quat.normalize(steady + rng.normal(0, 0.02, steady.shape))
    noisy[::7] *= -1  # sign flips are the same rotation and must not be averaged away
    out = smooth_rotations(noisy)
    assert np.allclose(np.linalg.norm(out, axis=-1), 1.0)

    def err(q):
        return np.abs(np.abs(np.sum(q * steady, axis=-1)) - 1.0)[3:-3].mean()

    assert err(out) < 0.5 * err(noisy)
    assert np.allclose(np.abs(np.sum(smooth_rotations(steady) * steady, -1))[3:-3], 1.0, atol=1e-6)
