"""How well a candidate camera shows the acting characters: the ``in_view`` test, run before the shot.

The director (services.render.director) frames each shot from a few candidates (sides, turns, heights,
distances) and keeps the one that shows its acting characters best over the shot, measured exactly as
the ``in_view`` story check measures the video (services.render.visibility.judged_view: body points in
the picture and unhidden by furniture triangles, walls seen from inside and other characters' bodies; a
seated character by its head, trunk and arms, its own seat hiding nothing). Scoring every point of a
seated body instead made every candidate fail on the legs under the table, so the table hid the hands
and chest from whichever camera came first.

    cover = Coverage.from_rigs(rigs, scene, width=640, height=480)
    share = cover.shown(poses, frames, ["Tom", "Mary"])  # share of (frame, character) shown >= 70 %
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from proto.scene import Room, Scene
from services.render.camera import CameraPose
from services.render.sightlines import Furniture
from services.render.skinning import Rig
from services.render.staging import CameraTrack
from services.render.visibility import VISIBLE_SHARE, capsule_radii, judged_view, own_supports


@dataclass(frozen=True)
class Coverage:
    """The characters' joints and the scene's occluders, for scoring cameras.

    Attributes:
        joints: character -> (T, J, 3) world joint positions.
        furniture: the scene's objects.
        room: the room.
        radii: character -> (B,) capsule radii of its body.
        width, height: the picture's size in pixels.
    """

    joints: dict[str, np.ndarray]
    furniture: Furniture
    room: Room
    radii: dict[str, np.ndarray]
    width: int = 640
    height: int = 480

    @classmethod
    def from_rigs(
        cls, rigs: Mapping[str, Rig], scene: Scene, width: int = 640, height: int = 480
    ) -> Coverage:
        return cls(
            joints={n: r.joint_positions for n, r in rigs.items()},
            furniture=Furniture.from_scene(scene),
            room=scene.room,
            radii={
                n: capsule_radii(r.character.rest_joint_positions(), r.character.vertices)
                for n, r in rigs.items()
            },
            width=width,
            height=height,
        )

    def shown(self, poses: Sequence[CameraPose], frames: Sequence[int], who: Sequence[str]) -> float:
        """Share of (frame, character) pairs in which the camera of that frame shows the character.

        Args:
            poses: one camera per frame.
            frames: (F,) story frames (past a motion's end its final pose holds).
            who: the characters that must be seen.
        """
        names = [w for w in who if w in self.joints]
        if not names or not len(frames):
            return 1.0
        return float(self.shown_each(poses, frames, names).mean())

    def shown_each(
        self, poses: Sequence[CameraPose], frames: Sequence[int], who: Sequence[str]
    ) -> np.ndarray:
        """(F, C) True where the camera of frame i shows character ``who[j]`` (C = len(who); a name
        without a skeleton counts as shown)."""
        out = np.ones((len(frames), len(who)), dtype=bool)
        names = [w for w in who if w in self.joints]
        if not names or not len(frames):
            return out
        idx = np.asarray(frames, dtype=np.int64)
        local = {n: j[np.clip(idx, 0, len(j) - 1)] for n, j in self.joints.items()}
        track = CameraTrack(
            eye=np.array([p.eye for p in poses], dtype=np.float64),
            target=np.array([p.target for p in poses], dtype=np.float64),
            up=np.array([p.up for p in poses], dtype=np.float64),
            fov_deg=np.array([p.fov_deg for p in poses], dtype=np.float64),
            width=self.width,
            height=self.height,
        )
        steps = np.arange(len(idx))
        for j, n in enumerate(who):
            if n in self.joints:
                _, part = judged_view(
                    n,
                    steps,
                    local,
                    track,
                    self.furniture,
                    self.room,
                    self.width,
                    self.height,
                    self.radii,
                    supports=own_supports(self.joints[n], idx, self.furniture),  # the same for every camera
                )
                out[:, j] = part >= VISIBLE_SHARE
        return out
