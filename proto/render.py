"""Messages of the render service: frames of a frame range, and whole-file exports.

A render request is self-contained: the scene, every character's motion, the camera/weather
commands already placed on frames and the captions. Each frame depends only on those, never on
earlier frames, so a long video is split into frame ranges that several render workers render
at once and that join without a seam (``services.render.video.join_chunks``).
"""

from __future__ import annotations

from typing import Literal

import msgspec

from proto.common import Header, Request, Status
from proto.fidelity import Check
from proto.motion_data import Motion
from proto.scene import Scene
from proto.ssg import Command

FrameEncoding = Literal["png", "jpeg", "raw", "mp4"]
ExportFormat = Literal["mp4", "glb", "bvh", "usd", "fbx"]  # usd: usd-core; fbx: Blender (bpy)
# open3d: the rasterised preview; blender: Blender's Cycles path tracer on the CPU (needs bpy), same shots
Renderer = Literal["open3d", "blender"]


class TimedCommand(msgspec.Struct, frozen=True, kw_only=True):
    """A camera or weather command that takes effect at a frame."""

    frame: int  # 0-based frame index (30 fps) from which the command applies
    command: Command
    sentence_id: str = ""  # the sentence that gave the command ("" = unknown), for its command_visible check
    implied_target: bool = False  # camera: the command named nobody; its target is the current character,
    # and the camera turns to whoever acts in each sentence of its scope


class Caption(msgspec.Struct, frozen=True, kw_only=True):
    """The sentence shown under the picture for frames [start_frame, end_frame)."""

    start_frame: int
    end_frame: int
    text: str
    sentence_id: str = ""


class StorySentence(msgspec.Struct, frozen=True, kw_only=True):
    """One sentence of the document as the render service needs it to place captions and commands itself."""

    sentence_id: str
    text: str  # as written (the caption)
    commands: list[Command] = []  # camera / weather commands of this sentence, in order


class Shot(msgspec.Struct, frozen=True, kw_only=True):
    """One shot of the video's camera: frames [start_frame, end_frame)."""

    start_frame: int
    end_frame: int  # exclusive
    type: str  # wide, medium, tracking, close_up, two_shot, over_shoulder (the director's) or a commanded
    # camera: front, back, left, right, top, follow, close
    subject: str = ""  # the character it is on ("" = the room)
    partner: str = ""  # the second character of a two-person shot
    sentence_id: str = ""  # the sentence that cut to it, or whose command it plays
    source: Literal["director", "command"] = "director"


class RenderRequest(Request["RenderReply"], frozen=True, kw_only=True, tag="render_request"):
    """Render frames [start_frame, end_frame) of the animation."""

    header: Header
    scene: Scene
    motions: list[Motion] = []
    commands: list[TimedCommand] = []
    captions: list[Caption] = []  # drawn into the frames when show_captions
    start_frame: int = 0
    end_frame: int = -1  # exclusive; -1 = the last frame of the animation
    n_frames: int = 0  # whole animation; 0 = longest motion (1 s without), held 1.5 s past the last command
    width: int = 640  # pixels
    height: int = 480  # pixels
    encoding: FrameEncoding = "png"  # per-frame png/jpeg/raw RGB bytes, or one H.264 MP4 chunk
    show_captions: bool = True
    # The document's sentences in order: when given, the render service places the commands and captions
    # on frames from them and the motions' segments (services/render/timeline.py), and `commands` and
    # `captions` must be empty.
    story: list[StorySentence] = []
    renderer: Renderer = "open3d"
    samples: int = 0  # blender: Cycles samples per pixel (0 = 16)
    cast: list[CastMember] = []  # these characters wear the user's mesh (as ExportRequest.cast)


class RenderReply(msgspec.Struct, frozen=True, kw_only=True, tag="render_reply"):
    """Frames of the requested range.

    ``frames`` holds one entry per frame for png/jpeg (image file bytes) and raw (height*width*3
    bytes, RGB, row-major, top row first); for mp4 it is empty and ``video`` is the chunk.
    """

    header: Header
    status: Status = "ok"
    start_frame: int
    end_frame: int  # exclusive
    n_frames: int  # length of the whole animation
    width: int
    height: int
    fps: int = 30
    encoding: FrameEncoding = "png"
    frames: list[bytes] = []
    video: bytes = b""


class CastMember(msgspec.Struct, frozen=True, kw_only=True):
    """A user's own character for one story character (``wana animate --cast NAME=FILE``): the rigged mesh
    as GLB bytes (a VRM is one; an FBX is converted before it is sent) and an optional joint map
    (canonical joint -> the rig's joint name) for rigs whose names no table knows."""

    name: str
    glb: bytes
    joint_map: dict[str, str] = {}


class ExportRequest(Request["ExportReply"], frozen=True, kw_only=True, tag="export_request"):
    """Produce one whole file: the MP4 video, the animated GLB scene, one character's BVH, or the whole
    animation as USD (animation.usdc) or FBX (animation.fbx); the last two need optional packages on the
    render worker (usd-core; Blender's bpy) and are refused with a message that names them when absent."""

    header: Header
    format: ExportFormat
    scene: Scene
    motions: list[Motion] = []
    commands: list[TimedCommand] = []
    captions: list[Caption] = []
    character: str = ""  # BVH: which character ("" = the first motion)
    width: int = 640
    height: int = 480
    story: list[StorySentence] = []  # as RenderRequest.story
    cast: list[CastMember] = []  # every format: these characters wear the user's mesh, on its own joints
    renderer: Renderer = "open3d"  # MP4: which renderer draws the frames (blender: the cast wears its mesh)
    samples: int = 0  # MP4 with blender: Cycles samples per pixel (0 = 16)
    render_workers: int = 0  # MP4: processes rendering frame ranges at once on the worker (0 = its cores)


class ExportReply(msgspec.Struct, frozen=True, kw_only=True, tag="export_reply"):
    header: Header
    status: Status = "ok"
    format: ExportFormat
    filename: str  # suggested file name, e.g. "scene.glb", "Eve.bvh", "animation.usdc", "animation.fbx"
    media_type: str  # "video/mp4", "model/gltf-binary", "application/octet-stream" (BVH, USD, FBX)
    data: bytes
    n_frames: int = 0  # MP4: frames in the video
    commands: list[TimedCommand] = []  # MP4: the commands as placed on frames
    captions: list[Caption] = []  # MP4: the captions as placed on frames
    checks: dict[str, list[Check]] = {}  # MP4: the video's in_view/command_visible checks by sentence id
    shots: list[Shot] = []  # MP4, GLB, USD and FBX: the camera's shots, in frame order
