"""A composed scene: room plus placed catalog objects. Metres, world frame, Y up, right-handed."""

from __future__ import annotations

import msgspec


class Room(msgspec.Struct, frozen=True, kw_only=True):
    room_type: str  # e.g. "office", "living_room"
    width: float  # metres along X; the room spans x in [-width/2, width/2]
    depth: float  # metres along Z; z in [-depth/2, depth/2]
    height: float  # metres along Y; floor at y = 0


class PlacedObject(msgspec.Struct, frozen=True, kw_only=True):
    id: str  # unique in the scene; equals the SSG ObjectNode.id when the text asked for it
    category: str  # catalog category
    attributes: dict[str, str] = {}  # variant knobs passed to the catalog generator
    seed: int = 0  # variant seed passed to the catalog generator
    position: tuple[float, float, float] = (0.0, 0.0, 0.0)  # metres, world; centre of the base
    yaw: float = 0.0  # radians about +Y; 0 means the object's front faces +Z
    scale: tuple[float, float, float] = (1.0, 1.0, 1.0)
    support: str = ""  # id of the object it rests on, "" = floor
    from_text: bool = True  # False for context objects added by composition


class ObjectStateTrack(msgspec.Struct, frozen=True, kw_only=True):
    """How one state of a placed object changes over the animation: a door or lid open, a lamp or screen on.

    The value is 0 (closed / off) to 1 (open / on): piecewise linear between the keys (frames ascending),
    held before the first key and after the last. The orchestrator writes one key pair per change, from
    the frame the hand touches the object (services/orchestrator/stages/states.py).
    """

    object_id: str  # PlacedObject.id
    state: str  # "open" (door leaf, lid) | "on" (light, screen)
    frames: list[int] = []  # key frames, ascending
    values: list[float] = []  # the state at each key frame, 0..1


class Scene(msgspec.Struct, frozen=True, kw_only=True):
    room: Room
    objects: list[PlacedObject] = []
    seed: int = 0
    states: list[ObjectStateTrack] = []  # objects whose state the story changes (none: every object at rest)
