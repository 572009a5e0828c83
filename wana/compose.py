"""The composition root: the one place that puts services together in a process.

Services import ``proto`` and the domain library, never each other (the import-linter contracts in
``pyproject.toml``). What one service needs of another at run time is either a message over the bus
or a function handed over here: today only the optimiser's motion re-synthesis
(``services.optimizer.motion_port``). Every runtime that serves the optimiser calls ``compose()``
first: ``wana worker optimizer`` (wana.cli), the embedded runtime and the in-process backend
(services.orchestrator.embedded / backend).
"""

from __future__ import annotations

import importlib

from proto.motion_data import Motion
from proto.scene import Scene
from proto.ssg import CharacterNode
from services.optimizer import motion_port


def _character_motion(
    character: CharacterNode, scene: Scene, start: tuple[float, float, float], route_fn: motion_port.RouteFn
) -> Motion:
    from services.motion.planning import plan_actions
    from services.motion.synthesis import synthesise

    motion, _, _ = synthesise(plan_actions(character, scene, start, route_fn=route_fn))
    return motion


def motion_for_optimizer() -> motion_port.MotionSynthesis:
    """The motion service's planning + synthesis, as the optimiser's port wants them."""
    from services.motion.seated import seated_action_fn

    return motion_port.MotionSynthesis(character_motion=_character_motion, seated_action=seated_action_fn)


def compose() -> None:
    """Wire the services of this process together (idempotent; loads motion's modules once)."""
    motion_port.install(motion_for_optimizer())


def serve_worker(service: str, connect: str) -> None:
    """``wana worker SERVICE``: one worker at the broker ``connect``, with what it needs wired in.

    Raises:
        ImportError: the service is not in this build.
    """
    worker = importlib.import_module(f"services.{service}.worker")
    compose()
    worker.main(connect)


def optimizer_worker(connect: str) -> None:
    """``wana worker optimizer`` as a one-argument entry point (the contract tests' worker)."""
    serve_worker("optimizer", connect)
