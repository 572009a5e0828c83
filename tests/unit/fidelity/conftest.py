"""Hand-made scenes and motions for the story checks: a body whose every frame the test chooses."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from proto.motion_data import Motion, Segment
from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode, SentenceGraph
from wana.arrays import to_wire
from wana.domain.skeleton import JOINT_NAMES, identity_pose


def motion(name: str, root: np.ndarray, segments: list[tuple[str, int, int, str, int]]) -> Motion:
    """A T-posed body whose hips follow `root` (T, 3); segments as (action, start, end, sentence, index)."""
    root = np.asarray(root, dtype=np.float32)
    return Motion(
        character=name,
        joint_names=list(JOINT_NAMES),
        root_position=to_wire(root),
        rotations=to_wire(identity_pose(len(root)).astype(np.float32)),
        segments=[
            Segment(index=i, action=a, start_frame=s, end_frame=e, sentence_id=sid, action_index=k)
            for i, (a, s, e, sid, k) in enumerate(segments)
        ],
    )


def still(x: float, y: float, z: float, frames: int) -> np.ndarray:
    return np.tile(np.array([x, y, z], dtype=np.float32), (frames, 1))


def action_graph(sid: str, name: str, verb: str, action: str, target: str = "") -> SentenceGraph:
    node = ActionNode(verb=verb, action=action, target=target)
    return SentenceGraph(
        sentence_id=sid,
        text=f"{name} {verb}s.",
        kind="action",
        characters=[CharacterNode(name=name, actions=[node])],
    )


def scene(*objects: PlacedObject, width: float = 6.0, depth: float = 6.0) -> Scene:
    return Scene(room=Room(room_type="office", width=width, depth=depth, height=2.8), objects=list(objects))


@pytest.fixture
def make() -> SimpleNamespace:
    """The builders above, for the tests of this folder."""
    return SimpleNamespace(motion=motion, still=still, action_graph=action_graph, scene=scene)
