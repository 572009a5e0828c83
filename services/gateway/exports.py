"""Exports of a document (MP4 video, animated GLB scene, BVH motion, USD, FBX) through the render service.

The document is brought up to date first (a no-op when the live session already computed the current
version); the scene, motions and sentences with their commands then go to the render service as one
`proto.render.ExportRequest` (services/orchestrator/exports.py, as `wana animate` sends them), through the
same backend as the pipeline; the render service places captions and commands on frames.
"""

from __future__ import annotations

import io
import re
import zipfile

from proto.common import ErrorCode
from services.orchestrator.backend import StageFailed, StageUnavailable
from services.orchestrator.exports import export_request
from services.orchestrator.pipeline import PipelineResult
from services.orchestrator.session import Session

FORMATS: dict[str, str] = {
    "mp4": "video/mp4",
    "glb": "model/gltf-binary",
    "bvh": "application/octet-stream",
    "usd": "application/octet-stream",  # animation.usdc; the render worker needs usd-core
    "fbx": "application/octet-stream",  # animation.fbx; the render worker needs Blender's bpy
    "zip": "application/zip",  # animation.zip: the MP4, the GLB and every character's BVH (as --export zip)
}
BUNDLED = ("mp4", "glb", "bvh")  # what the zip holds unless asked for more (usd, fbx)


class ExportUnavailable(RuntimeError):
    """The render/export service is not in this build (or not enabled in this gateway)."""


class NothingToExport(RuntimeError):
    """The document has no scene or no motion yet (a stage could not run, or the text describes none)."""


class ExportFailed(RuntimeError):
    """The render service answered with an error."""

    def __init__(self, code: str, message: str) -> None:
        super().__init__(message)
        self.code = code


def current_result(session: Session) -> PipelineResult:
    """The pipeline result of the document's current version (computed when the session has none)."""
    with session.lock:
        last = session.last
        if last is not None and last.version == session.doc.version:
            return last
    return session.compute()  # on its own snapshot: edits are not blocked meanwhile


def export_document(
    session: Session,
    fmt: str,
    *,
    character: str = "",
    width: int = 640,
    height: int = 480,
    renderer: str = "open3d",
    samples: int = 0,
    bundle: tuple[str, ...] = BUNDLED,
) -> tuple[bytes, str, str]:
    """Render or export the document's current animation.

    Args:
        session: the open document.
        fmt: "mp4", "glb", "bvh", "usd" or "fbx" (the last two refused with a message naming the package
            when the render worker lacks it).
        character: for BVH, the character to export ("" = the first one, "*" = every one, in a zip).
        width, height: video size in pixels (MP4).
        renderer, samples: the MP4's renderer ("open3d", or "blender": Cycles, samples per pixel).
        bundle: for "zip", the formats it holds (every character's BVH for "bvh").

    The session's cast (the user's own characters, ``Session.cast``) is in every request.

    Returns:
        (file bytes, media type, file name).

    Raises:
        ValueError: an unknown format.
        ExportUnavailable: the render service is not in this build.
        NothingToExport: no scene (or, for BVH, no motion) to export yet.
        ExportFailed: the render service refused or failed (its error code and message).
    """
    if fmt not in FORMATS:
        raise ValueError(f"unknown export format {fmt!r}; choose one of {', '.join(FORMATS)}")
    missing = getattr(session.pipeline.backend, "missing", {})  # services this gateway cannot reach
    if "render" in missing:
        raise ExportUnavailable(f"the {fmt.upper()} export is not available: {missing['render']}")
    try:
        result = current_result(session)
    except Exception as exc:  # a failing stage must not take the request down with a bare 500
        raise ExportFailed(
            ErrorCode.HANDLER_FAILED, f"computing the animation failed: {type(exc).__name__}: {exc}"
        ) from exc
    if result.scene is None:
        why = "; ".join(result.unavailable.values()) or "the text describes no scene yet"
        raise NothingToExport(f"nothing to export yet: {why}")
    if fmt == "bvh" and not result.motions:
        why = result.unavailable.get("motion", "the text makes no character move yet")
        raise NothingToExport(f"no character motion to export as BVH: {why}")
    video = {"width": width, "height": height, "renderer": renderer, "samples": samples}
    if fmt == "zip":
        return _bundle(session, result, bundle, video)
    if fmt == "bvh" and character == "*":
        return _every_bvh(session, result)
    if fmt == "mp4":
        return _call(session, result, fmt, **video)
    return _call(session, result, fmt, character=character, width=width, height=height)


def _call(session: Session, result: PipelineResult, fmt: str, **options: object) -> tuple[bytes, str, str]:
    cast = list(session.cast.values())
    request = export_request(result, fmt, cast=cast, **options)  # type: ignore[arg-type]
    try:
        reply = session.pipeline.backend.call(request)
    except StageUnavailable as exc:
        raise ExportUnavailable(f"the {fmt.upper()} export is not available: {exc}") from exc
    except StageFailed as exc:
        raise ExportFailed(exc.code, str(exc)) from exc
    return bytes(reply.data), str(reply.media_type), str(reply.filename)


def _bundle(
    session: Session, result: PipelineResult, formats: tuple[str, ...], video: dict[str, object]
) -> tuple[bytes, str, str]:
    """The asked files in one zip (animation.zip), every character's BVH for "bvh"."""
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as zf:
        for fmt in [f for f in FORMATS if f in formats and f != "zip"]:
            if fmt == "bvh":
                for name in sorted(result.motions):
                    data, _, filename = _call(session, result, "bvh", character=name)
                    zf.writestr(filename, data)
                continue
            options = video if fmt == "mp4" else {"width": video["width"], "height": video["height"]}
            data, _, filename = _call(session, result, fmt, **options)
            zf.writestr(filename, data)
    return out.getvalue(), "application/zip", "animation.zip"


def _every_bvh(session: Session, result: PipelineResult) -> tuple[bytes, str, str]:
    """Every character's BVH in one zip, one `<name>.bvh` each (the editor's BVH button)."""
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as zf:
        for name in sorted(result.motions):
            data, _, _ = _call(session, result, "bvh", character=name)
            zf.writestr(f"{re.sub(r'[^A-Za-z0-9_-]+', '_', name) or 'character'}.bvh", data)
    return out.getvalue(), "application/zip", "characters-bvh.zip"
