"""Shared helpers of the optimizer tests."""

from __future__ import annotations

from collections.abc import Callable

import msgspec
import pytest

from proto.motion_data import Motion
from proto.scene import Scene
from proto.ssg import ActionNode
from services.motion.seated import seated_action_fn
from wana.arrays import from_wire, to_wire
from wana.compose import compose


def _typing_draft(scene: Scene) -> Motion:
    """The orchestrator's draft of "Eve types on the laptop" after she sat on "chair": the typing only,
    starting seated (real motion service)."""
    full = seated_action_fn("Eve", "chair", ActionNode(verb="type", action="type", target="laptop"))(scene)
    seg = next(s for s in full.segments if s.action == "type")
    cut = slice(seg.start_frame, seg.end_frame)
    return msgspec.structs.replace(
        full,
        root_position=to_wire(from_wire(full.root_position)[cut]),
        rotations=to_wire(from_wire(full.rotations)[cut]),
        foot_contact=to_wire(from_wire(full.foot_contact)[cut]),
        segments=[msgspec.structs.replace(seg, start_frame=0, end_frame=seg.end_frame - seg.start_frame)],
    )


@pytest.fixture(scope="session", autouse=True)
def composed() -> None:
    """The optimiser re-synthesises through the motion service's code, wired in as every runtime does."""
    compose()


@pytest.fixture(scope="session")
def typing_draft() -> Callable[[Scene], Motion]:
    """``typing_draft(scene)``: Eve's seated typing draft in that scene (see _typing_draft)."""
    return _typing_draft
