"""Walking routes: an occupancy grid from collision boxes, A* on it, and line-of-sight smoothing.

The grid covers the room floor; row r is z, column c is x. A cell is blocked when its centre lies
within ``radius`` (the character's radius) of a wall or of the floor footprint of any collision box
whose bottom is below ``max_height`` (things a walking body can hit; a hanging lamp is not an
obstacle). Footprints are oriented rectangles (an object's yaw rotates its boxes), so a rotated
object blocks exactly its own cells, not its bounding square.

A* is 8-connected with the octile heuristic and never cuts a corner (a diagonal step needs both
orthogonal neighbours free), so the free cells reachable from a cell are exactly its 4-connected
component; that lets an unreachable goal fail fast before any search.

``Reservations`` is the time axis of the same floor: where each character's body is at each frame, so
that a walker can tell whether its way is free when it gets there. Over 400 lines because the grid, the
search and the reservation table are one routing vocabulary that the motion service and the orchestrator
share.
"""

from __future__ import annotations

import heapq
import math
import threading
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from proto.scene import Room, Scene

SQRT2 = math.sqrt(2.0)
HOST_M = 0.1  # a goal this close to an object's footprint belongs to that object (plan_route's step-in)


class NoRouteError(ValueError):
    """No collision-free route joins the start and the goal."""


@dataclass(frozen=True)
class Footprints:
    """Floor footprints of collision boxes as oriented rectangles.

    Attributes:
        centre: (N, 2) x, z of each rectangle's centre, metres, world.
        half: (N, 2) half extents along the rectangle's own x and z axes, metres.
        yaw: (N,) rotation about +Y, radians (the object's yaw).
        y_min: (N,) bottom of each box, metres.
        y_max: (N,) top of each box, metres.
        owner: (N,) id of the object each box belongs to.
    """

    centre: np.ndarray
    half: np.ndarray
    yaw: np.ndarray
    y_min: np.ndarray
    y_max: np.ndarray
    owner: tuple[str, ...]

    @staticmethod
    def from_aabbs(boxes: np.ndarray, owner: Iterable[str] | None = None) -> Footprints:
        """Footprints of world axis-aligned boxes.

        Args:
            boxes: (N, 2, 3) min and max corners, metres, world.
            owner: object id per box; defaults to "" for each.
        """
        boxes = np.asarray(boxes, dtype=np.float64).reshape(-1, 2, 3)
        lo, hi = boxes[:, 0], boxes[:, 1]
        n = len(boxes)
        return Footprints(
            centre=(lo[:, [0, 2]] + hi[:, [0, 2]]) / 2,
            half=np.abs(hi[:, [0, 2]] - lo[:, [0, 2]]) / 2,
            yaw=np.zeros(n),
            y_min=np.minimum(lo[:, 1], hi[:, 1]),
            y_max=np.maximum(lo[:, 1], hi[:, 1]),
            owner=tuple(owner) if owner is not None else ("",) * n,
        )

    def select(self, keep: np.ndarray) -> Footprints:
        """The footprints where the boolean mask ``keep`` (N,) is true."""
        idx = np.flatnonzero(keep)
        return Footprints(
            self.centre[idx],
            self.half[idx],
            self.yaw[idx],
            self.y_min[idx],
            self.y_max[idx],
            tuple(self.owner[i] for i in idx),
        )

    def __len__(self) -> int:
        return len(self.centre)

    def concat(self, other: Footprints) -> Footprints:
        """These footprints and ``other``'s together."""
        return Footprints(
            np.concatenate([self.centre.reshape(-1, 2), other.centre.reshape(-1, 2)]),
            np.concatenate([self.half.reshape(-1, 2), other.half.reshape(-1, 2)]),
            np.concatenate([self.yaw, other.yaw]),
            np.concatenate([self.y_min, other.y_min]),
            np.concatenate([self.y_max, other.y_max]),
            self.owner + other.owner,
        )


