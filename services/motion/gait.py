"""Procedural locomotion: a parametric gait with planted feet, for the locomotion training corpus.

Given a root trajectory (ground position and heading per frame at 30 fps), feet are planted at
footstep positions for their stance phase and swing on an arc between steps; legs reach them by
two-bone IK, the hips bob half as far as legs that never over-extend would need (the ankle lifts a
little at heel strike and toe-off, up to 0.2 cm a frame at a walk), arms swing against the legs,
toward the midline and with the elbow flexing in front. Stance share, bob, ankle lift and arm swing
are fitted to the captured training takes (never to eval/gait.py's held-out people).
`random_trajectory` makes walks, runs, starts, stops, turns and side steps at varied speeds.
"""

from __future__ import annotations

import numpy as np

from wana.domain import quat
from wana.domain.skeleton import JOINT_INDEX, N_JOINTS, REST_OFFSETS
from wana.domain.units import FPS

J = JOINT_INDEX
UPPER_LEN = float(np.linalg.norm(REST_OFFSETS[J["LeftLeg"]]))
LOWER_LEN = float(np.linalg.norm(REST_OFFSETS[J["LeftFoot"]]))
ANKLE_HEIGHT = 0.06
HIP_WIDTH = float(REST_OFFSETS[J["LeftUpLeg"], 0])
ARM_ACROSS = 0.5  # the arm's sideways swing toward the midline, a share of its fore-aft swing
ELBOW_FLEX = 0.8  # the elbow's extra flexion at the front of the swing, a share of the fore-aft swing (x2)
BOB_SHARE = 0.5
SWING_SKEW = 0.63  # share of the hips' dip that the legs' reach asks for that the hips actually make


def gait_frequency(speed: np.ndarray) -> np.ndarray:
    """Gait cycles per second for a ground speed in m/s (a full cycle is two steps).

    Fitted to the captured takes of cmu_locomotion_daz (0.78 Hz at 0.9 m/s, 0.9 at 1.35, 1.3 at 3.4 m/s
    running); the older 0.75 + 0.42 v stepped half again as fast as any of those people.
    """
    return 0.6 + 0.2 * np.abs(speed)


DUTY_SPEEDS = (0.0, 1.0, 2.5, 3.5)  # m/s
DUTY_SHARES = (0.53, 0.51, 0.43, 0.30)


def duty_factor(speed: np.ndarray) -> np.ndarray:
    """Share of a cycle each foot is planted (its ankle low and still): 0.51 walking at 1 m/s, 0.43 at
    2.5 m/s, 0.30 running at 3.5 m/s.

    Fitted to the contacts that services.motion.train_locomotion.annotate labels on the captured training
    takes (0.47-0.53 at 0.6-1.1 m/s, 0.38-0.51 at 1.3-1.8, 0.42-0.46 at 1.9-2.5); the older 0.62 at a walk
    kept the procedural feet planted through heel-off, and the network learnt contact flags a tenth of a
    cycle longer than the people's, which the foot lock then held still and let go with a jerk.
    """
    return np.interp(np.abs(speed), DUTY_SPEEDS, DUTY_SHARES)


def two_bone_ik(
    root: np.ndarray, target: np.ndarray, pole: np.ndarray, l1: float, l2: float
) -> tuple[np.ndarray, np.ndarray]:
    """World positions of the middle joint and the reached end for a two-bone chain.

    Args:
        root: (T, 3) chain start.  target: (T, 3) wanted end.  pole: (T, 3) direction the middle joint bends toward.
        l1, l2: bone lengths.

    Returns:
        middle (T, 3), end (T, 3) (end = target when reachable, else the closest reachable point).
    """
    d = target - root
    dist = np.linalg.norm(d, axis=-1, keepdims=True)
    dist_c = np.clip(dist, abs(l1 - l2) + 1e-4, l1 + l2 - 1e-4)
    dirn = d / np.maximum(dist, 1e-9)
    end = root + dirn * dist_c
    a = (l1**2 - l2**2 + dist_c**2) / (2 * dist_c)
    h = np.sqrt(np.maximum(l1**2 - a**2, 0.0))
    side = pole - np.sum(pole * dirn, axis=-1, keepdims=True) * dirn
    side = side / np.maximum(np.linalg.norm(side, axis=-1, keepdims=True), 1e-9)
    return root + dirn * a + side * h, end


