"""Render frames of an animation: scene, skinned characters, shadows, camera, weather, captions.

    >>> with FrameRenderer(scene, motions, commands, width=640, height=480) as r:
    ...     for frame in r.frames(0, r.n_frames):  # (480, 640, 3) uint8 each
    ...         ...

Any frame range can be rendered on its own and gives the same pixels as inside a longer range
(every input of a frame is a function of its index), which is what chunked rendering relies on.
"""

from __future__ import annotations

import io
import multiprocessing
import os
import pickle
from collections.abc import Callable, Iterator, Mapping
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from proto.motion_data import Motion
from proto.render import Caption, TimedCommand
from proto.scene import Scene
from services.render import captions as captions_mod
from services.render.camera import CameraPose
from services.render.canvas import Canvas
from services.render.object_states import lights_at, posed, relit, stateful_objects
from services.render.scene_geometry import (
    FLOOR_RGBA,
    ColouredMesh,
    held_ids,
    merge,
    object_meshes,
    project_to_floor,
    prop_mesh,
    prop_pose,
    room_meshes,
    shadow_faces,
)
from services.render.staging import Staging
from services.render.timeline import caption_at, chunk_ranges
from services.render.walls import wall_of, walls_behind
from services.render.weather import background_for_render, grade, look_at, rain_segments, snow_points

if TYPE_CHECKING:
    from services.render.cast_gltf import CastCharacter
    from services.render.cast_skin import CastBody

AWAY = np.array([0.0, -1000.0, 0.0])  # where a mesh that must not show is moved (below the floor, unseen)


