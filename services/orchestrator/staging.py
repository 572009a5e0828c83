"""Who is on stage when, and where they stand before they act: the door, entrances, exits, starting spots.

A character is on stage from its first sentence only (`Motion.present`). One who "walks in" / "enters" /
"comes in" waits hidden outside the room and steps in at the door: it appears on the doorway's threshold
and walks into the room; one whose first sentence comes later in the story also comes in at the door rather
than popping up in the room; one who "leaves" / "goes out" walks to the door's threshold and is gone
afterwards. The catalog's door is a closed leaf in a solid wall, so walking through it would show a body
inside the door: the character is shown from the threshold on instead, and while hidden it waits outside
the room (its own place there, so hidden bodies never overlap). Characters on stage from the first frame start at free spots near where
they first act (the object their first action names, else around the room's middle), spread out, never in a
line. The room gets a door when its description has none (`with_door`), so every entrance has one.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import msgspec
import numpy as np

from proto.scene import PlacedObject, Scene
from proto.ssg import ActionNode
from wana.domain.object_geometry import scene_footprints
from wana.domain.routes import NoRouteError, OccupancyGrid, occupancy_grid, plan_route

ENTRANCE_VERBS = ("walk in", "enter", "come in", "run in", "step in", "burst in", "walk into", "come into")
EXIT_VERBS = ("leave", "go out", "walk out", "run out", "exit", "step out", "get out", "go away", "walk away")
DOOR_INSET = 0.085  # metres between a wall and a door's centre (a hung door's half depth and its gap)
DOOR_WIDTH = 0.95  # metres, the catalog door's width
OUTSIDE_M = 0.5  # metres outside the wall where a hidden character waits
QUEUE_M = 0.8  # metres between characters waiting outside one door
THRESHOLD_M = 0.45  # metres in front of the door where a character appears or disappears
IN_WALL_M = 0.35  # metres: a door whose centre is this close to a wall is in it
BESIDE_M = 0.6  # metres along the wall between characters coming in together
BODY_M = 0.3  # metres: a body's radius for the starting-spot grid
APART_M = 1.25  # metres between starting spots (two stretching side by side, arms out, still clear)
ROUTE_BODY_M = 0.25  # metres: a walking body's clearance (wana.domain.routes.plan_route's default)
STEP_OUT_CANDIDATES = 2000  # free points, nearest first, tried as where a boxed-in start steps out to
STEP_OUT_SAMPLES = 40  # points along each candidate step tested against the furniture
STEP_OUT_WEIGHT = 10.0  # metres of a longer step one metre less through furniture is worth


def _verb_is(action: ActionNode, verbs: tuple[str, ...]) -> bool:
    return _verb_in(action.verb, verbs)


@functools.lru_cache(maxsize=4096)
def _verb_in(verb: str, verbs: tuple[str, ...]) -> bool:
    """Whether ``verb`` (as written) is one of ``verbs`` or starts with one (asked for every action of the
    story on every compute: a long story asks the same few verbs thousands of times)."""
    verb = verb.lower()
    return any(verb == v or verb.startswith(v + " ") for v in verbs)


BARE_ENTRANCE_VERBS = ("come", "walk", "run", "step")  # "in" dropped by the parser: "Mary and John walk in"


def is_entrance(action: ActionNode) -> bool:
    """ "walks in", "enters", "comes in" (the verb as written; the action is usually plain "walk"), and a bare
    "come" / "walk" going nowhere named (the parser drops the particle of a plural: "Tom and Sam come in",
    "Mary and John walk in"; a walk to nowhere is a way onto the stage too), or only into the room itself
    ("Sam walks into the workshop": the parser keeps "walk" and the room as its destination)."""
    goals = [g for g in (action.target, action.destination, action.instrument) if g]
    bare = action.verb.lower() in BARE_ENTRANCE_VERBS and all(_is_room_word(g) for g in goals)
    return _verb_is(action, ENTRANCE_VERBS) or bare


def _is_room_word(ref: str) -> bool:
    """True for a word naming the room itself ("the workshop" in "Sam walks into the workshop")."""
    from wana.assets.vocabulary import ROOM_TYPES

    word = ref.split("#")[0].split("/")[0].replace("_", " ").lower()
    return word in ("room", "inside") or any(
        word == room.replace("_", " ") or word in synonyms for room, synonyms in ROOM_TYPES.items()
    )


def is_exit(action: ActionNode) -> bool:
    """ "leaves", "goes out", "walks out", "exits"."""
    return _verb_is(action, EXIT_VERBS)


@dataclass(frozen=True)
class Doorway:
    """A door in a wall: where it is on the floor and which way is into the room.

    Attributes:
        centre: (2,) x, z of the door, metres, world.
        inward: (2,) unit floor direction from the door into the room.
    """

    centre: np.ndarray
    inward: np.ndarray

    @property
    def yaw_in(self) -> float:
        """Facing into the room (radians about +Y, 0 faces +Z)."""
        return float(math.atan2(self.inward[0], self.inward[1]))

    def outside(self, i: int) -> tuple[float, float]:
        """Where the i-th hidden character waits, queued outward from the door."""
        p = self.centre - self.inward * (OUTSIDE_M + QUEUE_M * i)
        return float(p[0]), float(p[1])

    @property
    def along(self) -> np.ndarray:
        """(2,) unit floor direction along the door's wall."""
        return np.array([self.inward[1], -self.inward[0]])

    def inside(
        self, depth: float = THRESHOLD_M, beside: int = 0, spacing: float = BESIDE_M
    ) -> tuple[float, float]:
        """A point ``depth`` metres into the room from the door; ``beside`` steps of ``spacing`` along the wall
        (+1, -1, +2...)."""
        step = (beside + 1) // 2 * (1 if beside % 2 else -1) * spacing
        p = self.centre + self.inward * depth + self.along * step
        return float(p[0]), float(p[1])

    def side_of(self, xz: tuple[float, float]) -> float:
        """Metres along the wall from the door's centre to a floor point (signed, as ``inside`` steps)."""
        return float(np.dot(np.asarray(xz, float) - self.centre, self.along))

    def way_in(self, xz: tuple[float, float], depth: float = 1.6) -> tuple[float, float]:
        """Where one who came in at ``xz`` on the threshold heads first: ``depth`` into the room on its own side
        of the door (those who came in side by side stay side by side, APART_M apart, and never cross)."""
        offset = self.side_of(xz) * APART_M / BESIDE_M
        p = self.centre + self.inward * depth + self.along * offset
        return float(p[0]), float(p[1])


