"""Cameras from commands: front, back, left, right, top, follow and close-up, with smooth transitions.

Every frame's camera is a pure function of the frame index, the camera keys and the characters'
whole tracks (no state carried from frame to frame), so that chunks rendered by different workers
join without a seam.

Conventions: world Y up, metres. ``CameraPose.extrinsic()`` is the OpenCV-style world -> camera
matrix (x right, y down, z forward) that open3d's pinhole parameters expect.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from proto.scene import Room

CAMERA_MODES = ("overview", "front", "back", "left", "right", "top", "follow", "close")
TRANSITION_FRAMES = 24  # a camera change eases in over 0.8 s at 30 fps
SMOOTH_RADIUS = 12  # frames either side averaged for the look-at point (removes gait bob)


@dataclass(frozen=True)
class CameraPose:
    """One camera: eye and target in world metres, up vector, vertical field of view in degrees."""

    eye: np.ndarray  # (3,)
    target: np.ndarray  # (3,)
    up: np.ndarray  # (3,)
    fov_deg: float = 55.0

    def rotation(self) -> np.ndarray:
        """(3, 3) world -> camera rotation; rows are camera x (right), y (down), z (forward) in world."""
        f = self.target - self.eye
        f = f / max(np.linalg.norm(f), 1e-9)
        up = self.up / max(np.linalg.norm(self.up), 1e-9)
        r = np.cross(f, up)
        if np.linalg.norm(r) < 1e-6:  # looking along up: pick any perpendicular
            r = np.cross(f, np.array([0.0, 0.0, -1.0]))
        r = r / np.linalg.norm(r)
        u = np.cross(r, f)
        return np.stack([r, -u, f])

    def extrinsic(self) -> np.ndarray:
        """(4, 4) world -> camera (OpenCV axes)."""
        m = np.eye(4)
        rot = self.rotation()
        m[:3, :3] = rot
        m[:3, 3] = -rot @ self.eye
        return m


def intrinsics(fov_deg: float, width: int, height: int) -> tuple[float, float, float, float]:
    """(fx, fy, cx, cy) in pixels for a vertical field of view; the centre is where open3d puts it."""
    fy = (height / 2.0) / np.tan(np.radians(fov_deg) / 2.0)
    return float(fy), float(fy), width / 2.0 - 0.5, height / 2.0 - 0.5


def project(points: np.ndarray, pose: CameraPose, width: int, height: int) -> tuple[np.ndarray, np.ndarray]:
    """Pixel coordinates of world points.

    Args:
        points: (N, 3) world positions.

    Returns:
        uv (N, 2) pixel column/row and depth (N,) metres along the view axis (negative: behind).
    """
    fx, fy, cx, cy = intrinsics(pose.fov_deg, width, height)
    cam = (np.asarray(points, float) - pose.eye) @ pose.rotation().T
    z = cam[:, 2]
    safe = np.where(np.abs(z) < 1e-9, 1e-9, z)
    uv = np.stack([fx * cam[:, 0] / safe + cx, fy * cam[:, 1] / safe + cy], axis=1)
    return uv, z


@dataclass(frozen=True)
class CameraKey:
    """From ``frame`` on, the camera is in ``mode`` relative to ``character`` ("" = none)."""

    frame: int
    mode: str
    character: str = ""


@dataclass(frozen=True)
class CharacterTrack:
    """Where a character is: positions (T, 3) of the Hips and facing (T, 3) unit vectors in XZ."""

    hips: np.ndarray
    facing: np.ndarray
    head: np.ndarray  # (T, 3) head joint position

    def at(self, frame: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        f = int(np.clip(frame, 0, len(self.hips) - 1))
        return self.hips[f], self.facing[f], self.head[f]

    def smoothed(self, frame: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Mean of hips, facing and head over a window around the frame (clamped at the ends)."""
        n = len(self.hips)
        lo, hi = max(0, frame - SMOOTH_RADIUS), min(n, frame + SMOOTH_RADIUS + 1)
        if lo >= hi:
            return self.at(frame)
        face = self.facing[lo:hi].mean(axis=0)
        norm = np.linalg.norm(face)
        face = face / norm if norm > 1e-6 else self.facing[min(frame, n - 1)]
        return self.hips[lo:hi].mean(axis=0), face, self.head[lo:hi].mean(axis=0)


