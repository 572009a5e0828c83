"""The scene stage: the `scene` node composes one room from the scene sentences (retrieval service)."""

from __future__ import annotations

from collections.abc import Sequence

from proto.retrieval import ComposeReply, ComposeRequest
from proto.scene import Room, Scene
from proto.ssg import SentenceGraph
from services.orchestrator.stages import StageContext, content_of
from services.orchestrator.staging import with_door
from services.orchestrator.views import ScenePart, scene_part


def compose(ctx: StageContext, part: ScenePart) -> tuple[Scene, ComposeReply | None]:
    """The composed room and the retrieval report; an empty room (no report) when nothing is described."""
    if not part.objects:  # nothing to retrieve: an empty room for the characters
        room = Room(room_type=part.room_type or "room", width=5.0, depth=5.0, height=2.8)
        return with_door(Scene(room=room, seed=ctx.seed)), None
    reply = ctx.backend.call(
        ComposeRequest(
            header=ctx.header(),
            objects=part.objects,
            relations=part.relations,
            room_type=part.room_type,
            seed=ctx.seed,
        )
    )
    return with_door(reply.scene), content_of(reply)  # every entrance and exit needs a door


def scene(ctx: StageContext, graphs: Sequence[SentenceGraph]) -> tuple[Scene, ComposeReply | None]:
    """The `scene` node: keyed by the scene sentences' objects, relations and room kind only."""
    part = scene_part(graphs)
    return ctx.engine.query("scene", part, lambda: compose(ctx, part))
