"""Pure request -> reply functions of the render service (no sockets here).

A worker keeps the renderer of its latest job: the chunks of one video that land on the same
worker reuse its scene meshes, skinned rigs and GL canvas.
"""

from __future__ import annotations

import hashlib
import io
import threading
from collections.abc import Callable
from typing import Any

import msgspec
import numpy as np
from PIL import Image

from proto.common import reply_header
from proto.motion_data import Motion
from proto.render import Caption, ExportReply, ExportRequest, RenderReply, RenderRequest, TimedCommand
from proto.scene import Scene
from services.render.bvh_export import motion_bvh, safe_filename
from services.render.camera_checks import staged_checks
from services.render.cast_gltf import CastCharacter, load_cast
from services.render.cycles_render import DEFAULT_SAMPLES, CyclesJob, cycles_frames, render_mp4_cycles
from services.render.director import shot_messages
from services.render.fbx_export import glb_to_fbx
from services.render.gltf_export import scene_glb
from services.render.renderer import FrameRenderer, render_mp4
from services.render.staging import Staging
from services.render.timeline import make_captions, place_commands
from services.render.usd_export import scene_usd
from services.render.video import FPS, encode_mp4
from wana.bus.service import InvalidInput
from wana.cast import CastError

MAX_REPLY_BYTES = 30 * 1024 * 1024  # under the bus's 32 MiB frame cap
MAX_SIDE = 2048

_lock = threading.Lock()
_cache: dict[str, Any] = {"key": None, "renderer": None}
_staged: dict[str, Any] = {"key": None, "staging": None}
_staged_lock = threading.Lock()


def staging_for(
    scene: Scene, motions: list[Motion], commands: list[TimedCommand], n_frames: int = 0
) -> Staging:
    """The video staged (rigs, tracks, the director's shots), the latest one remembered: the MP4, the GLB,
    the USD and the FBX of one story ask for the same staging, and the director's planning is most of it."""
    key = hashlib.sha256(msgspec.msgpack.encode([scene, motions, commands, n_frames])).hexdigest()
    with _staged_lock:
        if _staged["key"] != key:
            _staged["staging"] = _staged["key"] = None
            _staged["staging"] = Staging.build(scene, motions, commands, n_frames)
            _staged["key"] = key
        return _staged["staging"]


def placed(req: RenderRequest | ExportRequest) -> tuple[list[TimedCommand], list[Caption]]:
    """The request's commands and captions on frames: as sent, or placed here from its story."""
    if not req.story:
        return list(req.commands), list(req.captions)
    if req.commands or req.captions:
        raise InvalidInput("send either a story or placed commands and captions, not both")
    motions = list(req.motions)
    sentences = [(s.sentence_id, s.text) for s in req.story]
    commands = [(s.sentence_id, c) for s in req.story for c in s.commands]
    return place_commands(commands, sentences, motions), make_captions(sentences, motions)


def _drawn(req: RenderRequest | ExportRequest) -> tuple[list[TimedCommand], list[Caption]]:
    """The commands and the captions drawn into the frames (none where the request turns captions off)."""
    commands, captions = placed(req)
    return commands, captions if getattr(req, "show_captions", True) else []


def _renderer_for(req: RenderRequest | ExportRequest, n_frames: int = 0) -> FrameRenderer:
    """The cached renderer when the job is the same, else a new one (the old one is closed)."""
    key_src = msgspec.msgpack.encode(
        [
            req.scene,
            req.motions,
            req.commands,
            req.captions,
            req.story,
            req.width,
            req.height,
            n_frames,
            getattr(req, "show_captions", True),
            getattr(req, "cast", []),
        ]
    )
    key = hashlib.sha256(key_src).hexdigest()
    if _cache["key"] == key and _cache["renderer"] is not None:
        return _cache["renderer"]
    if _cache["renderer"] is not None:
        _cache["renderer"].close()
        _cache["renderer"] = _cache["key"] = None
    commands, captions = _drawn(req)
    try:
        r = FrameRenderer(
            req.scene,
            list(req.motions),
            commands,
            captions,
            n_frames=n_frames,
            width=req.width,
            height=req.height,
            cast=_cast(req),
            staging=staging_for(req.scene, list(req.motions), commands, n_frames),
        )
    except (ValueError, KeyError) as exc:
        raise InvalidInput(str(exc)) from exc
    _cache["key"], _cache["renderer"] = key, r
    return r


