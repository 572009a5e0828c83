"""Elbow room: where a standing character plays an action so that its arms stay out of the furniture beside it.

The planner picks where an action is done from the object it is done at (a stand point, a spot within reach of
the contacts) or leaves the character where it is (a sweep with the broom it just took, a thank-you gesture);
neither looks at what stands next to that spot. A filing cabinet at the elbow then takes the sweeping hand, the
hanging left hand of a dishwasher goes into the cabinet beside the sink. Here the clip's own arm path (forward
kinematics of the clip as synthesis layers it on the standing pose) is laid at a candidate spot and facing and
tested against the scene's collision boxes; the nearest spot where no arm point is inside one is where the
action plays. Arms that reach a contact point (IK'd onto the object) are tested in their rest pose only: the
clip's own path for them is replaced by the reach.
"""

from __future__ import annotations

import functools
from collections.abc import Iterable

import numpy as np

from proto.scene import Scene
from services.motion.blend import layer, upper_body_mask
from wana.domain import quat
from wana.domain.actions import get_clip, neutral_rotations
from wana.domain.routes import Footprints, point_rect_distance
from wana.domain.skeleton import JOINT_INDEX, REST_OFFSETS, forward_kinematics

ARM_JOINTS = ("Arm", "ForeArm", "Hand", "HandMiddle1")  # per side, from the shoulder to the knuckles
FINGER_TIP_M = 0.08  # metres the fingertips reach past the last hand joint
ARM_RADIUS_M = 0.05  # metres kept between an arm point and a box (the bone capsules' radius and a little)
SAMPLE_FPS = 10  # frames per second the clip's arm path is tested at
DEDUPE_M = 0.02  # metres: arm points closer than this count once
CHUNK = 48  # arm points tested at a time: a spot is given up at its first chunk with a hit
LOW_BOX_M = 0.1  # metres: boxes lower than this (a rug) are not in the arms' way
RINGS_M = tuple(np.round(np.arange(0.05, 0.65, 0.05), 3))  # metres: distances of the candidate spots tried
DIRECTIONS = 16  # candidate directions per ring


def _side(joint: str) -> str:
    return "Left" if joint.startswith("Left") else "Right" if joint.startswith("Right") else ""


@functools.lru_cache(maxsize=256)
def arm_path(action: str, reaching: frozenset[str] = frozenset()) -> np.ndarray:
    """(P, 3) metres, character frame (hips over the origin at standing height, facing +z): every point the
    arms pass through while the clip plays standing; the sides in ``reaching`` ("Left", "Right") in their
    first and last frames only (the reach itself goes to a contact point on the object)."""
    clip = get_clip(action)
    rot, offs, _ = clip.sample(SAMPLE_FPS)
    if not clip.drives_lower_body:  # layered on the standing pose, as synthesis plays it
        base = np.repeat(neutral_rotations()[None], len(rot), 0)
        rot = layer(base, rot, upper_body_mask())
        offs = np.zeros_like(offs)
    root = offs + np.array([0.0, REST_OFFSETS[0, 1], 0.0])
    pos, _ = forward_kinematics(rot, root)
    points = []
    for side in ("Left", "Right"):
        chain = pos[:, [JOINT_INDEX[side + j] for j in ARM_JOINTS]]  # (T, 4, 3)
        tip = chain[:, -1] + FINGER_TIP_M * _unit(chain[:, -1] - chain[:, -2])
        mids = (chain[:, 1:] + chain[:, :-1]) / 2
        pts = np.concatenate([chain, mids, tip[:, None]], axis=1)
        if side in reaching:
            pts = pts[[0, -1]]
        points.append(pts.reshape(-1, 3))
    out = np.concatenate(points)
    _, first = np.unique(np.round(out / DEDUPE_M), axis=0, return_index=True)  # held keys repeat points
    return out[np.sort(first)]


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.maximum(np.linalg.norm(v, axis=-1, keepdims=True), 1e-9)


def reaching_sides(joints: Iterable[str]) -> frozenset[str]:
    """The sides ("Left", "Right") whose hand a set of contact joints puts on the object."""
    return frozenset(s for j in joints if "Hand" in j and (s := _side(j)))


def placed_path(path: np.ndarray, xz: np.ndarray, yaw: float) -> np.ndarray:
    """(P, 3) world points of a character-frame arm path for a character at xz facing yaw."""
    world = quat.rotate(quat.yaw(np.array(yaw)), path)
    return world + np.array([xz[0], 0.0, xz[1]])


def _near(points: np.ndarray, fp: Footprints) -> np.ndarray:
    """(P, N) whether each point lies within ARM_RADIUS_M of each box (its floor rectangle and its height)."""
    flat = point_rect_distance(points[:, [0, 2]], fp) < ARM_RADIUS_M
    y = points[:, 1:2]
    return flat & (y > fp.y_min[None] - ARM_RADIUS_M) & (y < fp.y_max[None] + ARM_RADIUS_M)


