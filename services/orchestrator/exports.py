"""One way to turn a pipeline result into files: `ExportRequest`s to the render service, over the backend.

`wana animate` and the gateway's export routes both send what `export_request` builds: the scene, the
motions and the document's sentences with their commands; the render service places captions and commands
on frames itself (services/render/handlers.py), so no caller needs render's code.
"""

from __future__ import annotations

from collections.abc import Sequence

from proto.common import Header
from proto.render import CastMember, ExportFormat, ExportReply, ExportRequest, Renderer, StorySentence
from proto.ssg import Command
from services.orchestrator.backend import Backend
from services.orchestrator.result import PipelineResult


def story_of(result: PipelineResult) -> list[StorySentence]:
    """The document's sentences in order, each with its camera and weather commands."""
    commands: dict[str, list[Command]] = {}
    for sid, command in result.commands:
        commands.setdefault(sid, []).append(command)
    return [
        StorySentence(sentence_id=s.id, text=s.text, commands=commands.get(s.id, []))
        for s in result.sentences
    ]


def export_request(
    result: PipelineResult,
    fmt: ExportFormat,
    *,
    character: str = "",
    width: int = 640,
    height: int = 480,
    cast: Sequence[CastMember] = (),
    renderer: Renderer = "open3d",
    samples: int = 0,
    render_workers: int = 0,
) -> ExportRequest:
    """The render service's request for one file of a result that has a scene (``renderer``, ``samples``
    and ``render_workers``: how the MP4 is rendered, services.render.handlers).

    Raises:
        ValueError: the result has no scene.
    """
    if result.scene is None:
        raise ValueError("a result without a scene has nothing to export")
    return ExportRequest(
        header=Header(doc_id=result.doc_id, revision=result.version),
        format=fmt,
        scene=result.scene,
        motions=[result.motions[name] for name in sorted(result.motions)],
        character=character,
        width=width,
        height=height,
        story=story_of(result),
        cast=list(cast),  # every format shows the user's characters (services.render.cast_skin)
        renderer=renderer if fmt == "mp4" else "open3d",
        samples=samples if fmt == "mp4" else 0,
        render_workers=render_workers if fmt == "mp4" else 0,
    )


def export(
    backend: Backend,
    result: PipelineResult,
    fmt: ExportFormat,
    *,
    character: str = "",
    width: int = 640,
    height: int = 480,
    cast: Sequence[CastMember] = (),
    renderer: Renderer = "open3d",
    samples: int = 0,
    render_workers: int = 0,
) -> ExportReply:
    """One file of the result from the render service (StageFailed / StageUnavailable as any stage call)."""
    return backend.call(
        export_request(
            result,
            fmt,
            character=character,
            width=width,
            height=height,
            cast=cast,
            renderer=renderer,
            samples=samples,
            render_workers=render_workers,
        )
    )
