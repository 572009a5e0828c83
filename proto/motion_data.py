"""Skeletal motion on the wire: canonical skeleton, 30 fps, local rotations as quaternions (x, y, z, w)."""

from __future__ import annotations

import msgspec

from proto.common import NDArray


class Segment(msgspec.Struct, frozen=True, kw_only=True):
    index: int  # k-th action of the character
    action: str  # action-library name or "walk"
    start_frame: int
    end_frame: int  # exclusive
    sentence_id: str = ""
    action_index: int = -1  # index of the character's ActionNode this segment serves; -1 = none


class PropTrack(msgspec.Struct, frozen=True, kw_only=True):
    """A small object held in a hand: from start_frame to end_frame (exclusive) it moves with the joint.

    Outside those frames the object is where the scene placed it. position / rotation are the object's
    world pose per held frame (what a renderer or an animated GLB node plays); the object's grip point
    (catalog contact point, object frame) is then on the holding joint.
    """

    object_id: str  # PlacedObject.id of the scene
    joint: str  # canonical joint holding it, e.g. "RightHand"
    start_frame: int
    end_frame: int  # exclusive
    grip: tuple[float, float, float] = (0.0, 0.0, 0.0)  # metres, object frame: the point held
    position: NDArray  # (end - start, 3) float32, metres, world: the object's origin
    rotation: NDArray  # (end - start, 4) float32 world rotation, quaternion x, y, z, w


class Motion(msgspec.Struct, frozen=True, kw_only=True):
    character: str  # character name
    fps: int = 30
    joint_names: list[str] = []  # canonical skeleton order (wana.domain.skeleton.JOINT_NAMES)
    root_position: NDArray  # (T, 3) float32, metres, world frame: the Hips joint position
    rotations: NDArray  # (T, J, 4) float32 local joint rotations, quaternion x, y, z, w
    foot_contact: NDArray | None = None  # (T, 2) uint8, left/right foot planted
    expression: NDArray | None = None  # (T, E) float32 face blendshape weights
    segments: list[Segment] = []
    present: NDArray | None = None  # (T,) uint8, 1 while the character is on stage (None: always)
    props: list[PropTrack] = []  # objects held in a hand, in frame order
