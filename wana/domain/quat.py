"""Vectorised quaternion helpers, (..., 4) arrays in (x, y, z, w) order, scalar last.

numpy-only and broadcast-friendly so that synthesis of thousands of frames stays fast; scipy's
Rotation is used for Euler conversions only.
"""

from __future__ import annotations

import numpy as np


def identity(shape: tuple[int, ...] = ()) -> np.ndarray:
    """Identity quaternions of shape (*shape, 4)."""
    q = np.zeros((*shape, 4))
    q[..., 3] = 1.0
    return q


def normalize(q: np.ndarray) -> np.ndarray:
    """Unit quaternions (..., 4)."""
    n = np.sqrt(np.einsum("...i,...i->...", q, q))[..., None]
    return q / np.maximum(n, 1e-12)


def mul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Hamilton product a * b (apply b first, then a), (..., 4)."""
    a = np.asarray(a)
    b = np.asarray(b)
    ax, ay, az, aw = a[..., 0], a[..., 1], a[..., 2], a[..., 3]
    bx, by, bz, bw = b[..., 0], b[..., 1], b[..., 2], b[..., 3]
    out = np.empty(np.broadcast_shapes(a.shape, b.shape), dtype=np.result_type(a, b))
    out[..., 0] = aw * bx + ax * bw + ay * bz - az * by
    out[..., 1] = aw * by - ax * bz + ay * bw + az * bx
    out[..., 2] = aw * bz + ax * by - ay * bx + az * bw
    out[..., 3] = aw * bw - ax * bx - ay * by - az * bz
    return out


def inv(q: np.ndarray) -> np.ndarray:
    """Inverse of unit quaternions (..., 4)."""
    return q * np.array([-1.0, -1.0, -1.0, 1.0])


def rotate(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Rotate vectors v (..., 3) by unit quaternions q (..., 4)."""
    q = np.asarray(q)
    v = np.asarray(v)
    qv = q[..., :3]
    w = q[..., 3:4]
    t = 2.0 * cross(qv, v)
    return v + w * t + cross(qv, t)


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Cross product of (..., 3) arrays (broadcasting), without np.cross's per-call overhead."""
    a = np.asarray(a)
    b = np.asarray(b)
    ax, ay, az = a[..., 0], a[..., 1], a[..., 2]
    bx, by, bz = b[..., 0], b[..., 1], b[..., 2]
    out = np.empty(np.broadcast_shapes(a.shape, b.shape), dtype=np.result_type(a, b))
    out[..., 0] = ay * bz - az * by
    out[..., 1] = az * bx - ax * bz
    out[..., 2] = ax * by - ay * bx
    return out


def slerp(a: np.ndarray, b: np.ndarray, u: np.ndarray | float) -> np.ndarray:
    """Spherical interpolation from a to b by u in [0, 1]; shapes broadcast, u (...,) or scalar."""
    u = np.asarray(u, dtype=np.float64)[..., None]
    d = np.einsum("...i,...i->...", *np.broadcast_arrays(a, b))[..., None]
    b = np.where(d < 0, -b, b)
    d = np.abs(d)
    theta = np.arccos(np.minimum(d, 1.0))
    s = np.sin(theta)
    small = s < 1e-6
    s = np.where(small, 1.0, s)
    wa = np.where(small, 1.0 - u, np.sin((1.0 - u) * theta) / s)
    wb = np.where(small, u, np.sin(u * theta) / s)
    return normalize(wa * a + wb * b)


def from_axis_angle(axis: np.ndarray, angle: np.ndarray | float) -> np.ndarray:
    """Quaternions (..., 4) from unit axes (..., 3) and angles in radians (...)."""
    angle = np.asarray(angle, dtype=np.float64)
    axis = np.asarray(axis, dtype=np.float64)
    shape = np.broadcast_shapes(axis.shape[:-1], angle.shape)
    axis = np.broadcast_to(axis, shape + (3,))
    angle = np.broadcast_to(angle, shape)
    return np.concatenate([axis * np.sin(angle / 2)[..., None], np.cos(angle / 2)[..., None]], axis=-1)


def yaw(angle: np.ndarray | float) -> np.ndarray:
    """Rotations about +Y by angle radians, (..., 4)."""
    angle = np.asarray(angle, dtype=np.float64)
    q = np.zeros(angle.shape + (4,))
    q[..., 1] = np.sin(angle / 2)
    q[..., 3] = np.cos(angle / 2)
    return q


def between(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Shortest rotation taking unit vectors a to b, (..., 4)."""
    a = a / np.linalg.norm(a, axis=-1, keepdims=True)
    b = b / np.linalg.norm(b, axis=-1, keepdims=True)
    c = np.cross(a, b)
    d = np.sum(a * b, axis=-1, keepdims=True)
    q = np.concatenate([c, 1.0 + d], axis=-1)
    # Opposite vectors: rotate by pi about any axis orthogonal to a.
    opp = (1.0 + d[..., 0]) < 1e-9
    if np.any(opp):
        ortho = np.cross(a, np.array([1.0, 0.0, 0.0]))
        ortho = np.where(
            np.linalg.norm(ortho, axis=-1, keepdims=True) < 1e-6, np.cross(a, [0.0, 1.0, 0.0]), ortho
        )
        q = np.where(opp[..., None], np.concatenate([ortho, np.zeros_like(d)], axis=-1), q)
    return normalize(q)


_AXIS = {"X": 0, "Y": 1, "Z": 2}


def from_euler(order: str, degrees_xyz: np.ndarray) -> np.ndarray:
    """Quaternions from intrinsic Euler angles (upper-case order as in BVH, e.g. "ZYX"), degrees (..., 3).

    The elementary rotations composed in order, as scipy's ``Rotation.from_euler`` composes them (the same
    bits, signs included), without its per-call cost: the action library reads 16,000 keys at start-up.
    """
    a = np.radians(np.asarray(degrees_xyz, dtype=np.float64))
    out = None
    for i, axis in enumerate(order.upper()):
        half = a[..., i] / 2.0
        q = np.zeros(a.shape[:-1] + (4,))
        q[..., _AXIS[axis]] = np.sin(half)
        q[..., 3] = np.cos(half)
        out = q if out is None else mul(out, q)
    if out is None:
        raise ValueError(f"an Euler order names three axes, got {order!r}")
    return out


def to_euler(order: str, q: np.ndarray) -> np.ndarray:
    """Intrinsic Euler angles in degrees (..., 3) in the given order (e.g. "ZYX")."""
    from scipy.spatial.transform import Rotation

    q = np.asarray(q, dtype=np.float64)
    return (
        Rotation.from_quat(q.reshape(-1, 4))
        .as_euler(order.upper(), degrees=True)
        .reshape(q.shape[:-1] + (3,))
    )


def yaw_of(q: np.ndarray) -> np.ndarray:
    """Heading angle (radians about +Y) of the rotated +Z axis, (...)."""
    f = rotate(q, np.broadcast_to(np.array([0.0, 0.0, 1.0]), q.shape[:-1] + (3,)))
    return np.arctan2(f[..., 0], f[..., 2])


def canonical(q: np.ndarray) -> np.ndarray:
    """Same rotations with w >= 0 (one sign per rotation, for hashing and comparison)."""
    return np.where(q[..., 3:4] < 0, -q, q)
