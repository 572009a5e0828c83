"""Export downloads: MP4, animated GLB, BVH, USD, FBX, made by the render service (503 when it is not available)."""

from __future__ import annotations

from typing import Literal

from fastapi import APIRouter, Query, Response
from starlette.concurrency import run_in_threadpool

from proto.common import ErrorCode
from services.gateway.deps import OrchestratorDep, error
from services.gateway.exports import (
    FORMATS,
    ExportFailed,
    ExportUnavailable,
    NothingToExport,
    export_document,
)
from services.orchestrator.store import DocumentNotFound

router = APIRouter(prefix="/api/documents", tags=["exports"])


@router.get(
    "/{doc_id}/export/{fmt}",
    summary="Download the animation as MP4, USD or FBX, the scene as animated GLB, or a character's motion as BVH",
    responses={
        200: {"content": {m: {} for m in [*FORMATS.values(), "application/zip"]}},
        409: {"description": "nothing to export yet (no scene, or no motion for BVH)"},
        422: {"description": "the render service refused the request"},
        503: {"description": "the render/export service is not available"},
    },
    response_class=Response,
)
async def export(
    doc_id: str,
    fmt: Literal["mp4", "glb", "bvh", "usd", "fbx"],
    orch: OrchestratorDep,
    character: str = Query(
        "", max_length=100, description="BVH: which character ('' = the first, '*' = every one, as a zip)"
    ),
    width: int = Query(640, ge=16, le=2048, description="MP4: width in pixels"),
    height: int = Query(480, ge=16, le=2048, description="MP4: height in pixels"),
) -> Response:
    try:
        session = await run_in_threadpool(orch.open, doc_id)
    except DocumentNotFound:
        raise error(404, ErrorCode.INVALID_INPUT, f"no document {doc_id!r}") from None
    try:
        data, media_type, filename = await run_in_threadpool(
            export_document, session, fmt, character=character, width=width, height=height
        )
    except ExportUnavailable as exc:
        raise error(503, ErrorCode.UNAVAILABLE, str(exc)) from None
    except NothingToExport as exc:
        raise error(409, ErrorCode.INVALID_INPUT, str(exc)) from None
    except ExportFailed as exc:
        raise error(422, exc.code, str(exc)) from None
    return Response(
        data, media_type=media_type, headers={"Content-Disposition": f'attachment; filename="{filename}"'}
    )
