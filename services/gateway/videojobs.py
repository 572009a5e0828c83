"""MP4 exports as jobs with real progress and cancel: the video rendered in frame-range chunks.

`POST /api/documents/{id}/export/mp4/jobs` starts one; the gateway sends the render service one
`proto.render.RenderRequest` per chunk of `CHUNK_FRAMES` frames (`encoding="mp4"`: a complete H.264 chunk
that starts on a key frame, as the render service's own parallel renderer makes them), counts the frames
the chunks brought back against the animation's length (the first reply says it), and joins the chunks
into one MP4 by copying their packets (`wana.mp4.join_chunks`, no re-encoding). Between chunks it looks at the job's
cancel flag, so a cancelled export stops rendering on the server, not only in the browser.

The jobs live in this gateway's memory (`VideoJobs`): the latest `KEEP` are kept, finished ones for
`KEEP_S` seconds, so the editor can fetch the file once it is done.
"""

from __future__ import annotations

import io
import secrets
import threading
import time
from dataclasses import dataclass, field
from typing import Any

import msgspec

from proto.common import ErrorCode, Header
from proto.render import Renderer, RenderReply, RenderRequest
from services.gateway.exports import ExportFailed, ExportUnavailable, NothingToExport, current_result
from services.orchestrator.backend import StageFailed, StageUnavailable
from services.orchestrator.exports import story_of
from services.orchestrator.session import Session
from wana.mp4 import join_chunks

CHUNK_FRAMES = 48  # 1.6 s at 30 fps: a progress step, and the renderer is kept between chunks
KEEP = 16  # jobs kept per gateway
KEEP_S = 600.0  # how long a finished job (and its file) is kept


@dataclass
class VideoJob:
    """One MP4 export: its progress, and the file once done."""

    doc_id: str
    width: int
    height: int
    renderer: Renderer = "open3d"  # open3d (the preview's) or blender (Cycles)
    samples: int = 0  # blender: samples per pixel (0 = 16)
    id: str = field(default_factory=lambda: secrets.token_hex(8))
    state: str = "running"  # running | done | failed | cancelled
    stage: str = "computing"  # computing | staging | rendering | joining
    version: int | None = None  # the document version being rendered
    done: int = 0  # frames rendered
    total: int = 0  # frames of the animation (0 until the first chunk says)
    message: str = ""
    code: str = ""  # the error code of a failed job
    data: bytes = b""
    finished_at: float | None = None
    cancel: threading.Event = field(default_factory=threading.Event)

    def status(self) -> dict[str, Any]:
        """The job as the editor polls it."""
        return {
            "job_id": self.id,
            "doc_id": self.doc_id,
            "version": self.version,
            "state": self.state,
            "stage": self.stage,
            "done": self.done,
            "total": self.total,
            "percent": round(100.0 * self.done / self.total, 1) if self.total else 0.0,
            "message": self.message,
        }

    def finish(self, state: str, message: str = "", code: str = "") -> None:
        self.state, self.message, self.code = state, message, code
        self.finished_at = time.monotonic()


class VideoJobs:
    """The MP4 jobs of one gateway, by id."""

    def __init__(self) -> None:
        self._jobs: dict[str, VideoJob] = {}
        self._lock = threading.Lock()

    def add(self, job: VideoJob) -> VideoJob:
        with self._lock:
            now = time.monotonic()
            for jid, old in list(self._jobs.items()):
                if old.finished_at is not None and now - old.finished_at > KEEP_S:
                    del self._jobs[jid]
            while len(self._jobs) >= KEEP:
                finished = [j for j in self._jobs.values() if j.finished_at is not None]
                victim = min(finished, key=lambda j: j.finished_at or 0.0) if finished else None
                if victim is None:  # every kept job still runs: the oldest is cancelled
                    victim = next(iter(self._jobs.values()))
                    victim.cancel.set()
                del self._jobs[victim.id]
            self._jobs[job.id] = job
            return job

    def get(self, job_id: str) -> VideoJob | None:
        with self._lock:
            return self._jobs.get(job_id)


def run_job(session: Session, job: VideoJob) -> None:
    """Render the job's video (in a worker thread); its state says how it ended."""
    try:
        job.data = render_video(session, job)
        job.finish("done", f"{job.total} frames")
    except JobCancelled:
        job.finish("cancelled", "cancelled")
    except (ExportUnavailable, NothingToExport) as exc:
        job.finish("failed", str(exc), ErrorCode.UNAVAILABLE)
    except ExportFailed as exc:
        job.finish("failed", str(exc), exc.code)
    except Exception as exc:  # noqa: BLE001  (the job reports it; nothing else would)
        job.finish("failed", f"{type(exc).__name__}: {exc}", ErrorCode.HANDLER_FAILED)


class JobCancelled(RuntimeError):
    """The writer cancelled the export."""


def render_video(session: Session, job: VideoJob) -> bytes:
    """The document's current animation as one MP4, chunk by chunk, updating `job.done` / `job.total`.

    Raises:
        ExportUnavailable, NothingToExport, ExportFailed: as `exports.export_document`.
        JobCancelled: the job's cancel flag was set between two chunks.
    """
    missing = getattr(session.pipeline.backend, "missing", {})
    if "render" in missing:
        raise ExportUnavailable(f"the MP4 export is not available: {missing['render']}")
    result = current_result(session)
    if result.scene is None:
        why = "; ".join(result.unavailable.values()) or "the text describes no scene yet"
        raise NothingToExport(f"nothing to export yet: {why}")
    job.version = result.version
    job.stage = "staging"
    base = RenderRequest(
        header=Header(doc_id=result.doc_id, revision=result.version),
        scene=result.scene,
        motions=[result.motions[name] for name in sorted(result.motions)],
        width=job.width,
        height=job.height,
        encoding="mp4",
        story=story_of(result),
        renderer=job.renderer,
        samples=job.samples,
        cast=list(session.cast.values()),
    )
    # an empty range first: the render service stages the animation (kept for the chunks) and says its length
    first = _call(session, _with_range(base, 0, 0))
    total, fps = int(first.n_frames), int(first.fps)
    job.total = total
    job.stage = "rendering"
    chunks: list[bytes] = []
    for start in range(0, total, CHUNK_FRAMES):
        if job.cancel.is_set():
            raise JobCancelled()
        reply = _call(session, _with_range(base, start, min(start + CHUNK_FRAMES, total)))
        chunks.append(bytes(reply.video))
        job.done = int(reply.end_frame)
    if job.cancel.is_set():
        raise JobCancelled()
    job.stage = "joining"
    out = io.BytesIO()
    join_chunks(chunks, out, fps=fps)
    return out.getvalue()


def _with_range(base: RenderRequest, start: int, end: int) -> RenderRequest:
    return msgspec.structs.replace(base, start_frame=start, end_frame=end)


def _call(session: Session, request: RenderRequest) -> RenderReply:
    try:
        return session.pipeline.backend.call(request)
    except StageUnavailable as exc:
        raise ExportUnavailable(f"the MP4 export is not available: {exc}") from exc
    except StageFailed as exc:
        raise ExportFailed(exc.code, str(exc)) from exc
