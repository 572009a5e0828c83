"""Stated relations survive the layout's optimisation: a move that breaks one is taken back as little as needed."""

from __future__ import annotations

import msgspec
import numpy as np

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import RelationNode
from services.orchestrator.stages.scene import keep_relations
from wana.assets.catalog import make_object
from wana.assets.relations import relation_holds

ROOM = Room(room_type="bedroom", width=6, depth=6, height=3)
BED_HALF = float(make_object("bunk_bed").dims[0]) / 2
CHAIR_HALF = float(make_object("rocking_chair").dims[0]) / 2


def _room(chair_x: float, bed_scale: float = 1.0) -> Scene:
    bed = PlacedObject(id="bunk_bed", category="bunk_bed", position=(0.0, 0.0, 0.0), scale=(bed_scale,) * 3)
    chair = PlacedObject(id="rocking_chair", category="rocking_chair", position=(chair_x, 0.0, 0.0))
    lamp = PlacedObject(id="lamp", category="floor_lamp", position=(-2.0, 0.0, 2.0))
    return Scene(room=ROOM, objects=[bed, chair, lamp])


NEXT_TO = [RelationNode(subject="rocking_chair", relation="next_to", object="bunk_bed")]


def _by_id(scene: Scene) -> dict[str, PlacedObject]:
    return {o.id: o for o in scene.objects}


def test_a_move_that_breaks_next_to_is_taken_back_only_as_far_as_needed():
    before = _room(BED_HALF + CHAIR_HALF + 0.2)
    after = _room(BED_HALF + CHAIR_HALF + 0.9)  # the optimiser slid the chair 0.7 m away
    after = msgspec.structs.replace(
        after,
        objects=[*after.objects[:2], msgspec.structs.replace(after.objects[2], position=(-1.5, 0.0, 2.0))],
    )
    assert not relation_holds("next_to", _by_id(after)["rocking_chair"], _by_id(after)["bunk_bed"])
    kept = _by_id(keep_relations(before, after, NEXT_TO))
    assert relation_holds("next_to", kept["rocking_chair"], kept["bunk_bed"])
    x = kept["rocking_chair"].position[0]
    assert before.objects[1].position[0] < x < after.objects[1].position[0]  # part of the move is kept
    assert kept["lamp"].position == (-1.5, 0.0, 2.0)  # moves that broke nothing stay


def test_a_shrunk_anchor_is_grown_back_until_the_relation_holds():
    before = _room(BED_HALF + CHAIR_HALF + 0.3)
    after = _room(BED_HALF + CHAIR_HALF + 0.3, bed_scale=0.5)
    assert not relation_holds("next_to", _by_id(after)["rocking_chair"], _by_id(after)["bunk_bed"])
    kept = _by_id(keep_relations(before, after, NEXT_TO))
    assert relation_holds("next_to", kept["rocking_chair"], kept["bunk_bed"])
    assert 0.5 < kept["bunk_bed"].scale[0] <= 1.0


def test_nothing_broken_or_nothing_held_leaves_the_optimised_layout_as_it_is():
    before, after = _room(BED_HALF + CHAIR_HALF + 0.2), _room(BED_HALF + CHAIR_HALF + 0.25)
    assert keep_relations(before, after, NEXT_TO) is after
    far_before, far_after = _room(BED_HALF + CHAIR_HALF + 1.5), _room(BED_HALF + CHAIR_HALF + 2.0)
    # It never held: not the optimiser's doing.
    assert keep_relations(far_before, far_after, NEXT_TO) is far_after


def test_copies_of_a_counted_subject_are_all_kept():
    table = PlacedObject(id="dining_table", category="dining_table", position=(0.0, 0.0, 0.0))
    depth = float(make_object("dining_table").dims[2]) / 2 + float(make_object("chair").dims[2]) / 2 + 0.1
    chairs = [
        PlacedObject(id="chair", category="chair", position=(0.0, 0.0, depth), yaw=np.pi),
        PlacedObject(id="chair/2", category="chair", position=(0.0, 0.0, -depth), yaw=0.0),
    ]
    before = Scene(room=ROOM, objects=[table, *chairs])
    moved = msgspec.structs.replace(chairs[1], position=(0.0, 0.0, -depth - 1.2))
    after = Scene(room=ROOM, objects=[table, chairs[0], moved])
    around = [RelationNode(subject="chair", relation="around", object="dining_table")]
    kept = _by_id(keep_relations(before, after, around))
    assert all(relation_holds("around", kept[c], kept["dining_table"]) for c in ("chair", "chair/2"))
