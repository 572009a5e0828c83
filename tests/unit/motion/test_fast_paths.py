"""The fast paths: the phase-binned ONNX rollout, chain-only IK, spine lean for reach, clip cache, turning to a target."""

from __future__ import annotations

import numpy as np
import pytest

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.ik import bend_spine_to_reach, global_transforms, joint_globals, lock_feet, two_bone_ik
from services.motion.locomotion import MODEL_DIR
from services.motion.planning import plan_actions
from wana.domain import quat
from wana.domain.actions import get_clip
from wana.domain.skeleton import JOINT_INDEX, N_JOINTS


def _reference_fk_position(rot: np.ndarray, root: np.ndarray, joint: str) -> np.ndarray:
    from wana.domain.skeleton import (
        forward_kinematics,  # scipy-based reference FK, independent of services.motion.ik
    )

    return forward_kinematics(rot, root)[0][:, JOINT_INDEX[joint]]


def test_chain_fk_matches_the_reference_skeleton_fk():
    rot, off, _ = get_clip("wave").sample()
    root = off + [0.3, 0.95, -0.2]
    for joint in ("RightHandMiddle1", "LeftFoot", "Head"):
        pos, _ = joint_globals(rot, root, JOINT_INDEX[joint])
        assert np.allclose(pos, _reference_fk_position(rot, root, joint), atol=1e-9)
    full, _ = global_transforms(rot, root)
    assert np.allclose(
        full[:, JOINT_INDEX["LeftHand"]], _reference_fk_position(rot, root, "LeftHand"), atol=1e-9
    )


def test_ik_leaves_frames_with_zero_weight_untouched_and_solves_the_rest():
    rot, off, _ = get_clip("wave").sample()
    root = off + [0, 0.95, 0]
    weight = np.zeros(len(rot))
    weight[10:20] = 1.0
    target = np.array([-0.3, 1.2, 0.4])
    out = two_bone_ik(rot, root, "RightHandMiddle1", target, weight)
    assert np.array_equal(out[:10], rot[:10]) and np.array_equal(out[20:], rot[20:])
    hand = _reference_fk_position(out, root, "RightHandMiddle1")
    assert np.linalg.norm(hand[10:20] - target, axis=1).max() < 0.005


def test_foot_locking_pins_a_sliding_planted_foot():
    t = 30
    rot = np.repeat(get_clip("idle").sample()[0][:1], t, 0)
    root = np.stack(
        [np.linspace(0, 0.1, t), np.full(t, 0.85), np.zeros(t)], -1
    )  # hips drift 10 cm, knees a little bent
    contacts = np.ones((t, 2), np.uint8)
    locked = lock_feet(rot, root, contacts)
    foot = _reference_fk_position(locked, root, "LeftFoot")
    assert (
        np.linalg.norm(foot - foot[0], axis=1).max() < 0.01
    )  # straight legs at rest: 2 analytic passes leave < 1 cm
    raw = _reference_fk_position(rot, root, "LeftFoot")
    assert np.linalg.norm(raw - raw[0], axis=1).max() > 0.09


def test_spine_leans_only_as_far_as_a_low_target_needs():
    rot = np.repeat(get_clip("idle").sample()[0][:1], 20, 0)
    root = np.tile([0.0, 0.95, 0.0], (20, 1))
    weight = np.ones(20)
    low = np.array([-0.2, 0.7, 0.45])  # a table edge in front, too low for a standing arm
    bent = bend_spine_to_reach(rot, root, "RightHandMiddle1", low, weight)
    assert not np.allclose(bent, rot)
    solved = two_bone_ik(bent, root, "RightHandMiddle1", low, weight)
    assert np.linalg.norm(_reference_fk_position(solved, root, "RightHandMiddle1") - low, axis=1).max() < 0.01
    near = np.array([-0.3, 1.2, 0.35])  # already within reach: no lean
    assert np.array_equal(bend_spine_to_reach(rot, root, "RightHandMiddle1", near, weight), rot)


def test_clip_samples_are_cached_but_handed_out_as_copies():
    clip = get_clip("wave")
    a, _, _ = clip.sample(30, 2.0)
    a[:] = 0.0
    b, _, _ = clip.sample(30, 2.0)
    assert np.allclose(np.linalg.norm(b, axis=-1), 1.0)


