"""Retarget motion from another skeleton onto the canonical one by a joint-name map.

Position-based, so it does not care how the source rig's bones are oriented at rest (the CC_Base
rig of the CMU/iClone files has limbs whose rest frames point every which way): run FK on the
source, read where the mapped joints are, then aim each canonical bone along the same direction.
Two-bone limbs keep their bend plane (elbow/knee direction); the pelvis and chest take their
frame from the hips and shoulders. Units are converted and the root height rescaled to the
canonical skeleton.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from wana.domain import quat
from wana.domain.bvh import BvhClip
from wana.domain.skeleton import (
    JOINT_INDEX,
    N_JOINTS,
    PARENTS,
    REST_OFFSETS,
    forward_kinematics,
    rest_offsets,
)

# canonical joint -> source joint, for rigs we know. Unmapped canonical joints follow their parent.
CC_BASE_MAP: dict[str, str] = {
    "Hips": "CC_Base_Hip",
    "Spine": "CC_Base_Waist",
    "Spine1": "CC_Base_Spine01",
    "Spine2": "CC_Base_Spine02",
    "Neck": "CC_Base_NeckTwist01",
    "Head": "CC_Base_Head",
    "LeftShoulder": "CC_Base_L_Clavicle",
    "LeftArm": "CC_Base_L_Upperarm",
    "LeftForeArm": "CC_Base_L_Forearm",
    "LeftHand": "CC_Base_L_Hand",
    "LeftHandMiddle1": "CC_Base_L_Mid1",
    "RightShoulder": "CC_Base_R_Clavicle",
    "RightArm": "CC_Base_R_Upperarm",
    "RightForeArm": "CC_Base_R_Forearm",
    "RightHand": "CC_Base_R_Hand",
    "RightHandMiddle1": "CC_Base_R_Mid1",
    "LeftUpLeg": "CC_Base_L_Thigh",
    "LeftLeg": "CC_Base_L_Calf",
    "LeftFoot": "CC_Base_L_Foot",
    "LeftToeBase": "CC_Base_L_ToeBase",
    "RightUpLeg": "CC_Base_R_Thigh",
    "RightLeg": "CC_Base_R_Calf",
    "RightFoot": "CC_Base_R_Foot",
    "RightToeBase": "CC_Base_R_ToeBase",
}
# CMU as converted by cgspeed (Hips/LHipJoint/LeftUpLeg... 31 joints).
CMU_CGSPEED_MAP: dict[str, str] = {
    "Hips": "Hips",
    "Spine": "LowerBack",
    "Spine1": "Spine",
    "Spine2": "Spine1",
    "Neck": "Neck",
    "Head": "Head",
    "LeftShoulder": "LeftShoulder",
    "LeftArm": "LeftArm",
    "LeftForeArm": "LeftForeArm",
    "LeftHand": "LeftHand",
    "LeftHandMiddle1": "LeftFingerBase",
    "RightShoulder": "RightShoulder",
    "RightArm": "RightArm",
    "RightForeArm": "RightForeArm",
    "RightHand": "RightHand",
    "RightHandMiddle1": "RightFingerBase",
    "LeftUpLeg": "LeftUpLeg",
    "LeftLeg": "LeftLeg",
    "LeftFoot": "LeftFoot",
    "LeftToeBase": "LeftToeBase",
    "RightUpLeg": "RightUpLeg",
    "RightLeg": "RightLeg",
    "RightFoot": "RightFoot",
    "RightToeBase": "RightToeBase",
}
# CMU in the Daz/Poser conversion (hip/abdomen/chest..., 42 joints, no toe joints). The source has two
# trunk joints where we have four, so the lower spine is the midpoint of hip and abdomen ("a|b"), and
# the toes are the foot's End Site ("name@end").
DAZ_MAP: dict[str, str] = {
    "Hips": "hip",
    "Spine": "hip|abdomen",
    "Spine1": "abdomen",
    "Spine2": "chest",
    "Neck": "neck",
    "Head": "head",
    "LeftShoulder": "lCollar",
    "LeftArm": "lShldr",
    "LeftForeArm": "lForeArm",
    "LeftHand": "lHand",
    "LeftHandMiddle1": "lMid1",
    "RightShoulder": "rCollar",
    "RightArm": "rShldr",
    "RightForeArm": "rForeArm",
    "RightHand": "rHand",
    "RightHandMiddle1": "rMid1",
    "LeftUpLeg": "lThigh",
    "LeftLeg": "lShin",
    "LeftFoot": "lFoot",
    "LeftToeBase": "lFoot@end",
    "RightUpLeg": "rThigh",
    "RightLeg": "rShin",
    "RightFoot": "rFoot",
    "RightToeBase": "rFoot@end",
}
IDENTITY_MAP: dict[str, str] = {n: n for n in JOINT_INDEX}
KNOWN_MAPS = {"cc_base": CC_BASE_MAP, "cmu": CMU_CGSPEED_MAP, "daz": DAZ_MAP, "mixamo": IDENTITY_MAP}


def source_joints(spec: str) -> list[str]:
    """The source joint names a map value reads: "name", "a|b" (their midpoint), "name@end" (its End Site)."""
    return [part.removesuffix("@end") for part in spec.split("|")]


def _source_position(clip: BvhClip, gpos: np.ndarray, grot: np.ndarray, spec: str) -> np.ndarray:
    """(T, 3) file-unit position of one map value (see source_joints)."""
    pts = []
    for part in spec.split("|"):
        name = part.removesuffix("@end")
        j = clip.index(name)
        p = gpos[:, j]
        if part.endswith("@end"):
            end = clip.end_sites.get(j)
            if end is None:
                raise ValueError(f"joint {name!r} has no End Site")
            p = p + quat.rotate(grot[:, j], np.broadcast_to(end, p.shape))
        pts.append(p)
    return np.mean(pts, axis=0)


_LIMBS = (  # (upper, lower, end, end_child, hinge direction at rest)
    ("LeftArm", "LeftForeArm", "LeftHand", "LeftHandMiddle1", (0.0, 0.0, 1.0)),
    ("RightArm", "RightForeArm", "RightHand", "RightHandMiddle1", (0.0, 0.0, 1.0)),
    ("LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToeBase", (0.0, 0.0, -1.0)),
    ("RightUpLeg", "RightLeg", "RightFoot", "RightToeBase", (0.0, 0.0, -1.0)),
)


def guess_map(names: list[str]) -> dict[str, str]:
    """Pick the known map whose source names the clip has most of (mixamo prefixes are stripped)."""
    stripped = {n.split(":")[-1]: n for n in names}
    best, best_hits = IDENTITY_MAP, -1
    for m in KNOWN_MAPS.values():
        hits = sum(1 for v in m.values() for n in source_joints(v) if n in names or n in stripped)
        if hits > best_hits:
            best, best_hits = m, hits
    return {k: (v if v in names else stripped.get(v, v)) for k, v in best.items()}


def _frames(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(T, 3, 3) orthonormal frames with columns a, b orthogonalised, a x b."""
    a = a / np.linalg.norm(a, axis=-1, keepdims=True)
    b = b - np.sum(a * b, axis=-1, keepdims=True) * a
    b = b / np.maximum(np.linalg.norm(b, axis=-1, keepdims=True), 1e-9)
    return np.stack([a, b, np.cross(a, b)], axis=-1)


