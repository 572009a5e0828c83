"""How much of a character the video's camera shows: sample points on the body, in the picture and unhidden.

A frame shows a character's body point when the point projects inside the image, lies in front of the
lens, and the sight line from the eye to it passes through no furniture (collision boxes, then the drawn
triangles: services.render.sightlines), no wall seen from inside the room (walls are one-sided: from
outside the camera sees through them, as the renderer draws them) and no other character's body
(capsules around their bones). Each line stops STOP_SHORT before its joint, so the seat under the hips
or the keyboard under the fingers does not hide them; a joint sunk into furniture (inside its collision
boxes) is not hidden by the surface around it either, since no camera could show it (the penetration
check reports it), only by a part of that object farther in front (a backrest before seated legs). This is what the ``in_view`` check
(services.render.camera_checks) counts; it needs no pixels, only the camera track and the skeletons.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from proto.scene import Room
from services.render.camera import project
from services.render.sightlines import Furniture
from services.render.staging import CameraTrack
from services.render.walls import walls_behind
from wana.domain.skeleton import JOINT_INDEX

# What a camera must see of a character: head and trunk, shoulders, arms and hands, hips, knees, feet and
# toes; 20 points, so that the share shown moves in steps of 5 % (13 points made 9 of 13 = 69 % fail a 70 %
# bar on one hidden toe).
BODY_POINTS = (
    "Head",
    "Neck",
    "Spine2",
    "Spine1",
    "Spine",
    "Hips",
    "LeftArm",
    "RightArm",
    "LeftForeArm",
    "RightForeArm",
    "LeftHand",
    "RightHand",
    "LeftUpLeg",
    "RightUpLeg",
    "LeftLeg",
    "RightLeg",
    "LeftFoot",
    "RightFoot",
    "LeftToeBase",
    "RightToeBase",
)
# Another character's body as capsules (from joint, to joint, radius in metres); "HeadTop" is above the head.
BODY_CAPSULES = (
    ("Hips", "Spine2", 0.14),
    ("Spine2", "Neck", 0.13),
    ("Neck", "Head", 0.06),
    ("Head", "HeadTop", 0.1),
    ("LeftArm", "LeftForeArm", 0.05),
    ("LeftForeArm", "LeftHand", 0.045),
    ("RightArm", "RightForeArm", 0.05),
    ("RightForeArm", "RightHand", 0.045),
    ("LeftUpLeg", "LeftLeg", 0.08),
    ("LeftLeg", "LeftFoot", 0.06),
    ("RightUpLeg", "RightLeg", 0.08),
    ("RightLeg", "RightFoot", 0.06),
)
HEAD_TOP = 0.16  # metres from the Head joint, along the neck -> head direction
STOP_SHORT = 0.1  # metres a sight line stops before its body point (the seat under the hips, the keyboard
# under the fingers, the partner's hand in a handshake do not hide the joint they touch)
TOUCH = 0.05  # metres beyond a capsule's radius: another body this close to a body point cannot hide it
# (a hand on a shoulder, arms round a partner in a hug: the body's surface lies outside the joint)
NEAR_CLIP = 0.05  # metres: the renderer's near plane
VISIBLE_SHARE = 0.7  # of the body's sample points, for a frame to show the character (the in_view check)
SEATED_HIPS_M = 0.75  # hips lower than this are sitting or lying (standing hips are at about 0.9 m)
SEAT_BELOW_M = 0.5  # the seat's top within this below the hips (a sofa's seat, a bed's mattress)
LEG_JOINTS = ("Hips", "UpLeg", "Leg", "Foot", "ToeBase")


@dataclass(frozen=True)
class BodyView:
    """Which body points of one character the camera shows, frame by frame.

    Attributes:
        frames: (F,) story frames.
        in_frame: (F, P) True where the point projects inside the image in front of the lens.
        hidden_by: (F, P) index into ``occluders`` of what hides the point, -1 where nothing does.
        occluders: names of what can hide ("the bookshelf", "the wall", "Tom").
    """

    frames: np.ndarray
    in_frame: np.ndarray
    hidden_by: np.ndarray
    occluders: list[str]

    @property
    def visible(self) -> np.ndarray:
        """(F, P) in the picture and not hidden."""
        return self.in_frame & (self.hidden_by < 0)


def body_points(joints: np.ndarray) -> np.ndarray:
    """(T, J, 3) world joint positions -> (T, P, 3) the BODY_POINTS."""
    return joints[:, [JOINT_INDEX[n] for n in BODY_POINTS]]


def body_capsules(
    joints: np.ndarray, radii: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(T, J, 3) joint positions -> capsule starts (T, B, 3), ends (T, B, 3) and radii (B,).

    Args:
        joints: (T, J, 3) world joint positions.
        radii: (B,) the character's own capsule radii (capsule_radii); default BODY_CAPSULES'.
    """
    head, neck = joints[:, JOINT_INDEX["Head"]], joints[:, JOINT_INDEX["Neck"]]
    up = head - neck
    up /= np.maximum(np.linalg.norm(up, axis=-1, keepdims=True), 1e-9)

    def joint(name: str) -> np.ndarray:
        return head + up * HEAD_TOP if name == "HeadTop" else joints[:, JOINT_INDEX[name]]

    starts = np.stack([joint(a) for a, _, _ in BODY_CAPSULES], axis=1)
    ends = np.stack([joint(b) for _, b, _ in BODY_CAPSULES], axis=1)
    default = np.array([r for _, _, r in BODY_CAPSULES])
    return starts, ends, default if radii is None else radii


