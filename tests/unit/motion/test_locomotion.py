"""PFNN: ONNX-vs-torch parity, phase function, controller, procedural gait."""

from __future__ import annotations

import numpy as np
import pytest
import torch

from services.motion.gait import random_trajectory, synthesize_gait
from services.motion.ik import global_transforms
from services.motion.locomotion import MODEL_DIR, locomote, plan_root
from services.motion.pfnn import N_IN, PFNN, catmull_rom_coefficients
from wana.domain.skeleton import JOINT_INDEX


def test_catmull_rom_weights_sum_to_one_and_pick_the_control_set_at_knots():
    phase = torch.tensor([[0.0], [0.25], [0.5], [0.75], [0.1], [0.9]])
    c = catmull_rom_coefficients(phase)
    assert torch.allclose(c.sum(1), torch.ones(6), atol=1e-6)
    assert torch.allclose(c[:4], torch.eye(4), atol=1e-6)


def test_onnx_matches_torch():
    ort = pytest.importorskip("onnxruntime")
    if not (MODEL_DIR / "pfnn_step.onnx").is_file():
        pytest.skip("no trained model in models/locomotion (run services.motion.train_locomotion)")
    from services.motion.train_locomotion import load_torch

    net = load_torch()
    rng = np.random.default_rng(0)
    x = rng.normal(size=(16, N_IN)).astype(np.float32) * net.x_std.numpy() + net.x_mean.numpy()
    ph = rng.uniform(size=(16, 1)).astype(np.float32)
    with torch.no_grad():
        ref = net(torch.from_numpy(x), torch.from_numpy(ph)).numpy()
    sess = ort.InferenceSession(str(MODEL_DIR / "pfnn_step.onnx"), providers=["CPUExecutionProvider"])
    out = sess.run(None, {"x": x, "phase": ph})[0]
    assert np.abs(out - ref).max() < 1e-3 * max(1.0, np.abs(ref).max())


def test_untrained_network_exports_with_normalisation_inside(tmp_path):
    pytest.importorskip("onnxruntime")
    from services.motion.train_locomotion import export

    net = PFNN(hidden=16)
    net.x_mean.fill_(2.0)
    net.y_std.fill_(3.0)
    export(net, tmp_path)
    import onnxruntime as ort

    x = np.full((1, N_IN), 2.0, np.float32)
    ph = np.zeros((1, 1), np.float32)
    with torch.no_grad():
        ref = net.eval()(torch.from_numpy(x), torch.from_numpy(ph)).numpy()
    out = ort.InferenceSession(str(tmp_path / "pfnn_step.onnx")).run(None, {"x": x, "phase": ph})[0]
    assert np.allclose(out, ref, atol=1e-4)


def test_controller_stops_at_the_goal_facing_the_target():
    pos, heading, speed = plan_root(np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 3.0]]), 1.4, 0.0, face_yaw=np.pi)
    assert np.linalg.norm(pos[-1] - [2.0, 3.0]) < 1e-6
    assert abs(np.sin(heading[-1] - np.pi)) < 1e-6 and np.cos(heading[-1] - np.pi) > 0
    assert speed.max() <= 1.4 + 1e-9 and speed[-1] == 0


@pytest.mark.parametrize("use_network", [True, False])
def test_locomotion_follows_waypoints_with_planted_feet(use_network):
    loco = locomote(np.array([[0.0, 0.0], [3.0, 2.0]]), 1.4, 0.0, use_network=use_network)
    assert np.linalg.norm(loco.root_position[-1, [0, 2]] - [3.0, 2.0]) < 0.05
    assert loco.rotations.shape == (len(loco.root_position), 24, 4) and np.all(np.isfinite(loco.rotations))
    hips = loco.root_position[:, 1]
    assert 0.7 < hips.mean() < 1.0


def test_procedural_gait_does_not_slide():
    rng = np.random.default_rng(5)
    pos, heading, speed = random_trajectory(rng, 8.0)
    g = synthesize_gait(pos, heading, speed)
    p, _ = global_transforms(g["rotations"], g["root_position"])
    for k, name in enumerate(("LeftFoot", "RightFoot")):
        c = g["contacts"][:, k].astype(bool)
        both = c[1:] & c[:-1]
        slide = np.linalg.norm(np.diff(p[:, JOINT_INDEX[name]][:, [0, 2]], axis=0), axis=1)[both]
        assert slide.mean() < 0.005
