"""eval/gait.py's Frechet-distance decomposition: per-feature terms that add up to the distance."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest

_SPEC = importlib.util.spec_from_file_location("eval_gait", Path(__file__).parents[3] / "eval" / "gait.py")
gait = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(gait)


def _windows(rng: np.random.Generator, shift: float, scale: float) -> np.ndarray:
    n = len(gait.feature_names())
    mix = rng.normal(size=(n, n)) * 0.2 + np.eye(n)
    return (rng.normal(size=(400, n)) * scale) @ mix + shift


def test_feature_names_match_the_window_layout():
    names = gait.feature_names()
    assert len(names) == 44 and len(set(names)) == 44
    assert names[0] == "mean:Hips.y" and names[22] == "std:Hips.y" and "std:LeftFoot.z" in names


def test_terms_and_joint_rows_sum_to_the_frechet_distance():
    rng = np.random.default_rng(3)
    a, b = _windows(rng, 0.0, 1.0), _windows(rng, 0.3, 1.4)
    fd = gait.frechet_distance(a, b)
    mean_t, cov_t = gait.frechet_terms(a, b)
    assert mean_t.sum() + cov_t.sum() == pytest.approx(fd, rel=1e-9)
    rows = gait.fd_by_joint(a, b)
    assert set(rows) == set(gait.FEATURE_JOINTS)
    assert sum(r["total"] for r in rows.values()) == pytest.approx(fd, abs=1e-3)
    for r in rows.values():
        assert r["mean_features"] + r["std_features"] == pytest.approx(r["total"], abs=1e-3)


def test_a_shifted_joint_carries_the_mean_term():
    rng = np.random.default_rng(4)
    a = _windows(rng, 0.0, 1.0)
    b = a.copy()
    head = [i for i, n in enumerate(gait.feature_names()) if ".".join(n.split(":")[1:]).startswith("Head")]
    b[:, head] += 0.5
    rows = gait.fd_by_joint(a, b)
    assert rows["Head"]["mean_term"] == pytest.approx(0.25 * len(head), rel=1e-6)
    assert max(r["total"] for j, r in rows.items() if j != "Head") < 1e-6
    assert gait.top_features(a, b, 3)[0]["feature"].split(":")[1].startswith("Head")