def body_footprints(points: Iterable[tuple[float, float]], radius: float = 0.22) -> Footprints:
    """Other characters standing at floor points (x, z), as squares of half side ``radius`` from the floor
    to head height: what a route planned for one character walks around (the others where they are)."""
    xz = np.asarray(list(points), dtype=np.float64).reshape(-1, 2)
    lo = np.column_stack([xz[:, 0] - radius, np.zeros(len(xz)), xz[:, 1] - radius])
    hi = np.column_stack([xz[:, 0] + radius, np.full(len(xz), 1.8), xz[:, 1] + radius])
    return Footprints.from_aabbs(np.stack([lo, hi], axis=1), owner=[f"body:{i}" for i in range(len(xz))])


@dataclass(frozen=True)
class OccupancyGrid:
    """Blocked cells of the floor.

    Attributes:
        blocked: (H, W) bool, row = z index, column = x index.
        origin: (2,) world x, z of the centre of cell (0, 0).
        cell: cell size in metres.
    """

    blocked: np.ndarray
    origin: np.ndarray
    cell: float

    def to_cell(self, xz: np.ndarray) -> np.ndarray:
        """(..., 2) world x, z -> (..., 2) integer (row, col), clipped into the grid."""
        xz = np.asarray(xz, dtype=np.float64)
        col = np.rint((xz[..., 0] - self.origin[0]) / self.cell).astype(np.int64)
        row = np.rint((xz[..., 1] - self.origin[1]) / self.cell).astype(np.int64)
        h, w = self.blocked.shape
        return np.stack([np.clip(row, 0, h - 1), np.clip(col, 0, w - 1)], axis=-1)

    def to_world(self, rc: np.ndarray) -> np.ndarray:
        """(..., 2) (row, col) -> (..., 2) world x, z of the cell centres."""
        rc = np.asarray(rc, dtype=np.float64)
        return np.stack(
            [self.origin[0] + rc[..., 1] * self.cell, self.origin[1] + rc[..., 0] * self.cell], axis=-1
        )

    def is_free_xz(self, xz: np.ndarray) -> np.ndarray:
        """(..., 2) world points -> (...) bool, false outside the grid or on a blocked cell."""
        xz = np.asarray(xz, dtype=np.float64)
        col = np.rint((xz[..., 0] - self.origin[0]) / self.cell).astype(np.int64)
        row = np.rint((xz[..., 1] - self.origin[1]) / self.cell).astype(np.int64)
        h, w = self.blocked.shape
        inside = (row >= 0) & (row < h) & (col >= 0) & (col < w)
        free = np.zeros(row.shape, dtype=bool)
        free[inside] = ~self.blocked[row[inside], col[inside]]
        return free


def point_rect_distance(points: np.ndarray, fp: Footprints) -> np.ndarray:
    """Distance from each point to each footprint rectangle (0 inside).

    Args:
        points: (P, 2) world x, z.
        fp: N footprints.

    Returns:
        (P, N) distances in metres.
    """
    d = points[:, None, :] - fp.centre[None, :, :]  # (P, N, 2)
    c, s = np.cos(fp.yaw), np.sin(fp.yaw)
    # World -> box frame is R_y(-yaw); for x, z: lx = c*dx - s*dz, lz = s*dx + c*dz.
    lx = c * d[..., 0] - s * d[..., 1]
    lz = s * d[..., 0] + c * d[..., 1]
    ex = np.maximum(np.abs(lx) - fp.half[:, 0], 0.0)
    ez = np.maximum(np.abs(lz) - fp.half[:, 1], 0.0)
    return np.hypot(ex, ez)


FLOOR_COVERING_M = 0.03  # metres: a box no taller than this is walked over


