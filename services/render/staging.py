"""What a frame shows, without pixels: rigs, camera and weather keys, occluders and the video's length.

The renderer draws from a ``Staging`` and the camera checks (services.render.camera_checks) read the
same one, so the camera a check judges is the camera the MP4 shows: there is one camera planner, and
``Staging.camera`` is the only way to it. Building one needs no GL context.

    stage = Staging.build(scene, motions, timed_commands)
    track = stage.camera_track()  # eye, target, up, fov of every frame of the video
    track = camera_track(scene, motions, commands, sentences, width=640, height=480)  # the same, from
    # what write_outputs takes
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from proto.motion_data import Motion
from proto.render import TimedCommand
from proto.scene import Scene
from services.render.camera import CameraKey, CameraPose, CharacterTrack, camera_at
from services.render.director import Shot, plan_shots, shot_keys
from services.render.framing import Occluders
from services.render.skinning import Rig
from services.render.timeline import (
    as_motion_list,
    camera_keys,
    place_commands,
    video_frames,
    weather_keys,
)
from services.render.weather import WeatherKey

MAX_FRAMES = 30 * 60 * 20  # 20 minutes at 30 fps


@dataclass(frozen=True)
class CameraTrack:
    """The camera of every frame of a video.

    Attributes:
        eye: (T, 3) world metres.
        target: (T, 3) world metres.
        up: (T, 3) up vectors.
        fov_deg: (T,) vertical field of view, degrees.
        width, height: the picture's size in pixels.
    """

    eye: np.ndarray
    target: np.ndarray
    up: np.ndarray
    fov_deg: np.ndarray
    width: int = 640
    height: int = 480

    def __len__(self) -> int:
        return len(self.eye)

    def pose(self, frame: int) -> CameraPose:
        return CameraPose(
            eye=self.eye[frame],
            target=self.target[frame],
            up=self.up[frame],
            fov_deg=float(self.fov_deg[frame]),
        )


@dataclass
class Staging:
    """The scene, the posed characters and the commands of one video, by frame index.

    Attributes:
        scene: the composed scene.
        rigs: character name -> rig (its motion on the character's skeleton).
        tracks: character name -> hips/facing/head track (what the camera follows).
        camera_keys: the shots' camera keys (services.render.director), or the commands' own without
            the director.
        weather_keys: weather/light commands on frames.
        occluders: the scene's collision boxes (the camera moves until it sees past them).
        n_frames: the video's length, frames.
        commands: the timed commands it was built from.
        motions: character name -> the motion its rig was built from (segments: which sentence when).
        shots: the director's plan with the commands in it (empty without the director).
    """

    scene: Scene
    rigs: dict[str, Rig]
    tracks: dict[str, CharacterTrack]
    camera_keys: list[CameraKey]
    weather_keys: list[WeatherKey]
    occluders: Occluders
    n_frames: int
    commands: list[TimedCommand]
    motions: dict[str, Motion]
    shots: list[Shot] = field(default_factory=list)
    _poses: dict[int, CameraPose] = field(default_factory=dict, repr=False)

    @classmethod
    def build(
        cls,
        scene: Scene,
        motions: list[Motion],
        commands: list[TimedCommand] | None = None,
        n_frames: int = 0,
        *,
        director: bool = True,
    ) -> Staging:
        """Stage a video.

        Args:
            scene: the composed scene.
            motions: one Motion per character.
            commands: camera/weather commands placed on frames (services.render.timeline.place_commands).
            n_frames: video length; 0 = the longest motion, held so that the last command shows
                (timeline.video_frames).
            director: plan shots per sentence (services.render.director); False: the commands alone,
                with the establishing overview before the first.

        Raises:
            ValueError: a video longer than MAX_FRAMES, an unknown command word, a malformed motion.
        """
        cmds = list(commands or [])
        rigs = {m.character: Rig.from_motion(m) for m in motions}
        n = int(n_frames) if n_frames > 0 else video_frames(motions, cmds)
        if n > MAX_FRAMES:
            raise ValueError(f"{n} frames is more than the {MAX_FRAMES} one render may have")
        tracks = {name: rig.track() for name, rig in rigs.items()}
        by_name = {m.character: m for m in motions}
        keys = camera_keys(cmds)  # raises on an unknown camera word, director or not
        shots: list[Shot] = []
        if director:
            from services.render.coverage import Coverage  # it measures with Staging's CameraTrack

            shots = plan_shots(by_name, tracks, cmds, n, scene.room, Coverage.from_rigs(rigs, scene))
        return cls(
            scene=scene,
            rigs=rigs,
            tracks=tracks,
            camera_keys=shot_keys(shots) if director else keys,
            weather_keys=weather_keys(cmds),
            occluders=Occluders.from_scene(scene),
            n_frames=n,
            commands=cmds,
            motions=by_name,
            shots=shots,
        )

    def camera(self, frame: int) -> CameraPose:
        """The camera of one frame: the commanded shot, moved until it sees its character (memoised: the
        checks and the frames of one video ask for the same poses)."""
        pose = self._poses.get(frame)
        if pose is None:
            pose = camera_at(frame, self.camera_keys, self.tracks, self.scene.room, self.occluders)
            self._poses[frame] = pose
        return pose

    def camera_track(self, width: int = 640, height: int = 480) -> CameraTrack:
        """Every frame's camera, (T, ...) arrays over the video's n_frames, for a picture of that size."""
        poses = [self.camera(f) for f in range(self.n_frames)]
        return CameraTrack(
            eye=np.array([p.eye for p in poses], dtype=np.float64).reshape(-1, 3),
            target=np.array([p.target for p in poses], dtype=np.float64).reshape(-1, 3),
            up=np.array([p.up for p in poses], dtype=np.float64).reshape(-1, 3),
            fov_deg=np.array([p.fov_deg for p in poses], dtype=np.float64),
            width=int(width),
            height=int(height),
        )


def camera_track(
    scene: Scene,
    motions: Iterable[Motion] | Mapping[str, Motion],
    commands: Iterable[Any] | None,
    sentences: Iterable[Any] | None,
    *,
    width: int = 640,
    height: int = 480,
) -> CameraTrack:
    """The per-frame camera of the video ``write_outputs`` renders from these inputs, without rendering.

    Args:
        scene, motions, commands, sentences: as ``services.render.export.write_outputs`` takes them.
        width, height: the video's size in pixels (the field of view is vertical, so the camera itself
            does not change with them; they travel with the track for projecting points).
    """
    mlist = as_motion_list(motions)
    sents = list(sentences or [])
    stage = Staging.build(scene, mlist, place_commands(commands, sents, mlist))
    return stage.camera_track(width=width, height=height)
