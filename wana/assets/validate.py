"""Scene validation: interpenetration, room bounds, support and relation checks.

A scene is valid when no two objects' collision boxes overlap (an object and the thing it rests on
are checked by the support test instead: it must sit at a surface height with its footprint inside
that surface), every object lies inside the room, wall things touch a wall, and every SSG relation
holds geometrically (``relations.relation_holds``).
"""

from __future__ import annotations

import numpy as np

from proto.scene import PlacedObject, Scene
from proto.ssg import RelationNode
from wana.assets.catalog import asset_for, to_world, world_bounds, world_collision_boxes
from wana.assets.relations import relation_holds, to_anchor_frame

OVERLAP_TOL_M = 0.004  # boxes may touch; they must not overlap deeper than this on every axis
WALL_TOL_M = 0.03


def boxes_overlap(a: np.ndarray, b: np.ndarray, tol: float = OVERLAP_TOL_M) -> bool:
    """Whether any box of a (N, 2, 3) overlaps any box of b (M, 2, 3) by more than tol on all axes."""
    lo = np.maximum(a[:, None, 0], b[None, :, 0])
    hi = np.minimum(a[:, None, 1], b[None, :, 1])
    return bool(np.any(np.all(hi - lo > tol, axis=-1)))


def aabbs_overlap(a: np.ndarray, b: np.ndarray, tol: float = OVERLAP_TOL_M) -> bool:
    """Whether two (2, 3) boxes overlap by more than tol on every axis."""
    return bool(np.all(np.minimum(a[1], b[1]) - np.maximum(a[0], b[0]) > tol))


def rests_on(subject: PlacedObject, support: PlacedObject, tol: float = 0.01) -> bool:
    """Subject's base lies on one of the support's surfaces with its whole footprint inside it."""
    obj = asset_for(subject)
    hw, hd = obj.dims[0] / 2.0 * subject.scale[0], obj.dims[2] / 2.0 * subject.scale[2]
    corners = np.array([[-hw, 0.0, -hd], [hw, 0.0, -hd], [hw, 0.0, hd], [-hw, 0.0, hd]])
    base = to_world(
        PlacedObject(id="", category=subject.category, position=subject.position, yaw=subject.yaw), corners
    )
    local = to_anchor_frame(support, base)
    for surf in asset_for(support).support_surfaces:
        if (
            np.all(np.abs(local[:, 1] - surf.height) <= tol)
            and np.all(local[:, [0, 2]] >= surf.min_xz - tol)
            and np.all(local[:, [0, 2]] <= surf.max_xz + tol)
        ):
            return True
    return False


def scene_problems(scene: Scene, relations: list[RelationNode] | tuple[RelationNode, ...] = ()) -> list[str]:
    """Everything wrong with a scene, as readable sentences (empty list = valid)."""
    problems: list[str] = []
    room = scene.room
    by_id = {o.id: o for o in scene.objects}
    if len(by_id) != len(scene.objects):
        problems.append("duplicate object ids")
    lo_room = np.array([-room.width / 2, 0.0, -room.depth / 2])
    hi_room = np.array([room.width / 2, room.height, room.depth / 2])
    bounds = {o.id: world_bounds(o) for o in scene.objects}
    boxes = {o.id: world_collision_boxes(o) for o in scene.objects}
    for o in scene.objects:
        b = bounds[o.id]
        if np.any(b[0] < lo_room - 1e-6) or np.any(b[1] > hi_room + 1e-6):
            problems.append(f"{o.id} sticks out of the room")
        mount = asset_for(o).mount
        if o.support:
            sup = by_id.get(o.support)
            if sup is None:
                problems.append(f"{o.id} rests on missing {o.support}")
            elif not rests_on(o, sup):
                problems.append(f"{o.id} does not rest on {o.support}")
        elif mount == "wall":
            gaps = np.concatenate([b[0] - lo_room, hi_room - b[1]])[[0, 2, 3, 5]]
            if gaps.min() > WALL_TOL_M:
                problems.append(f"{o.id} is not on a wall")
        elif abs(b[0, 1]) > 1e-6:
            problems.append(f"{o.id} floats above the floor")
    objs = scene.objects
    for i, first in enumerate(objs):
        for second in objs[i + 1 :]:
            if first.support == second.id or second.support == first.id:
                continue
            if aabbs_overlap(bounds[first.id], bounds[second.id]) and boxes_overlap(
                boxes[first.id], boxes[second.id]
            ):
                problems.append(f"{first.id} interpenetrates {second.id}")
    for rel in relations:
        subject, anchor = by_id.get(rel.subject), by_id.get(rel.object)
        if subject is None or anchor is None:
            problems.append(f"relation {rel.subject} {rel.relation} {rel.object} names a missing object")
        elif not relation_holds(rel, subject, anchor):
            problems.append(f"relation {rel.subject} {rel.relation} {rel.object} does not hold")
    return problems
