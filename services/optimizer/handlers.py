"""Pure request -> reply handlers of the optimizer service (no bus code here)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from proto.common import ErrorReply, reply_header
from proto.motion_data import Motion
from proto.optimizer import (
    CostReply,
    CostRequest,
    OptimiseReply,
    OptimiseRequest,
)
from proto.scene import Scene
from services.optimizer.annealing import optimise_interaction
from services.optimizer.resynthesis import motion_service_fn
from services.optimizer.scoring import InteractionScorer
from services.optimizer.verify import optimise_and_verify
from wana.bus.service import InvalidInput
from wana.domain.object_geometry import CatalogUnavailable
from wana.domain.routes import NoRouteError
from wana.domain.units import FPS

MAX_OBJECTS = 512
MAX_FRAMES = FPS * 600  # ten minutes of motion


def _check_scene(scene: Scene) -> None:
    room = scene.room
    if not (room.width > 0 and room.depth > 0 and room.height > 0):
        raise InvalidInput(
            f"room dimensions must be positive, got {room.width} x {room.depth} x {room.height}"
        )
    if len(scene.objects) > MAX_OBJECTS:
        raise InvalidInput(f"at most {MAX_OBJECTS} objects, got {len(scene.objects)}")
    ids = [o.id for o in scene.objects]
    if len(set(ids)) != len(ids):
        raise InvalidInput("object ids must be unique in a scene")
    for o in scene.objects:
        if not all(np.isfinite(o.position)) or not all(np.isfinite(o.scale)) or min(o.scale) <= 0:
            raise InvalidInput(f"object {o.id!r} needs a finite position and a positive scale")


def _check_motion(motion: Motion) -> None:
    frames = motion.root_position.shape[0] if motion.root_position.shape else 0
    if not 0 < frames <= MAX_FRAMES:
        raise InvalidInput(f"a motion needs 1 to {MAX_FRAMES} frames, got {frames}")


def optimise(request: OptimiseRequest) -> OptimiseReply:
    """Anneal the layout around one interaction; the motion follows every proposal."""
    _check_scene(request.scene)
    _check_motion(request.motion)
    st = request.settings
    if not 0 <= st.steps <= 10_000 or not 1 <= st.proposals <= 64 or st.sigma <= 0:
        raise InvalidInput("settings need 0..10000 steps, 1..64 proposals and sigma > 0")
    mode = request.resynthesis
    if mode in ("hybrid", "motion_service") and request.character is None:
        raise InvalidInput(f"resynthesis {mode!r} needs the character's actions (`character`)")
    try:
        if mode == "motion_service":
            result = optimise_interaction(
                request.scene,
                motion_service_fn(request.character, request.start),  # type: ignore[arg-type]
                request.interaction,
                seed=st.seed,
                steps=st.steps,
                budget_s=st.budget_s if st.budget_s > 0 else None,
                settings=st,
                motion=request.motion,
            )
            scene, after, made = result.scene, result.after, "motion_service"
        else:
            verified = optimise_and_verify(
                request.scene,
                request.interaction,
                request.motion,
                character=request.character if mode == "hybrid" else None,
                start=request.start,
                settings=st,
            )
            result = verified.search
            scene, after, made = verified.scene, verified.after, verified.made
    except (ValueError, KeyError, NoRouteError) as exc:
        raise InvalidInput(str(exc)) from exc
    except CatalogUnavailable as exc:
        raise RuntimeError(str(exc)) from exc
    return OptimiseReply(
        header=reply_header(request),
        scene=scene,
        before=result.before,
        after=after,
        cost_curve=result.cost_curve,
        best_curve=result.best_curve,
        steps_run=result.steps_run,
        elapsed_ms=result.elapsed_ms,
        resynthesis=made,
        movable=result.movable,
    )


def cost(request: CostRequest) -> CostReply:
    """C_D, C_T and C of a scene with a motion."""
    _check_scene(request.scene)
    _check_motion(request.motion)
    try:
        scorer = InteractionScorer(
            request.scene,
            request.interaction,
            lambda_d=request.lambda_d,
            lambda_t=request.lambda_t,
            frame_stride=1,
        )
        report = scorer.score_scenes([request.scene], [request.motion]).report(0, scorer.pairs)
    except (ValueError, KeyError) as exc:
        raise InvalidInput(str(exc)) from exc
    return CostReply(header=reply_header(request), report=report)


CONTRACT: dict[type, Callable[[Any], OptimiseReply | CostReply | ErrorReply]] = {
    OptimiseRequest: optimise,
    CostRequest: cost,
}
