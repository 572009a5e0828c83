"""Blending: cross-fades over time and upper/lower body layering."""

from __future__ import annotations

import numpy as np

from wana.domain import quat
from wana.domain.skeleton import JOINT_INDEX, JOINT_NAMES, N_JOINTS, UPPER_BODY


def upper_body_mask(spine_weight: float = 1.0) -> np.ndarray:
    """(J,) weight of the action per joint: 1 above the hips, 0 for hips and legs."""
    m = np.zeros(N_JOINTS)
    for name in UPPER_BODY:
        m[JOINT_INDEX[name]] = spine_weight if name.startswith("Spine") else 1.0
    return m


def layer(base: np.ndarray, action: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """Per-joint slerp from base (T, J, 4) toward action (T, J, 4) by mask (J,) or (T, J)."""
    m = np.broadcast_to(mask, base.shape[:2])
    if np.all((m == 0) | (m == 1)):  # a hard mask selects joints; no interpolation needed
        return np.where(m[..., None] == 1, action, base)
    return quat.slerp(base, action, m)


def crossfade_weights(t: int, fade_in: int, fade_out: int) -> np.ndarray:
    """(T,) weight rising 0 -> 1 over fade_in frames and falling back over fade_out (smoothstep)."""
    w = np.ones(t)
    if fade_in > 0:
        u = np.clip(np.arange(t) / fade_in, 0, 1)
        w = np.minimum(w, u * u * (3 - 2 * u))
    if fade_out > 0:
        u = np.clip((t - 1 - np.arange(t)) / fade_out, 0, 1)
        w = np.minimum(w, u * u * (3 - 2 * u))
    return w


def fade_from(pose: np.ndarray, motion: np.ndarray, frames: int) -> np.ndarray:
    """Blend the first frames of motion (T, J, 4) from a fixed pose (J, 4) so pieces join without a pop."""
    if frames <= 0 or len(motion) == 0:
        return motion
    n = min(frames, len(motion))  # the weight is 1 from frame `frames` on
    w = crossfade_weights(len(motion), frames, 0)[:n]
    out = np.array(motion, dtype=np.float64, copy=True)
    out[:n] = quat.slerp(
        np.broadcast_to(pose, (n, *motion.shape[1:])), motion[:n], np.repeat(w[:, None], N_JOINTS, 1)
    )
    return out


def fade_root(start: np.ndarray, root: np.ndarray, frames: int) -> np.ndarray:
    """Blend the first frames of root positions (T, 3) from start (3,)."""
    if frames <= 0 or len(root) == 0:
        return root
    w = crossfade_weights(len(root), frames, 0)[:, None]
    return start + (root - start) * w


__all__ = ["JOINT_NAMES", "crossfade_weights", "fade_from", "fade_root", "layer", "upper_body_mask"]