def occupancy_grid(
    room: Room, footprints: Footprints, *, radius: float = 0.25, cell: float = 0.05, max_height: float = 1.8
) -> OccupancyGrid:
    """Rasterise the room floor: walls and box footprints grown by the character radius.

    Args:
        room: room bounds (x in [-width/2, width/2], z in [-depth/2, depth/2]).
        footprints: collision boxes; those with bottom at or above ``max_height`` are ignored.
        radius: character radius in metres.
        cell: cell size in metres.
        max_height: boxes starting at or above this height (metres) do not block walking.

    Returns:
        The occupancy grid.
    """
    if cell <= 0 or radius < 0:
        raise ValueError(f"cell must be > 0 and radius >= 0, got cell={cell}, radius={radius}")
    w = max(1, int(math.floor(room.width / cell)))
    h = max(1, int(math.floor(room.depth / cell)))
    origin = np.array(
        [
            -room.width / 2 + (room.width - (w - 1) * cell) / 2,
            -room.depth / 2 + (room.depth - (h - 1) * cell) / 2,
        ]
    )
    xs = origin[0] + np.arange(w) * cell
    zs = origin[1] + np.arange(h) * cell
    blocked = np.zeros((h, w), dtype=bool)
    blocked[:, (xs < -room.width / 2 + radius) | (xs > room.width / 2 - radius)] = True
    blocked[(zs < -room.depth / 2 + radius) | (zs > room.depth / 2 - radius), :] = True
    # Boxes starting overhead do not block, nor floor coverings (a rug, a mat) one steps over.
    walk_over = footprints.y_max <= FLOOR_COVERING_M
    fp = footprints.select((footprints.y_min < max_height) & ~walk_over) if len(footprints) else footprints
    if len(fp) == 0:
        return OccupancyGrid(blocked=blocked, origin=origin, cell=cell)
    c, s = np.abs(np.cos(fp.yaw)), np.abs(np.sin(fp.yaw))
    ext = (
        np.stack([c * fp.half[:, 0] + s * fp.half[:, 1], s * fp.half[:, 0] + c * fp.half[:, 1]], axis=1)
        + radius
    )
    lo, hi = fp.centre - ext, fp.centre + ext  # (N, 2) grown bounding boxes
    rects = np.column_stack([fp.centre, fp.half, fp.yaw])  # (N, 5)
    by_owner: dict[str, list[int]] = {}
    for i, owner in enumerate(fp.owner):
        by_owner.setdefault(owner, []).append(i)
    for mine in by_owner.values():
        window = _owner_cells(rects[mine], lo[mine], hi[mine], xs, zs, origin, cell, radius)
        if window is not None:
            r0, c0, cells = window
            blocked[r0 : r0 + cells.shape[0], c0 : c0 + cells.shape[1]] |= cells
    return OccupancyGrid(blocked=blocked, origin=origin, cell=cell)


_OWNER_CELLS: dict[tuple[object, ...], tuple[int, int, np.ndarray] | None] = {}
_OWNER_CELLS_MAX = 4096  # cached windows (a few kB each); cleared when full
_OWNER_CELLS_LOCK = threading.Lock()


def _owner_cells(
    rects: np.ndarray,
    lo: np.ndarray,
    hi: np.ndarray,
    xs: np.ndarray,
    zs: np.ndarray,
    origin: np.ndarray,
    cell: float,
    radius: float,
) -> tuple[int, int, np.ndarray] | None:
    """The cells one object's rectangles ((N, 5) centre x, z, half x, z, yaw) block: (first row, first column, (rows, cols) bool window), or None
    when its window misses the grid. Memoised on the rectangles and the grid's geometry: a room's furniture
    is the same from one route to the next (the orchestrator plans every walk of every edit over it), so only
    the other characters' bodies are rasterised afresh."""
    key = (
        len(xs),
        len(zs),
        origin.tobytes(),
        cell,
        radius,
        rects.tobytes(),
    )
    with _OWNER_CELLS_LOCK:
        if key in _OWNER_CELLS:
            return _OWNER_CELLS[key]
    w, h = len(xs), len(zs)
    # One window per object, tested against all its rectangles at once.
    c0 = max(0, int(math.floor((lo[:, 0].min() - origin[0]) / cell)))
    c1 = min(w, int(math.ceil((hi[:, 0].max() - origin[0]) / cell)) + 1)
    r0 = max(0, int(math.floor((lo[:, 1].min() - origin[1]) / cell)))
    r1 = min(h, int(math.ceil((hi[:, 1].max() - origin[1]) / cell)) + 1)
    window: tuple[int, int, np.ndarray] | None = None
    if c0 < c1 and r0 < r1:
        gx, gz = np.meshgrid(xs[c0:c1], zs[r0:r1])
        pts = np.stack([gx.ravel(), gz.ravel()], axis=1)
        # Voxelised objects stack many boxes on one footprint: test each distinct rectangle once.
        _, first = np.unique(np.round(rects, 6), axis=0, return_index=True)
        rects = rects[np.sort(first)]
        near = np.ones(len(pts), dtype=bool)
        for chunk in range(0, len(rects), 256):
            part = rects[chunk : chunk + 256]
            n = len(part)
            sub = Footprints(part[:, 0:2], part[:, 2:4], part[:, 4], np.zeros(n), np.zeros(n), ("",) * n)
            near &= ~(point_rect_distance(pts, sub) <= radius).any(axis=1)
        cells = ~near.reshape(gx.shape)
        cells.flags.writeable = False
        window = (r0, c0, cells)
    with _OWNER_CELLS_LOCK:
        if len(_OWNER_CELLS) >= _OWNER_CELLS_MAX:
            _OWNER_CELLS.clear()
        _OWNER_CELLS[key] = window
    return window


