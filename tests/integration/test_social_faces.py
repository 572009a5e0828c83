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
