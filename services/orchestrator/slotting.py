"""Each character its own slot: which cushion of the sofa, which chair of the table, which spot at the counter.

The motion stage walks the story's actions in order and asks `claim` for each: an action that sits or lies
on an object takes a free seat slot of it (wana.domain.slots), else a free one of another object of the
same kind (a second chair); an action at an object, or a walk to one, takes a free stand slot there. A
character keeps its slot until it walks, stands up or leaves. What it took goes to the motion service as
`SynthesizeRequest.seats` / `spots`; the first slot, the one the planner takes by itself, is left unsaid so
that a story with one character per object plans as before.
"""

from __future__ import annotations

import hashlib
from collections import OrderedDict
from collections.abc import Sequence
from dataclasses import dataclass, field
from itertools import permutations

import msgspec
import numpy as np

from proto.scene import PlacedObject, Scene
from proto.ssg import ActionNode
from wana.assets.relations import footprint_gap
from wana.domain.actions import ActionClip, get_clip
from wana.domain.hiding import HIDE_ACTIONS, hiding_spots
from wana.domain.object_geometry import find_object, scene_footprints
from wana.domain.routes import OccupancyGrid, occupancy_grid
from wana.domain.slots import SlotBook, seat_slots, stand_slots

LYING = ("lie_down", "sleep")
AROUND_M = 1.6  # metres: the seats "at" a table are within this of its middle
AT_GAP_M = 1.0  # ... or within this of its footprint (as "near"): the ends of a long table
RING_M = 0.45  # metres from an object's centre at most for a stand spot round it
CLEAR_M = 0.75  # metres from a bystander's hips within which a stand slot is not clear (arms that move)
ELBOW_M = 0.7  # metres between two sitters' hips below which their arms and shoulders touch
KNEE_OUT_M = 0.5  # metres in front of a seat's hips point where a sitter's knees and feet are
KNEE_M = 0.4  # metres between two sitters' knee points below which their legs meet (a table's corner)
MAX_ROWS = 4  # rows of stand slots at most (a crowd at a window whose front is behind a sofa)
# spots side by side in a row at least, when as many stand at one object (beyond its width: the second of
# two at a painting stood in the row behind, 1.1 m from it, duo-gallery-15 s4)
MAX_ACROSS = 3
STAND_KEY = "#stand"  # a stand slot's object key in the book: "<object id>#stand"
HIDE_KEY = "#hide"  # a hiding spot's object key in the book


@dataclass
class Claim:
    """What one action was given: the action (retargeted to another seat when its own was full), and its
    seat (a contact point name) or stand spot (x, z) when it is not the planner's default."""

    action: ActionNode
    seat: str = ""
    spot: tuple[float, float] | None = None


def _clip(action: ActionNode) -> ActionClip | None:
    try:
        return get_clip(action.action or action.verb)
    except KeyError:
        return None