def _nearest_free(grid: OccupancyGrid, rc: np.ndarray) -> np.ndarray:
    """The free cell nearest to ``rc`` (itself when free); raises NoRouteError on a full grid."""
    if not grid.blocked[rc[0], rc[1]]:
        return rc
    if grid.blocked.all():
        raise NoRouteError("every cell of the room is blocked for a character of this radius")
    from scipy import ndimage  # imported when a route is planned, not when the orchestrator starts

    _, (ri, ci) = ndimage.distance_transform_edt(grid.blocked, return_indices=True)
    return np.array([ri[rc[0], rc[1]], ci[rc[0], rc[1]]])


def astar(blocked: np.ndarray, start: tuple[int, int], goal: tuple[int, int]) -> list[tuple[int, int]]:
    """Shortest 8-connected path of free cells (octile heuristic, no corner cutting).

    Args:
        blocked: (H, W) bool grid.
        start: (row, col) free cell.
        goal: (row, col) free cell.

    Returns:
        The cells from start to goal, both included.

    Raises:
        NoRouteError: when the goal cannot be reached.
    """
    h, w = blocked.shape
    free = ~blocked
    gr, gc = goal
    start_i, goal_i = start[0] * w + start[1], gr * w + gc
    g = np.full(h * w, np.inf)
    parent = np.full(h * w, -1, dtype=np.int64)
    closed = np.zeros(h * w, dtype=bool)
    g[start_i] = 0.0
    moves = (
        (-1, 0, 1.0),
        (1, 0, 1.0),
        (0, -1, 1.0),
        (0, 1, 1.0),
        (-1, -1, SQRT2),
        (-1, 1, SQRT2),
        (1, -1, SQRT2),
        (1, 1, SQRT2),
    )

    def octile(r: int, c: int) -> float:
        dr, dc = abs(r - gr), abs(c - gc)
        return (dr + dc) + (SQRT2 - 2.0) * min(dr, dc)

    heap: list[tuple[float, float, int]] = [(octile(*start), 0.0, start_i)]
    while heap:
        _, gi, i = heapq.heappop(heap)
        if closed[i]:
            continue
        if i == goal_i:
            break
        closed[i] = True
        r, c = divmod(i, w)
        for dr, dc, cost in moves:
            nr, nc = r + dr, c + dc
            if not (0 <= nr < h and 0 <= nc < w) or not free[nr, nc]:
                continue
            if dr and dc and not (free[r, nc] and free[nr, c]):
                continue
            j = nr * w + nc
            ng = gi + cost
            if ng < g[j] and not closed[j]:
                g[j] = ng
                parent[j] = i
                heapq.heappush(heap, (ng + octile(nr, nc), ng, j))
    if not np.isfinite(g[goal_i]):
        raise NoRouteError(f"no free path from cell {start} to cell {goal}")
    cells = [goal_i]
    while cells[-1] != start_i:
        cells.append(int(parent[cells[-1]]))
    return [divmod(i, w) for i in reversed(cells)]


