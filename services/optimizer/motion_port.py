"""The motion synthesis the optimiser re-runs on a changed layout, given to it, never imported.

The optimiser verifies its winning layouts with the motion service's own planning and synthesis.
Services never import each other (STYLE.md, Boundaries), so the composition root — the process that
puts services together: ``wana.compose``, called by ``wana worker optimizer``, the embedded runtime
and the in-process backend — installs motion's functions here once, before the first request.

Why an installed port and not a bus call: verification runs many re-syntheses per request inside a
time budget, on the scenes of the annealing's proposals; through the bus each would cost an encode,
two hops and a decode of a Scene and a Motion, and an in-process backend has no bus to call through.
Why not a parameter of every handler: ``CONTRACT`` stays the same plain request -> reply table that
every runtime already serves, and what differs between runtimes is only who calls ``install``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from proto.motion_data import Motion
from proto.scene import Scene
from proto.ssg import ActionNode, CharacterNode

RouteFn = Callable[[Scene, tuple[float, float], tuple[float, float]], np.ndarray]  # -> (N, 2) x, z


class MotionSynthesisMissing(RuntimeError):
    """No composition root installed motion synthesis in this process."""


@dataclass(frozen=True)
class MotionSynthesis:
    """What the optimiser needs of the motion service.

    Attributes:
        character_motion: (character, scene, start (x, z, yaw), route_fn) -> the Motion of the
            character's whole plan in that scene, walking the routes route_fn gives.
        seated_action: (character name, seat id, action) -> a function scene -> the Motion of
            sitting down on the seat from its approach point and doing the action (memoised by the
            motion service; callers must not change the Motion returned).
    """

    character_motion: Callable[[CharacterNode, Scene, tuple[float, float, float], RouteFn], Motion]
    seated_action: Callable[[str, str, ActionNode], Callable[[Scene], Motion]]


_installed: MotionSynthesis | None = None


def install(synthesis: MotionSynthesis | None) -> None:
    """Give the optimiser its motion synthesis (None takes it away again, for tests)."""
    global _installed
    _installed = synthesis


def installed() -> MotionSynthesis:
    """The installed motion synthesis.

    Raises:
        MotionSynthesisMissing: no composition root called ``install`` in this process.
    """
    if _installed is None:
        raise MotionSynthesisMissing(
            "the optimizer re-synthesises motion through the motion service, which this process did "
            "not wire in: start it with `wana worker optimizer` or call wana.compose.compose() first"
        )
    return _installed