@dataclass
class Slotting:
    """The slot book of one pass over the story, with the grid that says which stand spots are free."""

    scene: Scene
    book: SlotBook = field(default_factory=SlotBook)
    sitters: dict[str, set[str]] = field(default_factory=dict)  # object id -> who sits on it in the story
    standers: dict[str, set[str]] = field(default_factory=dict)  # object id -> who stands at it in the story
    _grid: OccupancyGrid | None = None
    _regions: np.ndarray | None = None  # labels of the connected free floor of the grid (0: blocked)
    _spots: dict[tuple[str, int, int], tuple[list[tuple[float, float]], set[tuple[float, float]]]] = field(
        default_factory=dict
    )

    def expect(self, who: str, action: ActionNode) -> None:
        """Note, before the story is planned, that ``who`` sits on or stands at the object ``action`` names: a
        sofa that two will share seats them apart (its end cushions), not side by side in the middle, and a
        counter two will stand at gives each its own stand slot."""
        clip = _clip(action)
        if clip is None:
            return
        kind = clip.interaction.object if clip.interaction is not None else ""
        if kind in ("seat", "bed"):
            obj = find_object(self.scene, action.target or action.instrument or action.destination)
            if obj is not None:
                self.sitters.setdefault(obj.id, set()).add(who)
            return
        if "locomotion" in clip.tags:
            obj = find_object(self.scene, action.destination or action.target)
        elif kind and kind not in ("handheld", "person"):
            obj = find_object(self.scene, action.target or action.instrument or action.destination)
        else:
            obj = None
        if obj is not None:
            self.standers.setdefault(obj.id, set()).add(who)

    @property
    def grid(self) -> OccupancyGrid:
        if self._grid is None:
            self._grid = _stand_grid(self.scene)
        return self._grid

    def claim(
        self,
        who: str,
        action: ActionNode,
        here: tuple[float, float] | None = None,
        company: Sequence[tuple[float, float]] = (),
        crowd: Sequence[tuple[float, float]] = (),
        joined: bool = False,
    ) -> Claim:
        """The slot ``who`` takes for ``action`` (or gives back), in story order.

        ``here``: where ``who`` is when the action starts; ``company``: where the others are who go to the same
        object in the same sentence and claim after it ("They walk to the statue"). With company the slots are
        shared out so that the walks, together, are shortest (`matched`): such paths never cross, so two
        walking side by side stay side by side instead of walking through each other to swapped slots.
        ``crowd``: where the others on stage stand; a stand slot within CLEAR_M of one is taken last.
        ``joined``: others of the sentence went to the same object before it: the last of them to claim takes
        the free slot nearest to it (what the shortest sharing-out left it), not the first free one.
        """
        clip = _clip(action)
        if clip is None:
            return Claim(action)
        kind = clip.interaction.object if clip.interaction is not None else ""
        if kind in ("seat", "bed"):
            return self._seat(who, action, "lie" if clip.name in LYING else "sit", here, company, joined)
        if "locomotion" in clip.tags:
            obj = find_object(self.scene, action.destination or action.target)
            if obj is None:
                self.book.release(who)
                return Claim(action)
            obj, action = self._reachable_copy(obj, action, here)
            return self._stand(who, action, obj, here, company, crowd, joined)
        if kind and kind not in ("handheld", "person"):
            obj = find_object(self.scene, action.target or action.instrument or action.destination)
            if obj is not None:
                return self._stand(who, action, obj, here, company, crowd, joined)
        if clip.name in HIDE_ACTIONS:
            obj = find_object(self.scene, action.target or action.destination)
            if obj is not None:
                return self._hide(who, action, obj, here, company, joined)
        if clip.name == "stand":
            self.book.release(who)
        return Claim(action)

    def _reachable_copy(
        self, obj: PlacedObject, action: ActionNode, here: tuple[float, float] | None
    ) -> tuple[PlacedObject, ActionNode]:
        """The copy of a multiplied object ("Eight chairs are around the table": chair, chair/2, ...) a walk to
        "a chair" goes to: the one named while it can be walked to from ``here``, else the nearest that can.

        The sentence names the group, which the scene resolves to its first copy; on the far side of a long
        table ringed with chairs that copy has no way to it, and the walk went straight through the table
        (solo-meeting_room-18 s10: the belly 13 cm inside it) while a chair stood free on the walker's side.
        """
        if here is None or "/" in obj.id:
            return obj, action
        copies = [o for o in self.scene.objects if o.id.startswith(obj.id + "/")]
        if not copies:
            return obj, action
        start = self._region(here)
        if start == 0 or self._region_of(obj) == start:
            return obj, action
        at = np.asarray(here, float)
        for other in sorted(
            copies, key=lambda o: float(np.hypot(o.position[0] - at[0], o.position[2] - at[1]))
        ):
            if self._region_of(other) == start:
                field_name = "destination" if action.destination and not action.target else "target"
                return other, msgspec.structs.replace(action, **{field_name: other.id})
        return obj, action

    def _region(self, xz: tuple[float, float] | np.ndarray) -> int:
        """The label of the connected free floor ``xz`` is on (the nearest free cell's; 0: no free floor)."""
        if self._regions is None:
            from scipy import ndimage

            self._regions = ndimage.label(~self.grid.blocked)[0]
        rc = self.grid.to_cell(np.asarray(xz, float))
        free = np.argwhere(self._regions > 0)
        if not len(free):
            return 0
        r, c = int(rc[0]), int(rc[1])
        if 0 <= r < self._regions.shape[0] and 0 <= c < self._regions.shape[1] and self._regions[r, c]:
            return int(self._regions[r, c])
        near = free[int(np.argmin(np.sum((free - np.array([r, c])) ** 2, axis=1)))]
        return int(self._regions[near[0], near[1]])

    def _region_of(self, obj: PlacedObject) -> int:
        """The floor region of an object's free stand spot, else of the free floor nearest the object (a chair's
        spot in front of it is under the table it is tucked in at)."""
        spots = [p for p in stand_slots(obj) if bool(self.grid.is_free_xz(np.asarray(p)))]
        return self._region(spots[0] if spots else (obj.position[0], obj.position[2]))

    def _hide(
        self,
        who: str,
        action: ActionNode,
        obj: PlacedObject,
        here: tuple[float, float] | None,
        company: Sequence[tuple[float, float]],
        joined: bool = False,
    ) -> Claim:
        """A spot of its own to hide at by ``obj`` (wana.domain.hiding): two hiding behind one door take its
        two sides."""
        spots = hiding_spots(obj, self.scene, need=1 + len(company))
        if not spots:
            return Claim(action)
        names = [str(i) for i in range(len(spots))]
        order = self._preferred(obj.id + HIDE_KEY, names, spots, who, here, company, joined)
        taken = self.book.take(obj.id + HIDE_KEY, order, who)
        return Claim(action) if taken is None else Claim(action, spot=spots[int(taken)])

    def _preferred(
        self,
        object_id: str,
        slots: list[str],
        where: Sequence[tuple[float, float]],
        who: str,
        here: tuple[float, float] | None,
        company: Sequence[tuple[float, float]],
        joined: bool = False,
    ) -> list[str]:
        """``slots`` with the one `matched` gives ``who`` first (unchanged when it goes there alone)."""
        if here is None or not (company or joined):
            return slots
        free = [i for i, n in enumerate(slots) if self.book.holder(object_id, n) in ("", who)]
        pick = matched([here, *company], [where[i] for i in free])
        if pick is None:
            return slots
        first = slots[free[pick]]
        return [first, *(n for n in slots if n != first)]

    def _seat(
        self,
        who: str,
        action: ActionNode,
        kind: str,
        here: tuple[float, float] | None = None,
        company: Sequence[tuple[float, float]] = (),
        joined: bool = False,
    ) -> Claim:
        obj = find_object(self.scene, action.target or action.instrument or action.destination)
        if obj is None:
            return Claim(action)
        every = seat_slots(obj, kind)
        if not every:  # "sits at the table": a free seat around it
            return self._seat_at(who, action, obj, kind, here, company, joined)
        default = every[0]  # what the planner takes by itself
        slots = seat_slots(obj, kind, self.scene.objects)  # those no prop rests on
        rest: list[str] = []
        if len(self.sitters.get(obj.id, ())) == 2 and len(slots) >= 3:
            # two on three cushions: the ends, with the middle between them
            slots, rest = slots[1:], slots[:1]
        slots = [*self._preferred(obj.id, slots, seat_points(obj, slots), who, here, company, joined), *rest]
        if kind == "sit":
            slots, beside = self._roomy_cushion(who, action, obj, slots)
            if beside is not None:
                return beside
        taken = self.book.take(obj.id, slots, who)
        if taken is not None:
            return Claim(action, seat="" if taken == default else taken)
        # Full: the nearest object of the same kind with a free slot (a second chair at the table).
        at = np.array([obj.position[0], obj.position[2]])
        same = sorted(
            (o for o in self.scene.objects if o.category == obj.category and o.id != obj.id),
            key=lambda o: float(np.linalg.norm(np.array([o.position[0], o.position[2]]) - at)),
        )
        for other in same:
            slots = seat_slots(other, kind, self.scene.objects)
            taken = self.book.take(other.id, slots, who) if slots else None
            if taken is not None:
                moved = msgspec.structs.replace(action, target=other.id) if action.target else action
                if not action.target:
                    moved = msgspec.structs.replace(action, destination=other.id)
                return Claim(moved, seat="" if taken == seat_slots(other, kind)[0] else taken)
        return Claim(action)

    def _roomy_cushion(
        self, who: str, action: ActionNode, obj: PlacedObject, slots: list[str]
    ) -> tuple[list[str], Claim | None]:
        """``slots`` with a free one that is not within ELBOW_M of another sitter's hips first, or, when every
        free one is (a lamp on the sofa's third cushion leaves two side by side), a roomy seat of another
        object of its kind beside it (a second bench, within AT_GAP_M: "sits on the bench" still holds) when
        there is one; else ``slots`` as they were (an armchair is not the sofa the sentence names)."""
        held = self._held_points(who)
        free = [n for n in slots if self.book.holder(obj.id, n) in ("", who)]
        if not held or not free or _roomy(seat_points(obj, free[:1])[0], held):
            return slots, None
        roomy = [n for n in free if _roomy(seat_points(obj, [n])[0], held)]
        if roomy:
            return [roomy[0], *(n for n in slots if n != roomy[0])], None
        beside = sorted(
            (
                (_gap_to(o, obj), o)
                for o in self.scene.objects
                if o.id != obj.id and o.category == obj.category and _gap_to(o, obj) <= AT_GAP_M
            ),
            key=lambda g_o: g_o[0],
        )
        for _, other in beside:
            names = seat_slots(other, "sit", self.scene.objects)
            open_slots = [n for n in names if self.book.holder(other.id, n) in ("", who)]
            pick = next((n for n in open_slots if _roomy(seat_points(other, [n])[0], held)), None)
            if pick is None or self.book.take(other.id, [pick], who) is None:
                continue
            field_name = "destination" if action.destination and not action.target else "target"
            moved = msgspec.structs.replace(action, **{field_name: other.id})
            return slots, Claim(moved, seat="" if pick == seat_slots(other, "sit")[0] else pick)
        return slots, None

    def _seat_at(
        self,
        who: str,
        action: ActionNode,
        obj: PlacedObject,
        kind: str,
        here: tuple[float, float] | None = None,
        company: Sequence[tuple[float, float]] = (),
        joined: bool = False,
    ) -> Claim:
        """A free seat slot of the seats at an object that has none itself (a table): within AROUND_M of its
        middle or AT_GAP_M of its footprint.

        Seats whose slot is within ELBOW_M of one another already holds, or whose knees (KNEE_OUT_M in front
        of it) are within KNEE_M of theirs, are passed over while others are free (two chairs pushed together
        seat two people shoulder in shoulder; two chairs at a table's corner, legs in legs), and with company
        the seats are shared out as `matched` says (walks to them do not cross)."""
        here_xz = np.array([obj.position[0], obj.position[2]])
        near = sorted(
            (
                (float(np.linalg.norm(np.array([o.position[0], o.position[2]]) - here_xz)), o)
                for o in self.scene.objects
                if o.id != obj.id and not o.support
            ),
            key=lambda d_o: d_o[0],
        )
        # beyond AROUND_M of its middle, a seat whose footprint is within AT_GAP_M of the table's is at it
        # too (a chair at the end of a long conference table), when none nearer is free
        far = sorted(((_gap_to(o, obj), o) for d, o in near if d > AROUND_M), key=lambda g_o: g_o[0])

        def free_of(
            seats: list[PlacedObject],
        ) -> list[tuple[PlacedObject, list[str], tuple[float, float], str]]:
            out = []
            for seat in seats:
                slots = seat_slots(seat, kind, self.scene.objects)
                open_slots = [n for n in slots if self.book.holder(seat.id, n) in ("", who)]
                if open_slots:
                    out.append((seat, slots, seat_points(seat, open_slots[:1])[0], open_slots[0]))
            return out

        free = free_of([o for d, o in near if d <= AROUND_M]) or free_of([o for g, o in far if g <= AT_GAP_M])
        held, knees = self._held_points(who), self._held_points(who, KNEE_OUT_M)
        roomy = [
            f
            for f in free
            if _roomy(f[2], held) and _roomy(seat_points(f[0], [f[3]], KNEE_OUT_M)[0], knees, KNEE_M)
        ]
        free = roomy + [f for f in free if f not in roomy]
        if here is not None and (company or joined):
            pick = matched([here, *company], [f[2] for f in roomy]) if len(roomy) > len(company) else None
            pick = pick if pick is not None else matched([here, *company], [f[2] for f in free])
            if pick is not None:
                free.insert(0, free.pop(pick))
        for seat, slots, _, _ in free:
            taken = self.book.take(seat.id, slots, who)
            if taken is not None:
                field_name = (
                    "target" if action.target == obj.id or action.target == obj.category else "destination"
                )
                moved = msgspec.structs.replace(action, **{field_name: seat.id})
                return Claim(moved, seat="" if taken == seat_slots(seat, kind)[0] else taken)
        return Claim(action)

    def _held_points(self, who: str, forward: float = 0.0) -> list[tuple[float, float]]:
        """World (x, z) of the seat slots the others hold now (``forward`` metres in front of them: their
        knees)."""
        out: list[tuple[float, float]] = []
        ids = {o.id: o for o in self.scene.objects}
        for (object_id, slot), holder in self.book.held.items():
            if holder == who or object_id not in ids or object_id.endswith(STAND_KEY):
                continue
            try:
                out.extend(seat_points(ids[object_id], [slot], forward))
            except (KeyError, ValueError):
                continue
        return out

    def _stand(
        self,
        who: str,
        action: ActionNode,
        obj: PlacedObject,
        here: tuple[float, float] | None = None,
        company: Sequence[tuple[float, float]] = (),
        crowd: Sequence[tuple[float, float]] = (),
        joined: bool = False,
    ) -> Claim:
        rows, standers = 2, len(self.standers.get(obj.id, set()) | {who})
        across = min(standers, MAX_ACROSS)  # several at it: side by side in the front row first
        spots, front = self._stand_spots(obj, rows, across)
        while standers >= 2 and len(spots) < standers and rows < MAX_ROWS:
            rows += 1  # ... then rows further out until each has its own free spot
            spots, front = self._stand_spots(obj, rows, across)
        reach = [p for p in spots if p in front]
        if crowd and reach and all(_near_any(p, crowd) for p in reach):  # bystanders there: round the object
            spots = [*reach, *self._ring(obj, reach[0]), *(p for p in spots if p not in front)]
        names = [str(i) for i in range(len(spots))]
        # shared out over the front row when it has room for the whole group (the shortest walks would send
        # one to the nearer row behind it), else over every row
        row = [n for n in names if spots[int(n)] in front]
        if sum(self.book.holder(obj.id + STAND_KEY, n) in ("", who) for n in row) < 1 + len(company):
            row = names
        order = self._preferred(
            obj.id + STAND_KEY, row, [spots[int(n)] for n in row], who, here, company, joined
        )
        order = [*order, *(n for n in names if n not in order)]
        seated = self._seats_of_others(who, obj)
        clear = [n for n in order if not _near_any(spots[int(n)], [*crowd, *seated])]
        order = [*clear, *(n for n in order if n not in clear)]
        taken = self.book.take(obj.id + STAND_KEY, order, who)
        if taken is None or (
            taken == names[0]
            and len(self.standers.get(obj.id, ())) < 2
            and not _near_any(spots[0], crowd)
            and not _near_any(_own_stand_point(obj, spots[0]), seated)
        ):
            return Claim(action)
        # Two or more at one object: the first is told its slot too (the planner's own spot, the middle of
        # the front, would stand between the first two slots, within a body of the second); one whose
        # default spot is where someone else stands is sent to a clear one.
        return Claim(action, spot=spots[int(taken)])

    def _seats_of_others(self, who: str, obj: PlacedObject) -> list[tuple[float, float]]:
        """World (x, z) of the seat slots of the objects others sit on in the story (those of ``obj`` itself
        aside): a stand spot there is in the way of one sitting down (Hana at the counter between the two
        stools, and Kofi's hand in her as he sat on one, bakery s6)."""
        ids = {o.id: o for o in self.scene.objects}
        out: list[tuple[float, float]] = []
        for object_id, sitters in self.sitters.items():
            if object_id == obj.id or object_id not in ids or not sitters - {who}:
                continue
            try:
                out.extend(seat_points(ids[object_id], seat_slots(ids[object_id])))
            except (KeyError, ValueError):
                continue
        return out

    def _stand_spots(
        self, obj: PlacedObject, rows: int = 2, across: int = 1
    ) -> tuple[list[tuple[float, float]], set[tuple[float, float]]]:
        """The free stand spots at ``obj`` in ``rows`` rows of at least ``across`` (its first spot when none is
        free) and its first row (within reach), worked out once per object, rows and across: the layout and
        the grid do not change while the story runs."""
        key = (obj.id, rows, across)
        if key not in self._spots:
            every = stand_slots(obj, rows=rows, across=across)
            spots = [p for p in every if bool(self.grid.is_free_xz(np.asarray(p)))]
            self._spots[key] = (spots or stand_slots(obj)[:1], set(stand_slots(obj, across=across)))
        spots, front = self._spots[key]
        return list(spots), front

    def _ring(self, obj: PlacedObject, front: tuple[float, float]) -> list[tuple[float, float]]:
        """Free stand spots round an object, as far from it as its front spot (RING_M at most: within reach of
        a small thing), every 45 degrees."""
        centre = np.array([obj.position[0], obj.position[2]], float)
        d = np.asarray(front, float) - centre
        r, a0 = min(float(np.linalg.norm(d)), RING_M), float(np.arctan2(d[0], d[1]))
        try:  # as far as the planner's own stand point (the catalog's), where the clip's reach fits
            from wana.assets.catalog import asset_for, to_world

            stand = to_world(obj, np.asarray(asset_for(obj).stand_point, float))
            r = min(r, float(np.hypot(stand[0] - centre[0], stand[2] - centre[1])))
        except Exception:  # noqa: BLE001 - an unknown category: the front spot's distance
            pass
        out = []
        for k in (1, -1, 2, -2, 3, -3, 4):
            a = a0 + k * np.pi / 4
            p = centre + r * np.array([np.sin(a), np.cos(a)])
            if bool(self.grid.is_free_xz(p)):
                out.append((round(float(p[0]), 3), round(float(p[1]), 3)))
        return out


