"""Place objects in a room so that every stated relation holds and nothing interpenetrates.

Objects joined by relations form a component, placed together: its root first (a wall-mounted object
when there is one, else the first object that rests on nothing), then the others breadth-first, each
through the relation that reaches it from an object already placed ("laptop on desk" from the desk;
"mirror near dresser" from the mirror as "dresser near mirror"). A candidate pose is kept when the
object stays inside the room, overlaps nothing placed before it (its support aside), rests inside its
support surface, and every relation to an already placed object holds. When no pose fits a member,
the component moves to the root's next candidate.

Determinism and locality: candidate lists come from each object's own generator (seeded by the
composition seed and its id), components are placed in document order, and a pose from the previous
scene is tried first, so an edit moves only the objects whose relations changed or that would now
collide.

Length: the search, its candidate order and its fallbacks share the layout's state and read as one
algorithm, so they stay in one module (the batched checks live in trials.py and collide.py).
"""

from __future__ import annotations

import hashlib
import itertools
import math
from collections import OrderedDict
from collections.abc import Callable, Container, Iterator, Sequence
from dataclasses import dataclass, field

import numpy as np

from proto.scene import PlacedObject
from proto.ssg import RelationNode
from services.retrieval.clearance import KeepClear, against_wall, along_walls, wall_of, wall_order
from services.retrieval.collide import ObstacleIndex
from services.retrieval.geometry import Footprint, extents, inside_room, surface_rects
from services.retrieval.placement import Candidate, Placed, mount_height, relation_candidates
from services.retrieval.screen import screen
from services.retrieval.trials import Trials

ROOT_CANDIDATES = 2000  # free poses tried per root
MEMBER_TRIES = 120  # candidate poses tried per member
SEARCH_BUDGET = 3000  # candidate poses evaluated per component before giving up
GRID_STEP = 0.25  # metres between free floor positions scanned for roots
INDEXES_KEPT = 16  # collision indexes kept per layout (sets of placed objects a search returns to)

# How tightly a relation pins its subject: the tightest are placed first, so that "right of the desk"
# takes the desk's right side before "next to the desk" has to choose one.
FLEXIBILITY: dict[str, int] = {
    "on": 0,
    "in": 0,
    "under": 0,
    "above": 0,
    "hanging_above": 0,
    "in_front_of": 1,
    "behind": 1,
    "left_of": 1,
    "right_of": 1,
    "around": 1,
    "facing": 2,
    "next_to": 2,
    "near": 3,
}

# Relation used to place the anchor from its subject when the subject is placed first.
PLACE_ANCHOR_FROM_SUBJECT: dict[str, str] = {
    "near": "near",
    "next_to": "next_to",
    "left_of": "right_of",
    "right_of": "left_of",
    "in_front_of": "behind",
    "behind": "in_front_of",
    "above": "under",
    "hanging_above": "under",
    "under": "above",
    "facing": "in_front_of",
}

Holds = Callable[[RelationNode, PlacedObject, PlacedObject], bool]


def object_seed(seed: int, object_id: str) -> int:
    """A stable 32-bit seed for one object (independent of every other object)."""
    digest = hashlib.sha1(f"{seed}:{object_id}".encode()).digest()
    return int.from_bytes(digest[:4], "little")


@dataclass
class Item:
    """One object to place (an instance of an SSG object node, or a context object)."""

    id: str
    category: str
    attributes: dict[str, str]
    variant_seed: int
    fp: Footprint
    order: int  # document order
    from_text: bool = True
    instance: int = 0  # copy number of a counted object
    previous: PlacedObject | None = None  # its placement in the previous scene, when comparable


@dataclass
class RoomBox:
    width: float
    depth: float
    height: float


@dataclass
class LayoutResult:
    placed: dict[str, Placed] = field(default_factory=dict)
    forced: list[str] = field(default_factory=list)  # ids placed without a valid pose
    crowded: bool = False  # some component found no free spot (a larger room could help)


def to_placed_object(p: Placed, item: Item) -> PlacedObject:
    return PlacedObject(
        id=p.id,
        category=item.category,
        attributes=dict(item.attributes),
        seed=item.variant_seed,
        position=(
            round(float(p.position[0]), 5),
            round(float(p.position[1]), 5),
            round(float(p.position[2]), 5),
        ),
        yaw=round(float(p.yaw), 6),
        support=p.support,
        from_text=item.from_text,
    )


