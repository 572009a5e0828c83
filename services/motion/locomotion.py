"""Locomotion at run time: a path-following controller driving the PFNN through onnxruntime.

The controller turns waypoints and a speed into a root trajectory at 30 fps (accelerating from rest,
rate-limited turning, decelerating to stop at the goal, then turning in place to face a target);
the network, given that trajectory, produces the poses autoregressively. The rollout runs
models/locomotion/pfnn_fast.onnx in onnxruntime (one thread); WANA_PFNN_RUNTIME=numpy runs the
same graph's phase tables in numpy instead (services.motion.pfnn_tables: the same arithmetic
without onnxruntime's per-frame weight gathers, about 1.5x faster, equal to 1e-5). Without the
ONNX model it falls back to the procedural gait, so synthesis always works.

The root follows the planned path exactly: the network's root-velocity output (dx, dz, dyaw) is
trained but not used at run time, so path following stays exact; the network supplies the poses,
foot contacts and the phase.
"""

from __future__ import annotations

import functools
import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Protocol

import numpy as np

from services.motion.gait import synthesize_gait
from services.motion.gait_style import apply_gait_style, gait_style
from services.motion.locomotion_features import sensor_features, trajectory_features
from services.motion.pfnn_layout import (
    N_JOINTS,
    N_OUT,
    N_POSE,
    SLICE_CONTACT,
    SLICE_DPHASE,
    SLICE_POSE,
    SLICE_ROOT,
    SLICE_ROT,
)
from wana.domain import quat
from wana.domain.paths import model_path
from wana.domain.units import FPS

MODEL_DIR = model_path("locomotion")
ACCEL = 1.6  # m/s^2
TURN_RATE = 4.0  # rad/s while walking
TURN_IN_PLACE_RATE = 2.5  # rad/s
# The network's poses jitter from frame to frame (the fast graph's 24 phase bins switch its weights in steps;
# a planted ankle jumps 1-2 cm a frame before locking): a binomial low-pass (sigma 1 frame, 1/e at 4.8 Hz,
# above a walk's and a run's cycle harmonics that carry the swing) takes the jitter out of rotations and height.
SMOOTH_KERNEL = np.array([1.0, 4.0, 6.0, 4.0, 1.0]) / 16.0
# Frames the foot lock eases in and out outside a contact the network flags (services.motion.ik.lock_feet):
# one; holding the pin three frames into the swing kept the lifting foot back and let it go with a jerk.
LOCK_BLEND = 1


@dataclass(frozen=True)
class Locomotion:
    """A locomotion piece: root_position (T, 3), rotations (T, J, 4), contacts (T, 2), heading (T,), phase (T,)."""

    root_position: np.ndarray
    rotations: np.ndarray
    contacts: np.ndarray
    heading: np.ndarray
    phase: np.ndarray
    source: str  # "pfnn" or "procedural"
    # The network's own root speed (T,) m/s from its root-velocity output (the root follows the plan, so this
    # only measures whether the gait it chose fits the commanded speed); None for the procedural gait.
    network_speed: np.ndarray | None = None


def _wrap(a: np.ndarray | float) -> np.ndarray:
    return (np.asarray(a) + np.pi) % (2 * np.pi) - np.pi