def capsule_radii(rest_joints: np.ndarray, vertices: np.ndarray) -> np.ndarray:
    """(B,) how thick a character is around each capsule of BODY_CAPSULES, from its rest mesh.

    Each vertex belongs to the capsule whose axis is nearest; a capsule's radius is the 75th percentile
    of its vertices' distances (a bulky character hides more than a slim one). Capsules with no vertex
    keep the default radius.

    Args:
        rest_joints: (J, 3) rest-pose joint positions.
        vertices: (V, 3) rest-pose mesh vertices.
    """
    c0, c1, default = body_capsules(rest_joints[None])
    v = np.asarray(vertices, dtype=np.float64)[:, None, :]  # (V, 1, 3)
    dist = segment_distances(v, v, c0, c1)  # (V, B)
    owner = dist.argmin(axis=1)
    out = default.copy()
    for b in range(len(out)):
        mine = dist[owner == b, b]
        if len(mine) >= 8:
            out[b] = float(np.percentile(mine, 75))
    return out


def segment_distances(p0: np.ndarray, p1: np.ndarray, q0: np.ndarray, q1: np.ndarray) -> np.ndarray:
    """Closest distance between segments p0-p1 and q0-q1 (arrays (..., 3), broadcast) -> (...)."""
    eps = 1e-12
    d1, d2, r = p1 - p0, q1 - q0, p0 - q0
    a = (d1 * d1).sum(-1)
    e = (d2 * d2).sum(-1)
    f = (d2 * r).sum(-1)
    c = (d1 * r).sum(-1)
    b = (d1 * d2).sum(-1)
    a_safe, e_safe = np.maximum(a, eps), np.maximum(e, eps)
    denom = a * e - b * b
    s = np.where(denom > eps, np.clip((b * f - c * e) / np.maximum(denom, eps), 0.0, 1.0), 0.0)
    t = (b * s + f) / e_safe
    s = np.where(
        t < 0.0, np.clip(-c / a_safe, 0.0, 1.0), np.where(t > 1.0, np.clip((b - c) / a_safe, 0.0, 1.0), s)
    )
    t = np.clip(t, 0.0, 1.0)
    s = np.where(a <= eps, 0.0, s)
    t = np.where(a <= eps, np.clip(f / e_safe, 0.0, 1.0), t)
    t = np.where(e <= eps, 0.0, t)
    s = np.where(e <= eps, np.where(a <= eps, 0.0, np.clip(-c / a_safe, 0.0, 1.0)), s)
    return np.linalg.norm(p0 + d1 * s[..., None] - (q0 + d2 * t[..., None]), axis=-1)


