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
from dataclasses import dataclass, field

import msgspec
import numpy as np

from proto.scene import PlacedObject, Scene
from proto.ssg import ActionNode
from wana.domain.actions import ActionClip, get_clip
from wana.domain.object_geometry import find_object, scene_footprints
from wana.domain.routes import OccupancyGrid, occupancy_grid
from wana.domain.slots import SlotBook, seat_slots, stand_slots

LYING = ("lie_down", "sleep")
AROUND_M = 1.6  # metres: the seats "at" a table are within this of it
STAND_KEY = "#stand"  # a stand slot's object key in the book: "<object id>#stand"


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

    def claim(self, who: str, action: ActionNode) -> Claim:
        """The slot ``who`` takes for ``action`` (or gives back), in story order."""
        clip = _clip(action)
        if clip is None:
            return Claim(action)
        kind = clip.interaction.object if clip.interaction is not None else ""
        if kind in ("seat", "bed"):
            return self._seat(who, action, "lie" if clip.name in LYING else "sit")
        if "locomotion" in clip.tags:
            obj = find_object(self.scene, action.destination or action.target)
            if obj is None:
                self.book.release(who)
                return Claim(action)
            return self._stand(who, action, obj)
        if kind and kind not in ("handheld", "person"):
            obj = find_object(self.scene, action.target or action.instrument or action.destination)
            if obj is not None:
                return self._stand(who, action, obj)
        if clip.name == "stand":
            self.book.release(who)
        return Claim(action)

    def _seat(self, who: str, action: ActionNode, kind: str) -> Claim:
        obj = find_object(self.scene, action.target or action.instrument or action.destination)
        if obj is None:
            return Claim(action)
        every = seat_slots(obj, kind)
        if not every:  # "sits at the table": a free seat around it
            return self._seat_at(who, action, obj, kind)
        default = every[0]  # what the planner takes by itself
        slots = seat_slots(obj, kind, self.scene.objects)  # those no prop rests on
        if len(self.sitters.get(obj.id, ())) == 2 and len(slots) >= 3:
            slots = [*slots[1:], slots[0]]  # two on three cushions: the ends, with the middle between them
        taken = self.book.take(obj.id, slots, who)
        if taken is not None:
            return Claim(action, seat="" if taken == default else taken)
        # Full: the nearest object of the same kind with a free slot (a second chair at the table).
        here = np.array([obj.position[0], obj.position[2]])
        same = sorted(
            (o for o in self.scene.objects if o.category == obj.category and o.id != obj.id),
            key=lambda o: float(np.linalg.norm(np.array([o.position[0], o.position[2]]) - here)),
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

    def _seat_at(self, who: str, action: ActionNode, obj: PlacedObject, kind: str) -> Claim:
        """A free seat slot of the seats within AROUND_M of an object that has none itself (a table)."""
        here = np.array([obj.position[0], obj.position[2]])
        near = sorted(
            (
                (float(np.linalg.norm(np.array([o.position[0], o.position[2]]) - here)), o)
                for o in self.scene.objects
                if o.id != obj.id and not o.support
            ),
            key=lambda d_o: d_o[0],
        )
        for distance, seat in near:
            if distance > AROUND_M:
                break
            slots = seat_slots(seat, kind, self.scene.objects)
            taken = self.book.take(seat.id, slots, who) if slots else None
            if taken is not None:
                field_name = (
                    "target" if action.target == obj.id or action.target == obj.category else "destination"
                )
                moved = msgspec.structs.replace(action, **{field_name: seat.id})
                return Claim(moved, seat="" if taken == seat_slots(seat, kind)[0] else taken)
        return Claim(action)

    def _stand(self, who: str, action: ActionNode, obj: PlacedObject) -> Claim:
        spots = [p for p in stand_slots(obj, rows=2) if bool(self.grid.is_free_xz(np.asarray(p)))]
        spots = spots or stand_slots(obj)[:1]
        names = [str(i) for i in range(len(spots))]
        taken = self.book.take(obj.id + STAND_KEY, names, who)
        if taken is None or (taken == names[0] and len(self.standers.get(obj.id, ())) < 2):
            return Claim(action)
        # Two or more at one object: the first is told its slot too (the planner's own spot, the middle of
        # the front, would stand between the first two slots, within a body of the second).
        return Claim(action, spot=spots[int(taken)])


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


__all__ = ["Claim", "Slotting"]
