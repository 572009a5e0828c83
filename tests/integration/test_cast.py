"""Several characters through the real pipeline (in-process services): who is on stage when, where they
come in and go out, their own seats, and titled names kept whole."""

from __future__ import annotations

import numpy as np
import pytest

from services.orchestrator.backend import InProcessBackend
from services.orchestrator.session import Orchestrator
from services.orchestrator.staging import doorway
from wana.arrays import from_wire
from wana.fidelity import story_checks

pytestmark = [pytest.mark.integration, pytest.mark.slow]

VISIT = (
    "A sofa is near a window$.\n"
    "Eve sits on the sofa.\n"
    "Eve laughs.\n"  # Eve is busy sitting down: the next sentences start later
    "Tom walks in.\n"
    "He sits on the sofa.\n"
    "Eve waves at Tom.\n"
    "Tom leaves.\n"
)
TRIO = (
    "A sofa is near a window$.\nAda walks to the window.\nBen walks to the window.\nThey sit on the sofa.\n"
)


@pytest.fixture(scope="module")
def orchestrator(tmp_path_factory):
    orch = Orchestrator(tmp_path_factory.mktemp("db") / "s.db", InProcessBackend())
    yield orch
    orch.close()


@pytest.fixture(scope="module")
def visit(orchestrator):
    return orchestrator.create(VISIT).compute()


def on_stage(motion) -> np.ndarray:
    return from_wire(motion.present).astype(bool)


def first_frame(motion, sentence_id: str) -> int:
    return min(s.start_frame for s in motion.segments if s.sentence_id == sentence_id)


def test_a_character_who_walks_in_is_off_stage_until_his_sentence_and_appears_at_the_door(visit):
    tom = visit.motions["Tom"]
    walks_in = next(s.id for s in visit.sentences if s.text == "Tom walks in.")
    start = first_frame(tom, walks_in)
    on = on_stage(tom)
    assert start > 0 and not on[:start].any() and on[start]
    door = doorway(visit.scene)
    assert door is not None
    hips = from_wire(tom.root_position)
    assert np.hypot(*(hips[start, [0, 2]] - door.centre)) < 1.0  # shown from the door's threshold on
    room = visit.scene.room
    waiting = hips[:start]
    assert np.all((np.abs(waiting[:, 0]) > room.width / 2) | (np.abs(waiting[:, 2]) > room.depth / 2))


def test_the_character_on_stage_from_the_start_is_shown_from_frame_zero(visit):
    assert on_stage(visit.motions["Eve"]).all()


def test_a_character_who_leaves_walks_to_the_door_and_is_gone_afterwards(visit):
    tom = visit.motions["Tom"]
    leaves = next(s.id for s in visit.sentences if s.text == "Tom leaves.")
    end = max(s.end_frame for s in tom.segments if s.sentence_id == leaves)
    on = on_stage(tom)
    assert on[end - 1] and not on[end:].any()
    hips = from_wire(tom.root_position)
    assert np.hypot(*(hips[end - 1, [0, 2]] - doorway(visit.scene).centre)) < 1.0


def test_two_characters_sent_to_one_sofa_sit_on_two_cushions_without_overlapping(visit):
    checks = story_checks(
        [(s.id, s.kind) for s in visit.sentences], visit.graphs, visit.scene, visit.motions, visit.unavailable
    )
    sits = next(s.id for s in visit.sentences if s.text == "He sits on the sofa.")
    assert [c for c in checks[sits] if c.name == "overlap" and not c.ok] == []
    tom_sit = next(s for s in visit.motions["Tom"].segments if s.sentence_id == sits and s.action == "sit")
    frame = tom_sit.end_frame - 1
    eve = from_wire(visit.motions["Eve"].root_position)[frame]
    tom = from_wire(visit.motions["Tom"].root_position)[frame]
    assert np.hypot(eve[0] - tom[0], eve[2] - tom[2]) > 0.5
    assert eve[1] < 0.7 and tom[1] < 0.7  # both seated, not one standing on the other's spot


def test_characters_on_stage_from_the_start_do_not_stand_in_a_line(orchestrator):
    result = orchestrator.create(
        "A desk is near a window$. A lamp is on the desk$.\nAda waves. Ben nods. Eve laughs.\n"
    ).compute()
    starts = np.array([from_wire(result.motions[n].root_position)[0, [0, 2]] for n in ("Ada", "Ben", "Eve")])
    gaps = [np.linalg.norm(starts[i] - starts[j]) for i in range(3) for j in range(i + 1, 3)]
    assert min(gaps) > 0.8
    assert np.ptp(starts[:, 0]) > 0.2 and np.ptp(starts[:, 1]) > 0.2


def test_three_sent_to_a_three_seat_sofa_take_three_cushions(orchestrator):
    result = orchestrator.create(
        TRIO.replace("Ben walks to the window.", "Ben walks to the window.\nEve walks to the window.")
    ).compute()
    hips = np.array([from_wire(m.root_position)[-1, [0, 2]] for m in result.motions.values()])
    assert len(hips) == 3
    assert min(np.linalg.norm(hips[i] - hips[j]) for i in range(3) for j in range(i + 1, 3)) > 0.45


def test_a_titled_name_is_one_character(orchestrator):
    result = orchestrator.create("Dr. Jones walks in. Mrs. Brown waves at Dr. Jones.\n").compute()
    assert [s.text for s in result.sentences] == ["Dr. Jones walks in.", "Mrs. Brown waves at Dr. Jones."]
    assert not {"Dr", "Mrs", "Dr.", "Mrs."} & set(result.motions)


def _social_eval():
    import importlib.util
    import sys
    from pathlib import Path

    path = Path(__file__).resolve().parents[2] / "eval" / "social.py"
    spec = importlib.util.spec_from_file_location("eval_social", path)
    module = importlib.util.module_from_spec(spec)
    sys.modules["eval_social"] = module
    spec.loader.exec_module(module)
    return module


def test_eval_social_counts_no_overlap_and_a_good_entrance_on_the_sofa_visit():
    social = _social_eval()
    cast = social.cast_metrics({"visit": social.CAST_STORIES["sofa_visit"]})
    assert cast == {
        "overlap_frames": 0,
        "entrance_ok_share": 1.0,
        "entrances": 1,
        "shared_slots": 0,
        "hand_contact_cm": 0.0,  # no two-person action in it
        "paired_actions": 0,
    }


@pytest.mark.slow
def test_eval_social_finds_the_hands_of_every_greeting_touching():
    social = _social_eval()
    cast = social.cast_metrics({"greetings": social.CAST_STORIES["greetings"]})
    assert cast["paired_actions"] >= 4  # a handshake, a hug, two hands of a high five, a hand on the shoulder
    assert cast["hand_contact_cm"] <= 3.0
    assert cast["overlap_frames"] == 0