def overview_pose(room: Room) -> CameraPose:
    """The establishing shot: from the +Z side, raised, seeing the whole room."""
    eye = np.array([room.width * 0.18, max(2.2, room.height * 0.85), room.depth / 2.0 + 2.2])
    target = np.array([0.0, 0.7, -room.depth * 0.08])
    return CameraPose(eye=eye, target=target, up=np.array([0.0, 1.0, 0.0]), fov_deg=60.0)


def _mode_pose(mode: str, track: CharacterTrack | None, frame: int, room: Room,
               held_facing: np.ndarray | None) -> CameraPose:
    up = np.array([0.0, 1.0, 0.0])
    if track is None or mode == "overview":
        return overview_pose(room)
    hips, facing, head = track.smoothed(frame)
    chest = hips + np.array([0.0, 0.35, 0.0])
    face = held_facing if held_facing is not None else facing
    left = np.array([face[2], 0.0, -face[0]])  # the character's left (+X at rest when facing +Z)
    if mode == "front":
        return CameraPose(eye=chest + face * 3.2 + np.array([0, 0.5, 0]), target=chest, up=up, fov_deg=50.0)
    if mode == "back":
        return CameraPose(eye=chest - face * 3.2 + np.array([0, 0.5, 0]), target=chest, up=up, fov_deg=50.0)
    if mode == "left":
        return CameraPose(eye=chest + left * 3.2 + np.array([0, 0.4, 0]), target=chest, up=up, fov_deg=50.0)
    if mode == "right":
        return CameraPose(eye=chest - left * 3.2 + np.array([0, 0.4, 0]), target=chest, up=up, fov_deg=50.0)
    if mode == "follow":
        return CameraPose(eye=chest - facing * 2.6 + np.array([0, 0.8, 0]), target=chest + facing * 0.8, up=up,
                          fov_deg=55.0)
    if mode == "close":
        return CameraPose(eye=head + facing * 0.9 + np.array([0, 0.02, 0]), target=head - np.array([0, 0.05, 0]),
                          up=up, fov_deg=40.0)
    if mode == "top":
        return CameraPose(eye=hips + np.array([0.0, 5.5, 0.01]), target=hips, up=np.array([0.0, 0.0, -1.0]),
                          fov_deg=55.0)
    raise ValueError(f"unknown camera mode {mode!r}; choose one of {', '.join(CAMERA_MODES)}")


def _smoothstep(x: float) -> float:
    x = min(max(x, 0.0), 1.0)
    return x * x * (3.0 - 2.0 * x)


def _blend(a: CameraPose, b: CameraPose, s: float) -> CameraPose:
    return CameraPose(eye=a.eye + (b.eye - a.eye) * s, target=a.target + (b.target - a.target) * s,
                      up=a.up + (b.up - a.up) * s if s < 1 else b.up, fov_deg=a.fov_deg + (b.fov_deg - a.fov_deg) * s)


def camera_at(frame: int, keys: list[CameraKey], tracks: dict[str, CharacterTrack], room: Room) -> CameraPose:
    """The camera of one frame.

    Args:
        frame: frame index (0-based, 30 fps).
        keys: camera keys sorted by frame; before the first key the camera shows the room overview.
        tracks: character name -> track.
        room: the room (for the overview).
    """
    active = [k for k in keys if k.frame <= frame]

    def pose_of(i: int, f: int) -> CameraPose:
        if i < 0:
            return overview_pose(room)
        k = active[i]
        track = tracks.get(k.character) if k.character else None
        if track is None and tracks and k.mode != "overview":
            track = tracks[sorted(tracks)[0]]
        held = None
        if track is not None and k.mode in ("front", "back", "left", "right"):
            held = track.smoothed(k.frame)[1]  # the side is fixed when the command starts
        return _mode_pose(k.mode, track, f, room, held)

    if not active:
        return overview_pose(room)
    cur = pose_of(len(active) - 1, frame)
    since = frame - active[-1].frame
    if since >= TRANSITION_FRAMES:
        return cur
    prev = pose_of(len(active) - 2, frame)
    return _blend(prev, cur, _smoothstep(since / TRANSITION_FRAMES))