def _check_size(width: int, height: int) -> None:
    if not (16 <= width <= MAX_SIDE and 16 <= height <= MAX_SIDE):
        raise InvalidInput(f"image size must be 16..{MAX_SIDE} pixels a side, got {width}x{height}")


def _encode_image(frame: np.ndarray, encoding: str) -> bytes:
    if encoding == "raw":
        return np.ascontiguousarray(frame, dtype=np.uint8).tobytes()
    buf = io.BytesIO()
    if encoding == "png":
        Image.fromarray(frame).save(buf, format="PNG", compress_level=1)
    else:
        Image.fromarray(frame).save(buf, format="JPEG", quality=90)
    return buf.getvalue()


def _cycles_job(
    req: RenderRequest | ExportRequest, n_frames: int = 0, cast: dict[str, CastCharacter] | None = None
) -> CyclesJob:
    """The request staged for Blender's Cycles (the same staging, so the same frames and shots)."""
    commands, captions = _drawn(req)
    try:
        return CyclesJob.build(
            req.scene,
            list(req.motions),
            commands,
            captions,
            n_frames=n_frames,
            width=req.width,
            height=req.height,
            samples=req.samples or DEFAULT_SAMPLES,
            cast=cast,
        )
    except (ValueError, KeyError) as exc:
        raise InvalidInput(str(exc)) from exc


def _frames_of(req: RenderRequest):  # noqa: ANN202 - (n_frames, frames(start, end))
    """The animation's length and a function that renders a range of it, with the request's renderer."""
    if req.renderer == "blender":
        job = _cycles_job(req, req.n_frames, cast=_cast(req))

        def cycles(a: int, b: int):  # noqa: ANN202 - an iterator of frames
            try:
                yield from cycles_frames(job, a, b, workers=1)  # one worker, one range: one Blender
            except ModuleNotFoundError as exc:  # this worker has no bpy
                raise InvalidInput(str(exc)) from exc

        return job.n_frames, cycles
    r = _renderer_for(req, req.n_frames)
    return r.n_frames, r.frames


def handle_render(req: RenderRequest) -> RenderReply:
    """Render frames [start_frame, end_frame) of the request's animation (open3d, or Blender's Cycles)."""
    _check_size(req.width, req.height)
    if req.n_frames < 0:
        raise InvalidInput("n_frames must be >= 0")
    with _lock:
        n_frames, render = _frames_of(req)
        start = int(req.start_frame)
        end = n_frames if req.end_frame < 0 else int(req.end_frame)
        if not (0 <= start <= end <= n_frames):
            raise InvalidInput(f"frame range [{start}, {end}) is outside the animation's [0, {n_frames})")
        if req.encoding == "raw" and (end - start) * req.width * req.height * 3 > MAX_REPLY_BYTES:
            raise InvalidInput(
                f"{end - start} raw frames of {req.width}x{req.height} exceed the "
                f"{MAX_REPLY_BYTES} byte reply limit; ask for a shorter range or png/jpeg/mp4"
            )
        frames: list[bytes] = []
        video = b""
        if req.encoding == "mp4":
            buf = io.BytesIO()
            if end > start:
                encode_mp4(render(start, end), buf, fps=FPS)
            video = buf.getvalue()
        else:
            size = 0
            for img in render(start, end):
                frames.append(_encode_image(img, req.encoding))
                size += len(frames[-1])
                if size > MAX_REPLY_BYTES:
                    raise InvalidInput(
                        f"frames [{start}, {end}) exceed the {MAX_REPLY_BYTES} byte reply limit; "
                        "ask for a shorter range"
                    )
        return RenderReply(
            header=reply_header(req),
            start_frame=start,
            end_frame=end,
            n_frames=n_frames,
            width=req.width,
            height=req.height,
            fps=FPS,
            encoding=req.encoding,
            frames=frames,
            video=video,
        )


def _cast(req: RenderRequest | ExportRequest) -> dict[str, CastCharacter]:
    """The request's own characters, loaded (a file that cannot be used is the caller's error)."""
    try:
        return load_cast(list(req.cast))
    except CastError as exc:
        raise InvalidInput(str(exc)) from exc


