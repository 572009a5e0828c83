"""A character's body over time as joint positions and a cloud of capsule spheres, from one FK pass.

The checks never look at the skinned mesh: each bone is a capsule (a radius per bone, slightly thinner than
the procedural characters' limbs so that a grazing touch is not called a collision), sampled as a few
spheres along the bone plus one at every joint and one at the centre of the head.
"""

from __future__ import annotations

import hashlib
from collections import OrderedDict
from dataclasses import dataclass

import numpy as np

from proto.motion_data import Motion
from wana.arrays import from_wire
from wana.assets.characters import character_for
from wana.domain import quat
from wana.domain.skeleton import JOINT_INDEX, JOINT_NAMES, PARENTS, forward_kinematics

# metres, by the bone's child joint (the bone runs parent -> child)
BONE_RADII: dict[str, float] = {
    "Spine": 0.11,
    "Spine1": 0.11,
    "Spine2": 0.12,
    "Neck": 0.045,
    "Head": 0.05,
    "LeftShoulder": 0.045,
    "LeftArm": 0.045,
    "LeftForeArm": 0.04,
    "LeftHand": 0.035,
    "LeftHandMiddle1": 0.025,
    "LeftUpLeg": 0.06,
    "LeftLeg": 0.06,
    "LeftFoot": 0.045,
    "LeftToeBase": 0.035,
}
BONE_RADII.update({k.replace("Left", "Right"): v for k, v in list(BONE_RADII.items()) if "Left" in k})
HEAD_CENTRE = (0.0, 0.10, 0.0)  # metres above the Head joint in the head's own frame
HEAD_RADIUS = 0.09
# Where each bone is sampled, as a share of its length: every 1/8 keeps the spheres of a 40 cm thigh 5 cm apart,
# so that a limb through a 4 cm table top is seen as deep as it goes (at 1/4 a sphere could straddle the top).
ALONG = (0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875)


@dataclass(frozen=True)
class Body:
    """One character's animated body.

    Attributes:
        name: the character.
        joints: (T, J, 3) world joint positions, metres, canonical joint order.
        points: (T, P, 3) world centres of the capsule spheres.
        radii: (P,) sphere radii, metres.
        point_joint: (P,) index of the joint each sphere belongs to (the bone's child joint).
    """

    name: str
    joints: np.ndarray
    points: np.ndarray
    radii: np.ndarray
    point_joint: np.ndarray

    @property
    def bounds(self) -> np.ndarray:
        """(T, 2, 3) per frame, the box around every sphere (min and max corners)."""
        r = self.radii[None, :, None]
        return np.stack([(self.points - r).min(axis=1), (self.points + r).max(axis=1)], axis=1)

    @property
    def frames(self) -> int:
        return int(self.joints.shape[0])

    def joint(self, name: str) -> np.ndarray:
        """(T, 3) world positions of one joint."""
        return self.joints[:, JOINT_INDEX[name]]


def _sphere_layout() -> tuple[list[tuple[int, int, float]], np.ndarray, np.ndarray]:
    """(parent, child, share) per sphere, its radius and owning joint; share 1.0 is the child joint."""
    spec: list[tuple[int, int, float]] = []
    radii: list[float] = []
    owner: list[int] = []
    for j, name in enumerate(JOINT_NAMES):
        p = int(PARENTS[j])
        if p < 0:
            spec.append((j, j, 1.0))  # the hips
            radii.append(BONE_RADII["Spine"])
            owner.append(j)
            continue
        r = BONE_RADII.get(name, 0.04)
        for t in (*ALONG, 1.0):
            spec.append((p, j, t))
            radii.append(r)
            owner.append(j)
    return spec, np.array(radii), np.array(owner, dtype=np.int64)


_SPEC, _RADII, _OWNER = _sphere_layout()
_SPEC_PARENT = np.array([s[0] for s in _SPEC])
_SPEC_CHILD = np.array([s[1] for s in _SPEC])
_SPEC_SHARE = np.array([s[2] for s in _SPEC])[None, :, None]


def skeleton_offsets(name: str) -> np.ndarray:
    """(J, 3) rest offsets of the character who plays `name`, as the renderer picks it (an unknown name gets a
    built-in character chosen by the sum of its letters)."""
    return np.asarray(character_for(name).offsets, dtype=np.float64)


BODY_CACHE_SIZE = 32  # bodies kept: an edit usually leaves most characters' motions as they were
_BODIES: OrderedDict[bytes, Body] = OrderedDict()


def body_of(motion: Motion) -> Body:
    """FK once (on the character's own skeleton), then the capsule spheres (vectorised over frames).

    Bodies are kept by the content of the motion's arrays, so the checks after an edit redo FK only for the
    characters whose motion changed.
    """
    key = hashlib.blake2b(
        motion.character.encode() + motion.rotations.data + motion.root_position.data, digest_size=16
    ).digest()
    found = _BODIES.get(key)
    if found is not None:
        _BODIES.move_to_end(key)
        return found
    body = _body_of(motion)
    _BODIES[key] = body
    if len(_BODIES) > BODY_CACHE_SIZE:
        _BODIES.popitem(last=False)
    return body


def _body_of(motion: Motion) -> Body:
    rotations = from_wire(motion.rotations)
    root = from_wire(motion.root_position)
    joints, global_rot = forward_kinematics(rotations, root, skeleton_offsets(motion.character))
    a, b = joints[:, _SPEC_PARENT], joints[:, _SPEC_CHILD]
    spheres = a + (b - a) * _SPEC_SHARE
    head = JOINT_INDEX["Head"]
    centre = joints[:, head] + quat.rotate(quat.normalize(global_rot[:, head]), np.array(HEAD_CENTRE))
    points = np.concatenate([spheres, centre[:, None]], axis=1)
    radii = np.concatenate([_RADII, [HEAD_RADIUS]])
    owner = np.concatenate([_OWNER, [head]])
    for array in (joints, points, radii, owner):
        array.setflags(write=False)  # shared through the cache
    return Body(motion.character, joints, points, radii, owner)


__all__ = ["BONE_RADII", "Body", "body_of"]