def arm_hits(points: np.ndarray, fp: Footprints, per_object: tuple | None = None) -> int:
    """How many world arm points lie within ARM_RADIUS_M of a box. The points are first tested against one
    box round each object's boxes (a filing cabinet is hundreds of drawer boxes), then only those inside one
    against that object's own boxes; ``per_object``: those boxes (by_object(fp)) when already made."""
    if not len(fp) or not len(points):
        return 0
    owner, coarse = per_object if per_object is not None else by_object(fp)
    near = _near(points, coarse)  # (P, O)
    hit = np.zeros(len(points), dtype=bool)
    for k in np.flatnonzero(near.any(axis=0)):
        rows = np.flatnonzero(near[:, k] & ~hit)
        if len(rows):
            hit[rows] = _near(points[rows], fp.select(owner == k)).any(axis=1)
    return int(hit.sum())


def by_object(fp: Footprints) -> tuple[np.ndarray, Footprints]:
    """(N,) the index of each box's object and one world-axis box round each object's boxes."""
    owners = sorted(set(fp.owner))
    owner = np.array([owners.index(o) for o in fp.owner])
    ext = _extent(fp)
    lo = np.stack([np.min(fp.centre[owner == k] - ext[owner == k], axis=0) for k in range(len(owners))])
    hi = np.stack([np.max(fp.centre[owner == k] + ext[owner == k], axis=0) for k in range(len(owners))])
    y_lo = np.array([fp.y_min[owner == k].min() for k in range(len(owners))])
    y_hi = np.array([fp.y_max[owner == k].max() for k in range(len(owners))])
    return owner, Footprints((lo + hi) / 2, (hi - lo) / 2, np.zeros(len(owners)), y_lo, y_hi, tuple(owners))


def _extent(fp: Footprints) -> np.ndarray:
    """(N, 2) half extents along world x and z of each (rotated) floor rectangle."""
    c, s = np.abs(np.cos(fp.yaw)), np.abs(np.sin(fp.yaw))
    return np.stack([c * fp.half[:, 0] + s * fp.half[:, 1], s * fp.half[:, 0] + c * fp.half[:, 1]], axis=1)


def obstacles(scene: Scene, ignore: Iterable[str]) -> Footprints:
    """The collision boxes the arms must keep out of: every object's but the ignored ones and low ones."""
    from wana.domain.object_geometry import object_shape, scene_footprints

    skip = set(ignore)
    for o in scene.objects:  # a category the catalog lacks has no known boxes
        try:
            object_shape(o)
        except (KeyError, ValueError):
            skip.add(o.id)
    fp = scene_footprints(scene, ignore=skip)
    return fp.select(fp.y_max > LOW_BOX_M)


def roomy_spot(
    scene: Scene,
    action: str,
    xz: np.ndarray,
    yaw: float,
    *,
    ignore: Iterable[str] = (),
    reaching: frozenset[str] = frozenset(),
    body_radius: float,
    face_to: np.ndarray | None = None,
    within: float = np.inf,
) -> tuple[np.ndarray, float] | None:
    """Where (x, z) and facing (radians) a standing character plays ``action`` with its arms out of the
    furniture, nearest ``xz``; None when the arms are clear there already or no spot nearby clears them.

    Args:
        scene: the scene (its collision boxes; the room's walls for where a body fits).
        action: the clip's name.
        xz: where the planner would have the character stand, world metres.
        yaw: the facing there (kept, unless ``face_to``).
        ignore: objects the action is done at or holds (its hands go there): not obstacles.
        reaching: the sides whose hand reaches a contact point (reaching_sides).
        body_radius: metres a candidate spot keeps from furniture and walls (a walking body, or one reaching
            over the object it works at).
        face_to: a point each candidate spot faces (the action's contact points), else ``yaw`` is kept.
        within: metres a candidate may stand from ``face_to`` at most (the contacts stay in reach).
    """
    from services.motion.routing import CELL, scene_grid

    path = arm_path(action, reaching)
    here = np.asarray(xz, dtype=np.float64)
    fp = obstacles(scene, ignore)
    reach = float(np.linalg.norm(path[:, [0, 2]], axis=1).max()) + RINGS_M[-1] + ARM_RADIUS_M
    if len(fp):  # only the boxes an arm can get to from any spot tried
        fp = fp.select(point_rect_distance(here[None], fp)[0] < reach)

    def facing(p: np.ndarray) -> float:
        if face_to is None:
            return yaw
        d = face_to - p
        return float(np.arctan2(d[0], d[1])) if np.linalg.norm(d) > 1e-6 else yaw

    if not len(fp):
        return None
    split = by_object(fp)
    if arm_hits(placed_path(path, here, facing(here)), fp, split) == 0:
        return None
    grid = scene_grid(scene, frozenset(ignore), body_radius, CELL)
    angles = np.linspace(0.0, 2 * np.pi, DIRECTIONS, endpoint=False)
    for r in RINGS_M:
        best: tuple[float, np.ndarray, float] | None = None
        for a in angles:
            p = here + r * np.array([np.sin(a), np.cos(a)])
            if face_to is not None and np.linalg.norm(face_to - p) > within:
                continue
            if not grid.is_free_xz(p):
                continue
            f = facing(p)
            pts = placed_path(path, p, f)
            if not any(arm_hits(pts[i : i + CHUNK], fp, split) for i in range(0, len(pts), CHUNK)):
                turn = abs(float(np.arctan2(np.sin(f - yaw), np.cos(f - yaw))))
                if best is None or turn < best[0]:
                    best = (turn, p, f)
        if best is not None:
            return best[1], best[2]
    return None
