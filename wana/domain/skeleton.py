"""The canonical skeleton (Mixamo joint names) and forward kinematics.

Conventions (DESIGN §6): metres, Y up, right-handed, the character faces +Z at rest, so its
left side is +X. Rest pose is a T-pose. Rotations are local, as quaternions (x, y, z, w),
scalar last (as glTF and scipy).
"""

from __future__ import annotations

import numpy as np

from wana.domain import quat

# (name, parent, rest offset from parent in metres) for a 1.75 m reference character.
_JOINTS: tuple[tuple[str, str | None, tuple[float, float, float]], ...] = (
    ("Hips", None, (0.0, 0.95, 0.0)),
    ("Spine", "Hips", (0.0, 0.10, 0.0)),
    ("Spine1", "Spine", (0.0, 0.12, 0.0)),
    ("Spine2", "Spine1", (0.0, 0.12, 0.0)),
    ("Neck", "Spine2", (0.0, 0.16, 0.0)),
    ("Head", "Neck", (0.0, 0.10, 0.0)),
    ("LeftShoulder", "Spine2", (0.04, 0.12, 0.0)),
    ("LeftArm", "LeftShoulder", (0.14, 0.0, 0.0)),
    ("LeftForeArm", "LeftArm", (0.28, 0.0, 0.0)),
    ("LeftHand", "LeftForeArm", (0.25, 0.0, 0.0)),
    ("LeftHandMiddle1", "LeftHand", (0.10, 0.0, 0.0)),
    ("RightShoulder", "Spine2", (-0.04, 0.12, 0.0)),
    ("RightArm", "RightShoulder", (-0.14, 0.0, 0.0)),
    ("RightForeArm", "RightArm", (-0.28, 0.0, 0.0)),
    ("RightHand", "RightForeArm", (-0.25, 0.0, 0.0)),
    ("RightHandMiddle1", "RightHand", (-0.10, 0.0, 0.0)),
    ("LeftUpLeg", "Hips", (0.09, -0.05, 0.0)),
    ("LeftLeg", "LeftUpLeg", (0.0, -0.42, 0.0)),
    ("LeftFoot", "LeftLeg", (0.0, -0.42, 0.0)),
    ("LeftToeBase", "LeftFoot", (0.0, -0.06, 0.13)),
    ("RightUpLeg", "Hips", (-0.09, -0.05, 0.0)),
    ("RightLeg", "RightUpLeg", (0.0, -0.42, 0.0)),
    ("RightFoot", "RightLeg", (0.0, -0.42, 0.0)),
    ("RightToeBase", "RightFoot", (0.0, -0.06, 0.13)),
)

JOINT_NAMES: tuple[str, ...] = tuple(j[0] for j in _JOINTS)
JOINT_INDEX: dict[str, int] = {name: i for i, name in enumerate(JOINT_NAMES)}
PARENTS: np.ndarray = np.array([-1 if p is None else JOINT_INDEX[p] for _, p, _ in _JOINTS], dtype=np.int64)
REST_OFFSETS: np.ndarray = np.array([o for _, _, o in _JOINTS], dtype=np.float64)  # (J, 3) metres
N_JOINTS = len(JOINT_NAMES)

# The upper body, driven by actions when blending (DESIGN §2 Motion): everything above the hips.
UPPER_BODY: tuple[str, ...] = tuple(
    n for n in JOINT_NAMES if n not in ("Hips",) and "Leg" not in n and "Foot" not in n and "Toe" not in n
)
LOWER_BODY: tuple[str, ...] = tuple(n for n in JOINT_NAMES if n not in UPPER_BODY)


def rest_offsets(height: float = 1.75) -> np.ndarray:
    """Rest offsets (J, 3) scaled for a character of the given height in metres."""
    return REST_OFFSETS * (height / 1.75)


def forward_kinematics(
    rotations: np.ndarray, root_position: np.ndarray, offsets: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Global joint positions and rotations.

    Args:
        rotations: (T, J, 4) local quaternions (x, y, z, w).
        root_position: (T, 3) world position of the Hips joint, metres.
        offsets: (J, 3) rest offsets; defaults to REST_OFFSETS. The root's offset is ignored.

    Returns:
        positions (T, J, 3) in metres and global rotations (T, J, 4) as quaternions (x, y, z, w).
    """
    rotations = np.asarray(rotations, dtype=np.float64)
    root_position = np.asarray(root_position, dtype=np.float64)
    if rotations.ndim != 3 or rotations.shape[1:] != (N_JOINTS, 4):
        raise ValueError(f"rotations must be (T, {N_JOINTS}, 4), got {rotations.shape}")
    if root_position.shape != (rotations.shape[0], 3):
        raise ValueError(f"root_position must be ({rotations.shape[0]}, 3), got {root_position.shape}")
    offsets = REST_OFFSETS if offsets is None else np.asarray(offsets, dtype=np.float64)
    t = rotations.shape[0]
    # numpy quaternions (wana.domain.quat), not scipy's Rotation: the same products to 1e-15, a few
    # times faster on long time lines (the idle layer runs this over a whole story).
    local = quat.normalize(rotations)
    quats = np.empty_like(local)
    positions = np.zeros((t, N_JOINTS, 3))
    for j in range(N_JOINTS):
        p = PARENTS[j]
        if p < 0:
            quats[:, j] = local[:, j]
            positions[:, j] = root_position
        else:
            quats[:, j] = quat.mul(quats[:, p], local[:, j])
            positions[:, j] = positions[:, p] + quat.rotate(quats[:, p], offsets[j])
    return positions, quats


def identity_pose(frames: int = 1) -> np.ndarray:
    """(frames, J, 4) rest-pose rotations."""
    q = np.zeros((frames, N_JOINTS, 4))
    q[..., 3] = 1.0
    return q