class FrameRenderer:
    """Holds the GL canvas, the static scene and the rigs; renders frames by index.

    Args:
        scene: the composed scene.
        motions: one Motion per character.
        commands: camera/weather commands placed on frames.
        captions: sentences to draw under the picture (empty: none).
        n_frames: animation length; 0 = the longest motion (at least 1 s), held until the last
            command has been on screen 1.5 s (timeline.video_frames).
        width, height: image size in pixels.
        cast: story name -> the user's own character (services.render.cast_gltf): drawn with its mesh skinned
            on its own joints (services.render.cast_skin), the motion retargeted as in the GLB; the camera
            and the checks follow the story's motion as without it.
        staging: the video already staged from these scene, motions, commands and n_frames (the render
            service stages a story once for its MP4 and its GLB); None: staged here.
    """

    def __init__(
        self,
        scene: Scene,
        motions: list[Motion],
        commands: list[TimedCommand] | None = None,
        captions: list[Caption] | None = None,
        *,
        n_frames: int = 0,
        width: int = 640,
        height: int = 480,
        cast: Mapping[str, CastCharacter] | None = None,
        staging: Staging | None = None,
    ) -> None:
        self.scene = scene
        self.width, self.height = int(width), int(height)
        self.staging = staging or Staging.build(scene, motions, commands, n_frames)
        self.rigs = self.staging.rigs
        self.bodies: dict[str, CastBody] = {}
        if cast:
            from services.render.cast_skin import CastBody

            by_name = {m.character: m for m in motions}
            self.bodies = {n: CastBody.build(c, by_name[n]) for n, c in cast.items() if n in by_name}
        self.n_frames = self.staging.n_frames
        self.camera_keys = self.staging.camera_keys
        self.weather_keys = self.staging.weather_keys
        self.captions = list(captions or [])
        self.tracks = self.staging.tracks
        self.occluders = self.staging.occluders
        room_parts = room_meshes(scene.room)
        held = held_ids(motions)
        objects = object_meshes(scene, held)
        self._motions = list(motions)
        self._props = {o.id: (o, prop_mesh(o)) for o in scene.objects if o.id in held}
        self._stateful = {k: v for k, v in stateful_objects(scene).items() if k not in held}
        still = [m for m in objects if m.name not in self._stateful]  # doors, lamps, screens: drawn per frame
        # what hangs on a wall is drawn with its wall: cut away when the camera stands behind that wall
        self._wall = {o.id: wall_of(o, scene.room) for o in scene.objects}
        hung: dict[str, list[ColouredMesh]] = {}
        for m in still:
            if self._wall.get(m.name):
                hung.setdefault(self._wall[m.name], []).append(m)
        self._static = merge(room_parts + [m for m in still if not self._wall.get(m.name)])
        self._hung = {wall: merge(ms, f"hung:{wall}") for wall, ms in sorted(hung.items())}
        self._cut: frozenset[str] = frozenset()  # the walls cut away in the last frame drawn
        self._objects = merge(objects, "objects")
        self._lit: tuple[float, ...] = ()  # the lamps' values the static mesh's colours show (set on open)
        self._canvas: Canvas | None = None
        self._shadow_look: tuple[float, tuple[float, ...]] | None = None  # (strength, sun) last drawn

    # ------------------------------------------------------------------ lifetime
    def _open(self) -> Canvas:
        if self._canvas is not None and self._canvas.closed:  # another renderer took the GL context
            self._canvas = None
            self._shadow_look = None
        if self._canvas is None:
            c = Canvas(self.width, self.height)
            st = self._static
            if len(st.faces):
                c.set_mesh("static", st.vertices, st.faces, st.colours[:, :3] / 255.0)
            for wall, mesh in self._hung.items():
                c.set_mesh(f"hung:{wall}", mesh.vertices, mesh.faces, mesh.colours[:, :3] / 255.0)
            self._cut = frozenset()
            for name, rig in self.rigs.items():
                body = self.bodies.get(name)
                if body is not None:
                    c.set_mesh(f"char:{name}", body.rest_vertices, body.faces, body.colours)
                    continue
                ch = rig.character
                c.set_mesh(
                    f"char:{name}",
                    ch.vertices.astype(np.float64),
                    ch.faces.astype(np.int64),
                    ch.colours[:, :3] / 255.0,
                )
            self._canvas = c
            self._lit = tuple(0.0 for _ in lights_at(self._stateful, self.scene, 0))  # base colours: all off
        return self._canvas

    def __getstate__(self) -> dict[str, object]:
        """What a render process is handed: everything staged, no GL context (it opens its own)."""
        state = dict(self.__dict__)
        state.update(_canvas=None, _shadow_look=None, _lit=())
        return state

    def close(self) -> None:
        if self._canvas is not None:
            self._canvas.close()
            self._canvas = None

    def __enter__(self) -> FrameRenderer:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # ------------------------------------------------------------------ frames
    def camera(self, frame: int) -> CameraPose:
        """The frame's camera (the one services.render.staging plans for the checks too)."""
        return self.staging.camera(frame)

    def _shadow_colour(self, strength: float) -> np.ndarray:
        floor = np.asarray(FLOOR_RGBA[:3], dtype=np.float64) / 255.0
        return floor * (1.0 - strength)

    def _update_shadows(self, c: Canvas, look, char_verts: dict[str, np.ndarray]) -> None:  # noqa: ANN001
        colour = self._shadow_colour(look.shadow)
        room = self.scene.room
        key = (round(float(look.shadow), 3), tuple(np.round(look.sun, 3)))
        if len(self._objects.faces) and self._shadow_look != key:
            sv = project_to_floor(self._objects.vertices, look.sun, room)
            c.set_mesh("shadow:objects", sv, shadow_faces(self._objects.faces), np.tile(colour, (len(sv), 1)))
            self._shadow_look = key
        for name, verts in char_verts.items():
            body = self.bodies.get(name)
            faces = body.faces if body is not None else self.rigs[name].character.faces.astype(np.int64)
            sv = project_to_floor(verts, look.sun, room)
            new = f"shadow:{name}" not in c.names()
            c.set_mesh(
                f"shadow:{name}", sv, shadow_faces(faces) if new else None, np.tile(colour, (len(sv), 1))
            )

    def render(
        self, frame: int, pose: CameraPose | None = None, *, hide_characters: bool = False
    ) -> np.ndarray:
        """One frame (H, W, 3) uint8; ``pose`` overrides the commanded camera (tests, previews);
        ``hide_characters`` leaves the bodies out but keeps everything else, their shadows included (the
        difference of the two pictures is the characters' silhouette, which the preview test compares)."""
        if not 0 <= frame < self.n_frames:
            raise ValueError(f"frame {frame} is outside the animation's [0, {self.n_frames})")
        posed = {name: v[0] for name, v in self._posed(np.array([frame])).items()}
        return self._draw(frame, posed, pose, hide_characters)

    def _posed(self, frames: np.ndarray) -> dict[str, np.ndarray]:
        """Each character's skinned vertices at the frames: (N, V, 3), the user's mesh where cast."""
        return {
            name: (self.bodies[name] if name in self.bodies else rig).vertices(frames)
            for name, rig in self.rigs.items()
        }

    def _draw(
        self, f: int, verts: dict[str, np.ndarray], pose: CameraPose | None = None, hide: bool = False
    ) -> np.ndarray:
        c = self._open()
        look = look_at(f, self.weather_keys)
        pose = pose or self.camera(f)
        self._cut_walls(c, walls_behind(pose.eye, self.scene.room))
        for name, v in verts.items():
            c.set_mesh(f"char:{name}", v + np.array([0.0, -1000.0, 0.0]) if hide else v)  # far below
        for oid, (placed, mesh) in self._props.items():  # held props move with the hand
            m = prop_pose(placed, self._motions, f)
            key = f"prop:{oid}"
            fresh = key not in c.names()
            c.set_mesh(
                key,
                mesh.vertices @ m[:3, :3].T + m[:3, 3],
                mesh.faces if fresh else None,
                mesh.colours[:, :3] / 255.0 if fresh else None,
            )
        self._draw_states(c, f)
        self._update_shadows(c, look, verts)
        room = self.scene.room
        c.set_lines("rain", rain_segments(f, room, look.rain), (0.78, 0.82, 0.9))
        c.set_points("snow", snow_points(f, room, look.snow), (1.0, 1.0, 1.0))
        fog = look.fog > 1e-4
        rgb, depth = c.draw(
            pose,
            tuple(background_for_render(look)),
            with_depth=fog,
            gain=None if fog else look.gain,  # no fog: the light's gain is graded in the read-back
        )
        img = grade(rgb, depth, look) if fog else rgb
        text = caption_at(self.captions, f)
        if text:
            img = captions_mod.draw_caption(img, text)
        return img

    def _draw_states(self, c: Canvas, f: int) -> None:
        """Doors and lids posed, lamps and screens lit at frame f; the room relit when a lamp changed."""
        for oid, obj in self._stateful.items():
            v, rgb = posed(obj, self.scene, f)
            if self._wall.get(oid) in self._cut:
                v = v + AWAY  # a door in a wall cut away
            key = f"state:{oid}"
            fresh = key not in c.names()
            c.set_mesh(key, v, obj.mesh.faces if fresh else None, rgb)
        lit = lights_at(self._stateful, self.scene, f)
        st = self._static
        if lit != self._lit and len(st.faces):
            c.set_mesh(
                "static",
                st.vertices,
                None,
                relit(st.colours[:, :3] / 255.0, st.vertices, self._stateful, lit),
            )
            for wall, mesh in self._hung.items():
                colours = relit(mesh.colours[:, :3] / 255.0, mesh.vertices, self._stateful, lit)
                c.set_mesh(f"hung:{wall}", self._hung_vertices(wall), None, colours)
            self._lit = lit

    def _hung_vertices(self, wall: str) -> np.ndarray:
        mesh = self._hung[wall]
        return mesh.vertices + AWAY if wall in self._cut else mesh.vertices

    def _cut_walls(self, c: Canvas, cut: frozenset[str]) -> None:
        """Hide what hangs on the walls the camera stands behind (moved far below), show the rest."""
        if cut == self._cut:
            return
        changed = (cut ^ self._cut) & set(self._hung)
        self._cut = cut
        for wall in changed:
            c.set_mesh(f"hung:{wall}", self._hung_vertices(wall))

    def frames(
        self, start: int = 0, end: int | None = None, progress: Callable[[int], None] | None = None
    ) -> Iterator[np.ndarray]:
        """Frames [start, end) as (H, W, 3) uint8 arrays.

        Args:
            start: first frame (0-based).
            end: exclusive end; None or -1 = the end of the animation.
            progress: called with 1 after each frame.

        Raises:
            ValueError: a range outside [0, n_frames].
        """
        end = self.n_frames if end is None or end < 0 else int(end)
        if not (0 <= start <= end <= self.n_frames):
            raise ValueError(f"frame range [{start}, {end}) is outside the animation's [0, {self.n_frames})")
        block = 16  # skin a block of frames at once (vectorised), then draw them one by one
        for b0 in range(start, end, block):
            idx = np.arange(b0, min(b0 + block, end))
            posed = self._posed(idx)
            for i, f in enumerate(idx):
                img = self._draw(int(f), {name: v[i] for name, v in posed.items()})
                if progress is not None:
                    progress(1)
                yield img


