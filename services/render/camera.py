"""Cameras from commands: front, back, left, right, top, follow and close-up, with smooth transitions.

Every frame's camera is a pure function of the frame index, the camera keys and the characters'
whole tracks (no state carried from frame to frame), so that chunks rendered by different workers
join without a seam.

When the scene's occluders are given (services.render.framing), a commanded pose that cannot see
its character (a tall cabinet in between) moves along the arc, rises or comes closer until it can;
the choice is made every DECISION_STEP frames from the frames around it (keeping the previous
choice while it stays clear, else moving to the nearest clear one) and eased in between, so the
camera glides instead of jumping. The establishing overview picks, among views from around the
room, the first that sees the characters while it is on screen.

The director's shots (services.render.director: wide, medium, tracking, close-up, two-shot,
over-the-shoulder; poses in services.render.shots) play through the same ``camera_at``: a shot it framed
by measuring carries its ``adjust`` and is played as it is, and it cuts in instead of easing. (Both kinds
of key in one player take the module just past 400 lines.)

Conventions: world Y up, metres. ``CameraPose.extrinsic()`` is the OpenCV-style world -> camera
matrix (x right, y down, z forward) that open3d's pinhole parameters expect.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from proto.scene import Room
from services.render.framing import (
    ADJUSTMENTS,
    Adjust,
    Occluders,
    adjust_eye,
    blend_adjust,
    person_box,
    sight_points,
)
from services.render.shots import (
    SHOT_MODES,
    TWO_PERSON_MODES,
    over_shoulder_pose,
    single_pose,
    two_shot_pose,
)

CAMERA_MODES = ("overview", "front", "back", "left", "right", "top", "follow", "close", *SHOT_MODES)
TRANSITION_FRAMES = 24  # a camera change eases in over 0.8 s at 30 fps
SMOOTH_RADIUS = 12  # frames either side averaged for the look-at point (removes gait bob)
DECISION_STEP = 20  # frames between occlusion decisions (eased in between)
DECISION_LOOK = (-10, 0, 10)  # frames around a decision whose views must be clear
UNBLOCKED_MODES = ("front", "back", "left", "right", "follow", "close", *SHOT_MODES[1:])
LINE_TURN = np.radians(75.0)  # a two-person shot turns at most this far, so it never crosses the line
OVERVIEW_SAMPLES = 8  # character frames checked for the overview
ROOM_WEIGHT = 0.4  # how much a hidden part of the room counts against an overview, against a hidden character
OVERVIEW_ADJUSTMENTS = tuple(
    Adjust(turn=np.radians(a) * sgn, rise=r)
    for r in (0.0, 0.8)
    for a in (0, 25, 45, 70, 90)
    for sgn in ((1,) if a == 0 else (1, -1))
) + tuple(Adjust(turn=np.radians(a) * sgn, rise=1.2, scale=0.6) for a in (0, 45, 90) for sgn in (1, -1))


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
    """From ``frame`` on, the camera is in ``mode`` relative to ``character`` ("" = none).

    The director's shots (services.render.director) add: ``partner``, the second character of a two-shot
    or over-the-shoulder; ``side`` (+1/-1), the three-quarter side or the side of the pair's line;
    ``end``, where a wide shot stops (it sees the characters of [frame, end)); ``cut``, a hard cut into
    the shot instead of an eased transition; ``adjust``, the framing the director chose by measuring what
    it shows (services.render.coverage), played as it is (None: the camera moves off boxes in its way).
    """

    frame: int
    mode: str
    character: str = ""
    partner: str = ""
    side: int = 1
    end: int = -1
    cut: bool = False
    adjust: Adjust | None = None


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


def pair_track(a: CharacterTrack, b: CharacterTrack) -> CharacterTrack:
    """The middle of two characters as one track (hips and head averaged), facing as the first."""
    n = max(len(a.hips), len(b.hips))
    ia, ib = np.minimum(np.arange(n), len(a.hips) - 1), np.minimum(np.arange(n), len(b.hips) - 1)
    return CharacterTrack(
        hips=(a.hips[ia] + b.hips[ib]) / 2.0, facing=a.facing[ia], head=(a.head[ia] + b.head[ib]) / 2.0
    )


def overview_pose(room: Room) -> CameraPose:
    """The establishing shot: from the +Z side, raised, seeing the whole room."""
    eye = np.array([room.width * 0.18, max(2.2, room.height * 0.85), room.depth / 2.0 + 2.2])
    target = np.array([0.0, 0.7, -room.depth * 0.08])
    return CameraPose(eye=eye, target=target, up=np.array([0.0, 1.0, 0.0]), fov_deg=60.0)


def _mode_pose(
    mode: str, track: CharacterTrack | None, frame: int, room: Room, held_facing: np.ndarray | None
) -> CameraPose:
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
        return CameraPose(
            eye=chest - facing * 2.6 + np.array([0, 0.8, 0]), target=chest + facing * 0.8, up=up, fov_deg=55.0
        )
    if mode == "close":
        # What the writer asked for: closer than the director's own close-up (head to knees), head and chest
        # large, the trunk and hands still in the picture so that what the character does reads (in_view).
        eye, target, fov = single_pose("close", hips, face, 1)
        return CameraPose(eye=eye, target=target, up=up, fov_deg=fov)
    if mode == "top":
        return CameraPose(
            eye=hips + np.array([0.0, 5.5, 0.01]), target=hips, up=np.array([0.0, 0.0, -1.0]), fov_deg=55.0
        )
    raise ValueError(f"unknown camera mode {mode!r}; choose one of {', '.join(CAMERA_MODES)}")


def _smoothstep(x: float) -> float:
    x = min(max(x, 0.0), 1.0)
    return x * x * (3.0 - 2.0 * x)


def _blend(a: CameraPose, b: CameraPose, s: float) -> CameraPose:
    return CameraPose(
        eye=a.eye + (b.eye - a.eye) * s,
        target=a.target + (b.target - a.target) * s,
        up=a.up + (b.up - a.up) * s if s < 1 else b.up,
        fov_deg=a.fov_deg + (b.fov_deg - a.fov_deg) * s,
    )


def _with_adjust(pose: CameraPose, adj: Adjust) -> CameraPose:
    if adj == Adjust():
        return pose
    return CameraPose(
        eye=adjust_eye(pose.eye, pose.target, adj), target=pose.target, up=pose.up, fov_deg=pose.fov_deg
    )


def room_points(room: Room) -> np.ndarray:
    """(9, 3) a grid over the room's floor at table height: what an establishing shot should show."""
    xs, zs = (room.width / 3.0) * np.array([-1.0, 0.0, 1.0]), (room.depth / 3.0) * np.array([-1.0, 0.0, 1.0])
    return np.array([[x, 0.6, z] for x in xs for z in zs])