def _mat_to_quat(m: np.ndarray) -> np.ndarray:
    return Rotation.from_matrix(m.reshape(-1, 3, 3)).as_quat().reshape(m.shape[:-2] + (4,))


def retarget_positions(src: dict[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Canonical local rotations from canonical-named joint positions.

    Args:
        src: canonical joint name -> (T, 3) world position (metres) for every canonical joint.

    Returns:
        rotations (T, J, 4) local quaternions and global rotations (T, J, 4).
    """
    t = next(iter(src.values())).shape[0]
    local = quat.identity((t, N_JOINTS))
    glob = quat.identity((t, N_JOINTS))

    def set_global(name: str, g: np.ndarray) -> None:
        j = JOINT_INDEX[name]
        glob[:, j] = g
        p = PARENTS[j]
        local[:, j] = g if p < 0 else quat.mul(quat.inv(glob[:, p]), g)

    def follow_parent(name: str) -> None:
        j = JOINT_INDEX[name]
        glob[:, j] = glob[:, PARENTS[j]]

    left = src["LeftUpLeg"] - src["RightUpLeg"]
    set_global("Hips", _pelvis(left, src["Spine1"] - src["Hips"]))
    shoulders = src["LeftArm"] - src["RightArm"]
    chain = [("Spine", "Spine1"), ("Spine1", "Spine2"), ("Spine2", "Neck"), ("Neck", "Head")]
    for k, (j, c) in enumerate(chain):
        w = min(1.0, (k + 1) / 3.0)
        side = (1 - w) * left / np.linalg.norm(left, axis=-1, keepdims=True) + w * shoulders / np.linalg.norm(
            shoulders, axis=-1, keepdims=True
        )
        set_global(j, _pelvis(side, src[c] - src[j]))
    follow_parent("Head")
    local[:, JOINT_INDEX["Head"]] = quat.identity((t,))
    for sh, arm in (("LeftShoulder", "LeftArm"), ("RightShoulder", "RightArm")):
        p = PARENTS[JOINT_INDEX[sh]]
        rest = REST_OFFSETS[JOINT_INDEX[arm]]
        d = quat.rotate(quat.inv(glob[:, p]), src[arm] - src[sh])
        set_global(sh, quat.mul(glob[:, p], quat.between(np.broadcast_to(rest, d.shape), d)))
    for upper, lower, end, tip, hinge in _LIMBS:
        p = PARENTS[JOINT_INDEX[upper]]
        rest = REST_OFFSETS[JOINT_INDEX[lower]] / np.linalg.norm(REST_OFFSETS[JOINT_INDEX[lower]])
        gp_inv = quat.inv(glob[:, p])
        u = quat.rotate(gp_inv, src[lower] - src[upper])
        f = quat.rotate(gp_inv, src[end] - src[lower])
        u = u / np.linalg.norm(u, axis=-1, keepdims=True)
        f = f / np.linalg.norm(f, axis=-1, keepdims=True)
        bend = f - np.sum(f * u, axis=-1, keepdims=True) * u
        straight = np.linalg.norm(bend, axis=-1) < 1e-3
        fallback = np.asarray(hinge) - np.sum(np.asarray(hinge) * u, axis=-1, keepdims=True) * u
        bend = np.where(straight[:, None], fallback, bend)
        m_rest = _frames(rest[None], np.asarray(hinge, dtype=np.float64)[None])[0]
        m_goal = _frames(u, bend)
        q_up = _mat_to_quat(m_goal @ m_rest.T)
        set_global(upper, quat.mul(glob[:, p], q_up))
        f_local = quat.rotate(quat.inv(q_up), f)
        set_global(
            lower,
            quat.mul(
                glob[:, JOINT_INDEX[upper]], quat.between(np.broadcast_to(rest, f_local.shape), f_local)
            ),
        )
        rest_end = REST_OFFSETS[JOINT_INDEX[tip]]
        d = quat.rotate(quat.inv(glob[:, JOINT_INDEX[lower]]), src[tip] - src[end])
        set_global(
            end, quat.mul(glob[:, JOINT_INDEX[lower]], quat.between(np.broadcast_to(rest_end, d.shape), d))
        )
        follow_parent(tip)
    return local, glob


def _pelvis(side: np.ndarray, up: np.ndarray) -> np.ndarray:
    """Global rotation whose +X is along side and +Y along up (orthogonalised), (T, 4)."""
    up = up / np.linalg.norm(up, axis=-1, keepdims=True)
    x = side - np.sum(side * up, axis=-1, keepdims=True) * up
    x = x / np.linalg.norm(x, axis=-1, keepdims=True)
    z = np.cross(x, up)
    return _mat_to_quat(np.stack([x, up, z], axis=-1))


ANKLE_HEIGHT = 0.06  # metres above the floor of a planted ankle, as the reference skeleton's rest pose


def stance_ankle_height(rotations: np.ndarray, root: np.ndarray, fps: float, height: float = 1.75) -> float:
    """Median height of the lower ankle on frames where it is (nearly) still: where the floor is.

    A clip's lowest ankle frame is no floor (a heel strike or a rolling foot dips below the planted height),
    so the floor is read from planted frames; a clip without such frames falls back to the 10th percentile.
    """
    pos, _ = forward_kinematics(rotations, root, rest_offsets(height))
    feet = pos[:, [JOINT_INDEX["LeftFoot"], JOINT_INDEX["RightFoot"]]]  # (T, 2, 3)
    lower = np.argmin(feet[:, :, 1], axis=1)
    y = feet[np.arange(len(feet)), lower, 1]
    speed = np.zeros(len(feet))
    if len(feet) > 1:
        step = np.linalg.norm(np.diff(feet[:, :, [0, 2]], axis=0), axis=-1)  # (T-1, 2)
        speed[1:] = step[np.arange(len(step)), lower[1:]]
    still = speed * fps < 0.3  # m/s
    if still.sum() >= 3:
        return float(np.median(y[still]))
    return float(np.percentile(y, 10))


def resample(
    root: np.ndarray, rotations: np.ndarray, src_fps: float, fps: float
) -> tuple[np.ndarray, np.ndarray]:
    """Resample (T, 3) root positions and (T, J, 4) rotations from src_fps to fps (slerp)."""
    t = root.shape[0]
    duration = (t - 1) / src_fps
    n = int(np.floor(duration * fps + 1e-3)) + 1
    x = np.arange(n) / fps * src_fps
    i0 = np.minimum(np.floor(x).astype(int), t - 1)
    i1 = np.minimum(i0 + 1, t - 1)
    u = x - i0
    r = root[i0] + (root[i1] - root[i0]) * u[:, None]
    q = quat.slerp(rotations[i0], rotations[i1], np.repeat(u[:, None], rotations.shape[1], axis=1))
    return r, q


def retarget_clip(
    clip: BvhClip,
    joint_map: dict[str, str] | None = None,
    units_to_m: float | None = None,
    fps: float = 30.0,
    height: float = 1.75,
) -> tuple[np.ndarray, np.ndarray]:
    """Retarget a BVH clip onto the canonical skeleton.

    Args:
        clip: a parsed BVH.
        joint_map: canonical name -> source name for all 24 canonical joints (default: guessed); a value
            may also be a midpoint "a|b" or an End Site "name@end".
        units_to_m: file units to metres (default: 0.01 when the hips rest above 3 units, i.e. centimetres).
        fps: output frame rate.
        height: canonical character height in metres (scales the root).

    Returns:
        root positions (T', 3) in metres and local rotations (T', J, 4) at fps.

    Raises:
        ValueError: when the map names joints the clip lacks.
    """
    joint_map = joint_map or guess_map(clip.joint_names)
    missing = sorted({n for v in joint_map.values() for n in source_joints(v) if n not in clip.joint_names})
    if missing or set(joint_map) != set(JOINT_INDEX):
        lacking = sorted(set(JOINT_INDEX) - set(joint_map))
        raise ValueError(
            f"joint map does not fit this skeleton: source lacks {missing[:8]}, map lacks {lacking[:8]}"
        )
    gpos, grot = clip.global_transforms()
    if units_to_m is None:
        units_to_m = 0.01 if np.median(gpos[:, clip.index(joint_map["Hips"]), 1]) > 3.0 else 1.0
    src = {k: _source_position(clip, gpos, grot, v) * units_to_m for k, v in joint_map.items()}
    # Bone lengths: ours replace the source's (the bones are aimed, not stretched), and the root path is
    # scaled by the ratio of leg lengths (hip joint to ankle, straight) so that strides fit our legs.
    src_leg = (
        np.mean(
            [
                np.median(np.linalg.norm(src[a] - src[b], axis=-1))
                for a, b in (
                    ("LeftUpLeg", "LeftLeg"),
                    ("LeftLeg", "LeftFoot"),
                    ("RightUpLeg", "RightLeg"),
                    ("RightLeg", "RightFoot"),
                )
            ]
        )
        * 2
    )
    canon_leg = float(
        np.linalg.norm(REST_OFFSETS[JOINT_INDEX["LeftLeg"]])
        + np.linalg.norm(REST_OFFSETS[JOINT_INDEX["LeftFoot"]])
    )
    ratio = canon_leg * height / 1.75 / max(float(src_leg), 1e-6)
    local, _ = retarget_positions(src)
    root = src["Hips"] * ratio
    root[:, 1] += ANKLE_HEIGHT * height / 1.75 - stance_ankle_height(local, root, clip.fps, height)
    return resample(root, local, clip.fps, fps)
