"""PFNN input/output features from canonical motion (shared by training and the controller)."""

from __future__ import annotations

import numpy as np

from services.motion.pfnn_layout import N_JOINTS, N_SENSOR, TRAJ_OFFSETS
from wana.domain import quat
from wana.domain.skeleton import forward_kinematics


def to_local(points: np.ndarray, ground: np.ndarray, heading: np.ndarray) -> np.ndarray:
    """Express world points (T, ..., 3) in the root frame (ground (T, 2) position, heading (T,))."""
    inv = quat.yaw(-heading)
    shape = points.shape
    p = points.reshape(shape[0], -1, 3).copy()
    p[..., 0] -= ground[:, None, 0]
    p[..., 2] -= ground[:, None, 1]
    return quat.rotate(inv[:, None], p).reshape(shape)


def trajectory_features(pos: np.ndarray, heading: np.ndarray) -> np.ndarray:
    """(T, 48) trajectory samples around every frame: local x, z and direction x, z, edges clamped."""
    t = len(pos)
    idx = np.clip(np.arange(t)[:, None] + np.array(TRAJ_OFFSETS)[None], 0, t - 1)  # (T, 12)
    rel = pos[idx] - pos[:, None]  # (T, 12, 2)
    c, s = np.cos(-heading)[:, None], np.sin(-heading)[:, None]
    # Rotation by -heading about +Y acting on (x, z): x' = x cos + z sin, z' = -x sin + z cos
    lx = rel[..., 0] * c + rel[..., 1] * s
    lz = -rel[..., 0] * s + rel[..., 1] * c
    dh = heading[idx] - heading[:, None]
    return np.concatenate([lx, lz, np.sin(dh), np.cos(dh)], axis=1)


def sensor_features(pos: np.ndarray, heading: np.ndarray, occupied=None) -> np.ndarray:
    """(T, 12) occupancy at the 6 future samples, 0.5 m to the left and right; occupied(xz (N, 2)) -> bool (N,)."""
    t = len(pos)
    if occupied is None:
        return np.zeros((t, N_SENSOR))
    fut = [5, 10, 15, 20, 25, 30]
    idx = np.clip(np.arange(t)[:, None] + np.array(fut)[None], 0, t - 1)
    left = np.stack([np.cos(heading), -np.sin(heading)], -1)[:, None] * 0.5
    pts = np.concatenate([pos[idx] + left, pos[idx] - left], axis=1)  # (T, 12, 2)
    return occupied(pts.reshape(-1, 2)).reshape(t, N_SENSOR).astype(np.float64)


def pose_features(
    root_position: np.ndarray, rotations: np.ndarray, ground: np.ndarray, heading: np.ndarray
) -> np.ndarray:
    """(T, J*6) joint positions in the root frame and their per-frame velocities (first frame: zero)."""
    pos, _ = forward_kinematics(rotations, root_position)
    local = to_local(pos, ground, heading).reshape(len(pos), -1)
    vel = np.zeros_like(local)
    vel[1:] = local[1:] - local[:-1]
    return np.concatenate([local, vel], axis=1)


def rotation_features(rotations: np.ndarray, heading: np.ndarray) -> np.ndarray:
    """(T, J*4) local rotations with the hips made relative to the heading, sign-canonical."""
    r = rotations.copy()
    r[:, 0] = quat.mul(quat.yaw(-heading), r[:, 0])
    return quat.canonical(r).reshape(len(r), -1)


def root_deltas(pos: np.ndarray, heading: np.ndarray) -> np.ndarray:
    """(T, 3) root motion from frame t-1 to t in the t-1 frame: dx, dz, dyaw (first row zero)."""
    d = np.zeros((len(pos), 3))
    rel = pos[1:] - pos[:-1]
    c, s = np.cos(-heading[:-1]), np.sin(-heading[:-1])
    d[1:, 0] = rel[:, 0] * c + rel[:, 1] * s
    d[1:, 1] = -rel[:, 0] * s + rel[:, 1] * c
    dh = heading[1:] - heading[:-1]
    d[1:, 2] = np.arctan2(np.sin(dh), np.cos(dh))
    return d


def extrapolated_trajectory_features(pos: np.ndarray, heading: np.ndarray, fit: int = 10) -> np.ndarray:
    """trajectory_features of a clip cut out of a longer walk: the path before and after it continues at
    the velocity and turning rate of its first and last `fit` frames, instead of standing still.

    A captured take starts and ends mid-stride; clamped edges would teach the network that a character
    who has been standing (the past samples all on one spot) is already walking at full speed.
    """
    pad = max(-min(TRAJ_OFFSETS), max(TRAJ_OFFSETS))
    t = len(pos)
    k = max(1, min(fit, t - 1))
    v0, v1 = (pos[k] - pos[0]) / k, (pos[-1] - pos[-1 - k]) / k
    w0, w1 = (heading[k] - heading[0]) / k, (heading[-1] - heading[-1 - k]) / k
    steps = np.arange(1, pad + 1)
    before = pos[0] - v0 * steps[::-1, None]
    after = pos[-1] + v1 * steps[:, None]
    h_before = heading[0] - w0 * steps[::-1]
    h_after = heading[-1] + w1 * steps
    feats = trajectory_features(
        np.concatenate([before, pos, after]), np.concatenate([h_before, heading, h_after])
    )
    return feats[pad : pad + t]


def build_xy(
    root_position: np.ndarray,
    rotations: np.ndarray,
    heading: np.ndarray,
    phase: np.ndarray,
    contacts: np.ndarray,
    occupied=None,
    extrapolate: bool = False,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Training pairs of one sequence: X (T-1, N_IN), phase (T-1, 1) of the previous frame, Y (T-1, N_OUT).

    extrapolate: the sequence is cut out of a longer walk (a captured take): see
    extrapolated_trajectory_features. Procedural sequences start and end at rest and keep clamped edges.
    """
    ground = root_position[:, [0, 2]]
    traj = (
        extrapolated_trajectory_features(ground, heading)
        if extrapolate
        else trajectory_features(ground, heading)
    )
    sensor = sensor_features(ground, heading, occupied)
    pose = pose_features(root_position, rotations, ground, heading)
    rot = rotation_features(rotations, heading)
    dphase = np.mod(np.diff(phase), 1.0)
    x = np.concatenate([traj[1:], sensor[1:], pose[:-1]], axis=1)
    y = np.concatenate(
        [pose[1:], rot[1:], root_deltas(ground, heading)[1:], dphase[:, None], contacts[1:]], axis=1
    )
    assert y.shape[1] == N_JOINTS * 10 + 6
    return x.astype(np.float32), phase[:-1, None].astype(np.float32), y.astype(np.float32)