def wall_hits(starts: np.ndarray, ends: np.ndarray, room: Room) -> np.ndarray:
    """(S,) True where a sight line (S, 3) -> (S, 3) leaves the room through a wall (seen from inside).

    A line that enters the room through a wall sees through it (one-sided walls, culled from behind).
    """
    half = {0: room.width / 2.0, 2: room.depth / 2.0}
    hit = np.zeros(len(starts), dtype=bool)
    for axis, other in ((0, 2), (2, 0)):
        for sign in (1.0, -1.0):
            plane = sign * half[axis]
            a, b = sign * starts[:, axis], sign * ends[:, axis]
            crosses = (a < half[axis]) & (b > half[axis])  # inner side -> outer side
            t = (plane - starts[:, axis]) / np.where(crosses, ends[:, axis] - starts[:, axis], 1.0)
            p = starts + (ends - starts) * t[:, None]
            inside = (np.abs(p[:, other]) <= half[other]) & (p[:, 1] >= 0.0) & (p[:, 1] <= room.height)
            hit |= crosses & inside
    return hit


def _stop_short(starts: np.ndarray, ends: np.ndarray) -> np.ndarray:
    d = ends - starts
    length = np.linalg.norm(d, axis=-1, keepdims=True)
    return starts + d * np.clip(1.0 - STOP_SHORT / np.maximum(length, 1e-9), 0.0, 1.0)


def _cut_away(hidden: np.ndarray, furniture: Furniture, eyes: np.ndarray, room: Room, per_frame: int) -> None:
    """Nothing hides a character from behind the camera's wall: what hangs on a wall the eye stands behind
    is cut away with it (services.render.walls), as the renderer leaves it out."""
    hung = [(k, w) for k, w in enumerate(furniture.walls) if w]
    if not hung:
        return
    behind = [walls_behind(eye, room) for eye in eyes]
    grid = hidden.reshape(len(eyes), per_frame)  # a view of ``hidden``, frame by frame
    for k, wall in hung:
        rows = np.array([wall in b for b in behind])
        grid[rows] = np.where(grid[rows] == k, -1, grid[rows])


