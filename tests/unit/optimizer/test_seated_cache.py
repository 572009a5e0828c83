"""The seated re-synthesis is memoised by the placements of the objects it names, and a memoised motion
is the one a fresh synthesis makes (real motion service)."""

from __future__ import annotations

import msgspec
import numpy as np

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode
from services.motion import seated
from services.motion.seated import seated_action_fn
from wana.arrays import from_wire

ROOM = Room(room_type="office", width=5.0, depth=5.0, height=3.0)
TYPE = ActionNode(verb="type", action="type", target="laptop", duration_s=2.0)


def _office(laptop_z: float = -1.0, lamp_x: float = 2.0, laptop_id: str = "laptop") -> Scene:
    return Scene(
        room=ROOM,
        objects=[
            PlacedObject(id="desk", category="desk", position=(0.0, 0.0, -0.9)),
            PlacedObject(id="chair", category="office_chair", position=(0.0, 0.0, -0.35), yaw=float(np.pi)),
            PlacedObject(id=laptop_id, category="laptop", position=(0.0, 0.75, laptop_z), support="desk"),
            PlacedObject(id="lamp", category="floor_lamp", position=(lamp_x, 0.0, 2.0)),
        ],
    )


def _same_motion(a, b) -> bool:
    return (
        all(
            np.array_equal(from_wire(getattr(a, f)), from_wire(getattr(b, f)))
            for f in ("root_position", "rotations")
        )
        and a.segments == b.segments
    )


def test_the_same_seat_and_laptop_give_the_memoised_motion_even_when_the_rest_of_the_room_changed():
    seated.clear_cache()
    fn = seated_action_fn("Eve", "chair", TYPE)
    first = fn(_office())
    assert seated.cache_size() == 1
    assert fn(_office()) is first
    assert fn(_office(lamp_x=-2.0)) is first  # the lamp is no part of sitting down and typing


def test_a_moved_laptop_is_resynthesised_and_matches_a_fresh_synthesis():
    seated.clear_cache()
    fn = seated_action_fn("Eve", "chair", TYPE)
    near = fn(_office(laptop_z=-1.0))
    moved = fn(_office(laptop_z=-0.8))
    assert moved is not near and not _same_motion(moved, near)  # the hands follow the laptop
    seated.clear_cache()
    assert _same_motion(fn(_office(laptop_z=-0.8)), moved)


def test_another_action_on_the_same_layout_is_not_taken_from_the_memo():
    seated.clear_cache()
    typing = seated_action_fn("Eve", "chair", TYPE)(_office())
    longer = seated_action_fn("Eve", "chair", msgspec.structs.replace(TYPE, duration_s=3.0))(_office())
    assert len(from_wire(longer.root_position)) > len(from_wire(typing.root_position))


def test_a_target_named_by_category_only_is_not_memoised():
    seated.clear_cache()
    fn = seated_action_fn("Eve", "chair", TYPE)  # "laptop" names no object id in this scene
    scene = _office(laptop_id="laptop#1")
    a, b = fn(scene), fn(scene)
    assert seated.cache_size() == 0 and a is not b and _same_motion(a, b)
