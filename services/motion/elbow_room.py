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
from dataclasses import dataclass

import numpy as np

from proto.scene import PlacedObject, Scene
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


@dataclass(frozen=True)
class Obstacles:
    """The collision boxes the arms keep out of, per object: one box round each object's boxes (``outer``, a
    filing cabinet is hundreds of drawer boxes) and the object's own boxes (``inner``, in the same order)."""

    outer: Footprints
    inner: tuple[Footprints, ...]

    def near(self, xz: np.ndarray, metres: float) -> Obstacles:
        """The objects whose outer box is within ``metres`` of a floor point."""
        keep = point_rect_distance(np.asarray(xz, dtype=np.float64)[None], self.outer)[0] < metres
        return Obstacles(
            self.outer.select(keep), tuple(f for f, k in zip(self.inner, keep, strict=True) if k)
        )


def arm_hits(points: np.ndarray, boxes: Obstacles) -> int:
    """How many world arm points lie within ARM_RADIUS_M of a box: tested against the objects' outer boxes
    first, then only the points inside one against that object's own boxes."""
    if not len(boxes.outer) or not len(points):
        return 0
    near = _near(points, boxes.outer)  # (P, O)
    hit = np.zeros(len(points), dtype=bool)
    for k in np.flatnonzero(near.any(axis=0)):
        rows = np.flatnonzero(near[:, k] & ~hit)
        if len(rows):
            hit[rows] = _near(points[rows], boxes.inner[k]).any(axis=1)
    return int(hit.sum())


def _object_boxes(placed: PlacedObject) -> tuple[Footprints, Footprints] | None:
    """(outer box, own boxes higher than LOW_BOX_M) of one placed object; None when it has none (a rug, a
    category the catalog lacks)."""
    key = (placed.id, placed.category, tuple(sorted(placed.attributes.items())), placed.seed, placed.position,
           placed.yaw, placed.scale)  # fmt: skip
    if key not in _BOXES:
        if len(_BOXES) > 1024:
            _BOXES.clear()
        _BOXES[key] = _boxes_of(placed)
    return _BOXES[key]


_BOXES: dict[tuple, tuple[Footprints, Footprints] | None] = {}


def _boxes_of(placed: PlacedObject) -> tuple[Footprints, Footprints] | None:
    from wana.domain.object_geometry import object_shape, world_obbs

    try:
        object_shape(placed)
    except (KeyError, ValueError):
        return None
    centre, half = world_obbs(placed)
    keep = centre[:, 1] + half[:, 1] > LOW_BOX_M
    if not keep.any():
        return None
    centre, half = centre[keep], half[keep]
    fp = Footprints(centre[:, [0, 2]], half[:, [0, 2]], np.full(len(centre), placed.yaw),
                    centre[:, 1] - half[:, 1], centre[:, 1] + half[:, 1], (placed.id,) * len(centre))  # fmt: skip
    c, s = np.abs(np.cos(fp.yaw)), np.abs(np.sin(fp.yaw))
    ext = np.stack([c * fp.half[:, 0] + s * fp.half[:, 1], s * fp.half[:, 0] + c * fp.half[:, 1]], axis=1)
    lo, hi = (fp.centre - ext).min(axis=0), (fp.centre + ext).max(axis=0)
    outer = Footprints(
        ((lo + hi) / 2)[None], ((hi - lo) / 2)[None], np.zeros(1), fp.y_min.min()[None], fp.y_max.max()[None],
        (placed.id,),
    )  # fmt: skip
    return outer, fp


def obstacles(scene: Scene, ignore: Iterable[str]) -> Obstacles:
    """The collision boxes the arms must keep out of: every object's but the ignored ones and low ones."""
    skip = set(ignore)
    got = [b for o in scene.objects if o.id not in skip and (b := _object_boxes(o)) is not None]
    if not got:
        return Obstacles(Footprints.from_aabbs(np.zeros((0, 2, 3))), ())
    outer = [g[0] for g in got]
    return Obstacles(
        Footprints(
            np.concatenate([f.centre for f in outer]), np.concatenate([f.half for f in outer]),
            np.concatenate([f.yaw for f in outer]), np.concatenate([f.y_min for f in outer]),
            np.concatenate([f.y_max for f in outer]), tuple(f.owner[0] for f in outer),
        ),
        tuple(g[1] for g in got),
    )  # fmt: skip


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
    reach = float(np.linalg.norm(path[:, [0, 2]], axis=1).max()) + RINGS_M[-1] + ARM_RADIUS_M
    boxes = obstacles(scene, ignore).near(here, reach)  # only what an arm can get to from any spot tried

    def facing(p: np.ndarray) -> float:
        if face_to is None:
            return yaw
        d = face_to - p
        return float(np.arctan2(d[0], d[1])) if np.linalg.norm(d) > 1e-6 else yaw

    if arm_hits(placed_path(path, here, facing(here)), boxes) == 0:
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
            if not any(arm_hits(pts[i : i + CHUNK], boxes) for i in range(0, len(pts), CHUNK)):
                turn = abs(float(np.arctan2(np.sin(f - yaw), np.cos(f - yaw))))
                if best is None or turn < best[0]:
                    best = (turn, p, f)
        if best is not None:
            return best[1], best[2]
    return None