def _wall_normal(scene: Scene, xz: np.ndarray) -> np.ndarray:
    """The inward normal of the wall nearest to a floor point."""
    hw, hd = scene.room.width / 2, scene.room.depth / 2
    gaps = [hw + xz[0], hw - xz[0], hd + xz[1], hd - xz[1]]
    normals = [(1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)]
    return np.array(normals[int(np.argmin(gaps))])


AGAINST_WALL_M = 0.45  # metres from a wall to the centre of what stands against it (a cabinet, a sink)
WAY_IN_M = (0.4, 0.7, 1.0, 1.2)  # metres into the room from a door that a body must be able to stand at


def _way_in_clear(grid: OccupancyGrid, centre: np.ndarray, inward: np.ndarray) -> bool:
    """Whether a body fits on the floor straight in from a door (WAY_IN_M), clear of the furniture."""
    return all(bool(grid.is_free_xz(centre + inward * d)) for d in WAY_IN_M)


def _wall_doors(scene: Scene) -> list[Doorway]:
    hw, hd = scene.room.width / 2, scene.room.depth / 2
    out = []
    for o in scene.objects:
        if o.category == "door":
            xz = np.array([o.position[0], o.position[2]], float)
            if min(hw - abs(xz[0]), hd - abs(xz[1])) <= IN_WALL_M:
                out.append(Doorway(centre=xz, inward=_wall_normal(scene, xz)))
    return out


