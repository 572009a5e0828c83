"""Pure request -> reply handlers of the social service (no bus code here)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from proto.common import ErrorReply, reply_header
from proto.social import (
    ExpressionTrackReply,
    ExpressionTrackRequest,
    SocialPlanReply,
    SocialPlanRequest,
)
from services.social.plan import MAX_MH_STEPS, expression_track, plan_social
from services.social.story import StoryError
from wana.arrays import to_wire
from wana.bus.service import InvalidInput
from wana.domain.units import FPS

MAX_GRAPHS = 2000
MAX_FRAMES = FPS * 600  # ten minutes


def social_plan(request: SocialPlanRequest) -> SocialPlanReply:
    """Sample the document's faces, response timing, distances and open reactions."""
    if len(request.graphs) > MAX_GRAPHS:
        raise InvalidInput(f"at most {MAX_GRAPHS} sentence graphs, got {len(request.graphs)}")
    if not 0 <= request.steps <= MAX_MH_STEPS:
        raise InvalidInput(f"steps must be in 0..{MAX_MH_STEPS}, got {request.steps}")
    try:
        plan = plan_social(request.graphs, seed=request.seed, steps=request.steps)
    except StoryError as exc:
        raise InvalidInput(str(exc)) from exc
    return SocialPlanReply(header=reply_header(request), plan=plan)


def expression(request: ExpressionTrackRequest) -> ExpressionTrackReply:
    """Motion.expression of one character from a plan and its segments."""
    frames = request.frames or None
    if frames is not None and not 0 < frames <= MAX_FRAMES:
        raise InvalidInput(f"frames must be in 1..{MAX_FRAMES}, got {frames}")
    if any(s.end_frame > MAX_FRAMES for s in request.segments):
        raise InvalidInput(f"segments must end by frame {MAX_FRAMES}")
    if not 1 <= request.fps <= 240:
        raise InvalidInput(f"fps must be in 1..240, got {request.fps}")
    try:
        track = expression_track(
            request.plan,
            request.character,
            request.segments,
            request.fps,
            frames=frames,
            others=request.others,
        )
    except ValueError as exc:
        raise InvalidInput(str(exc)) from exc
    return ExpressionTrackReply(header=reply_header(request), expression=to_wire(track))


CONTRACT: dict[type, Callable[[Any], SocialPlanReply | ExpressionTrackReply | ErrorReply]] = {
    SocialPlanRequest: social_plan,
    ExpressionTrackRequest: expression,
}
