"""Two-bone IK on the canonical skeleton and foot locking.

`two_bone_ik` (after the analytic solver popularised by D. Holden) bends the middle joint to get
the right reach and swings the upper joint to point at the target, blended by a per-frame weight.
`lock_feet` pins each foot where it touched down for as long as it stays in contact (blending in
and out over a few frames) and solves the legs, which removes foot sliding.
"""

from __future__ import annotations

import numpy as np

from wana.domain import quat
from wana.domain.skeleton import JOINT_INDEX, N_JOINTS, PARENTS, REST_OFFSETS

CHAINS = {  # end joint -> (upper, middle, end)
    "LeftHand": ("LeftArm", "LeftForeArm", "LeftHand"),
    "RightHand": ("RightArm", "RightForeArm", "RightHand"),
    "LeftHandMiddle1": ("LeftArm", "LeftForeArm", "LeftHandMiddle1"),
    "RightHandMiddle1": ("RightArm", "RightForeArm", "RightHandMiddle1"),
    "LeftFoot": ("LeftUpLeg", "LeftLeg", "LeftFoot"),
    "RightFoot": ("RightUpLeg", "RightLeg", "RightFoot"),
}


def global_transforms(
    rotations: np.ndarray, root: np.ndarray, offsets: np.ndarray = REST_OFFSETS
) -> tuple[np.ndarray, np.ndarray]:
    """Vectorised FK: positions (T, J, 3) and global rotations (T, J, 4)."""
    t = rotations.shape[0]
    gpos = np.empty((t, N_JOINTS, 3))
    grot = np.empty((t, N_JOINTS, 4))
    for j in range(N_JOINTS):
        p = PARENTS[j]
        if p < 0:
            grot[:, j] = rotations[:, j]
            gpos[:, j] = root
        else:
            grot[:, j] = quat.mul(grot[:, p], rotations[:, j])
            gpos[:, j] = gpos[:, p] + quat.rotate(grot[:, p], offsets[j])
    return gpos, grot


def path_to(joint: int) -> list[int]:
    """Joint indices from the root down to joint (inclusive)."""
    path = [joint]
    while PARENTS[path[-1]] >= 0:
        path.append(int(PARENTS[path[-1]]))
    return path[::-1]


def joint_globals(rotations: np.ndarray, root: np.ndarray, joint: int) -> tuple[np.ndarray, np.ndarray]:
    """FK along one path only: world position (T, 3) and global rotation (T, 4) of joint."""
    path = path_to(joint)
    g = rotations[:, path[0]]
    pos = np.asarray(root, dtype=np.float64)
    for j in path[1:]:
        pos = pos + quat.rotate(g, REST_OFFSETS[j])
        g = quat.mul(g, rotations[:, j])
    return pos, g