def doorway(scene: Scene) -> Doorway | None:
    """The room's first door in a wall whose way in is clear (else its first door in a wall), None when it
    has none (a door standing in the room is no way in). A context toilet in front of the bathroom's door
    had the sisters come in and go out through it (duo-bathroom-17 s6/s11, shins 15 cm in the toilet)."""
    doors = _wall_doors(scene)
    if len(doors) > 1:
        grid = _grid(scene, radius=0.25)
        return next((d for d in doors if _way_in_clear(grid, d.centre, d.inward)), doors[0])
    return doors[0] if doors else None


_GRIDS: dict[bytes, OccupancyGrid] = {}  # layout (room, objects) and radius -> its grid
_GRID_KEY = msgspec.msgpack.Encoder(order="deterministic")


def _grid(scene: Scene, radius: float = BODY_M) -> OccupancyGrid:
    """The floor's occupancy grid, rasterised once per layout (every motion stage run asks for it, and
    most edits leave the layout as it was)."""
    key = _GRID_KEY.encode([scene.room, scene.objects, radius])
    grid = _GRIDS.get(key)
    if grid is None:
        grid = occupancy_grid(scene.room, scene_footprints(scene), radius=radius, cell=0.05)
        grid.blocked.setflags(write=False)  # shared between calls: nobody may mark it
        if len(_GRIDS) >= 32:
            _GRIDS.clear()
        _GRIDS[key] = grid
    return grid


def with_door(scene: Scene) -> Scene:
    """The scene with a door, one added on the freest stretch of wall when the description named none or the
    doors it has are blocked (furniture in their way in).

    Candidates run along the four walls; the first whose way in (a body's width, 1.2 m deep) is clear of
    furniture and whose wall span holds no other wall object wins.
    """
    doors = _wall_doors(scene)
    grid = _grid(scene, radius=0.25)
    if any(_way_in_clear(grid, d.centre, d.inward) for d in doors):
        return scene
    room = scene.room
    hw, hd = room.width / 2, room.depth / 2
    wall_things = [np.array([o.position[0], o.position[2]]) for o in scene.objects if not o.support]
    candidates: list[tuple[np.ndarray, float]] = []
    for along in (0.0, 0.9, -0.9, 1.8, -1.8):
        for xz, yaw in (
            ((-hw + DOOR_INSET, along), math.pi / 2),
            ((hw - DOOR_INSET, along), -math.pi / 2),
            ((along, hd - DOOR_INSET), math.pi),
            ((along, -hd + DOOR_INSET), 0.0),
        ):
            p = np.array(xz, float)
            if abs(p[0]) > hw - 0.6 and abs(p[1]) > hd - 0.6:
                continue  # too near a corner
            candidates.append((p, yaw))
    best = candidates[0]
    for p, yaw in candidates:
        inward = np.array([math.sin(yaw), math.cos(yaw)])
        clear = _way_in_clear(grid, p, inward)
        # what stands on or against that stretch of wall (a mirror, a cabinet), not what stands out in the
        # room beside it (a toilet whose way is the door's way in is already not clear)
        crowded = any(
            np.linalg.norm(p - q) < DOOR_WIDTH and float(inward @ (q - p)) < AGAINST_WALL_M
            for q in wall_things
        )
        if clear and not crowded:
            best = (p, yaw)
            break
    else:
        if doors:
            return scene  # the door there is blocked, and no wall has a clear stretch for another
    p, yaw = best
    ids = {o.id for o in scene.objects}
    door = PlacedObject(
        id=next(f"door#{i}" for i in range(2, len(ids) + 3) if f"door#{i}" not in ids)
        if "door" in ids
        else "door",
        category="door",
        position=(float(p[0]), 0.0, float(p[1])),
        yaw=yaw,
        from_text=False,
    )
    return msgspec.structs.replace(scene, objects=[*scene.objects, door])