def clear_overview(
    room: Room,
    tracks: dict[str, CharacterTrack],
    occluders: Occluders | None,
    until: int,
    since: int = 0,
) -> CameraPose:
    """The overview turned about the room (and raised) until it sees the characters of frames [since, until).

    Among the views that see the characters, the one that sees most of the room (room_points) wins;
    ties go to the least turned.
    """
    base = overview_pose(room)
    if occluders is None or not tracks:
        return base
    memo_key = ("overview", until) if since == 0 else ("overview", since, until)
    adj = occluders.memo.get(memo_key)
    if adj is None:
        n = max(since + 1, until)
        frames = sorted({int(round(x)) for x in np.linspace(since, n - 1, OVERVIEW_SAMPLES)})
        points = [sight_points(t.at(f)[0], t.at(f)[2]) for t in tracks.values() for f in frames]
        characters = occluders.shares([(base.eye, base.target, np.concatenate(points))], OVERVIEW_ADJUSTMENTS)
        floor = occluders.shares([(base.eye, base.target, room_points(room))], OVERVIEW_ADJUSTMENTS)
        rank = np.arange(len(OVERVIEW_ADJUSTMENTS)) / (100.0 * len(OVERVIEW_ADJUSTMENTS))
        adj = OVERVIEW_ADJUSTMENTS[int(np.argmin(characters + ROOM_WEIGHT * floor + rank))]
        occluders.memo[memo_key] = adj
    return _with_adjust(base, adj)


def shot_pose(k: CameraKey, tracks: dict[str, CharacterTrack], frame: int) -> CameraPose | None:
    """The pose of a director's shot (services.render.shots) at a frame; None for a wide shot or an
    unknown subject (the overview stands in)."""
    track = tracks.get(k.character)
    if track is None or k.mode == "wide":
        return None
    hips = track.smoothed(frame)[0]
    if k.mode in TWO_PERSON_MODES:
        other = tracks.get(k.partner)
        if other is None:
            return None
        partner = other.smoothed(frame)[0]
        if k.mode == "two_shot":
            first, second = (hips, partner) if k.character < k.partner else (partner, hips)
            eye, target, fov = two_shot_pose(first, second, k.side)
        else:
            eye, target, fov = over_shoulder_pose(hips, partner, k.side, k.character < k.partner)
    else:
        eye, target, fov = single_pose(k.mode, hips, track.smoothed(k.frame)[1], k.side)
    pose = CameraPose(eye=eye, target=target, up=np.array([0.0, 1.0, 0.0]), fov_deg=fov)
    return _with_adjust(pose, k.adjust) if k.adjust is not None else pose


def wide_pose(k: CameraKey, room: Room) -> CameraPose:
    """A wide shot the director framed (k.adjust set): the overview moved by that adjustment."""
    return _with_adjust(overview_pose(room), k.adjust or Adjust())