def body_view(
    name: str,
    frames: np.ndarray,
    joints: dict[str, np.ndarray],
    track: CameraTrack,
    furniture: Furniture,
    room: Room,
    width: int,
    height: int,
    radii: dict[str, np.ndarray] | None = None,
) -> BodyView:
    """What the camera shows of one character over the given frames.

    Args:
        name: the character.
        frames: (F,) story frames (each < len(track)); past a motion's end its final pose holds.
        joints: character -> (T, J, 3) world joint positions (the rigs' forward kinematics).
        track: the video's camera, frame by frame.
        furniture: the scene's objects (boxes, then triangles), with names.
        room: the room (its walls hide what is outside it).
        width, height: the video's size, pixels.
        radii: character -> (B,) its capsule radii (capsule_radii); default BODY_CAPSULES' radii.
    """
    frames = np.asarray(frames, dtype=np.int64)

    def posed(who: str) -> np.ndarray:
        j = joints[who]
        return j[np.clip(frames, 0, len(j) - 1)]

    pts = body_points(posed(name))  # (F, P, 3)
    n_f, n_p = pts.shape[:2]
    in_frame = np.zeros((n_f, n_p), dtype=bool)
    for i, f in enumerate(frames):
        uv, z = project(pts[i], track.pose(int(f)), width, height)
        in_frame[i] = (
            (z > NEAR_CLIP) & (uv[:, 0] >= 0) & (uv[:, 0] < width) & (uv[:, 1] >= 0) & (uv[:, 1] < height)
        )

    eyes = np.broadcast_to(track.eye[frames][:, None, :], pts.shape)
    starts, ends = eyes.reshape(-1, 3), _stop_short(eyes, pts).reshape(-1, 3)
    targets = pts.reshape(-1, 3)
    # A joint inside furniture (feet through a sofa's front, fingers in a keyboard) is the penetration
    # check's finding; no camera could show it, so the surface it is buried under does not count against
    # the camera (a backrest in front of it still does).
    hidden = furniture.first_blocker(starts, ends, targets)
    _cut_away(hidden, furniture, track.eye[frames], room, n_p)
    names = [f"the {n}" for n in furniture.names]
    names.append("the wall")
    hidden[(hidden < 0) & wall_hits(starts, targets, room)] = len(names) - 1
    for other in sorted(joints):
        if other == name:
            continue
        names.append(other)
        c0, c1, radius = body_capsules(posed(other), (radii or {}).get(other))  # (F, B, 3)
        ray0, ray1 = eyes[:, :, None, :], _stop_short(eyes, pts)[:, :, None, :]  # (F, P, 1, 3)
        dist = segment_distances(ray0, ray1, c0[:, None], c1[:, None])  # (F, P, B)
        touching = (
            segment_distances(pts[:, :, None, :], pts[:, :, None, :], c0[:, None], c1[:, None])
            < radius + TOUCH
        )
        by_body = ((dist < radius) & ~touching).any(axis=-1).reshape(-1)
        hidden[(hidden < 0) & by_body] = len(names) - 1
    return BodyView(frames=frames, in_frame=in_frame, hidden_by=hidden.reshape(n_f, n_p), occluders=names)


def seat_under(hips: np.ndarray, furniture: Furniture) -> np.ndarray:
    """(F,) index of the furniture a character sits or lies on at each frame (hips (F, 3)), -1 when none:
    the object with a box under the low hips whose top is at most SEAT_BELOW_M below them."""
    out = np.full(len(hips), -1, dtype=np.int64)
    best = np.full(len(hips), np.inf)
    low = hips[:, 1] < SEATED_HIPS_M
    if not low.any():
        return out
    for k, boxes in enumerate(furniture.boxes):
        under = (
            (boxes[None, :, 0, 0] <= hips[:, None, 0])
            & (hips[:, None, 0] <= boxes[None, :, 1, 0])
            & (boxes[None, :, 0, 2] <= hips[:, None, 2])
            & (hips[:, None, 2] <= boxes[None, :, 1, 2])
            & (boxes[None, :, 1, 1] <= hips[:, None, 1] + 0.05)
        )  # (F, N): boxes right under the hips, not above them
        top = np.where(under, boxes[None, :, 1, 1], -np.inf).max(axis=1)
        gap = hips[:, 1] - top
        mine = low & np.isfinite(top) & (gap <= SEAT_BELOW_M) & (gap < best)
        out[mine], best[mine] = k, gap[mine]
    return out


LEGS = np.array([n.removeprefix("Left").removeprefix("Right") in LEG_JOINTS for n in BODY_POINTS])


def shown_share(view: BodyView) -> np.ndarray:
    """(F,) the share of the head, trunk and arms shown on each frame: legs under a table, behind a chair
    or a sofa, or below a medium shot's edge leave a person seen, seated (what sitting hides) or standing."""
    return np.asarray(view.visible[:, ~LEGS].mean(axis=1))


HANDS = ("LeftHand", "RightHand")
HAND_ON_M = 0.08  # metres: a hand this close to an object's box is on it (typing, holding, leaning)


