"""The social model in the pipeline: faces from relations and emotions, responses timed after what they answer."""

from __future__ import annotations

import numpy as np
import pytest

from services.orchestrator.backend import InProcessBackend
from services.orchestrator.session import Orchestrator
from wana.arrays import from_wire
from wana.assets.characters import EXPRESSIONS

pytestmark = [pytest.mark.integration, pytest.mark.slow]


@pytest.fixture(scope="module")
def orchestrator(tmp_path_factory):
    orch = Orchestrator(tmp_path_factory.mktemp("db") / "sessions.db", InProcessBackend())
    yield orch
    orch.close()


def _face(result, name: str) -> np.ndarray:
    motion = result.motions[name]
    assert motion.expression is not None, f"{name} has no face track"
    face = from_wire(motion.expression)
    assert face.shape == (from_wire(motion.rotations).shape[0], len(EXPRESSIONS))
    assert face.dtype == np.float32 and face.min() >= 0.0 and face.max() <= 1.0
    return face


def test_an_angry_character_frowns_and_a_happy_one_smiles(orchestrator):
    session = orchestrator.create("Tom is angry. Tom waves. Eve is happy. Eve waves.")
    result = session.compute()
    assert "social" not in result.unavailable
    tom, eve = _face(result, "Tom"), _face(result, "Eve")
    frown, smile = EXPRESSIONS.index("frown"), EXPRESSIONS.index("smile")
    assert tom[-1, frown] > tom[-1, smile]
    assert eve[-1, smile] > eve[-1, frown]
    assert eve[-1, smile] > tom[-1, smile]


def test_the_same_story_gives_the_same_faces(orchestrator):
    text = "Tom and Eve are friends. Tom criticizes Eve. Eve apologizes to Tom."
    a = orchestrator.create(text).compute()
    b = orchestrator.create(text).compute()
    for name in ("Tom", "Eve"):
        assert np.array_equal(_face(a, name), _face(b, name))


def test_a_response_waits_for_the_action_it_answers(orchestrator):
    result = orchestrator.create("Tom shouts at Mary. Mary apologizes to Tom.").compute()
    acting = {
        name: [seg for seg in motion.segments if seg.action_index >= 0]
        for name, motion in result.motions.items()
    }
    tom_end = max(seg.end_frame for seg in acting["Tom"])
    mary_start = min(seg.start_frame for seg in acting["Mary"])
    assert mary_start >= tom_end  # she answers once he has finished, after a sampled delay
    assert mary_start - tom_end <= 3 * 30


def _gap(result, walker: str, other: str) -> float:
    """Metres between the two characters' roots at the end of the walker's walk up to the other."""
    walk = [s for s in result.motions[walker].segments if s.action in ("walk", "run")][-1]
    a = from_wire(result.motions[walker].root_position)[walk.end_frame - 1]
    b = from_wire(result.motions[other].root_position)[walk.end_frame - 1]
    return float(np.hypot(*(a - b)[[0, 2]]))


def test_friends_walk_up_closer_than_a_boss_and_his_employee(orchestrator):
    walks = "A door is in the room$. Mary walks to the door. Tom walks to Mary."
    friends = orchestrator.create(f"Tom and Mary are friends. {walks}").compute()
    boss = orchestrator.create(f"Tom is Mary's boss. {walks}").compute()
    assert _gap(friends, "Tom", "Mary") + 0.2 < _gap(boss, "Tom", "Mary")
    assert 0.6 < _gap(friends, "Tom", "Mary") < 1.3 and 1.0 < _gap(boss, "Tom", "Mary") < 1.8