def segment_is_free(grid: OccupancyGrid, a: np.ndarray, b: np.ndarray) -> bool:
    """Whether the straight segment a -> b (world x, z) stays on free cells."""
    n = max(2, int(math.ceil(np.linalg.norm(b - a) / (grid.cell * 0.5))) + 1)
    t = np.linspace(0.0, 1.0, n)[:, None]
    return bool(grid.is_free_xz(a[None] * (1 - t) + b[None] * t).all())


def smooth_path(grid: OccupancyGrid, points: np.ndarray) -> np.ndarray:
    """Greedy line-of-sight shortcut: from each kept point jump to the farthest visible one.

    Args:
        grid: the occupancy grid the points were planned on.
        points: (N, 2) world x, z waypoints.

    Returns:
        (M, 2) waypoints, M <= N, same first and last point.
    """
    if len(points) <= 2:
        return points
    kept = [0]
    i = 0
    while i < len(points) - 1:
        j = len(points) - 1
        while j > i + 1 and not segment_is_free(grid, points[i], points[j]):
            j -= 1
        kept.append(j)
        i = j
    return points[kept]


def plan_route_on_grid(grid: OccupancyGrid, start_xz: np.ndarray, goal_xz: np.ndarray) -> np.ndarray:
    """A* route on a grid, with start and goal snapped to their nearest free cells.

    Args:
        grid: occupancy grid.
        start_xz: (2,) world x, z of the character.
        goal_xz: (2,) world x, z where it wants to go.

    Returns:
        (N, 2) world x, z waypoints, N >= 2: the start itself, then the smoothed route, ending at the
        goal or at the centre of the free cell nearest to it when the goal itself is blocked.

    Raises:
        NoRouteError: when the goal's nearest free cell is not reachable from the start.
    """
    start = np.asarray(start_xz, dtype=np.float64).reshape(2)
    goal = np.asarray(goal_xz, dtype=np.float64).reshape(2)
    if not (np.isfinite(start).all() and np.isfinite(goal).all()):
        raise ValueError(f"start and goal must be finite, got {start}, {goal}")
    s_rc = _nearest_free(grid, grid.to_cell(start))
    g_rc = _nearest_free(grid, grid.to_cell(goal))
    from scipy import ndimage

    labels, _ = ndimage.label(~grid.blocked)  # 4-connected: exactly what no-corner-cutting A* reaches
    if labels[s_rc[0], s_rc[1]] != labels[g_rc[0], g_rc[1]]:
        raise NoRouteError(
            f"no route from ({start[0]:.2f}, {start[1]:.2f}) to ({goal[0]:.2f}, {goal[1]:.2f}): "
            "the goal is enclosed by obstacles for a character of this radius"
        )
    cells = np.array(astar(grid.blocked, (int(s_rc[0]), int(s_rc[1])), (int(g_rc[0]), int(g_rc[1]))))
    pts = grid.to_world(cells)
    pts[0] = start if grid.is_free_xz(start) else pts[0]
    pts[-1] = goal if grid.is_free_xz(goal) else pts[-1]
    route = smooth_path(grid, pts)
    if not grid.is_free_xz(start):
        route = np.vstack([start[None], route])  # step out of the obstacle first
    if len(route) == 1:
        route = np.vstack([route, route])
    return route