def held_under(hands: np.ndarray, furniture: Furniture) -> np.ndarray:
    """(F,) index of the furniture a hand is on at each frame (hands (F, H, 3)), -1 when none: the nearest
    object with a box within HAND_ON_M of a hand (what the hand works on does not hide its worker)."""
    out = np.full(len(hands), -1, dtype=np.int64)
    best = np.full(len(hands), HAND_ON_M)
    for k, boxes in enumerate(furniture.boxes):
        lo, hi = boxes[None, None, :, 0], boxes[None, None, :, 1]  # (1, 1, N, 3)
        p = hands[:, :, None]  # (F, H, 1, 3)
        gap = np.linalg.norm(np.maximum(np.maximum(lo - p, p - hi), 0.0), axis=3).min(axis=(1, 2))
        mine = gap < best
        out[mine], best[mine] = k, gap[mine]
    return out


def unhide_own_seat(view: BodyView, seat: np.ndarray) -> BodyView:
    """The view with the points hidden by the character's own seat counted as shown: a sofa's back hides
    a seated person's legs from behind as sitting does, and the sofa is where the sentence puts them."""
    own = (seat[:, None] >= 0) & (view.hidden_by == seat[:, None])
    if not own.any():
        return view
    return BodyView(view.frames, view.in_frame, np.where(own, -1, view.hidden_by), view.occluders)


def judged_view(
    name: str,
    frames: np.ndarray,
    joints: dict[str, np.ndarray],
    track: CameraTrack,
    furniture: Furniture,
    room: Room,
    width: int,
    height: int,
    radii: dict[str, np.ndarray] | None = None,
    supports: tuple[np.ndarray, np.ndarray] | None = None,
) -> tuple[BodyView, np.ndarray]:
    """What the ``in_view`` check counts of one character: its view (its own seat and what its hands are on
    hiding nothing) and (F,) the share of its head, trunk and arms shown per frame. The director scores its
    candidate cameras with this same function, so a framing it picks passes the check it was picked for.

    ``supports``: the character's (seat, held) at the frames when the caller has them (``own_supports``
    of its whole skeleton: the director asks about the same frames for every candidate camera).
    """
    view = body_view(name, frames, joints, track, furniture, room, width, height, radii)
    seat, held = supports if supports is not None else own_supports(joints[name], frames, furniture)
    view = unhide_own_seat(unhide_own_seat(view, seat), held)
    return view, shown_share(view)


_SUPPORTS: dict[tuple[int, int, bytes], tuple[np.ndarray, Furniture, np.ndarray, np.ndarray]] = {}
SUPPORTS_KEPT = 64  # (joints, frames) pairs remembered: the director's candidate cameras share a few


def own_supports(
    joints: np.ndarray, frames: np.ndarray, furniture: Furniture
) -> tuple[np.ndarray, np.ndarray]:
    """(F,) the seat under the hips and (F,) the furniture under the hands of one character (joints (T, J, 3))
    at the frames: ``seat_under`` and ``held_under``, memoised.

    They depend on the skeleton and the frames, not on the camera, and the director measures every
    candidate camera of a shot over the same frames: remembered by the very arrays asked about (identity,
    so a new skeleton or scene is never answered from an old one), the last SUPPORTS_KEPT of them.
    """
    frames = np.asarray(frames, dtype=np.int64)
    key = (id(joints), id(furniture), frames.tobytes())
    hit = _SUPPORTS.get(key)
    if hit is not None and hit[0] is joints and hit[1] is furniture:
        return hit[2], hit[3]
    pose = joints[np.clip(frames, 0, len(joints) - 1)]  # (F, J, 3)
    seat = seat_under(pose[:, JOINT_INDEX["Hips"]], furniture)
    held = held_under(pose[:, [JOINT_INDEX[h] for h in HANDS]], furniture)
    if len(_SUPPORTS) >= SUPPORTS_KEPT:
        _SUPPORTS.pop(next(iter(_SUPPORTS)))
    _SUPPORTS[key] = (joints, furniture, seat, held)
    return seat, held