def _own_stand_point(obj: PlacedObject, fallback: tuple[float, float]) -> tuple[float, float]:
    """World (x, z) where the motion service stands at ``obj`` by itself (the catalog's stand point), else
    ``fallback``."""
    try:
        from wana.assets.catalog import asset_for, to_world

        stand = to_world(obj, np.asarray(asset_for(obj).stand_point, float))
    except Exception:  # noqa: BLE001 - an unknown category: the first stand spot
        return fallback
    return (float(stand[0]), float(stand[2]))


def _gap_to(seat: PlacedObject, table: PlacedObject) -> float:
    """Metres between two objects' footprints (their centres' distance for an unknown category)."""
    try:
        return footprint_gap(seat, table)
    except KeyError:  # no catalog entry: the centres stand for them
        return float(np.hypot(seat.position[0] - table.position[0], seat.position[2] - table.position[2]))


def _roomy(p: tuple[float, float], others: Sequence[tuple[float, float]], apart: float = ELBOW_M) -> bool:
    """True when ``p`` is at least ``apart`` metres from each of ``others`` (x, z)."""
    return all(float(np.hypot(p[0] - o[0], p[1] - o[1])) >= apart for o in others)


def _near_any(p: tuple[float, float], crowd: Sequence[tuple[float, float]]) -> bool:
    """True when ``p`` is within CLEAR_M of one of ``crowd`` (x, z)."""
    return any(float(np.hypot(p[0] - c[0], p[1] - c[1])) < CLEAR_M for c in crowd)