MIN_CHUNK_FRAMES = 48  # 2 s: below this a process's start (its own GL context) costs more than it saves
_ADOPTED: list[FrameRenderer] = []  # in a render process: the renderer it was handed


def render_processes() -> int:
    """How many processes ``render_mp4`` uses by default: ``WANA_RENDER_PROCESSES``, else the CPUs other
    processes leave free (at most 4; on a busy shared machine a second render process only adds its start)."""
    env = os.environ.get("WANA_RENDER_PROCESSES", "")
    if env.strip():
        return max(1, int(env))
    cpus = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1
    free = cpus - os.getloadavg()[0] if hasattr(os, "getloadavg") else cpus
    return max(1, min(4, int(free + 0.5)))


def _adopt(staged: bytes) -> None:
    """In a render process: keep the parent's staged renderer (pickled once per process, not per chunk)."""
    _ADOPTED[:] = [pickle.loads(staged)]


def _render_chunk(span: tuple[int, int]) -> tuple[int, bytes]:
    """In a render process: frames [a, b) as one MP4 chunk (key frame first)."""
    from services.render.video import encode_mp4

    a, b = span
    buf = io.BytesIO()
    encode_mp4(_ADOPTED[0].frames(a, b), buf)
    return b - a, buf.getvalue()


def render_mp4(
    renderer: FrameRenderer,
    out: str | Path | io.BytesIO,
    *,
    processes: int = 0,
    progress: Callable[[int], None] | None = None,
) -> int:
    """The whole animation as an H.264 MP4, its frame ranges rendered by several processes at once.

    Every frame is a function of its index, and ``encode_mp4`` chunks start on a key frame with the same
    encoder settings, so chunks rendered apart and joined (``video.join_chunks``: packets copied, no
    re-encoding) play as one video. The processes come from a fork server (a process that never had a GL
    context: a GL/EGL context does not survive a fork, and this process may hold one) with the render
    modules imported once; each is handed the staged renderer, so nothing is planned twice, and opens its
    own context. A short video, or a platform without a fork server, is rendered here.

    Args:
        renderer: the staged renderer.
        out: file path or BytesIO.
        processes: how many render processes (0 = ``render_processes()``, 1 = render here).
        progress: called with the number of frames done, after each frame (here) or each chunk.

    Returns:
        The number of frames written.
    """
    from services.render.video import encode_mp4, join_chunks

    n = renderer.n_frames
    k = min(processes or render_processes(), n // MIN_CHUNK_FRAMES)
    if k <= 1 or "forkserver" not in multiprocessing.get_all_start_methods():
        return encode_mp4(renderer.frames(0, n, progress=progress), out)
    staged = pickle.dumps(renderer, protocol=pickle.HIGHEST_PROTOCOL)  # without its GL context
    spans = chunk_ranges(n, max(k, n // (MIN_CHUNK_FRAMES * 2)))  # a few chunks each: an even finish
    ctx = multiprocessing.get_context("forkserver")
    ctx.set_forkserver_preload(["services.render.renderer", "services.render.video", "open3d"])
    chunks = []
    with ctx.Pool(k, initializer=_adopt, initargs=(staged,)) as pool:
        for done, video in pool.imap(_render_chunk, spans):
            chunks.append(video)
            if progress is not None:
                progress(done)
    return join_chunks(chunks, out)
