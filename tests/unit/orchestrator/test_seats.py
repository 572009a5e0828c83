"""Seats the actions need: counted near the object sat at, added by retrieval when short, and used by the
characters (each on a seat of their own, hips on it), with a diagnostic that says what was added."""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode, SentenceGraph
from services.orchestrator.backend import InProcessBackend
from services.orchestrator.session import Orchestrator
from services.orchestrator.stages.seats import extra_nodes, missing_seats, seat_needs
from wana.arrays import from_wire

ROOM = Room(room_type="kitchen", width=6, depth=6, height=3)


def _sitting(*names: str, at: str = "table") -> list[SentenceGraph]:
    chars = [CharacterNode(name=n, actions=[ActionNode(verb="sit", action="sit", target=at)]) for n in names]
    return [SentenceGraph(sentence_id="s2", text="", kind="action", characters=chars)]


def test_missing_seats_counts_slots_near_the_object_sat_at():
    table = PlacedObject(id="table", category="dining_table", position=(0.0, 0.0, 0.0), yaw=0.0)
    chair = PlacedObject(id="chair", category="chair", position=(0.0, 0.0, 0.7), yaw=np.pi)
    far = PlacedObject(id="chair#2", category="chair", position=(2.8, 0.0, 2.8), yaw=0.0)
    needs = seat_needs(_sitting("Sam", "Zoe"), ["s2"])
    assert needs == {"table": (["Sam", "Zoe"], "s2")}
    assert missing_seats(Scene(room=ROOM, objects=[table, chair, far]), needs) == {"table": 1}
    assert missing_seats(Scene(room=ROOM, objects=[table]), needs) == {"table": 2}
    assert missing_seats(Scene(room=ROOM, objects=[table, chair]), seat_needs(_sitting("Sam"), ["s2"])) == {}
    on_chair = seat_needs(_sitting("Sam", at="chair"), ["s2"])  # a seat named: nothing to add
    assert missing_seats(Scene(room=ROOM, objects=[table, chair]), on_chair) == {}
    objects, relations = extra_nodes({"table": 2})
    assert [o.id for o in objects] == ["table_seat1", "table_seat2"]
    assert all(r.relation == "near" and r.object == "table" for r in relations)


def test_two_characters_sitting_at_a_table_with_no_chairs_each_get_an_added_chair():
    text = "In the kitchen there is a big table$.\nSam and Zoe sit at the table.\n"
    with tempfile.TemporaryDirectory() as tmp:
        orchestrator = Orchestrator(Path(tmp) / "s.db", InProcessBackend(), seed=0)
        try:
            result = orchestrator.create(text, doc_id="seats").compute()
        finally:
            orchestrator.close()
    added = [d for ds in result.diagnostics.values() for d in ds if d.code == "I201"]
    assert added and "chair" in added[0].message
    seats = {o.id: o for o in result.scene.objects if o.id.startswith("table_seat")}
    assert seats
    hips = {}
    for name in ("Sam", "Zoe"):
        motion = result.motions[name]
        sit = next(s for s in motion.segments if s.action == "sit")
        hips[name] = from_wire(motion.root_position)[sit.end_frame - 1]
        assert 0.35 < hips[name][1] < 0.7  # seated height, not standing, not on the floor
    assert np.linalg.norm(hips["Sam"][[0, 2]] - hips["Zoe"][[0, 2]]) > 0.4  # not on one seat