def test_a_character_already_at_the_desk_turns_to_face_it_before_wiping():
    scene = Scene(
        room=Room(room_type="office", width=6, depth=6, height=3),
        objects=[PlacedObject(id="desk", category="desk", position=(0.0, 0.0, 0.0), yaw=0.0)],
    )
    # Standing at the desk's front, but facing away from it (+Z).
    ch = CharacterNode(name="Eve", actions=[ActionNode(verb="wipe", action="wipe_table", target="desk")])
    plan = plan_actions(ch, scene, (0.0, 0.75, 0.0))
    kinds = [(s.kind, s.action) for s in plan.segments]
    assert kinds[-1] == ("action", "wipe_table") and kinds[0][0] == "locomotion"
    assert abs(np.cos(plan.segments[0].face_yaw - np.pi)) > 0.99  # turns to face -Z, toward the desk


@pytest.mark.skipif(
    not (MODEL_DIR / "pfnn_fast.onnx").is_file(), reason="no pfnn_fast.onnx (run services.motion.pfnn_onnx)"
)
def test_fast_rollout_matches_torch_at_the_bin_phases():
    ort = pytest.importorskip("onnxruntime")
    torch = pytest.importorskip("torch")
    from services.motion.pfnn import N_OUT, N_POSE, SLICE_DPHASE, SLICE_POSE
    from services.motion.pfnn_onnx import PHASE_BINS
    from services.motion.train_locomotion import load_torch

    net = load_torch()
    sess = ort.InferenceSession(str(MODEL_DIR / "pfnn_fast.onnx"), providers=["CPUExecutionProvider"])
    steps = sess.get_inputs()[0].shape[1]
    rng = np.random.default_rng(1)
    ctrl = (rng.normal(size=(1, steps, 60)) * 0.2).astype(np.float32)
    pose = (net.x_mean.numpy()[60:] + 0.1 * rng.normal(size=N_POSE) * net.x_std.numpy()[60:]).astype(
        np.float32
    )[None]
    phase = np.array([[0.37]], np.float32)
    y, last_pose, last_phase = sess.run(None, {"control": ctrl, "pose": pose, "phase": phase})
    assert y.shape == (1, steps, N_OUT)
    # Reference: the torch network run step by step at the centre of each step's phase bin.
    p, ph = torch.from_numpy(pose), float(phase[0, 0])
    with torch.no_grad():
        for k in range(3):
            centre = (np.floor(ph * PHASE_BINS) + 0.5) / PHASE_BINS
            ref = net(
                torch.cat([torch.from_numpy(ctrl[:, k]), p], 1), torch.tensor([[centre]], dtype=torch.float32)
            )
            assert np.abs(y[0, k] - ref[0].numpy()).max() < 2e-2 * max(1.0, float(ref.abs().max()))
            p = torch.from_numpy(y[:, k, SLICE_POSE])
            ph = (ph + float(np.clip(y[0, k, SLICE_DPHASE][0], 0, 0.5))) % 1.0
    assert last_pose.shape == (1, N_POSE) and 0.0 <= float(last_phase[0, 0]) < 1.0


def test_quaternion_helpers_agree_with_scipy():
    from scipy.spatial.transform import Rotation

    rng = np.random.default_rng(2)
    a, b = quat.normalize(rng.normal(size=(50, 4))), quat.normalize(rng.normal(size=(50, 4)))
    assert np.allclose(
        quat.canonical(quat.mul(a, b)),
        quat.canonical((Rotation.from_quat(a) * Rotation.from_quat(b)).as_quat()),
    )
    v = rng.normal(size=(50, 3))
    assert np.allclose(quat.rotate(a, v), Rotation.from_quat(a).apply(v))
    assert np.allclose(quat.cross(v, v[::-1]), np.cross(v, v[::-1]))
    assert N_JOINTS == 24


def test_numpy_phase_table_rollout_matches_onnxruntime_on_the_same_graph():
    assert (MODEL_DIR / "pfnn_fast.onnx").is_file(), "pfnn_fast.onnx is committed in models/locomotion"
    from services.motion.locomotion import PfnnRuntime, plan_root, standing_pose_features
    from services.motion.locomotion_features import sensor_features, trajectory_features
    from services.motion.pfnn_tables import PhaseTableRuntime

    pos, heading, _ = plan_root(np.array([[0.0, 0.0], [3.0, 1.0], [4.0, 4.0]]), 1.4, 0.0, face_yaw=1.0)
    control = np.concatenate([trajectory_features(pos, heading), sensor_features(pos, heading)], axis=1)
    ref = PfnnRuntime().run(control, standing_pose_features(), 0.3)
    out = PhaseTableRuntime(MODEL_DIR / "pfnn_fast.onnx").run(control, standing_pose_features(), 0.3)
    assert out.shape == ref.shape and np.all(np.isfinite(out))
    assert np.abs(out - ref).max() < 1e-3 * max(1.0, float(np.abs(ref).max()))