class Layout:
    """Places components of items one after the other in one room."""

    def __init__(
        self, items: Sequence[Item], relations: Sequence[RelationNode], room: RoomBox, seed: int, holds: Holds
    ) -> None:
        self.items = {it.id: it for it in items}
        self.relations = [
            r
            for r in relations
            if r.subject in self.items and r.object in self.items and r.subject != r.object
        ]
        self.room = room
        self.seed = seed
        self.holds = holds
        self.result = LayoutResult()
        self.keep_clear: KeepClear | None = None  # set before placing context objects (clearance.py)
        self._placed_objects: dict[str, PlacedObject] = {}
        self._indexes: OrderedDict[tuple[int, ...], ObstacleIndex] = OrderedDict()
        self.touching: dict[str, list[RelationNode]] = {i: [] for i in self.items}
        for r in self.relations:
            self.touching[r.subject].append(r)
            self.touching[r.object].append(r)

    # -- components ------------------------------------------------------------------------------
    def components(self, ids: Sequence[str]) -> list[list[str]]:
        """Connected components over the relations, each in document order, ordered by first member."""
        wanted = set(ids)
        parent = {i: i for i in ids}

        def find(i: str) -> str:
            while parent[i] != i:
                parent[i] = parent[parent[i]]
                i = parent[i]
            return i

        for r in self.relations:
            if r.subject in wanted and r.object in wanted:
                parent[find(r.subject)] = find(r.object)
        groups: dict[str, list[str]] = {}
        for i in sorted(ids, key=lambda i: self.items[i].order):
            groups.setdefault(find(i), []).append(i)
        return list(groups.values())

    def _root(self, members: list[str]) -> str:
        supported = {r.subject for r in self.relations if r.relation in ("on", "in") and r.subject in members}
        walls = [m for m in members if self.items[m].fp.mount == "wall" and m not in supported]
        if walls:
            return walls[0]
        free = [m for m in members if m not in supported]
        anchors_only = [m for m in free if not any(r.subject == m for r in self.touching[m])]
        return (anchors_only or free or members)[0]

    # -- checks ----------------------------------------------------------------------------------
    def _placed_object(self, p: Placed) -> PlacedObject:
        return to_placed_object(p, self.items[p.id])

    def _fits(self, p: Placed, others: dict[str, Placed]) -> bool:
        """Inside the room and overlapping nothing placed (what it rests on, or rests on it, aside)."""
        return inside_room(p.box, self.room.width, self.room.depth, self.room.height) and (
            self._collider(p, others) is None
        )

    def _collider(self, p: Placed, others: dict[str, Placed]) -> str | None:
        """The first placed object p interpenetrates (its support aside), or None."""
        return self._obstacles(others).first_collider(p)

    def _obstacles(self, others: dict[str, Placed]) -> ObstacleIndex:
        """The collision index of these placed objects (rebuilt only when the set changes)."""
        key = tuple(map(id, others.values()))  # the index holds the objects, so ids stay unique
        index = self._indexes.get(key)
        if index is None:
            index = self._indexes[key] = ObstacleIndex(list(others.values()))
            if len(self._indexes) > INDEXES_KEPT:
                self._indexes.popitem(last=False)
        else:
            self._indexes.move_to_end(key)
        return index

    def _supported(self, p: Placed, others: dict[str, Placed]) -> bool:
        """A resting object stands on a support surface of its support, its centre over the surface."""
        if not p.support:
            return True
        support = others.get(p.support)
        if support is None:
            return False
        y = float(p.position[1])
        if (
            support.box[0, 1] < y < support.box[1, 1]
            and np.all(p.position[[0, 2]] >= support.box[0, [0, 2]])
            and np.all(p.position[[0, 2]] <= support.box[1, [0, 2]])
        ):
            return True  # inside its container
        for height, rect in surface_rects(support.fp, support.position, support.yaw):
            if (
                abs(height - y) < 0.02
                and np.all(p.position[[0, 2]] >= rect[0] - 0.01)
                and np.all(p.position[[0, 2]] <= rect[1] + 0.01)
            ):
                return True
        return False

    def _screened(self, p: Placed, others: dict[str, Placed]) -> bool:
        """The fast relation screen against every placed object p is related to."""
        for r in self.touching[p.id]:
            other = others.get(r.object if r.subject == p.id else r.subject)
            if other is not None and not (
                screen(r.relation, p, other) if r.subject == p.id else screen(r.relation, other, p)
            ):
                return False
        return True

    def _relations_hold(self, p: Placed, others: dict[str, Placed]) -> bool:
        """The exact predicates (wana.assets.relations) against every placed object p is related to."""
        mine = self._placed_object(p)
        for r in self.touching[p.id]:
            other_id = r.object if r.subject == p.id else r.subject
            other = others.get(other_id)
            if other is None:
                continue
            theirs = self._placed_object(other)
            subject, anchor = (mine, theirs) if r.subject == p.id else (theirs, mine)
            if not self.holds(r, subject, anchor):
                return False
        return True

    # -- candidates ------------------------------------------------------------------------------
    def _rng(self, object_id: str) -> np.random.Generator:
        return np.random.default_rng(object_seed(self.seed, object_id))

    def _previous(self, item: Item) -> Iterator[Candidate]:
        if item.previous is not None:
            pos = np.array(item.previous.position, dtype=np.float64)
            yield pos, float(item.previous.yaw), item.previous.support

    def _root_candidates(self, item: Item) -> Iterator[Candidate]:
        yield from self._previous(item)
        rng = self._rng(item.id)
        w, d, h = self.room.width, self.room.depth, self.room.height
        if item.fp.mount == "wall":
            y = mount_height(item.fp, h)
            # Walls: back (-Z, facing +Z), front (+Z), left (-X), right (+X).
            walls = [
                (0.0, -d / 2.0, 0.0, w),
                (math.pi, d / 2.0, 0.0, w),
                (math.pi / 2.0, -w / 2.0, 1.0, d),
                (-math.pi / 2.0, w / 2.0, 1.0, d),
            ]
            walls = [walls[i] for i in rng.permutation(4)]
            for yaw, plane, axis, length in walls:
                e = extents(item.fp, yaw)
                half = (e[1, 0] - e[0, 0]) / 2.0 if axis == 0.0 else (e[1, 2] - e[0, 2]) / 2.0
                room_half = length / 2.0 - half - 0.05
                if room_half < 0:
                    continue
                t0 = float(rng.uniform(-room_half, room_half) * 0.5)
                ts = [t0] + sorted(
                    np.arange(-room_half, room_half + 1e-9, GRID_STEP), key=lambda t: abs(t - t0)
                )
                for t in ts:
                    if axis == 0.0:  # on a wall of constant z: the back of the object on the wall
                        z = plane - e[0, 2] + 0.005 if plane < 0 else plane - e[1, 2] - 0.005
                        yield np.array([t, y, z]), yaw, ""
                    else:
                        x = plane - e[0, 0] + 0.005 if plane < 0 else plane - e[1, 0] - 0.005
                        yield np.array([x, y, t]), yaw, ""
            return
        if against_wall(item.fp, item.from_text):
            load = None if item.from_text else self._wall_load()
            yield from along_walls(item.fp, w, d, wall_order(rng, load), rng)
            if not item.from_text:
                return  # context furniture stands against a wall or not at all
        yaws = [float(rng.choice([0.0, math.pi / 2.0, math.pi, -math.pi / 2.0]))]
        yaws += [y for y in (0.0, math.pi, math.pi / 2.0, -math.pi / 2.0) if y != yaws[0]]
        x0 = float(rng.uniform(-w / 2.0, w / 2.0) * 0.5)
        z0 = float(rng.uniform(-d / 2.0, d / 2.0) * 0.5)
        xs = np.arange(-w / 2.0 + GRID_STEP, w / 2.0 - 1e-9, GRID_STEP)
        zs = np.arange(-d / 2.0 + GRID_STEP, d / 2.0 - 1e-9, GRID_STEP)
        grid = sorted(itertools.product(xs, zs), key=lambda q: ((q[0] - x0) ** 2 + (q[1] - z0) ** 2, q))
        for x, z in [(x0, z0), *grid]:
            for yaw in yaws:
                yield np.array([x, 0.0, z]), yaw, ""

    def _wall_load(self) -> dict[str, int]:
        """How many context objects already stand against each wall."""
        load: dict[str, int] = {}
        for p in self.result.placed.values():
            if not p.from_text and not p.support:
                wall = wall_of(p.box, self.room.width, self.room.depth)
                if wall:
                    load[wall] = load.get(wall, 0) + 1
        return load

    def _member_candidates(
        self, item: Item, via: RelationNode, placed: dict[str, Placed]
    ) -> Iterator[Candidate]:
        yield from self._previous(item)
        rng = self._rng(item.id)
        if via.subject == item.id:
            relation, anchor = via.relation, placed[via.object]
        else:
            relation, anchor = PLACE_ANCHOR_FROM_SUBJECT[via.relation], placed[via.subject]
        instance = item.instance
        if via.each and via.subject == item.id:
            # "a chair at each desk": the chair at desk 2 is the first at that desk (its front), not the second
            instance = sum(
                1
                for pid in placed
                if any(
                    r.subject == pid and r.object == via.object and r.relation == relation
                    for r in self.touching[pid]
                )
            )
        yield from relation_candidates(
            relation, item.fp, anchor, rng, room_height=self.room.height, instance=instance
        )

    # -- placement -------------------------------------------------------------------------------
    def _reach(self, placed: Container[str], pending: list[str]) -> tuple[str, RelationNode] | None:
        """The next member to place and the relation that places it (from its anchor first, then inverses)."""
        best: tuple[tuple[int, int, int], str, RelationNode] | None = None  # (flexibility, order, k)
        for m in pending:
            for k, r in enumerate(self.touching[m]):
                if r.subject == m and r.object in placed:
                    key = (FLEXIBILITY.get(r.relation, 3), self.items[m].order, k)
                elif r.object == m and r.subject in placed and r.relation in PLACE_ANCHOR_FROM_SUBJECT:
                    key = (FLEXIBILITY.get(r.relation, 3) + 1, self.items[m].order, k)
                else:
                    continue
                if best is None or key < best[0]:
                    best = (key, m, r)
        return None if best is None else (best[1], best[2])

    def _plan(self, members: list[str], placed: Container[str]) -> list[tuple[str, RelationNode | None]]:
        """The order members are placed in, each with the relation that places it (None: a free root)."""
        have = set(m for m in members if m in placed)
        pending = [m for m in members if m not in have]
        plan: list[tuple[str, RelationNode | None]] = []
        while pending:
            step = self._reach(_Union(have, placed), pending)
            if step is None:
                m = self._root(pending) if not plan else pending[0]
                plan.append((m, None))
            else:
                m = step[0]
                plan.append(step)
            have.add(m)
            pending.remove(m)
        return plan

    def _candidates(self, m: str, via: RelationNode | None, local: dict[str, Placed]) -> Iterator[Candidate]:
        item = self.items[m]
        if via is None:
            poses = self._root_candidates(item)
        else:
            poses = self._member_candidates(item, via, local)
        zones = self.keep_clear
        if zones is not None and not item.from_text and item.fp.mount != "wall":
            poses = (c for c in poses if c[2] or not zones.blocks(extents(item.fp, c[1]) + c[0]))
        return itertools.islice(poses, ROOT_CANDIDATES if via is None else MEMBER_TRIES)

    @property
    def room_size(self) -> tuple[float, float, float]:
        return self.room.width, self.room.depth, self.room.height

    def _trials(self, m: str, via: RelationNode | None, local: dict[str, Placed]) -> Trials:
        """A member's candidate poses with their verdicts (as _check gives them), checked in batches."""
        item = self.items[m]

        def make(pos: np.ndarray, yaw: float, support: str) -> Placed:
            return Placed(m, item.fp, pos, yaw, support, item.from_text)

        return Trials(self, self._candidates(m, via, local), make, local)

    def _check(self, p: Placed, local: dict[str, Placed]) -> tuple[str, str | None]:
        """("ok", None), or why not: ("room", None), ("relation", None), ("collision", the other id)."""
        if not inside_room(p.box, self.room.width, self.room.depth, self.room.height):
            return "room", None
        if not self._supported(p, local) or not self._screened(p, local):
            return "relation", None
        other = self._collider(p, local)
        if other is not None:
            return "collision", other
        return ("ok", None) if self._relations_hold(p, local) else ("relation", None)

    def _search(
        self, plan: list[tuple[str, RelationNode | None]], local: dict[str, Placed]
    ) -> tuple[bool, dict[str, Placed]]:
        """Depth-first search over the members' candidate poses with conflict-directed backjumping.

        When no pose of a member fits, the search jumps back to the latest member that blocked it
        (something it collided with, or the object it is placed from), not merely the previous one.

        Returns:
            (all placed, the deepest partial placement reached).
        """
        best: dict[str, Placed] = {}
        if not plan:
            return True, best
        level = {m: i for i, (m, _) in enumerate(plan)}
        gens = [self._trials(plan[0][0], plan[0][1], local)]
        blame: list[set[str]] = [set()]
        seen = [[False, False]]  # per level: a candidate inside the room, one keeping its relations
        evals = 0
        while gens:
            i = len(gens) - 1
            m, via = plan[i]
            found = None
            for p, (why, other) in gens[i]:
                evals += 1
                seen[i][0] |= why != "room"
                seen[i][1] |= why in ("ok", "collision")
                if why == "ok":
                    found = p
                    break
                if other is not None:
                    blame[i].add(other)
                elif why == "room" and i > 0:
                    blame[i].add(plan[0][0])  # the walls: where the whole component stands
                if evals >= SEARCH_BUDGET:
                    break
            if found is not None:
                local[m] = found
                if i + 1 > len(best):
                    best = {plan[k][0]: local[plan[k][0]] for k in range(i + 1)}
                if i + 1 == len(plan):
                    return True, best
                nm, nvia = plan[i + 1]
                gens.append(self._trials(nm, nvia, local))
                blame.append(set())
                seen.append([False, False])
                continue
            if evals >= SEARCH_BUDGET or (seen[i][0] and not seen[i][1] and via is not None):
                # Out of budget, or no pose keeps this member's relations wherever its anchor stands.
                return False, best
            if via is not None:
                blame[i].add(via.object if via.subject == m else via.subject)
            culprits = [level[c] for c in blame[i] if c in level and level[c] < i]
            if not culprits:
                return False, best  # only objects placed before this component block it
            j = max(culprits)
            carried = {c for c in blame[i] if c != plan[j][0]}
            while len(gens) > j + 1:
                gens.pop()
                blame.pop()
                seen.pop()
                local.pop(plan[len(gens)][0], None)
            local.pop(plan[j][0], None)
            blame[j] |= carried
        return False, best

    def place_component(self, members: list[str], *, optional: bool = False) -> bool:
        """Place one component; False (placing what it can unless optional) when no pose fits everything."""
        placed = self.result.placed
        local = dict(placed)
        plan = self._plan(members, placed)
        ok, best = self._search(plan, local)
        if ok:
            self._commit({m: local[m] for m, _ in plan})
            return True
        self.result.crowded = True
        if not optional:
            self._force(plan, best)
        return False

    def _commit(self, added: dict[str, Placed]) -> None:
        for k, v in added.items():
            self.result.placed[k] = v
            self._placed_objects[k] = self._placed_object(v)

    def _force(self, plan: list[tuple[str, RelationNode | None]], partial: dict[str, Placed]) -> None:
        """Keep the best partial placement; put each other member at its first pose that keeps its
        relations (overlaps allowed, reported), else at its first candidate."""
        local = dict(self.result.placed)
        local.update(partial)
        for m, via in plan:
            if m in local:
                continue
            item = self.items[m]
            first: Placed | None = None
            chosen: Placed | None = None
            for pos, yaw, support in self._candidates(m, via, local):
                p = Placed(m, item.fp, pos, yaw, support, item.from_text)
                first = first or p
                why, _ = self._check(p, local)
                if why == "ok":
                    chosen = p
                    break
                if why == "collision" and chosen is None:
                    chosen = p
            pick = chosen or first
            if pick is None:
                pos, yaw, support = next(self._root_candidates(item))
                pick = Placed(m, item.fp, pos, yaw, support, item.from_text)
            p = pick
            if self._check(p, local)[0] != "ok":
                self.result.forced.append(m)
            local[m] = p
            partial[m] = p
        self._commit(partial)


class _Union:
    """Membership in either of two containers (ids placed before, ids planned so far)."""

    def __init__(self, a: Container[str], b: Container[str]) -> None:
        self.a, self.b = a, b

    def __contains__(self, key: object) -> bool:
        return key in self.a or key in self.b