def plan_root(
    waypoints: np.ndarray,
    speed: float,
    start_heading: float,
    face_yaw: float | None = None,
    settle_frames: int = 8,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Root trajectory along a polyline.

    Args:
        waypoints: (N, 2) x, z in metres; the first is the start.
        speed: cruising speed m/s.
        start_heading: heading at the start, radians (0 faces +Z).
        face_yaw: heading to turn to at the goal (None: keep the arrival heading).
        settle_frames: standing frames appended at the end so the feet come to rest.

    Returns:
        pos (T, 2), heading (T,), speed (T,).
    """
    wp = np.asarray(waypoints, dtype=np.float64).reshape(-1, 2)
    if len(wp) == 0:
        raise ValueError("waypoints must hold at least one point")
    seg = np.linalg.norm(np.diff(wp, axis=0), axis=1) if len(wp) > 1 else np.zeros(0)
    keep = np.concatenate([[True], seg > 1e-6]) if len(wp) > 1 else np.array([True])
    wp = wp[keep]
    cum = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(wp, axis=0), axis=1))])
    length = float(cum[-1])
    speed = float(np.clip(speed, 0.2, 6.0))
    # The speed profile and the rate-limited heading are sequential filters: plain Python floats
    # (a numpy scalar op per frame costs ~10x more); everything else is vectorised.
    s_list, v_list = [0.0], [0.0]
    if length > 0.02:
        s, v = 0.0, 0.0
        accel, dt, two_a = ACCEL / FPS, 1.0 / FPS, 2 * ACCEL
        sqrt, end = math.sqrt, length - 1e-4
        s_append, v_append = s_list.append, v_list.append
        while (
            s < end
        ):  # v = min(v + accel, speed, max(braking speed, 0.25)); inline compares beat min()/max()
            left = length - s
            brake = sqrt(two_a * left) if left > 0.0 else 0.0
            if brake < 0.25:
                brake = 0.25
            v += accel
            if v > speed:
                v = speed
            if v > brake:
                v = brake
            s += v * dt
            if s > length:
                s = length
            s_append(s)
            v_append(v)
    s_arr = np.array(s_list)
    pos = np.stack([np.interp(s_arr, cum, wp[:, 0]), np.interp(s_arr, cum, wp[:, 1])], -1)
    heading = np.empty(len(pos))
    h = float(start_heading)
    if length > 0.02:
        ahead = np.minimum(np.searchsorted(cum, s_arr + 0.25), len(wp) - 1)
        d = wp[ahead] - pos
        last_leg = wp[-1] - wp[max(len(wp) - 2, 0)]
        d = np.where((np.linalg.norm(d, axis=1) > 1e-6)[:, None], d, last_leg)
        want = np.arctan2(d[:, 0], d[:, 1]).tolist()
        limit = TURN_RATE / FPS
        two_pi = 2 * math.pi
        out: list[float] = []
        append, pi = out.append, math.pi
        for w in want:
            step = (w - h + pi) % two_pi - pi
            h += limit if step > limit else -limit if step < -limit else step
            append(h)
        heading[:] = out
    else:
        heading[:] = h
    if face_yaw is not None:
        delta = float(_wrap(face_yaw - h))
        n = int(np.ceil(abs(delta) / (TURN_IN_PLACE_RATE / FPS)))
        if n:
            u = np.arange(1, n + 1) / n
            u = u * u * (3 - 2 * u)
            heading = np.concatenate([heading, h + delta * u])
            pos = np.concatenate([pos, np.repeat(pos[-1:], n, axis=0)])
            v_list += [0.0] * n
    pos = np.concatenate([pos, np.repeat(pos[-1:], settle_frames, axis=0)])
    heading = np.concatenate([heading, np.repeat(heading[-1:], settle_frames)])
    v_list += [0.0] * settle_frames
    return pos, heading, np.array(v_list)


class PfnnRuntime:
    """The rollout graph in onnxruntime (one thread).

    Prefers models/locomotion/pfnn_fast.onnx (services.motion.pfnn_onnx: phase-binned weights,
    FAST_STEPS frames per call) and falls back to the traced pfnn_rollout.onnx.
    """

    def __init__(self, model_dir: Path = MODEL_DIR) -> None:
        import onnxruntime as ort

        opts = ort.SessionOptions()
        opts.intra_op_num_threads = 1
        opts.inter_op_num_threads = 1
        opts.graph_optimization_level = ort.GraphOptimizationLevel.ORT_ENABLE_ALL
        opts.log_severity_level = 3  # the graph's folded float16 initialisers trigger harmless warnings
        fast = model_dir / "pfnn_fast.onnx"
        path = fast if fast.is_file() else model_dir / "pfnn_rollout.onnx"
        self.session = ort.InferenceSession(str(path), opts, providers=["CPUExecutionProvider"])
        self.kind = "fast" if path == fast else "traced"
        self.steps = int(self.session.get_inputs()[0].shape[1])

    def run(self, control: np.ndarray, pose0: np.ndarray, phase0: float) -> np.ndarray:
        """Y (T, N_OUT) float32 for control (T, 60); T is padded up to a multiple of the rollout steps."""
        t = len(control)
        k = self.steps
        n_chunks = max(1, int(np.ceil(t / k)))
        ctrl = np.empty((n_chunks * k, control.shape[1]), np.float32)
        ctrl[:t] = control
        ctrl[t:] = control[-1]
        chunks = ctrl.reshape(n_chunks, 1, k, -1)
        pose = np.ascontiguousarray(pose0.reshape(1, N_POSE), dtype=np.float32)
        phase = np.array([[phase0]], np.float32)
        out = np.empty((n_chunks, k, N_OUT), np.float32)
        run = self.session.run
        for c in range(n_chunks):
            y, pose, phase = run(None, {"control": chunks[c], "pose": pose, "phase": phase})
            out[c] = y[0]
        return out.reshape(-1, N_OUT)[:t]


class RolloutRuntime(Protocol):
    kind: str

    def run(self, control: np.ndarray, pose0: np.ndarray, phase0: float) -> np.ndarray: ...


@functools.lru_cache(maxsize=1)
def runtime() -> RolloutRuntime | None:
    """The shared rollout runtime, or None when no model can be loaded.

    onnxruntime on pfnn_fast.onnx (or the traced rollout when the fast graph is missing) by
    default; the numpy executor of pfnn_fast.onnx's phase tables when WANA_PFNN_RUNTIME=numpy.
    """
    if (
        os.environ.get("WANA_PFNN_RUNTIME", "onnxruntime") == "numpy"
        and (MODEL_DIR / "pfnn_fast.onnx").is_file()
    ):
        try:
            from services.motion.pfnn_tables import PhaseTableRuntime

            return PhaseTableRuntime(MODEL_DIR / "pfnn_fast.onnx")
        except Exception:  # noqa: BLE001 - a graph without tables: let onnxruntime run it
            pass
    return onnxruntime_runtime()


@functools.lru_cache(maxsize=1)
def onnxruntime_runtime() -> PfnnRuntime | None:
    """The rollout graph in onnxruntime, or None when the model or onnxruntime is missing."""
    try:
        if not any((MODEL_DIR / f).is_file() for f in ("pfnn_fast.onnx", "pfnn_rollout.onnx")):
            return None
        return PfnnRuntime()
    except Exception:  # noqa: BLE001 - any loading problem means: use the procedural fallback
        return None


@functools.lru_cache(maxsize=1)
def standing_pose_features() -> np.ndarray:
    """(N_POSE,) pose features of the neutral standing gait frame (positions; zero velocities)."""
    from services.motion.locomotion_features import pose_features

    g = synthesize_gait(np.zeros((2, 2)), np.zeros(2), np.zeros(2))
    return (
        pose_features(g["root_position"], g["rotations"], np.zeros((2, 2)), np.zeros(2))[1]
        * np.r_[np.ones(N_POSE // 2), np.zeros(N_POSE // 2)]
    )


def smooth_rotations(rotations: np.ndarray, kernel: np.ndarray = SMOOTH_KERNEL) -> np.ndarray:
    """(T, J, 4) unit quaternions low-passed over time per joint (sign-aligned, edge-padded, renormalised)."""
    if len(rotations) < 2:
        return rotations
    q = rotations.copy()
    flip = np.sum(q[1:] * q[:-1], axis=-1) < 0  # (T-1, J)
    q *= np.cumprod(np.concatenate([np.ones((1, q.shape[1])), np.where(flip, -1.0, 1.0)]), axis=0)[..., None]
    return quat.normalize(_lowpass(q, kernel))


def _lowpass(x: np.ndarray, kernel: np.ndarray) -> np.ndarray:
    """x (T, ...) convolved over time with an odd kernel, edges padded with the end values."""
    h = len(kernel) // 2
    padded = np.concatenate([np.repeat(x[:1], h, axis=0), x, np.repeat(x[-1:], h, axis=0)])
    return sum(w * padded[i : i + len(x)] for i, w in enumerate(kernel))


def lock_walk(rotations: np.ndarray, root: np.ndarray, contacts: np.ndarray) -> np.ndarray:
    """A walk's planted feet pinned as synthesis shows them (and eval/gait.py, eval/motion.py measure them)."""
    from services.motion.ik import lock_feet

    return lock_feet(rotations, root, contacts, blend=LOCK_BLEND)


def locomote(
    waypoints: np.ndarray,
    speed: float = 1.4,
    start_heading: float = 0.0,
    face_yaw: float | None = None,
    phase0: float = 0.0,
    occupied=None,
    use_network: bool = True,
    rollout: RolloutRuntime | None = None,
    manner: str = "",
) -> Locomotion:
    """Walk (or run) along waypoints and stop at the last one, facing face_yaw when given.

    Args:
        waypoints: (N, 2) x, z metres; waypoints[0] is where the character stands now.
        speed: cruising speed m/s (1.4 walk, 3+ run).
        start_heading: current heading, radians.
        face_yaw: heading at the goal, radians (None keeps the arrival heading).
        phase0: gait phase to continue from.
        occupied: optional callable xz (N, 2) -> bool (N,) for the occupancy sensor.
        use_network: False forces the procedural gait.
        rollout: the network runtime to use (default: the shared one; eval/gait.py passes another model's).
        manner: the story's manner word ("tiredly", "happily"): arm swing and posture (services.motion.gait_style;
            the planner has already scaled the speed by it).
    """
    style = gait_style(manner)
    pos, heading, spd = plan_root(waypoints, speed, start_heading, face_yaw)
    rt = (rollout or runtime()) if use_network else None
    if rt is None:
        g = synthesize_gait(pos, heading, spd, phase0=phase0)
        return Locomotion(
            g["root_position"],
            apply_gait_style(g["rotations"], style),
            g["contacts"],
            heading,
            g["phase"],
            "procedural",
        )
    control = np.concatenate(
        [trajectory_features(pos, heading), sensor_features(pos, heading, occupied)], axis=1
    )
    y = rt.run(control, standing_pose_features(), phase0)
    t = len(pos)
    rot = smooth_rotations(quat.normalize(y[:, SLICE_ROT].reshape(t, N_JOINTS, 4).astype(np.float64)))
    rot[:, 0] = quat.mul(quat.yaw(heading), rot[:, 0])
    local_pos = y[:, SLICE_POSE][:, : N_JOINTS * 3].reshape(t, N_JOINTS, 3)
    height = _lowpass(local_pos[:, 0, 1].astype(np.float64), SMOOTH_KERNEL)
    root = np.stack([pos[:, 0], height, pos[:, 1]], -1)
    contacts = (y[:, SLICE_CONTACT] > 0.5).astype(np.uint8)
    # Standing still: both feet down whatever the network says.
    contacts[spd < 0.05] = 1
    phase = np.mod(phase0 + np.cumsum(np.clip(y[:, SLICE_DPHASE][:, 0], 0, 0.5)), 1.0)
    net_speed = np.linalg.norm(y[:, SLICE_ROOT][:, :2].astype(np.float64), axis=1) * FPS
    return Locomotion(root, apply_gait_style(rot, style), contacts, heading, phase, "pfnn", net_speed)
