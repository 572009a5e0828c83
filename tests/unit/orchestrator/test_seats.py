"""Seats the actions need: counted near the object sat at, added by retrieval when short, and used by the
characters (each on a seat of their own, hips on it), with a diagnostic that says what was added."""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode, SentenceGraph
from services.orchestrator.backend import InProcessBackend
from services.orchestrator.document import Sentence
from services.orchestrator.session import Orchestrator
from services.orchestrator.stages.seats import extra_nodes, missing_seats, seat_at_instruments, seat_needs
from wana.arrays import from_wire
from wana.assets.catalog import asset_for, to_world

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


def _studio(stool_at: tuple[float, float, float]) -> Scene:
    kit = PlacedObject(id="drum_kit", category="drum_kit", position=(0.0, 0.0, 0.0), yaw=0.0)
    stool = PlacedObject(id="stool", category="stool", position=stool_at, yaw=0.0)
    return Scene(room=Room(room_type="music_studio", width=6, depth=6, height=3), objects=[kit, stool])


def _leo() -> dict:
    acts = [
        ActionNode(verb="sit", action="sit", target="stool"),
        ActionNode(verb="play", action="play_drums", target="drum_kit"),
    ]
    return {"Leo": (CharacterNode(name="Leo", actions=acts), ["s1", "s1"])}


def test_the_stool_sat_on_to_play_the_drums_goes_to_the_kits_place_to_sit():
    """duo-music_studio-12: "A stool is next to the drum kit$. Leo sits on the stool and plays the drums."
    sat 1.5 m from the drums with the hands in the air: the stool goes to the kit's "sit" point."""
    scene = _studio((1.4, 0.0, 0.0))
    moved, notes = seat_at_instruments(scene, _leo(), [Sentence(id="s1", start=0, end=1, text="x")])
    kit, stool = moved.objects
    place = to_world(kit, np.asarray(asset_for(kit).contact_points["sit"].position, float))
    seat = to_world(stool, np.asarray(asset_for(stool).contact_points["sit"].position, float))
    assert np.hypot(*(place - seat)[[0, 2]]) < 1e-6
    assert abs(np.cos(stool.yaw - np.pi)) > 0.999  # facing the kit (which faces +z)
    assert [d.code for _, d in notes] == ["I203"] and "stool" in notes[0][1].message


def test_a_seat_not_followed_by_an_action_at_a_place_to_sit_stays_where_it_is():
    scene = _studio((1.4, 0.0, 0.0))
    acts = [ActionNode(verb="sit", action="sit", target="stool"), ActionNode(verb="laugh", action="laugh")]
    chars = {"Leo": (CharacterNode(name="Leo", actions=acts), ["s1", "s1"])}
    assert seat_at_instruments(scene, chars, [Sentence(id="s1", start=0, end=1, text="x")]) == (scene, [])
