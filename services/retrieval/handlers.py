"""Pure request -> reply handlers of the retrieval service (no sockets; the orchestrator may call them
in-process). Bad input raises wana.bus.service.InvalidInput, which the bus turns into an E010 reply."""

from __future__ import annotations

from functools import lru_cache

from proto.common import reply_header
from proto.retrieval import (
    ActionMatchReply,
    ActionMatchRequest,
    ActionMatchResult,
    ComposeReply,
    ComposeRequest,
)
from services.retrieval.actions import ClipWords, match_action, prepare_clips
from services.retrieval.compose import compose_scene
from wana.bus.service import Contract, InvalidInput

MAX_OBJECTS = 200  # a scene description with more objects than this is refused (E010)
MAX_QUERIES = 500


def handle_compose(req: ComposeRequest) -> ComposeReply:
    """Compose one room from the scene objects and relations (see services.retrieval.compose)."""
    if len(req.objects) > MAX_OBJECTS:
        raise InvalidInput(f"{len(req.objects)} objects: at most {MAX_OBJECTS} per scene")
    scene, report = compose_scene(
        list(req.objects), list(req.relations), room_type=req.room_type, seed=req.seed, previous=req.previous
    )
    return ComposeReply(
        header=reply_header(req),
        scene=scene,
        matches=report.matches,
        relations=report.relations,
        match_score=round(report.match_score, 6),
        overlaps=report.overlaps,
        diagnostics=report.diagnostics,
    )


@lru_cache(maxsize=1)
def _clips() -> tuple[ClipWords, ...]:
    from wana.domain.actions import load_library

    return tuple(prepare_clips(load_library()))


def clear_clip_cache() -> None:
    """Forget the prepared library (after `wana motion import` adds a clip)."""
    _clips.cache_clear()


def handle_action_match(req: ActionMatchRequest) -> ActionMatchReply:
    """Template clips for each action query, best first."""
    if len(req.queries) > MAX_QUERIES:
        raise InvalidInput(f"{len(req.queries)} queries: at most {MAX_QUERIES} per request")
    if req.top_k < 1:
        raise InvalidInput(f"top_k must be at least 1, got {req.top_k}")
    clips = list(_clips())
    results: list[ActionMatchResult] = [match_action(q, clips, top_k=req.top_k) for q in req.queries]
    return ActionMatchReply(header=reply_header(req), results=results)


CONTRACT: Contract = {
    ComposeRequest: handle_compose,
    ActionMatchRequest: handle_action_match,
}
