"""Export downloads: MP4, animated GLB, BVH, USD, FBX, made by the render service (503 when it is not available)."""

from __future__ import annotations

import asyncio
from typing import Literal

from fastapi import APIRouter, Query, Request, Response
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
from services.gateway.videojobs import VideoJob, VideoJobs, run_job
from services.orchestrator.store import DocumentNotFound

router = APIRouter(prefix="/api/documents", tags=["exports"])


@router.get(
    "/{doc_id}/export/{fmt}",
    summary="Download the animation as MP4, USD or FBX, the scene as animated GLB, a character's motion as BVH, "
    "or several of them as a zip",
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
    fmt: Literal["mp4", "glb", "bvh", "usd", "fbx", "zip"],
    orch: OrchestratorDep,
    character: str = Query(
        "", max_length=100, description="BVH: which character ('' = the first, '*' = every one, as a zip)"
    ),
    width: int = Query(640, ge=16, le=2048, description="MP4: width in pixels"),
    height: int = Query(480, ge=16, le=2048, description="MP4: height in pixels"),
    renderer: Literal["open3d", "blender"] = Query(
        "open3d", description="MP4: open3d (the preview) or blender (Cycles on the render worker's CPU)"
    ),
    samples: int = Query(0, ge=0, le=4096, description="MP4 with blender: samples per pixel (0 = 16)"),
    formats: str = Query(
        "mp4,glb,bvh", max_length=40, description="zip: the files it holds (mp4, glb, bvh, usd, fbx)"
    ),
) -> Response:
    try:
        session = await run_in_threadpool(orch.open, doc_id)
    except DocumentNotFound:
        raise error(404, ErrorCode.INVALID_INPUT, f"no document {doc_id!r}") from None
    try:
        bundle = tuple(f.strip() for f in formats.split(",") if f.strip())
        unknown = [f for f in bundle if f not in FORMATS or f == "zip"]
        if unknown:
            raise error(422, ErrorCode.INVALID_INPUT, f"a zip cannot hold {', '.join(unknown)}")
        data, media_type, filename = await run_in_threadpool(
            export_document,
            session,
            fmt,
            character=character,
            width=width,
            height=height,
            renderer=renderer,
            samples=samples,
            bundle=bundle,
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


def _jobs(request: Request) -> VideoJobs:
    jobs: VideoJobs | None = getattr(request.app.state, "video_jobs", None)
    if jobs is None:
        jobs = request.app.state.video_jobs = VideoJobs()
    return jobs


def _job(request: Request, doc_id: str, job_id: str) -> VideoJob:
    job = _jobs(request).get(job_id)
    if job is None or job.doc_id != doc_id:
        raise error(404, ErrorCode.INVALID_INPUT, f"no MP4 export job {job_id!r} of document {doc_id!r}")
    return job


_running: set[asyncio.Task[None]] = set()  # the jobs' tasks (kept referenced until they end)


@router.post(
    "/{doc_id}/export/mp4/jobs",
    status_code=202,
    summary="Start rendering the MP4 (poll its progress, fetch the file once done, DELETE to cancel)",
)
async def start_video_job(
    doc_id: str,
    request: Request,
    orch: OrchestratorDep,
    width: int = Query(640, ge=16, le=2048, description="width in pixels"),
    height: int = Query(480, ge=16, le=2048, description="height in pixels"),
    renderer: Literal["open3d", "blender"] = Query(
        "open3d", description="the MP4's renderer: open3d (the preview's) or blender (Cycles, final quality)"
    ),
    samples: int = Query(0, ge=0, le=4096, description="with blender: samples per pixel (0 = 16)"),
) -> dict[str, object]:
    try:
        session = await run_in_threadpool(orch.open, doc_id)
    except DocumentNotFound:
        raise error(404, ErrorCode.INVALID_INPUT, f"no document {doc_id!r}") from None
    job = _jobs(request).add(
        VideoJob(doc_id=doc_id, width=width, height=height, renderer=renderer, samples=samples)
    )
    task = asyncio.create_task(run_in_threadpool(run_job, session, job))
    _running.add(task)
    task.add_done_callback(_running.discard)
    return job.status()


@router.get(
    "/{doc_id}/export/mp4/jobs/{job_id}", summary="An MP4 job's state and frames rendered of the total"
)
async def video_job(doc_id: str, job_id: str, request: Request) -> dict[str, object]:
    return _job(request, doc_id, job_id).status()


@router.delete("/{doc_id}/export/mp4/jobs/{job_id}", summary="Cancel an MP4 job (rendering stops)")
async def cancel_video_job(doc_id: str, job_id: str, request: Request) -> dict[str, object]:
    job = _job(request, doc_id, job_id)
    job.cancel.set()
    return job.status()


@router.get(
    "/{doc_id}/export/mp4/jobs/{job_id}/file",
    summary="The finished MP4 of a job",
    responses={200: {"content": {"video/mp4": {}}}, 409: {"description": "the job has not finished"}},
    response_class=Response,
)
async def video_job_file(doc_id: str, job_id: str, request: Request) -> Response:
    job = _job(request, doc_id, job_id)
    if job.state != "done":
        raise error(409, job.code or ErrorCode.INVALID_INPUT, f"the MP4 job is {job.state}: {job.message}")
    return Response(
        job.data,
        media_type="video/mp4",
        headers={"Content-Disposition": 'attachment; filename="animation.mp4"'},
    )


MAX_CAST_BYTES = 25 * 1024 * 1024  # under the bus's frame cap with the rest of an export request


@router.get("/{doc_id}/cast", summary="The document's own characters: story name -> file size and joints")
async def list_cast(doc_id: str, orch: OrchestratorDep) -> dict[str, dict[str, int]]:
    session = await _session(orch, doc_id)
    return {
        name: {"bytes": len(m.glb), "mapped": len(m.joint_map)} for name, m in sorted(session.cast.items())
    }


@router.put(
    "/{doc_id}/cast/{name}",
    summary="Play the story character NAME with your own rigged humanoid (the request body: a .glb or .vrm)",
    responses={422: {"description": "not a GLB/VRM, or a rig whose joints cannot be mapped (named)"}},
)
async def put_cast(doc_id: str, name: str, request: Request, orch: OrchestratorDep) -> dict[str, int]:
    from wana.cast import CastError, map_joints, read_rig

    session = await _session(orch, doc_id)
    data = await request.body()
    if not name.strip() or len(name) > 100:
        raise error(422, ErrorCode.INVALID_INPUT, "a cast name is 1..100 characters")
    if len(data) > MAX_CAST_BYTES:
        raise error(422, ErrorCode.INVALID_INPUT, f"a character file may have at most {MAX_CAST_BYTES} bytes")
    try:
        rig = await run_in_threadpool(read_rig, data, f"the character for {name}")
        joints = map_joints(rig, None, f"the character for {name}")
    except CastError as exc:
        raise error(422, ErrorCode.INVALID_INPUT, str(exc)) from None
    await run_in_threadpool(session.set_cast, name, data)
    return {"bytes": len(data), "joints": rig.n_joints, "mapped": len(joints)}


@router.delete("/{doc_id}/cast/{name}", summary="Play NAME with the built-in character again")
async def delete_cast(doc_id: str, name: str, orch: OrchestratorDep) -> dict[str, bool]:
    session = await _session(orch, doc_id)
    removed = await run_in_threadpool(session.drop_cast, name)
    return {"removed": removed}


async def _session(orch: OrchestratorDep, doc_id: str):  # noqa: ANN202 - a Session
    try:
        return await run_in_threadpool(orch.open, doc_id)
    except DocumentNotFound:
        raise error(404, ErrorCode.INVALID_INPUT, f"no document {doc_id!r}") from None