def view_pose(
    k: CameraKey, track: CharacterTrack, tracks: dict[str, CharacterTrack], room: Room, f: int
) -> CameraPose:
    """A commanded view (front, back, left, right, top, follow, close) of its character, or of the
    middle of a pair when the key has a partner; moved by ``k.adjust`` when the director measured one."""
    held = None
    if k.mode in ("front", "back", "left", "right"):
        held = track.smoothed(k.frame)[1]  # the side is fixed when the command starts
    if k.partner in tracks and k.partner != k.character:  # a view of a pair: of their middle, further back
        pair = pair_track(track, tracks[k.partner])
        gap = float(np.linalg.norm((track.at(f)[0] - tracks[k.partner].at(f)[0])[[0, 2]]))
        pose = _mode_pose(k.mode, pair, f, room, held)
        if k.mode != "top":
            pose = _with_adjust(pose, Adjust(scale=1.0 + 0.35 * gap))
    else:
        pose = _mode_pose(k.mode, track, f, room, held)
    return _with_adjust(pose, k.adjust) if k.adjust is not None else pose


def camera_at(
    frame: int,
    keys: list[CameraKey],
    tracks: dict[str, CharacterTrack],
    room: Room,
    occluders: Occluders | None = None,
) -> CameraPose:
    """The camera of one frame.

    Args:
        frame: frame index (0-based, 30 fps).
        keys: camera keys sorted by frame; before the first key the camera shows the room overview.
        tracks: character name -> track.
        room: the room (for the overview).
        occluders: the scene's boxes; when given, the camera moves until it sees its character.
    """
    active = [k for k in keys if k.frame <= frame]
    first_key = keys[0].frame if keys else max((len(t.hips) for t in tracks.values()), default=1)

    def overview(k: CameraKey | None = None) -> CameraPose:
        if k is not None and k.mode == "wide" and k.adjust is not None:
            return wide_pose(k, room)
        if k is not None and k.mode == "wide":
            return clear_overview(room, tracks, occluders, max(k.end, k.frame + 1), k.frame)
        return clear_overview(room, tracks, occluders, first_key)

    def commanded(k: CameraKey, track: CharacterTrack | None, f: int) -> CameraPose:
        if k.mode in SHOT_MODES:
            return shot_pose(k, tracks, f) or overview(k)
        if track is None or k.mode == "overview":
            return overview()
        return view_pose(k, track, tracks, room, f)

    def decide(k: CameraKey, track: CharacterTrack, d: int, previous: Adjust | None) -> Adjust:
        assert occluders is not None
        views = []
        framed = [track]
        if k.mode == "two_shot" and k.partner in tracks:
            framed.append(tracks[k.partner])  # both must be seen
        others = [t for t in tracks.values() if all(t is not s for s in framed)]
        for g in sorted({max(k.frame, d + off) for off in DECISION_LOOK}):
            p = commanded(k, track, g)
            pts = []
            for t in framed:
                hips, _, head = t.smoothed(g)
                pts.append(sight_points(hips, head))
            people = np.array([person_box(t.at(g)[0], t.at(g)[2]) for t in others]).reshape(-1, 2, 3)
            views.append((p.eye, p.target, np.concatenate(pts), people))
        choices = ADJUSTMENTS
        if k.mode in TWO_PERSON_MODES:  # the 180° rule: never turn across the line between the two
            choices = tuple(a for a in ADJUSTMENTS if abs(a.turn) <= LINE_TURN)
        return occluders.choose(views, choices, previous)

    def decision(k: CameraKey, track: CharacterTrack, d: int) -> Adjust:
        """The choice at decision frame d; each depends on the one before (computed forward, memoised)."""
        assert occluders is not None
        key = (k.frame, k.mode, k.character, k.partner)
        start = d
        while start > k.frame and (*key, start - DECISION_STEP) not in occluders.memo:
            start -= DECISION_STEP
        for g in range(start, d + 1, DECISION_STEP):
            if (*key, g) not in occluders.memo:
                previous = occluders.memo.get((*key, g - DECISION_STEP)) if g > k.frame else None
                occluders.memo[(*key, g)] = decide(k, track, g, previous)
        return occluders.memo[(*key, d)]

    def pose_of(i: int, f: int) -> CameraPose:
        if i < 0:
            return overview()
        k = active[i]
        track = tracks.get(k.character) if k.character else None
        if track is None and tracks and k.mode != "overview":
            track = tracks[sorted(tracks)[0]]
        pose = commanded(k, track, f)
        if occluders is None or track is None or k.mode not in UNBLOCKED_MODES or k.adjust is not None:
            return pose
        if k.mode in SHOT_MODES and shot_pose(k, tracks, f) is None:
            return pose  # the overview stood in
        d0 = k.frame + (f - k.frame) // DECISION_STEP * DECISION_STEP
        s = _smoothstep((f - d0) / DECISION_STEP)
        adj = blend_adjust(decision(k, track, d0), decision(k, track, d0 + DECISION_STEP), s)
        return _with_adjust(pose, adj)

    if not active:
        return overview()
    cur = pose_of(len(active) - 1, frame)
    since = frame - active[-1].frame
    if since >= TRANSITION_FRAMES or active[-1].cut:
        return cur
    prev = pose_of(len(active) - 2, frame)
    return _blend(prev, cur, _smoothstep(since / TRANSITION_FRAMES))
