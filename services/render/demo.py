"""A small known scene and procedural walking motion, for the bench, the tests and a quick look.

The walk is analytic (hips on a straight line at walking height, legs and arms swinging with the
gait phase, the body turned to face the direction of travel), so a test knows where the character
must be on every frame without running the motion service.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from proto.motion_data import Motion, Segment
from proto.scene import PlacedObject, Room, Scene
from wana.arrays import to_wire
from wana.assets.characters import EXPRESSIONS, make_character
from wana.domain.skeleton import JOINT_INDEX, JOINT_NAMES, N_JOINTS


def demo_scene() -> Scene:
    """An office: desk with a laptop, office chair, bookshelf, sofa and plant; 6 x 5 x 2.8 m."""
    objects = [
        PlacedObject(id="desk", category="desk", position=(-1.2, 0.0, -1.6), yaw=0.0),
        PlacedObject(
            id="chair",
            category="office_chair",
            attributes={"colour": "red"},
            position=(-1.2, 0.0, -0.9),
            yaw=np.pi,
        ),
        PlacedObject(id="bookshelf", category="bookshelf", position=(2.2, 0.0, -2.2), yaw=0.0),
        PlacedObject(
            id="sofa",
            category="sofa",
            attributes={"colour": "blue"},
            position=(2.3, 0.0, 0.8),
            yaw=-np.pi / 2,
        ),
    ]
    return Scene(room=Room(room_type="office", width=6.0, depth=5.0, height=2.8), objects=objects, seed=0)


def walk_motion(
    character: str,
    start: tuple[float, float],
    end: tuple[float, float],
    frames: int = 90,
    *,
    expression: str = "smile",
    sentence_id: str = "s1",
    fps: int = 30,
) -> Motion:
    """A straight walk from ``start`` to ``end`` (x, z floor positions in metres) over ``frames`` frames.

    The Hips follow ``hips_path`` exactly: at frame t they are at
    start + (end - start) * t / (frames - 1), at the character's rest hip height plus a small bob.
    """
    root, rot = walk_arrays(character, start, end, frames)
    expr = np.zeros((frames, len(EXPRESSIONS)), dtype=np.float32)
    if expression in EXPRESSIONS:
        expr[:, EXPRESSIONS.index(expression)] = np.linspace(0.0, 1.0, frames)
    return Motion(
        character=character,
        fps=fps,
        joint_names=list(JOINT_NAMES),
        root_position=to_wire(root.astype(np.float32)),
        rotations=to_wire(rot.astype(np.float32)),
        expression=to_wire(expr),
        segments=[Segment(index=0, action="walk", start_frame=0, end_frame=frames, sentence_id=sentence_id)],
    )


def hips_path(
    character: str, start: tuple[float, float], end: tuple[float, float], frames: int
) -> np.ndarray:
    """(frames, 3) Hips positions of ``walk_motion``."""
    hip_h = float(make_character(character).offsets[0, 1]) if _known(character) else 0.95
    s = np.linspace(0.0, 1.0, frames)[:, None]
    xz = np.asarray(start, float) + (np.asarray(end, float) - np.asarray(start, float)) * s
    phase = np.linspace(0.0, 2 * np.pi * frames / 30.0, frames)
    y = hip_h - 0.03 + 0.02 * np.cos(2 * phase)
    return np.stack([xz[:, 0], y, xz[:, 1]], axis=1)


def _known(character: str) -> bool:
    try:
        make_character(character)
        return True
    except KeyError:
        return False


def walk_arrays(
    character: str, start: tuple[float, float], end: tuple[float, float], frames: int
) -> tuple[np.ndarray, np.ndarray]:
    """Root (T, 3) and local rotations (T, J, 4) of the walk."""
    root = hips_path(character, start, end, frames)
    d = np.asarray(end, float) - np.asarray(start, float)
    yaw = float(np.arctan2(d[0], d[1])) if np.linalg.norm(d) > 1e-6 else 0.0
    phase = np.linspace(0.0, 2 * np.pi * frames / 30.0, frames)  # one stride per second
    rv = np.zeros((frames, N_JOINTS, 3))
    rv[:, JOINT_INDEX["Hips"], 1] = yaw
    swing = 0.45 * np.sin(phase)
    rv[:, JOINT_INDEX["LeftUpLeg"], 0] = -swing
    rv[:, JOINT_INDEX["RightUpLeg"], 0] = swing
    rv[:, JOINT_INDEX["LeftLeg"], 0] = 0.5 * np.clip(np.sin(phase + 1.2), 0, None)
    rv[:, JOINT_INDEX["RightLeg"], 0] = 0.5 * np.clip(np.sin(phase + 1.2 + np.pi), 0, None)
    rv[:, JOINT_INDEX["LeftArm"], 2] = -1.25  # arms down from the T-pose
    rv[:, JOINT_INDEX["RightArm"], 2] = 1.25
    rv[:, JOINT_INDEX["LeftArm"], 0] = 0.35 * np.sin(phase)
    rv[:, JOINT_INDEX["RightArm"], 0] = -0.35 * np.sin(phase)
    rv[:, JOINT_INDEX["LeftForeArm"], 1] = 0.3
    rv[:, JOINT_INDEX["RightForeArm"], 1] = -0.3
    rot = Rotation.from_rotvec(rv.reshape(-1, 3)).as_quat().reshape(frames, N_JOINTS, 4)
    return root, rot
