"""Layouts that move the obstacles a walk runs into off its way, for the verifier to re-plan.

The annealing's anchored surrogate keeps the walk where it is, so it cannot see that moving an
obstacle opens a new route (a chair closed in by boxes and plants: the walk goes straight through
one of them until a gap opens). These candidates do what a person would: each object the walk hits
(its support, for an object resting on another; never a target of the action) is pushed off the
walked path, sideways to either side or away from the target, by enough to leave the character's
clearance between the path and the object's footprint. The motion service then re-plans the route
by A* in each candidate (``verify.optimise_and_verify``), and only a verified walk is kept.
Candidates whose moved objects would overlap other objects' footprints come last.
"""

from __future__ import annotations

import numpy as np

from proto.motion_data import Motion
from proto.optimizer import Interaction
from proto.scene import Scene
from services.optimizer.annealing import LayoutModel
from services.optimizer.body import motion_joint_positions
from services.optimizer.costs import LayoutBatch, SceneGeometry, world_boxes
from services.optimizer.scoring import is_locomotion

ROUTE_CLEARANCE_M = 0.3  # the motion service's route radius (resynthesis.motion_service_fn)
MARGIN_M = 0.15  # extra room beyond it (swinging arms, the walk's deviation from its path)
SCALES = (1.0, 1.6)  # push distances tried, in units of the needed push


def walked_path(motion: Motion) -> np.ndarray:
    """(W, 2) root x, z of the frames in walking segments (all frames without segments)."""
    root = motion_joint_positions(motion)[:, 0, :][:, [0, 2]]
    segs = [s for s in motion.segments if is_locomotion(s.action)]
    if not motion.segments:
        return root
    idx = np.concatenate(
        [np.arange(max(0, s.start_frame), min(len(root), s.end_frame)) for s in segs]
        or [np.zeros(0, np.int64)]
    )
    return root[idx.astype(np.int64)]


def _footprint_radius(geom: SceneGeometry, layout: LayoutBatch, o: int) -> tuple[np.ndarray, np.ndarray]:
    """World x, z AABB (lo (2,), hi (2,)) of object o's boxes."""
    centre, half, yaw = world_boxes(geom, layout)
    mine = geom.box_owner == o
    if not mine.any():
        xz = layout.position[0, o, [0, 2]]
        return xz.copy(), xz.copy()
    c, s = np.abs(np.cos(yaw[0, mine])), np.abs(np.sin(yaw[0, mine]))
    h = half[0, mine]
    ext = np.stack([c * h[:, 0] + s * h[:, 2], s * h[:, 0] + c * h[:, 2]], axis=1)
    ctr = centre[0, mine][:, [0, 2]]
    return (ctr - ext).min(axis=0), (ctr + ext).max(axis=0)


def clearing_layouts(
    scene: Scene,
    interaction: Interaction,
    motion: Motion,
    walk_hit_boxes: np.ndarray,
    geom: SceneGeometry,
) -> list[Scene]:
    """Candidate layouts with the obstacles of the walk pushed off it.

    Args:
        scene: the input layout.
        interaction: its targets never move.
        motion: the motion in ``scene``.
        walk_hit_boxes: (B,) bool, boxes the body hits while walking.
        geom: the scene's geometry.

    Returns:
        Layouts, most promising first (no overlap with other objects first, then the smaller push);
        empty when the walk hits nothing movable.
    """
    by_id = {o.id: i for i, o in enumerate(scene.objects)}
    movers: list[int] = []
    for o in np.unique(geom.box_owner[np.asarray(walk_hit_boxes, dtype=bool)]):
        obj = scene.objects[int(o)]
        root = obj
        while root.support and root.support in by_id and root.support != root.id:
            root = scene.objects[by_id[root.support]]
        if root.id in interaction.targets or obj.id in interaction.targets:
            continue
        if by_id[root.id] not in movers:
            movers.append(by_id[root.id])
    path = walked_path(motion)
    if not movers or len(path) == 0:
        return []
    base = LayoutBatch.from_scenes([scene])
    targets = [by_id[t] for t in interaction.targets if t in by_id]
    target_xz = base.position[0, targets[0], [0, 2]] if targets else path[-1]
    half_room = np.array([scene.room.width, scene.room.depth]) / 2
    # Per mover: its footprint, the nearest path point, and the push directions to try.
    options: list[list[np.ndarray]] = []
    for o in movers:
        lo, hi = _footprint_radius(geom, base, o)
        centre = (lo + hi) / 2
        radius = float(np.linalg.norm(hi - lo) / 2)
        d = path - centre
        near = int(np.argmin(np.einsum("ij,ij->i", d, d)))
        tangent = path[min(near + 1, len(path) - 1)] - path[max(near - 1, 0)]
        tangent = tangent / max(float(np.linalg.norm(tangent)), 1e-9)
        side = np.array([-tangent[1], tangent[0]])
        if float(np.dot(centre - path[near], side)) < 0:
            side = -side  # the side the object already leans to first
        away = centre - target_xz
        away = away / max(float(np.linalg.norm(away)), 1e-9)
        need = radius + ROUTE_CLEARANCE_M + MARGIN_M
        pushes = []
        for direction in (side, -side, away):
            # Distance from the path to the centre along the push direction, then what is missing.
            along = float(np.min(np.abs((path - centre) @ direction)))
            move = max(need - along, 0.05) if direction is not away else need
            pushes.append(direction * move)
        options.append(pushes)
    model = LayoutModel(scene, [scene.objects[o].id for o in movers])
    cands: list[tuple[tuple[int, float], np.ndarray]] = []
    for choice in range(3):
        for scale in SCALES:
            state = model.identity()
            for m, pushes in enumerate(options):
                state[m, :2] = pushes[choice] * scale
            # Keep each mover inside the room.
            for m, o in enumerate(movers):
                lo, hi = _footprint_radius(geom, base, o)
                new_lo, new_hi = lo + state[m, :2], hi + state[m, :2]
                state[m, :2] += np.maximum(-half_room - new_lo, 0) - np.maximum(new_hi - half_room, 0)
            layout = model.layouts(state[None])
            overlaps = _overlaps(geom, layout, movers, scene)
            cands.append(((overlaps, float(np.abs(state[:, :2]).sum())), state))
    cands.sort(key=lambda c: c[0])
    return [model.scene_at(model.layouts(s[None]), 0) for _, s in cands]


def _overlaps(geom: SceneGeometry, layout: LayoutBatch, movers: list[int], scene: Scene) -> int:
    """How many (mover, other floor object) pairs have overlapping floor AABBs in ``layout``."""
    boxes = [_footprint_radius(geom, layout, o) for o in range(len(geom.ids))]
    floor = [not o.support for o in scene.objects]  # objects on others ride on them
    count = 0
    for o in movers:
        lo, hi = boxes[o]
        for p, (plo, phi) in enumerate(boxes):
            if p != o and floor[p] and np.all(lo < phi) and np.all(hi > plo):
                count += 1
    return count