def _free(grid: OccupancyGrid, xz: np.ndarray, taken: Sequence[np.ndarray]) -> bool:
    return bool(grid.is_free_xz(xz)) and all(np.linalg.norm(xz - t) >= APART_M for t in taken)


def spot_near(
    scene: Scene,
    around: tuple[float, float],
    taken: Sequence[tuple[float, float]],
    radii: Sequence[float] = (1.1, 1.5, 2.0, 0.7),
) -> tuple[float, float, float]:
    """A free standing spot (x, z, yaw facing ``around``) near a point, at least APART_M from the taken ones.

    Rings round the point are tried from the side facing the room's middle outwards; with nothing free
    anywhere, the point nearest the room's middle that is free at all.
    """
    grid = _grid(scene)
    centre = np.asarray(around, float)
    others = [np.asarray(t, float) for t in taken]
    towards_middle = math.atan2(-centre[0], -centre[1]) if np.linalg.norm(centre) > 1e-6 else 0.0
    for r in radii:
        for step in range(16):
            turn = (step + 1) // 2 * (1 if step % 2 else -1) * math.pi / 8
            a = towards_middle + turn
            p = centre + r * np.array([math.sin(a), math.cos(a)])
            if _free(grid, p, others):
                yaw = math.atan2(centre[0] - p[0], centre[1] - p[1])
                return round(float(p[0]), 3), round(float(p[1]), 3), round(yaw, 3)
    free = np.argwhere(~grid.blocked)
    if len(free):
        pts = grid.to_world(free)
        p = pts[int(np.argmin(np.linalg.norm(pts, axis=1)))]
        return round(float(p[0]), 3), round(float(p[1]), 3), 0.0
    return 0.0, 0.0, 0.0


def kept_clear(
    scene: Scene,
    starts: dict[str, tuple[float, float, float]],
    hidden: Sequence[str] = (),
) -> dict[str, tuple[float, float, float]]:
    """The starting spots with each one furniture now covers moved to the nearest free one, facing as before.

    Starts are picked on the composed layout, before the optimiser moves furniture round the interactions; a
    table slid onto a spot would have the character stand inside it on the first frames. Spots still free, and
    those of the characters waiting ``hidden`` outside the door, stay as they are; a moved one keeps APART_M
    from the others when the room has such a spot, else takes the nearest free one.
    """
    grid = _grid(scene)
    free = np.argwhere(~grid.blocked)
    out = dict(starts)
    if not len(free):
        return out
    cells = grid.to_world(free)
    for name, (x, z, yaw) in starts.items():
        xz = np.array([x, z], float)
        if name in hidden or grid.is_free_xz(xz):
            continue
        taken = [np.array(out[n][:2], float) for n in out if n != name and n not in hidden]
        order = np.argsort(np.linalg.norm(cells - xz, axis=1), kind="stable")
        apart = (i for i in order[:4000] if all(np.linalg.norm(cells[i] - t) >= APART_M for t in taken))
        p = cells[next(apart, order[0])]  # the first one apart: the rest need not be tested
        out[name] = (round(float(p[0]), 3), round(float(p[1]), 3), yaw)
    return out


def _object_xz(scene: Scene, ref: str) -> tuple[float, float] | None:
    for o in scene.objects:
        if ref and (o.id == ref or o.category == ref or o.id.split("/")[0].split("#")[0] == ref):
            return float(o.position[0]), float(o.position[2])
    return None


def first_spot(
    scene: Scene, action: ActionNode | None, taken: Sequence[tuple[float, float]]
) -> tuple[float, float, float]:
    """Where a character on stage from the first frame stands: near what its first action names, else
    around the room's middle."""
    refs = [] if action is None else [action.target, action.instrument, action.destination]
    for ref in refs:
        xz = _object_xz(scene, ref)
        if xz is not None:
            return spot_near(scene, xz, taken)
    return spot_near(scene, (0.0, 0.0), taken, radii=(0.0, 0.9, 1.4, 1.9))