def handle_export(req: ExportRequest) -> ExportReply:
    """Produce the MP4 (with its camera checks, services.render.camera_checks), the GLB, one character's BVH,
    or the USD or FBX of the whole animation."""
    h = reply_header(req)
    try:
        if req.format == "glb":  # with the camera the MP4 of the same request shows
            _check_size(req.width, req.height)
            stage = staging_for(req.scene, list(req.motions), placed(req)[0])
            return ExportReply(
                header=h,
                format="glb",
                filename="scene.glb",
                media_type="model/gltf-binary",
                data=scene_glb(
                    req.scene,
                    list(req.motions),
                    camera=stage.camera_track(req.width, req.height),
                    cast=_cast(req),
                ),
                n_frames=stage.n_frames,
                shots=shot_messages(stage.shots),
            )
        if req.format in ("usd", "fbx"):  # the whole animation with the MP4's camera
            _check_size(req.width, req.height)
            stage = staging_for(req.scene, list(req.motions), placed(req)[0])
            camera = stage.camera_track(req.width, req.height)
            try:
                if req.format == "usd":
                    usd = scene_usd(req.scene, list(req.motions), camera, FPS, cast=_cast(req))
                    data, filename = usd, "animation.usdc"
                else:
                    glb = scene_glb(
                        req.scene, list(req.motions), camera=camera, armature_nodes=True, cast=_cast(req)
                    )
                    data, filename = glb_to_fbx(glb), "animation.fbx"
            except ModuleNotFoundError as exc:  # an optional package this worker lacks
                raise InvalidInput(str(exc)) from exc
            if len(data) > MAX_REPLY_BYTES:
                raise InvalidInput(f"the {req.format.upper()} file is larger than one reply may be")
            return ExportReply(
                header=h,
                format=req.format,
                filename=filename,
                media_type="application/octet-stream",
                data=data,
                n_frames=stage.n_frames,
                shots=shot_messages(stage.shots),
            )
        if req.format == "bvh":
            if not req.motions:
                raise InvalidInput("a BVH export needs at least one motion")
            pick = (
                [m for m in req.motions if m.character == req.character]
                if req.character
                else [req.motions[0]]
            )
            if not pick:
                raise InvalidInput(
                    f"no motion for character {req.character!r}; have "
                    f"{', '.join(m.character for m in req.motions)}"
                )
            m = pick[0]
            return ExportReply(
                header=h,
                format="bvh",
                filename=f"{safe_filename(m.character)}.bvh",
                media_type="application/octet-stream",
                data=motion_bvh(m, _cast(req).get(m.character)).encode(),  # the user's rig when cast
            )
    except (ValueError, KeyError) as exc:
        if isinstance(exc, InvalidInput):
            raise
        raise InvalidInput(str(exc)) from exc
    _check_size(req.width, req.height)
    commands, captions = placed(req)
    with _lock:
        buf = io.BytesIO()
        staged: Staging | None
        if req.renderer == "blender":  # the user's cast wears its mesh, as in the GLB the frames come from
            job = _cycles_job(req, cast=_cast(req))
            staged, n_frames = job.staging, job.n_frames  # CyclesJob.build keeps the staging
            try:
                render_mp4_cycles(job, buf, workers=req.render_workers)  # frame ranges, one Blender each
            except ModuleNotFoundError as exc:
                raise InvalidInput(str(exc)) from exc
        else:
            r = _renderer_for(req)
            staged, n_frames = r.staging, r.n_frames
            render_mp4(r, buf, processes=req.render_workers)  # frame ranges in parallel render processes
        assert staged is not None
        # The captions name the action sentences; commands carry their sentence ids.
        checks = staged_checks(staged, captions, width=req.width, height=req.height)
    if buf.getbuffer().nbytes > MAX_REPLY_BYTES:
        raise InvalidInput(
            "the video is larger than one reply may be; render it in chunks with RenderRequest"
        )
    return ExportReply(
        header=h,
        format="mp4",
        filename="animation.mp4",
        media_type="video/mp4",
        data=buf.getvalue(),
        n_frames=n_frames,
        commands=commands,
        captions=captions,
        checks=checks,
        shots=shot_messages(staged.shots),
    )


CONTRACT: dict[type, Callable[[Any], Any]] = {RenderRequest: handle_render, ExportRequest: handle_export}
