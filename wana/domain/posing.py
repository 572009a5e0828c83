"""Pose authoring helpers: limbs aimed by body-frame directions, spine and head by angles.

Used by the action authoring script (tools/authoring/author_actions.py) to write the keyframes of
assets/actions. Directions are in the parent's frame at rest, which for arms is the chest and for
legs the pelvis: x = the character's left, y = up, z = forward. A pose is a dict joint -> unit
quaternion (x, y, z, w); joints not named keep the neutral standing pose.
"""

from __future__ import annotations

import numpy as np

from wana.domain import quat
from wana.domain.skeleton import JOINT_INDEX, REST_OFFSETS

Pose = dict[str, np.ndarray]


def _unit(v: tuple[float, float, float] | np.ndarray) -> np.ndarray:
    v = np.asarray(v, dtype=np.float64)
    return v / np.linalg.norm(v)


def _frame(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Orthonormal frame (3, 3) with columns a, b (made orthogonal to a), a x b."""
    b = b - np.dot(b, a) * a
    b = b / np.linalg.norm(b)
    return np.stack([a, b, np.cross(a, b)], axis=1)


def _rotation_matrix_to_quat(m: np.ndarray) -> np.ndarray:
    from scipy.spatial.transform import Rotation

    return Rotation.from_matrix(m).as_quat()


def aim_chain(
    rest_dir: np.ndarray, hinge_dir: np.ndarray, upper: np.ndarray, lower: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Local rotations of a two-bone limb whose bones should point along upper and lower.

    Args:
        rest_dir: (3,) the bone direction at rest (both bones are collinear at rest).
        hinge_dir: (3,) the direction the lower bone swings toward when the joint flexes from rest.
        upper: (3,) wanted direction of the upper bone in the parent frame.
        lower: (3,) wanted direction of the lower bone in the parent frame.

    Returns:
        (4,) upper-bone local quaternion, (4,) lower-bone local quaternion.
    """
    u, f = _unit(upper), _unit(lower)
    bend = f - np.dot(f, u) * u
    if np.linalg.norm(bend) < 1e-4:  # straight limb: keep the hinge as close to its rest plane as possible
        bend = hinge_dir - np.dot(hinge_dir, u) * u
        if np.linalg.norm(bend) < 1e-4:
            bend = np.cross(u, np.array([1.0, 0.0, 0.0]))
    m_rest = _frame(_unit(rest_dir), _unit(hinge_dir))
    m_goal = _frame(u, _unit(bend))
    q_upper = _rotation_matrix_to_quat(m_goal @ m_rest.T)
    f_local = quat.rotate(quat.inv(q_upper), f)
    q_lower = quat.between(_unit(rest_dir), f_local)
    return q_upper, q_lower


def arm(
    side: str,
    upper: tuple[float, float, float],
    fore: tuple[float, float, float],
    hand: tuple[float, float, float] = (0.0, 0.0, 0.0),
) -> Pose:
    """Arm pose; directions for the left arm; the right arm mirrors x (pass side "R" with left-style dirs).

    Args:
        side: "L" or "R".
        upper: upper-arm direction (x toward the character's outer side, y up, z forward).
        fore: forearm direction in the same frame.
        hand: hand Euler angles in degrees (XYZ) relative to the forearm.
    """
    s = 1.0 if side == "L" else -1.0
    name = "Left" if side == "L" else "Right"
    up = np.array([s * upper[0], upper[1], upper[2]])
    fo = np.array([s * fore[0], fore[1], fore[2]])
    q_up, q_fo = aim_chain(np.array([s, 0.0, 0.0]), np.array([0.0, 0.0, 1.0]), up, fo)
    h = np.array([hand[0], s * hand[1], s * hand[2]])
    return {f"{name}Arm": q_up, f"{name}ForeArm": q_fo, f"{name}Hand": quat.from_euler("XYZ", h)}


def arms(
    upper: tuple[float, float, float],
    fore: tuple[float, float, float],
    hand: tuple[float, float, float] = (0.0, 0.0, 0.0),
) -> Pose:
    """Both arms, mirrored."""
    return {**arm("L", upper, fore, hand), **arm("R", upper, fore, hand)}


def leg(
    side: str, thigh: tuple[float, float, float], shin: tuple[float, float, float], foot_pitch: float = 0.0
) -> Pose:
    """Leg pose; x toward the character's outer side, y up, z forward; knee flexes toward -z."""
    s = 1.0 if side == "L" else -1.0
    name = "Left" if side == "L" else "Right"
    th = np.array([s * thigh[0], thigh[1], thigh[2]])
    sh = np.array([s * shin[0], shin[1], shin[2]])
    q_th, q_sh = aim_chain(np.array([0.0, -1.0, 0.0]), np.array([0.0, 0.0, -1.0]), th, sh)
    # Keep the foot level relative to the world when the shin tilts, plus an explicit pitch.
    q_foot = quat.mul(
        quat.inv(quat.mul(q_th, q_sh)), quat.from_euler("XYZ", np.array([foot_pitch, 0.0, 0.0]))
    )
    return {f"{name}UpLeg": q_th, f"{name}Leg": q_sh, f"{name}Foot": q_foot}


def legs(
    thigh: tuple[float, float, float], shin: tuple[float, float, float], foot_pitch: float = 0.0
) -> Pose:
    """Both legs, mirrored."""
    return {**leg("L", thigh, shin, foot_pitch), **leg("R", thigh, shin, foot_pitch)}


def spine(pitch: float = 0.0, yaw: float = 0.0, roll: float = 0.0) -> Pose:
    """Bend the spine, degrees spread over Spine, Spine1, Spine2: pitch > 0 bends forward, yaw > 0 turns left."""
    q = quat.from_euler("YXZ", np.array([yaw / 3.0, pitch / 3.0, roll / 3.0]))
    return {"Spine": q, "Spine1": q, "Spine2": q}


def head(pitch: float = 0.0, yaw: float = 0.0, roll: float = 0.0) -> Pose:
    """Turn the head, degrees spread over Neck and Head: pitch > 0 looks down, yaw > 0 looks left."""
    q = quat.from_euler("YXZ", np.array([yaw / 2.0, pitch / 2.0, roll / 2.0]))
    return {"Neck": q, "Head": q}


def hips(pitch: float = 0.0, yaw: float = 0.0, roll: float = 0.0) -> Pose:
    """Rotate the pelvis (root), degrees."""
    return {"Hips": quat.from_euler("YXZ", np.array([yaw, pitch, roll]))}


def neutral() -> Pose:
    """Relaxed standing pose: arms down along the body, slight elbow bend."""
    return {**arms((0.12, -1.0, 0.0), (0.08, -1.0, 0.18), (0.0, 0.0, 0.0))}


def merge(*poses: Pose) -> Pose:
    """Later poses override earlier ones, joint by joint."""
    out: Pose = {}
    for p in poses:
        out.update(p)
    return out


def leg_length() -> float:
    """Hip-to-ankle length of the reference skeleton, metres."""
    return float(
        np.linalg.norm(REST_OFFSETS[JOINT_INDEX["LeftLeg"]])
        + np.linalg.norm(REST_OFFSETS[JOINT_INDEX["LeftFoot"]])
    )
