"""Walking routes for planning: the domain library's A* (wana.domain.routes) on cached occupancy grids.

``scene_route`` answers exactly what ``wana.domain.routes.plan_route`` answers (the same grid,
the same A*, the same last step into the goal object's clearance), but rasterises each floor object
only once: the grid of a scene is the OR of per-object masks, cached by the object's placement
(category, variant, position, yaw, scale) and the room. An edit that moves one chair re-rasterises
that chair only, and ignoring the target object (so that a goal inside its clearance is reachable)
costs an OR over the other masks, not a new grid. Where no route exists the character walks the
straight line and the caller gets a diagnostic.
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Sequence

import msgspec
import numpy as np

from proto.scene import PlacedObject, Room, Scene
from wana.domain.object_geometry import scene_footprints
from wana.domain.routes import (
    HOST_M,
    Footprints,
    NoRouteError,
    OccupancyGrid,
    occupancy_grid,
    plan_route_on_grid,
    point_rect_distance,
    segment_is_free,
)

RADIUS = 0.25  # metres: the walking body's clearance (plan_route's default)
CELL = 0.05  # metres per grid cell (plan_route's default)
STEP_IN = 1.0  # metres: longest last step into the goal object's clearance
_CACHE_SIZE = 512
_masks: OrderedDict[tuple, tuple[np.ndarray, object]] = OrderedDict()
_lock = threading.Lock()


def _plain(obj: object) -> object:
    """numpy scalars and arrays in in-process structs -> plain Python values for the cache key."""
    if isinstance(obj, np.generic | np.ndarray):
        return obj.tolist()
    raise NotImplementedError(f"cannot key {type(obj).__name__}")


_encode = msgspec.msgpack.Encoder(order="deterministic", enc_hook=_plain).encode


def _cached(key: tuple, build):  # noqa: ANN001, ANN202 - tiny LRU shared by the grid pieces
    with _lock:
        hit = _masks.get(key)
        if hit is not None:
            _masks.move_to_end(key)
            return hit
    value = build()
    with _lock:
        _masks[key] = value
        while len(_masks) > _CACHE_SIZE:
            _masks.popitem(last=False)
    return value


def _room_key(room: Room) -> tuple:
    return (room.width, room.depth)


def _walls(room: Room, radius: float, cell: float) -> tuple[np.ndarray, np.ndarray]:
    def build():  # noqa: ANN202
        grid = occupancy_grid(room, Footprints.from_aabbs(np.zeros((0, 2, 3))), radius=radius, cell=cell)
        return grid.blocked, grid.origin

    return _cached(("walls", _room_key(room), radius, cell), build)


def wall_mask(room: Room, radius: float = RADIUS, cell: float = CELL) -> np.ndarray:
    """(H, W) bool: cells within ``radius`` of a wall (the grid of the empty room)."""
    return _walls(room, radius, cell)[0]


def object_mask(room: Room, obj: PlacedObject, radius: float = RADIUS, cell: float = CELL):  # noqa: ANN201
    """(blocked (H, W) bool of the object's footprints grown by ``radius``, its Footprints), cached by placement."""

    def build():  # noqa: ANN202
        try:
            fp = scene_footprints(Scene(room=room, objects=[obj]))
        except (KeyError, ValueError):  # a category the catalog lacks: nothing known to walk around
            fp = Footprints.from_aabbs(np.zeros((0, 2, 3)))
        grid = occupancy_grid(room, fp, radius=radius, cell=cell)
        return grid.blocked & ~wall_mask(room, radius, cell), fp

    key = ("object", _room_key(room), _encode(msgspec.structs.replace(obj, id="", support="")), radius, cell)
    return _cached(key, build)


def scene_grid(
    scene: Scene, ignore: frozenset[str] = frozenset(), radius: float = RADIUS, cell: float = CELL
):  # noqa: ANN201
    """The OccupancyGrid (wana.domain.routes) of the scene minus the ignored objects (built from cached masks)."""
    walls, origin = _walls(scene.room, radius, cell)
    blocked = walls.copy()
    for obj in scene.objects:
        if obj.id not in ignore:
            blocked |= object_mask(scene.room, obj, radius, cell)[0]
    return OccupancyGrid(blocked=blocked, origin=origin, cell=cell)


BODY_M = 0.32  # metres: a standing character as an obstacle: its body and the swing of a passing arm
# metres: a character this near the start is not walked round (the one stood beside when setting off), one
# this near the goal is walked round closer (the one walked up to, the one beside the goal): a disc that
# leaves the goal free
BODY_NEAR_END_M = 0.7
END_FREE_M = 0.1  # metres between such a shrunk disc and the goal
BODY_MIN_M = 0.3  # metres: the smallest disc kept round a body (hips this near touch); nearer ends drop it


def with_bodies(
    grid: OccupancyGrid, bodies: Sequence[Sequence[float]], radius: float = RADIUS
) -> OccupancyGrid:
    """The grid with the cells within ``radius`` + BODY_M of each standing character blocked too; a body given
    as (x, z, r) blocks the cells within r metres of it instead."""
    if not len(bodies):
        return grid
    h, w = grid.blocked.shape
    rows, cols = np.mgrid[0:h, 0:w]
    xz = grid.to_world(np.stack([rows, cols], axis=-1))
    blocked = grid.blocked.copy()
    for body in bodies:
        bx, bz = body[0], body[1]
        reach = body[2] if len(body) > 2 else radius + BODY_M
        blocked |= np.hypot(xz[..., 0] - bx, xz[..., 1] - bz) < reach
    return OccupancyGrid(blocked=blocked, origin=grid.origin, cell=grid.cell)


def round_bodies(
    bodies: Sequence[tuple[float, float]],
    start_xz: Sequence[float],
    goal_xz: Sequence[float],
    radius: float = RADIUS,
) -> list[tuple[float, ...]]:
    """The bodies a walk from ``start_xz`` to ``goal_xz`` goes round: (x, z) for those farther than
    BODY_NEAR_END_M from both ends, none for those that near the start (stood beside when setting off),
    (x, z, r) with a disc shrunk to leave the goal free for those that near the goal (the person walked up to
    is not walked through on the way to her, nor is the one beside the goal), none for those nearer the goal
    than BODY_MIN_M + END_FREE_M (the walk ends touching them)."""
    start, goal = np.asarray(start_xz, np.float64), np.asarray(goal_xz, np.float64)
    out: list[tuple[float, ...]] = []
    for b in bodies:
        if not np.isfinite(b).all():
            continue
        at = np.asarray(b, float)[:2]
        if float(np.linalg.norm(start - at)) <= BODY_NEAR_END_M:
            continue  # the one stood beside when setting off
        near = float(np.linalg.norm(goal - at))
        if near > BODY_NEAR_END_M:
            out.append((float(b[0]), float(b[1])))
        elif near - END_FREE_M >= BODY_MIN_M:
            out.append((float(b[0]), float(b[1]), min(radius + BODY_M, near - END_FREE_M)))
    return out


# metres between hips a walk passes another by where the full disc (RADIUS + BODY_M) closes the way (one
# standing in the mouth of a nook between the furniture, the goal inside it): shoulder by shoulder, arms in
PASS_BY_M = (0.5, 0.46, 0.42, 0.38)


def _narrowed(bodies: Sequence[tuple[float, ...]], reach: float) -> list[tuple[float, ...]]:
    """``bodies`` with each disc at most ``reach`` metres round the hips."""
    return [(b[0], b[1], min(reach, b[2] if len(b) > 2 else reach)) for b in bodies]


def plan_scene_route(
    scene: Scene,
    start_xz,
    goal_xz,
    *,
    ignore: frozenset[str] = frozenset(),  # noqa: ANN001
    radius: float = RADIUS,
    cell: float = CELL,
    step_in: float = STEP_IN,
    into_hosts: bool = True,
    bodies: Sequence[tuple[float, ...]] = (),  # (x, z), or (x, z, radius) to shrink one
) -> np.ndarray:
    """``wana.domain.routes.plan_route`` on cached grids (same arguments, same answer).

    With ``into_hosts=False`` the last step never enters an object the goal lies on (within HOST_M
    of its footprint): the caller has already ignored the object it walks to, so such a host is
    other furniture (a desk behind the chair's stand point) and the route ends at the free cell
    nearest to the goal; a goal merely near other objects is still reached past half their clearance.

    Args:
        scene: room and placed objects.
        start_xz: (2,) world x, z where the character stands, metres.
        goal_xz: (2,) world x, z where it should arrive, metres.
        ignore: ids of objects that do not block.
        radius: character radius, metres.
        cell: grid cell, metres.
        step_in: longest last step into the goal object's clearance, metres.
        into_hosts: whether the last step may enter the clearance of the object the goal lies on.
        bodies: (x, z) metres of other characters standing in the room: the route goes round them too.

    Returns:
        (N, 2) waypoints from the start to the goal (or the free cell nearest to it).

    Raises:
        NoRouteError: when no route exists.
    """
    grid = with_bodies(scene_grid(scene, ignore, radius, cell), bodies, radius)
    start = np.asarray(start_xz, dtype=np.float64).reshape(2)
    goal = np.asarray(goal_xz, dtype=np.float64).reshape(2)
    if (
        np.isfinite(start).all()
        and np.isfinite(goal).all()
        and grid.is_free_xz(np.stack([start, goal])).all()
        and segment_is_free(grid, start, goal)
    ):
        return np.stack(
            [start, goal]
        )  # what A* + line-of-sight smoothing give for a free straight line, for less
    route = plan_route_on_grid(grid, start_xz, goal_xz)
    last = route[-1]
    kept = [o for o in scene.objects if o.id not in ignore]
    if step_in <= 0 or np.allclose(last, goal) or np.linalg.norm(goal - last) > step_in or not kept:
        return route
    dist = {}
    for obj in kept:
        fp = object_mask(scene.room, obj, radius, cell)[1]
        if len(fp):  # type: ignore[arg-type]
            dist[obj.id] = float(point_rect_distance(goal[None], fp).min())  # type: ignore[arg-type]
    hosts = {i for i, d in dist.items() if d <= HOST_M}
    if into_hosts != bool(hosts):
        return route
    near = {i for i, d in dist.items() if d <= radius} - hosts
    blocked = wall_mask(scene.room, radius, cell).copy()
    for obj in kept:
        if obj.id in near:
            blocked |= object_mask(scene.room, obj, radius / 2, cell)[0]
        elif obj.id not in hosts:
            blocked |= object_mask(scene.room, obj, radius, cell)[0]
    if segment_is_free(OccupancyGrid(blocked=blocked, origin=grid.origin, cell=cell), last, goal):
        route = np.vstack([route, goal[None]])
    return route


def free_spot(
    scene: Scene,
    xz: tuple[float, float],
    *,
    radius: float = RADIUS,
    cell: float = CELL,
    max_move: float = 1.0,
    bodies: Sequence[tuple[float, ...]] = (),
) -> tuple[float, float]:
    """``xz`` itself when a body of ``radius`` fits there, else the nearest spot where one does.

    Only spots within ``max_move`` metres count; with none of them free, ``xz`` itself. ``bodies``: others
    standing there, (x, z) or (x, z, metres kept from their hips), as in ``with_bodies``.
    """
    from scipy import ndimage

    grid = with_bodies(scene_grid(scene, frozenset(), radius, cell), bodies, radius)
    if grid.is_free_xz(np.asarray(xz, dtype=np.float64)) or grid.blocked.all():
        return xz
    rc = grid.to_cell(np.asarray(xz, dtype=np.float64))
    _, (ri, ci) = ndimage.distance_transform_edt(grid.blocked, return_indices=True)
    spot = grid.to_world(np.array([ri[rc[0], rc[1]], ci[rc[0], rc[1]]]))
    if np.linalg.norm(spot - np.asarray(xz)) > max_move:
        return xz
    return float(spot[0]), float(spot[1])


SQUEEZE_M = 0.15  # metres: the clearance of a body turned sideways through a narrow way
LAST_STEP_M = 1.2  # metres: the longest last step from the nearest reachable point into an enclosed goal


def _reachable_near(
    scene: Scene,
    start_xz: tuple[float, float],
    goal_xz: tuple[float, float],
    ignore: frozenset[str],
    bodies: Sequence[tuple[float, ...]],
) -> np.ndarray | None:
    """A route to the reachable free cell nearest an enclosed goal (a chair pushed in between a table and the
    fridge), then the last step in; None when that point is farther than LAST_STEP_M from the goal.

    Better than the straight line from the start, which crosses the room through furniture and people.
    """
    from scipy import ndimage

    grid = with_bodies(scene_grid(scene, ignore), bodies)
    start = np.asarray(start_xz, dtype=np.float64)
    goal = np.asarray(goal_xz, dtype=np.float64)
    if not (np.isfinite(start).all() and np.isfinite(goal).all()) or grid.blocked.all():
        return None
    labels, _ = ndimage.label(~grid.blocked)
    free = ~grid.blocked
    rc = grid.to_cell(start)
    if not free[rc[0], rc[1]]:
        cells = np.argwhere(free)
        rc = cells[int(np.argmin(np.linalg.norm(grid.to_world(cells) - start, axis=1)))]
    mine = np.argwhere(labels == labels[rc[0], rc[1]])
    pts = grid.to_world(mine)
    gaps = np.linalg.norm(pts - goal, axis=1)
    best = int(np.argmin(gaps))
    if gaps[best] > LAST_STEP_M:
        return None
    try:
        route = plan_route_on_grid(grid, start, pts[best])
    except (NoRouteError, ValueError):
        return None
    return np.vstack([route, goal[None]])


THROUGH_M = 0.05  # metres: a route point this deep inside an ignored object's footprint passes through it
THROUGH_END_M = 0.35  # metres of a route's end that may come that close (the last step up to the object)
THROUGH_LOW_M = 0.1  # metres: boxes no higher than this (a rug) are walked over
THROUGH_HIGH_M = 1.8  # metres: boxes from this high up (a shelf over a desk) are walked under


def passes_through(scene: Scene, waypoints: np.ndarray, ignore: frozenset[str]) -> bool:
    """Whether a walk along ``waypoints`` ((N, 2) metres, world) crosses an ignored object's footprint deeper
    than THROUGH_M before its last THROUGH_END_M. The object walked to is ignored so that the walk may end
    close to it, which also lets a route lead straight over it to a stand point on its far side."""
    way = np.asarray(waypoints, float).reshape(-1, 2)
    kept = [o for o in scene.objects if o.id in ignore and not o.support]  # what rests on it is over it
    if len(way) < 2 or not kept:
        return False
    steps = [np.linalg.norm(way[i + 1] - way[i]) for i in range(len(way) - 1)]
    pts = np.vstack([
        way[i] + np.linspace(0.0, 1.0, int(n / CELL) + 2)[:, None] * (way[i + 1] - way[i])
        for i, n in enumerate(steps)
    ])  # fmt: skip
    pts = pts[np.linalg.norm(pts - way[-1], axis=1) > THROUGH_END_M]
    probes = np.array([[0.0, 0.0], [THROUGH_M, 0.0], [-THROUGH_M, 0.0], [0.0, THROUGH_M], [0.0, -THROUGH_M]])
    for obj in kept:
        fp = object_mask(scene.room, obj)[1]
        tall = (fp.y_max > THROUGH_LOW_M) & (fp.y_min < THROUGH_HIGH_M)
        if not len(pts) or not tall.any():
            continue
        boxes = Footprints(
            centre=fp.centre[tall], half=fp.half[tall], yaw=fp.yaw[tall],
            y_min=fp.y_min[tall], y_max=fp.y_max[tall],
            owner=tuple(o for o, k in zip(fp.owner, tall, strict=True) if k),
        )  # fmt: skip
        # deep inside: the point and the points THROUGH_M around it all in the footprint (a union of boxes)
        inside = [point_rect_distance(pts + d, boxes).min(axis=1) <= 1e-9 for d in probes]
        if np.any(np.all(inside, axis=0)):
            return True
    return False


def scene_route(
    scene: Scene,
    start_xz: tuple[float, float],
    goal_xz: tuple[float, float],
    ignore: frozenset[str] = frozenset(),
    bodies: Sequence[tuple[float, float]] = (),
) -> tuple[np.ndarray, str]:
    """``_scene_route`` (see there), round the ignored objects when its route leads over them (hips 13 cm into a
    dining table on the way to its far side, solo-dining_room-09 s5): to the free cell nearest the goal with
    nothing ignored, and a last step in."""
    wps, why = _scene_route(scene, start_xz, goal_xz, ignore, bodies)
    if why or not ignore or not passes_through(scene, wps, ignore):
        return wps, why
    around, why_around = _scene_route(scene, start_xz, goal_xz, frozenset(), bodies)
    goal = np.asarray(goal_xz, float).reshape(1, 2)
    if not np.allclose(around[-1], goal[0]):
        around = np.vstack([around, goal])
    if why_around or passes_through(scene, around, ignore):
        return wps, why
    return around, ""


def _scene_route(
    scene: Scene,
    start_xz: tuple[float, float],
    goal_xz: tuple[float, float],
    ignore: frozenset[str] = frozenset(),
    bodies: Sequence[tuple[float, float]] = (),
) -> tuple[np.ndarray, str]:
    """A collision-free route, or the straight line and a diagnostic when there is none.

    The route never ends inside other furniture (``into_hosts=False``); ``ignore`` should hold the
    object walked to and what rests on it. Where a body's width has no way through, a sideways squeeze
    (SQUEEZE_M) is tried, then the nearest reachable point and a last step in, before the straight line. ``bodies``: where other characters stand; the route goes
    round them (not those within BODY_NEAR_END_M of the start, closer round those that near the goal:
    round_bodies), closer past them (PASS_BY_M) where the full disc closes the way, or through them where even
    that does.

    Returns:
        waypoints (N, 2) metres, world; "" or a diagnostic saying why the route is straight.
    """
    around = round_bodies(bodies, start_xz, goal_xz)
    for discs in (around, *(_narrowed(around, reach) for reach in PASS_BY_M)) if around else ():
        try:
            return plan_scene_route(
                scene, start_xz, goal_xz, ignore=ignore, into_hosts=False, bodies=discs
            ), ""
        except (NoRouteError, ValueError):
            continue  # the others close the way: closer past them, at last round the furniture only
    try:
        return plan_scene_route(scene, start_xz, goal_xz, ignore=ignore, into_hosts=False), ""
    except NoRouteError as exc:
        for squeeze in ([*around], []):  # a narrow way: sideways past the furniture (and the others)
            try:
                return plan_scene_route(
                    scene,
                    start_xz,
                    goal_xz,
                    ignore=ignore,
                    into_hosts=False,
                    bodies=squeeze,
                    radius=SQUEEZE_M,
                ), ""
            except (NoRouteError, ValueError):
                continue
        near = _reachable_near(scene, start_xz, goal_xz, ignore, around)
        if near is not None:
            return near, ""
        line = np.array([start_xz, goal_xz], dtype=np.float64)
        return line, f"no free walking route, walking straight: {exc}"
    except ValueError as exc:  # non-finite points: plan_actions guards these, keep walking anyway
        return np.array(
            [start_xz, goal_xz], dtype=np.float64
        ), f"route planning failed, walking straight: {exc}"


def reachable_short_of(
    scene: Scene, pos: tuple[float, float], other: tuple[float, float], distance: float
) -> tuple[float, float] | None:
    """Where to stop ``distance`` metres from a person at ``other``, walking from ``pos``, when the point short
    of them on the straight line is inside furniture (the person stands behind the armchair the walker gets
    up from): the free point on the circle round them nearest to ``pos``; None when the straight one is free
    or none is. The route planner would otherwise end at the free cell nearest the blocked point, which can
    be inside the person."""
    grid = scene_grid(scene)
    p, o = np.asarray(pos, float), np.asarray(other, float)
    d = p - o
    n = float(np.linalg.norm(d))
    if n <= distance:
        return None
    straight = o + d / n * distance
    if grid.is_free_xz(straight):
        return None
    a0 = float(np.arctan2(d[0], d[1]))
    ring = [
        o + distance * np.array([np.sin(a0 + k * np.pi / 12), np.cos(a0 + k * np.pi / 12)])
        for k in range(-12, 12)
    ]
    free = [q for q in ring if grid.is_free_xz(q)]
    if not free:
        return None
    best = min(free, key=lambda q: float(np.linalg.norm(q - p)))
    return float(best[0]), float(best[1])


JOIN_M = 0.6  # metres along a given route from its start to where a walk starting elsewhere joins it


def joined_route(
    scene: Scene,
    start_xz: tuple[float, float],
    route: np.ndarray,
    ignore: frozenset[str] = frozenset(),
    bodies: Sequence[tuple[float, float]] = (),
) -> np.ndarray:
    """A route worked out beforehand (the orchestrator's way out through the door) for a walk that starts
    elsewhere: from ``start_xz`` round the furniture to the route's first waypoint JOIN_M or more from its
    start, then along the rest of it. The route as given when it starts at ``start_xz``.

    The orchestrator routes from where a seated character's state is, in front of the seat; the walk starts
    where getting up ends (beside a stool at a dressing table), and the given route's first step from there
    crossed the stool (solo-bedroom-21 s12: a foot 7 cm inside it).
    """
    way = np.asarray(route, float).reshape(-1, 2)
    start = np.asarray(start_xz, float)
    if len(way) < 2 or np.linalg.norm(way[0] - start) <= CELL:
        return way
    from_start = np.linalg.norm(way - way[0], axis=1)
    k = next((i for i in range(1, len(way)) if from_start[i] >= JOIN_M), len(way) - 1)
    head, why = scene_route(scene, (float(start[0]), float(start[1])), (float(way[k, 0]), float(way[k, 1])),
                            ignore, bodies)  # fmt: skip
    if why:
        return way  # no way round to it: the route as given
    return np.vstack([head, way[k + 1 :]])