def route(
    scene: Scene,
    start: tuple[float, float],
    goal: tuple[float, float],
    bodies: Sequence[tuple[float, float]] = (),
) -> list[tuple[float, float]]:
    """A* waypoints around the furniture and the other characters standing at ``bodies`` (around the
    furniture alone where the others close the way; the straight line where nothing is open)."""
    points: list[tuple[float, float]] = [start, goal]
    for around in (list(bodies), []):
        try:
            found = plan_route(scene, np.array(start), np.array(goal), bodies=around)
            points = [(float(p[0]), float(p[1])) for p in found]
            break
        except NoRouteError:
            continue
    else:
        points = _stepped_out(scene, start, goal) or points
    return _dedupe([start, *points[1:]])


def _stepped_out(
    scene: Scene, start: tuple[float, float], goal: tuple[float, float]
) -> list[tuple[float, float]] | None:
    """A route for a start boxed in by furniture (got up from a chair hemmed in between a table, another
    chair and the wall): the short step out to the nearest free point from which the goal is reachable, then
    the route from there; None when no free point reaches the goal. Better than the straight line to the
    goal, which crosses the room through the table."""
    from scipy import ndimage

    grid = occupancy_grid(scene.room, scene_footprints(scene), radius=ROUTE_BODY_M, cell=0.05)
    labels, _ = ndimage.label(~grid.blocked)
    g_rc = grid.to_cell(np.asarray(goal, float))
    if grid.blocked[g_rc[0], g_rc[1]]:
        return None
    here = np.asarray(start, float)
    pts = grid.to_world(np.argwhere(labels == labels[g_rc[0], g_rc[1]]))
    away = np.linalg.norm(pts - here, axis=1)
    near = np.argsort(away, kind="stable")[:STEP_OUT_CANDIDATES]
    # the step that crosses the least furniture (its own footprints, no clearance), then the shortest
    solid = occupancy_grid(scene.room, scene_footprints(scene), radius=0.0, cell=0.05)
    t = np.linspace(0.0, 1.0, STEP_OUT_SAMPLES)
    ways = here + t[None, :, None] * (pts[near][:, None] - here)  # (C, S, 2)
    inside = (~solid.is_free_xz(ways)).mean(axis=1) * away[near]
    out = pts[near[int(np.argmin(inside * STEP_OUT_WEIGHT + away[near]))]]
    try:
        found = plan_route(scene, out, np.asarray(goal, float))
    except NoRouteError:
        return None
    return [start, *((float(p[0]), float(p[1])) for p in found)]


def _dedupe(points: Sequence[tuple[float, float]]) -> list[tuple[float, float]]:
    out: list[tuple[float, float]] = []
    for p in points:
        q = (round(float(p[0]), 4), round(float(p[1]), 4))
        if not out or math.hypot(q[0] - out[-1][0], q[1] - out[-1][1]) > 0.02:
            out.append(q)
    if len(out) == 1:
        out.append(out[0])
    return out


def presence(
    frames: int,
    starts: Sequence[int],
    lengths: Sequence[int],
    actions: Sequence[ActionNode],
    on_at_zero: bool,
) -> np.ndarray:
    """(frames,) uint8: 1 while the character is on stage.

    On from its first action (or from frame 0 for a character on stage from the start), off after an exit
    action ends, on again at a later entrance or any action after an exit.
    """
    out = np.zeros(frames, np.uint8)
    on_from: int | None = 0 if on_at_zero else None
    for start, length, action in zip(starts, lengths, actions, strict=True):
        if on_from is None:
            on_from = start
        if is_exit(action):
            out[on_from : start + length] = 1
            on_from = None
    if on_from is not None:
        out[on_from:] = 1
    return out


__all__ = [
    "Doorway",
    "doorway",
    "first_spot",
    "is_entrance",
    "is_exit",
    "kept_clear",
    "presence",
    "route",
    "spot_near",
    "with_door",
]
