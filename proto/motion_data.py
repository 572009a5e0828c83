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