def plan_route(
    scene: Scene,
    start_xz: np.ndarray,
    goal_xz: np.ndarray,
    *,
    radius: float = 0.25,
    cell: float = 0.05,
    ignore: set[str] | frozenset[str] = frozenset(),
    step_in: float = 1.0,
    bodies: Iterable[tuple[float, float]] = (),
) -> np.ndarray:
    """Collision-free walking route through a scene (the motion service's ``route_fn``).

    A goal inside an object's clearance (the spot in front of a chair where one turns to sit) is
    snapped to the nearest free cell for the search; the route then takes one last straight step
    of at most ``step_in`` metres to the goal itself, provided that step crosses no clearance but
    that of the object the goal belongs to (on or within HOST_M of its footprint) and half that of
    other objects right around the goal. So a character walks up to what it is going to use, and a
    goal boxed in by other furniture still ends at the free cell.

    Args:
        scene: room and placed objects; collision boxes come from the asset catalog.
        start_xz: (2,) world x, z where the character stands.
        goal_xz: (2,) world x, z where it should arrive.
        radius: character radius in metres.
        cell: grid cell size in metres.
        ignore: ids of objects that do not block (e.g. the chair being walked to).
        step_in: longest final step into the goal objects' clearance, metres (0: end at the free cell).
        bodies: floor points (x, z) where other characters stand; the route goes around them too.

    Returns:
        (N, 2) world x, z waypoints from start to the goal (or the free cell nearest to it).

    Raises:
        NoRouteError: when no route exists.
    """
    from wana.domain.object_geometry import scene_footprints

    fp = scene_footprints(scene, ignore=ignore)
    others = list(bodies)
    if others:
        fp = fp.concat(body_footprints(others))
    grid = occupancy_grid(scene.room, fp, radius=radius, cell=cell)
    route = plan_route_on_grid(grid, start_xz, goal_xz)
    goal = np.asarray(goal_xz, dtype=np.float64).reshape(2)
    last = route[-1]
    if step_in > 0 and not np.allclose(last, goal) and np.linalg.norm(goal - last) <= step_in and len(fp):
        dist = point_rect_distance(goal[None], fp)[0]
        # The object the goal belongs to (it lies on or right at its footprint) does not block the
        # step; other objects whose clearance holds the goal keep half of it, the rest all of it.
        hosts = {fp.owner[i] for i in np.flatnonzero(dist <= HOST_M)}
        near = {fp.owner[i] for i in np.flatnonzero(dist <= radius)} - hosts
        if hosts:
            owner = np.array(fp.owner, dtype=object)
            rest = fp.select(~np.isin(owner, list(hosts | near)))
            open_grid = occupancy_grid(scene.room, rest, radius=radius, cell=cell)
            if near:
                tight = occupancy_grid(
                    scene.room, fp.select(np.isin(owner, list(near))), radius=radius / 2, cell=cell
                )
                open_grid = OccupancyGrid(open_grid.blocked | tight.blocked, open_grid.origin, cell)
            if segment_is_free(open_grid, last, goal):
                route = np.vstack([route, goal[None]])
    return route


@dataclass
class Reservations:
    """A space-time reservation table: where each character's body is at each frame of the story.

    Who walks first keeps the way: its trajectory is reserved (frame by frame, a disc of ``clearance`` round
    its hips), and a later walker asks ``first_conflict`` whether its own trajectory enters a reserved disc
    at the same frame, so it can wait (services/motion/giveway.py) instead of walking through. Frames where a
    character is off stage are not reserved (NaN).

    Attributes:
        clearance: metres between two hips below which two bodies touch (two walking bodies' shoulders
            and swinging arms).
    """

    clearance: float = 0.6
    tracks: dict[str, np.ndarray] | None = None  # name -> (T, 2) x, z per frame, NaN off stage

    def reserve(self, name: str, xz: np.ndarray) -> None:
        """Reserve ``name``'s trajectory (T, 2) metres, world (NaN rows: not on stage)."""
        if self.tracks is None:
            self.tracks = {}
        self.tracks[name] = np.asarray(xz, dtype=np.float64).reshape(-1, 2)

    def first_conflict(
        self, xz: np.ndarray, frames: range, exclude: Iterable[str] = ()
    ) -> tuple[int, str] | None:
        """The first frame of ``frames`` where the trajectory (T, 2) enters another's reserved disc, and whose.

        Args:
            xz: (T, 2) the asking character's trajectory, story frames (NaN: off stage).
            frames: the frames to test.
            exclude: characters whose reservations do not count (the asker itself).
        """
        skip = set(exclude)
        best: tuple[int, str] | None = None
        for name, track in (self.tracks or {}).items():
            if name in skip:
                continue
            lo, hi = max(frames.start, 0), min(frames.stop, len(track), len(xz))
            if hi <= lo:
                continue
            d = np.linalg.norm(track[lo:hi] - xz[lo:hi], axis=1)
            hit = np.flatnonzero(d < self.clearance)  # NaN compares False: off stage never conflicts
            if len(hit) and (best is None or lo + int(hit[0]) < best[0]):
                best = (lo + int(hit[0]), name)
        return best