def footsteps(
    pos: np.ndarray,
    heading: np.ndarray,
    phase: np.ndarray,
    offset: float,
    side: float,
    duty: np.ndarray,
    lift: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """World ankle positions (T, 3) and contact flags (T,) of one foot.

    Args:
        pos: (T, 2) ground root positions x, z.  heading: (T,) yaw radians.  phase: (T,) cycles, unwrapped.
        offset: this foot's phase offset (0 left, 0.5 right).  side: +1 left, -1 right.
        duty: (T,) stance share.  lift: (T,) swing height in metres.
    """
    t = len(pos)
    local = phase + offset  # stance when frac(local) < duty
    frac = local - np.floor(local)
    stance = frac < duty
    cyc = np.floor(local).astype(int)
    lateral = np.stack([np.cos(heading), -np.sin(heading)], -1) * side * HIP_WIDTH  # +X rotated by heading
    ground = pos + lateral
    plant = np.zeros((t, 2))
    # Each stance (one per cycle index) plants at the ground point of its middle frame.
    for c in np.unique(cyc[stance]):
        idx = np.where(stance & (cyc == c))[0]
        plant[idx] = ground[idx[len(idx) // 2]]
    # Swing frames: from the last plant to the next plant.
    out = np.zeros((t, 3))
    out[:, 1] = ANKLE_HEIGHT
    out[stance, 0], out[stance, 2] = plant[stance, 0], plant[stance, 1]
    swing = np.where(~stance)[0]
    if len(swing):
        stance_idx = np.where(stance)[0]
        for run in np.split(swing, np.where(np.diff(swing) > 1)[0] + 1):
            before = stance_idx[stance_idx < run[0]]
            after = stance_idx[stance_idx > run[-1]]
            a = plant[before[-1]] if len(before) else ground[run[0]]
            b = plant[after[0]] if len(after) else ground[run[-1]]
            u = (np.arange(len(run)) + 1) / (len(run) + 1)
            s = u * u * (3 - 2 * u)
            xz = a + (b - a) * s[:, None]
            out[run, 0], out[run, 2] = xz[:, 0], xz[:, 1]
            moving = np.linalg.norm(b - a) > 0.02
            # The ankle rises fast as the heel comes off and sinks slowly to the heel strike: the peak a
            # third of the way through the swing (u ** 0.63 = 0.5 at u = 1/3).
            out[run, 1] = ANKLE_HEIGHT + (lift[run] * np.sin(np.pi * u**SWING_SKEW) if moving else 0.0)
    return out, stance


def synthesize_gait(
    pos: np.ndarray, heading: np.ndarray, speed: np.ndarray, phase0: float = 0.0, lean_deg: float = 4.0
) -> dict[str, np.ndarray]:
    """Full-body gait for a root trajectory.

    Args:
        pos: (T, 2) ground positions x, z in metres.  heading: (T,) yaw radians (0 = facing +Z).
        speed: (T,) ground speed m/s (drives cadence, stride, lean, lift).

    Returns:
        dict with root_position (T, 3), rotations (T, J, 4), phase (T,) in [0, 1), contacts (T, 2).
    """
    t = len(pos)
    spd = np.abs(speed)
    moving = spd > 0.05
    freq = np.where(moving, gait_frequency(spd), 0.0)
    phase = phase0 + np.concatenate([[0.0], np.cumsum(freq[1:] / FPS)])
    duty = np.where(moving, duty_factor(spd), 1.0)
    # Swing height of the ankle: the captured training walkers lift it at 0.34-0.4 m/s (its windows' spread)
    # at 0.9-1.8 m/s, 1.0 running; 5 cm + 5 cm per m/s on a symmetric arc lifted it at 0.19-0.26.
    lift = 0.09 + 0.04 * np.minimum(spd, 3.0)
    # Feet stay planted (at their last step) when standing: stance for the whole idle stretch.
    feet, contacts = [], []
    for offset, side in ((0.0, 1.0), (0.5, -1.0)):
        f, c = footsteps(pos, heading, phase, offset, side, duty, lift)
        feet.append(f)
        contacts.append(c)
    hq = quat.yaw(heading)
    lean = np.radians(lean_deg * np.clip(spd, 0, 3.5))
    hips_rot = quat.mul(hq, quat.from_axis_angle(np.array([1.0, 0.0, 0.0]), lean * 0.5))
    # Hip height: as high as rest allows while both ankles stay reachable.
    root = np.zeros((t, 3))
    root[:, 0], root[:, 2] = pos[:, 0], pos[:, 1]
    reach = (UPPER_LEN + LOWER_LEN) * 0.985
    height = np.full(t, REST_OFFSETS[0, 1])
    for k, f in enumerate(feet):
        hip_off = quat.rotate(
            hips_rot, np.broadcast_to(REST_OFFSETS[J["LeftUpLeg" if k == 0 else "RightUpLeg"]], (t, 3))
        )
        horiz = np.linalg.norm((root[:, [0, 2]] + hip_off[:, [0, 2]]) - f[:, [0, 2]], axis=-1)
        need = f[:, 1] - hip_off[:, 1] + np.sqrt(np.maximum(reach**2 - horiz**2, 0.05))
        height = np.minimum(height, need)
    kernel = np.ones(5) / 5
    height = np.minimum(np.convolve(np.pad(height, 2, mode="edge"), kernel, mode="valid"), REST_OFFSETS[0, 1])
    # Captured walkers bob half as much as flat-footed legs of fixed length need (the training takes'
    # hips move 0.09 m/s vertically at 0.9 m/s, 0.15-0.2 at 1.6; these legs 0.15 and 0.29): the heel
    # lifts and the knee flexes through stance. Half the dip; a foot out of reach is left by the IK a cm
    # or two above its step, as a lifting heel is.
    # (standing, the hips stay where the legs put them)
    root[:, 1] = height + (1.0 - BOB_SHARE) * (REST_OFFSETS[0, 1] - height) * np.minimum(spd / 0.5, 1.0)
    rot = quat.identity((t, N_JOINTS))
    rot[:, J["Hips"]] = hips_rot
    spine_q = quat.from_axis_angle(np.array([1.0, 0.0, 0.0]), lean * 0.25)
    for name in ("Spine", "Spine1"):
        rot[:, J[name]] = spine_q
    glob_hips = hips_rot
    fwd = quat.rotate(hq, np.broadcast_to([0.0, 0.0, 1.0], (t, 3)))
    for name, f in (("Left", feet[0]), ("Right", feet[1])):
        hip = root + quat.rotate(glob_hips, np.broadcast_to(REST_OFFSETS[J[f"{name}UpLeg"]], (t, 3)))
        knee, ankle = two_bone_ik(hip, f, fwd, UPPER_LEN, LOWER_LEN)
        up_dir = quat.rotate(quat.inv(glob_hips), knee - hip)
        q_up = quat.between(np.broadcast_to([0.0, -1.0, 0.0], (t, 3)), up_dir)
        g_up = quat.mul(glob_hips, q_up)
        lo_dir = quat.rotate(quat.inv(g_up), ankle - knee)
        q_lo = quat.between(np.broadcast_to([0.0, -1.0, 0.0], (t, 3)), lo_dir)
        g_lo = quat.mul(g_up, q_lo)
        # Foot flat and along the heading: global foot rotation = heading.
        rot[:, J[f"{name}UpLeg"]] = q_up
        rot[:, J[f"{name}Leg"]] = q_lo
        rot[:, J[f"{name}Foot"]] = quat.mul(quat.inv(g_lo), hq)
    # Arms swing against the legs, amplitude with speed (5° + 6° per m/s: what the captured walkers of
    # cmu_locomotion_daz swing; 8° + 10° per m/s swung the hands twice as fast as any of them).
    from wana.domain.actions import neutral_rotations

    base = neutral_rotations()
    amp = np.radians(np.minimum(5 + 6 * spd, 30))
    swing = np.sin(2 * np.pi * phase) * amp
    for name, sgn in (("Left", 1.0), ("Right", -1.0)):
        for j in ("Arm", "ForeArm", "Hand"):
            rot[:, J[f"{name}{j}"]] = base[J[f"{name}{j}"]]
        # The swing is not a rigid pendulum: the hand crosses toward the body's midline as it comes forward
        # and the elbow flexes in the forward swing and opens behind (the captured walkers' hands move
        # sideways 0.1-0.3 m/s and up and down 0.15-0.5 m/s at 1 m/s; a pendulum about one axis, not at all).
        # 1: this arm at its most forward; nothing standing (the standing pose stays the neutral one)
        forward = sgn * np.sin(2 * np.pi * phase) * np.minimum(spd / 0.5, 1.0)
        q = quat.from_axis_angle(np.array([1.0, 0.0, 0.0]), -sgn * swing)
        across = quat.from_axis_angle(np.array([0.0, 0.0, 1.0]), -sgn * ARM_ACROSS * amp * forward)
        rot[:, J[f"{name}Arm"]] = quat.mul(across, quat.mul(q, base[J[f"{name}Arm"]]))
        flex = np.radians(np.minimum(10 * spd, 60)) + ELBOW_FLEX * amp * (
            np.minimum(spd / 0.5, 1.0) + forward
        )
        bend = quat.from_axis_angle(np.array([0.0, sgn * -1.0, 0.0]), flex)
        rot[:, J[f"{name}ForeArm"]] = quat.mul(base[J[f"{name}ForeArm"]], bend)
    return {
        "root_position": root,
        "rotations": rot,
        "phase": np.mod(phase, 1.0),
        "contacts": np.stack(contacts, -1).astype(np.uint8),
    }


def random_trajectory(
    rng: np.random.Generator, seconds: float = 20.0
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A random locomotion script: segments of idle/walk/run/turn/side-step with smooth speed changes.

    Returns:
        pos (T, 2), heading (T,) radians, speed (T,) signed forward speed m/s.
    """
    t = int(seconds * FPS)
    target_speed = np.zeros(t)
    target_turn = np.zeros(t)
    target_side = np.zeros(t)
    i = 0
    while i < t:
        n = int(rng.uniform(1.0, 4.0) * FPS)
        kind = rng.choice(
            ["idle", "walk", "walk", "run", "turn", "side", "slow"], p=[0.1, 0.3, 0.1, 0.15, 0.15, 0.1, 0.1]
        )
        sp = {
            "idle": 0.0,
            "walk": rng.uniform(1.0, 1.7),
            "run": rng.uniform(2.5, 4.0),
            "turn": rng.uniform(0.6, 1.6),
            "side": 0.0,
            "slow": rng.uniform(0.4, 0.9),
        }[kind]
        target_speed[i : i + n] = sp
        if kind == "turn":
            target_turn[i : i + n] = rng.uniform(-1.6, 1.6)
        else:
            target_turn[i : i + n] = rng.normal(0, 0.15)
        if kind == "side":
            target_side[i : i + n] = rng.choice([-1.0, 1.0]) * rng.uniform(0.5, 1.0)
        i += n
    # First-order smoothing gives realistic accelerations for starts and stops.
    speed = np.zeros(t)
    turn = np.zeros(t)
    side = np.zeros(t)
    for k in range(1, t):
        speed[k] = speed[k - 1] + (target_speed[k] - speed[k - 1]) * 0.06
        turn[k] = turn[k - 1] + (target_turn[k] - turn[k - 1]) * 0.1
        side[k] = side[k - 1] + (target_side[k] - side[k - 1]) * 0.08
    heading = np.cumsum(turn) / FPS + rng.uniform(-np.pi, np.pi)
    vel = np.stack(
        [np.sin(heading) * speed + np.cos(heading) * side, np.cos(heading) * speed - np.sin(heading) * side],
        -1,
    )
    pos = np.cumsum(vel, axis=0) / FPS
    return pos, heading, np.hypot(speed, side)