MATCH_MAX = 4  # characters shared out over slots together at most (beyond, in story order)


def matched(walkers: Sequence[tuple[float, float]], slots: Sequence[tuple[float, float]]) -> int | None:
    """The slot (an index into ``slots``) the first walker takes when every walker gets its own slot and the
    walks' total length is least; None when there are fewer slots than walkers or too many walkers.

    A shortest sharing-out has no two crossing walks (swap the ends of two crossing ones and both get
    shorter), which is why it is used rather than giving each the slot nearest to it in turn.
    """
    if len(slots) < len(walkers) or not walkers or len(walkers) > MATCH_MAX:
        return None
    w = np.asarray(walkers, float)
    p = np.asarray(slots, float)
    cost = np.linalg.norm(w[:, None, :] - p[None, :, :], axis=2)
    best, pick = float("inf"), None
    for chosen in permutations(range(len(p)), len(w)):
        total = float(cost[range(len(w)), chosen].sum())
        if total < best - 1e-9:
            best, pick = total, chosen[0]
    return pick


def seat_points(
    placed: PlacedObject, slots: Sequence[str], forward: float = 0.0
) -> list[tuple[float, float]]:
    """World (x, z) of each named seat slot (a hip contact point) of an object, or of the point ``forward``
    metres in front of it (the way the seat faces: a sitter's knees)."""
    from wana.assets.catalog import asset_for, to_world

    points = asset_for(placed).contact_points
    local = np.array([points[n].position for n in slots], float).reshape(-1, 3)
    local = local + np.array([0.0, 0.0, forward / placed.scale[2]])
    world = to_world(placed, local)
    return [(float(q[0]), float(q[2])) for q in world]


_GRIDS: OrderedDict[bytes, OccupancyGrid] = OrderedDict()


def _stand_grid(scene: Scene) -> OccupancyGrid:
    """Where a person may stand in the room (cached by the scene's content: every compute of an unchanged
    layout, and the draft and final passes over it, share one grid)."""
    key = hashlib.blake2b(msgspec.msgpack.encode(scene), digest_size=16).digest()
    grid = _GRIDS.get(key)
    if grid is None:
        grid = occupancy_grid(scene.room, scene_footprints(scene), radius=0.2, cell=0.05)
        _GRIDS[key] = grid
        if len(_GRIDS) > 32:
            _GRIDS.popitem(last=False)
    else:
        _GRIDS.move_to_end(key)
    return grid


__all__ = ["Claim", "Slotting", "matched"]