def _angle(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    an = a / np.maximum(_norm(a)[..., None], 1e-9)
    bn = b / np.maximum(_norm(b)[..., None], 1e-9)
    return np.arccos(np.clip(np.einsum("...i,...i->...", an, bn), -1.0, 1.0))


def _norm(v: np.ndarray) -> np.ndarray:
    return np.sqrt(np.einsum("...i,...i->...", v, v))


def two_bone_ik(
    rotations: np.ndarray,
    root: np.ndarray,
    end: str,
    target: np.ndarray,
    weight: np.ndarray | float = 1.0,
    pole: np.ndarray | None = None,
) -> np.ndarray:
    """Bring a joint to target positions: two analytic passes, then a slerp by weight.

    Only frames with a non-zero weight are solved, and only the chain's joints are evaluated
    (FK down to the chain's parent once, then the three chain joints per pass).

    Args:
        rotations: (T, J, 4) local rotations (not modified).
        root: (T, 3) hips positions.
        end: a key of CHAINS, e.g. "RightHandMiddle1" or "LeftFoot".
        target: (T, 3) or (3,) world targets.
        weight: (T,) or scalar in [0, 1]: 0 keeps the pose, 1 reaches the target.
        pole: (T, 3) direction the middle joint should bend toward when the limb is straight.

    Returns:
        new (T, J, 4) local rotations (upper and middle joints of the chain changed).
    """
    t = rotations.shape[0]
    w = np.broadcast_to(np.asarray(weight, dtype=np.float64), (t,))
    idx = np.nonzero(w > 1e-6)[0]
    out = rotations.copy()
    if len(idx) == 0:
        return out
    ua, mb, ec = (JOINT_INDEX[n] for n in CHAINS[end])
    tail = path_to(ec)[path_to(ec).index(mb) + 1 :]
    sub = rotations[idx]
    gp_pos, gp_rot = joint_globals(sub, np.asarray(root)[idx], int(PARENTS[ua]))
    tgt = np.broadcast_to(np.asarray(target, dtype=np.float64), (t, 3))[idx]
    pl = None if pole is None else np.broadcast_to(pole, (t, 3))[idx]
    r_ua, r_mb = sub[:, ua], sub[:, mb]
    r_tail = [sub[:, j] for j in tail]
    for _ in range(2):
        r_ua, r_mb = _two_bone_pass(r_ua, r_mb, r_tail, gp_pos, gp_rot, (ua, mb, tail), tgt, pl)
    wi = w[idx]
    out[idx, ua] = quat.slerp(sub[:, ua], r_ua, wi)
    out[idx, mb] = quat.slerp(sub[:, mb], r_mb, wi)
    return out


def _two_bone_pass(
    r_ua: np.ndarray,
    r_mb: np.ndarray,
    r_tail: list[np.ndarray],
    gp_pos: np.ndarray,
    gp_rot: np.ndarray,
    chain: tuple[int, int, list[int]],
    target: np.ndarray,
    pole: np.ndarray | None,
) -> tuple[np.ndarray, np.ndarray]:
    """One analytic pass (after D. Holden): new local rotations (n, 4) of the upper and middle joints.

    Args:
        r_ua, r_mb: (n, 4) local rotations of the upper and middle joints; r_tail: (n, 4) each, the
            joints from below the middle joint down to the end.
        gp_pos, gp_rot: (n, 3), (n, 4) world position and rotation of the upper joint's parent.
        chain: (upper, middle, tail joint indices).
        target: (n, 3) world targets.  pole: (n, 3) bend direction for straight limbs, or None.
    """
    ua, mb, tail = chain
    n = len(r_ua)
    g_a = quat.mul(gp_rot, r_ua)
    a = gp_pos + quat.rotate(gp_rot, REST_OFFSETS[ua])
    g_b = quat.mul(g_a, r_mb)
    b = a + quat.rotate(g_a, REST_OFFSETS[mb])
    c, g = b, g_b
    for j, r in zip(tail, r_tail, strict=True):
        c = c + quat.rotate(g, REST_OFFSETS[j])
        g = quat.mul(g, r)
    lab = _norm(b - a)
    lcb = _norm(c - b)
    lat = np.clip(_norm(target - a), 0.01, lab + lcb - 1e-3)
    ac_ab_0 = _angle(c - a, b - a)
    ba_bc_0 = _angle(a - b, c - b)
    ac_at_0 = _angle(c - a, target - a)
    ac_ab_1 = np.arccos(np.clip((lcb**2 - lab**2 - lat**2) / (-2 * lab * lat), -1, 1))
    ba_bc_1 = np.arccos(np.clip((lat**2 - lab**2 - lcb**2) / (-2 * lab * lcb), -1, 1))
    axis0 = quat.cross(c - a, b - a)
    bad = _norm(axis0) < 1e-6
    if np.any(bad):
        alt = quat.cross(c - a, pole if pole is not None else np.broadcast_to([0.0, 0.0, 1.0], (n, 3)))
        axis0 = np.where(bad[:, None], alt, axis0)
    axis0 = axis0 / np.maximum(_norm(axis0)[:, None], 1e-9)
    axis1 = quat.cross(c - a, target - a)
    n1 = _norm(axis1)[:, None]
    axis1 = np.where(n1 > 1e-9, axis1 / np.maximum(n1, 1e-9), axis0)
    ga_inv, gb_inv = quat.inv(g_a), quat.inv(g_b)
    r0 = quat.from_axis_angle(quat.rotate(ga_inv, axis0), ac_ab_1 - ac_ab_0)
    r1 = quat.from_axis_angle(quat.rotate(gb_inv, axis0), ba_bc_1 - ba_bc_0)
    r2 = quat.from_axis_angle(quat.rotate(ga_inv, axis1), ac_at_0)
    return quat.normalize(quat.mul(r_ua, quat.mul(r0, r2))), quat.normalize(quat.mul(r_mb, r1))


SPINE = ("Spine", "Spine1", "Spine2")


def chain_reach(end: str) -> float:
    """Longest distance (metres) from the chain's upper joint to its end joint, limb straight."""
    ua, mb, ec = (JOINT_INDEX[n] for n in CHAINS[end])
    path = path_to(ec)
    return float(sum(np.linalg.norm(REST_OFFSETS[j]) for j in path[path.index(ua) + 1 :]))


def bend_spine_to_reach(
    rotations: np.ndarray,
    root: np.ndarray,
    end: str,
    target: np.ndarray,
    weight: np.ndarray,
    max_pitch: float = np.radians(80.0),
    slack: float = 0.97,
) -> np.ndarray:
    """Lean the spine forward just enough that a hand target comes within the arm's reach.

    Two-bone IK alone cannot reach a point lower or farther than the arm (wiping a table, pressing a
    low button). The smallest pitch among 15 candidates (spread evenly over Spine, Spine1, Spine2,
    about the pelvis' left axis) that brings the shoulder within slack * reach of the target, over
    the frames where weight is 1, is applied to every frame scaled by weight (so it eases in and
    out with the contact).

    Args:
        rotations: (T, J, 4) local rotations.  root: (T, 3).  end: a hand key of CHAINS.
        target: (T, 3) or (3,) world target.  weight: (T,) contact weight in [0, 1].

    Returns:
        new (T, J, 4) rotations (spine joints changed where needed).
    """
    t = rotations.shape[0]
    w = np.broadcast_to(np.asarray(weight, dtype=np.float64), (t,))
    needed = lean_needed(rotations, root, end, target, w, max_pitch, slack)
    return lean_spine(rotations, max_pitch if needed is None else needed, w)


def lean_spine(rotations: np.ndarray, pitch: float, weight: np.ndarray) -> np.ndarray:
    """Pitch the spine forward by ``pitch`` radians (spread over Spine, Spine1, Spine2) scaled by weight (T,)."""
    if pitch <= 0.0:
        return rotations
    spine = [JOINT_INDEX[n] for n in SPINE]
    out = rotations.copy()
    bend = quat.from_axis_angle(
        np.array([1.0, 0.0, 0.0]), pitch * np.asarray(weight, dtype=np.float64) / len(spine)
    )
    for j in spine:
        out[:, j] = quat.mul(out[:, j], bend)
    return out


def lean_needed(
    rotations: np.ndarray,
    root: np.ndarray,
    end: str,
    target: np.ndarray,
    weight: np.ndarray,
    max_pitch: float = np.radians(80.0),
    slack: float = 0.97,
) -> float | None:
    """The smallest spine pitch (radians, of 15 candidates up to max_pitch) that brings the shoulder
    within slack * reach of the target over the frames where weight is 1; 0 with no such frame;
    None when even max_pitch is not enough.

    Args: as bend_spine_to_reach.
    """
    t = rotations.shape[0]
    w = np.broadcast_to(np.asarray(weight, dtype=np.float64), (t,))
    full = np.nonzero(w >= 0.999)[0]
    if len(full) == 0:
        return 0.0
    ua, mb, ec = (JOINT_INDEX[n] for n in CHAINS[end])
    tgt = np.broadcast_to(np.asarray(target, dtype=np.float64), (t, 3))[full]
    sub = rotations[full]
    hips = np.asarray(root)[full]
    # Reach as posed: the wrist's bend shortens the lower "bone" (forearm + hand) below its straight length.
    mid, _ = joint_globals(sub, hips, mb)
    tip, _ = joint_globals(sub, hips, ec)
    reach = (float(np.linalg.norm(REST_OFFSETS[mb])) + float(np.min(_norm(tip - mid)))) * slack
    spine = [JOINT_INDEX[n] for n in SPINE]
    x_axis = np.array([1.0, 0.0, 0.0])
    for pitch in np.linspace(0.0, max_pitch, 15):
        trial = sub.copy()
        bend = quat.from_axis_angle(x_axis, pitch / len(spine))
        for j in spine:
            trial[:, j] = quat.mul(trial[:, j], bend)
        shoulder, _ = joint_globals(trial, hips, ua)
        if np.max(_norm(tgt - shoulder)) <= reach:
            return float(pitch)
    return None


def contact_runs(contact: np.ndarray) -> list[tuple[int, int]]:
    """[start, end) frame ranges where contact (T,) is set."""
    c = np.concatenate([[0], contact.astype(np.int8), [0]])
    d = np.diff(c)
    return list(zip(np.where(d == 1)[0].tolist(), np.where(d == -1)[0].tolist(), strict=True))


def lock_feet(
    rotations: np.ndarray,
    root: np.ndarray,
    contacts: np.ndarray,
    blend: int = 3,
    floor_y: float | None = None,
) -> np.ndarray:
    """Pin planted feet; returns new (T, J, 4) rotations (root unchanged).

    Args:
        rotations: (T, J, 4).  root: (T, 3).  contacts: (T, 2) left/right planted flags.
        blend: frames to blend the lock in and out at each contact boundary.
        floor_y: optional ankle height to hold locked feet at (default: height at touch-down).
    """
    out = rotations
    t = len(root)
    fwd = None
    for k, name in enumerate(("LeftFoot", "RightFoot")):
        if not np.any(contacts[:, k]):
            continue
        foot, _ = joint_globals(rotations, root, JOINT_INDEX[name])
        target = foot.copy()
        weight = np.zeros(t)
        for s, e in contact_runs(contacts[:, k]):
            pin = foot[s].copy()
            if floor_y is not None:
                pin[1] = floor_y
            target[s:e] = pin
            weight[s:e] = 1.0
            for i in range(1, blend + 1):  # ease the foot toward / away from the pin outside the run
                u = 1.0 - i / (blend + 1)
                if e - 1 + i < t and weight[e - 1 + i] < u:
                    target[e - 1 + i] = pin
                    weight[e - 1 + i] = u
                if s - i >= 0 and weight[s - i] < u:
                    target[s - i] = pin
                    weight[s - i] = u
        weight[_norm(foot - target) < 1e-5] = 0.0  # already there: nothing to solve
        if np.any(weight > 0):
            if fwd is None:
                fwd = quat.rotate(rotations[:, 0], np.array([0.0, 0.0, 1.0]))
            out = two_bone_ik(out, root, name, target, weight, pole=fwd)
    return out


def limb_lengths(end: str) -> tuple[float, float]:
    """Rest lengths (upper, lower) of a chain."""
    ua, mb, ec = (JOINT_INDEX[n] for n in CHAINS[end])
    return float(np.linalg.norm(REST_OFFSETS[mb])), float(np.linalg.norm(REST_OFFSETS[ec]))


def trunk_tilt(rotations: np.ndarray, root: np.ndarray, weight: np.ndarray) -> float:
    """Largest angle (radians) between the trunk (hips -> neck) and upright over the frames where weight
    is 1 (0 with none): how far a clip already bends before any reach lean is added, so that the lean
    a standing reach may add keeps the whole trunk within its budget."""
    full = np.nonzero(np.asarray(weight) >= 0.999)[0]
    if len(full) == 0:
        return 0.0
    hips = np.asarray(root, dtype=np.float64)[full]
    neck, _ = joint_globals(rotations[full], hips, JOINT_INDEX["Neck"])
    up = neck - hips
    return float(np.max(np.arccos(np.clip(up[:, 1] / np.maximum(_norm(up), 1e-9), -1.0, 1.0))))
