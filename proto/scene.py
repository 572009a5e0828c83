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


class Scene(msgspec.Struct, frozen=True, kw_only=True):
    room: Room
    objects: list[PlacedObject] = []
    seed: int = 0
