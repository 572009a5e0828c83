"""Whole-pipeline behaviour on short stories (real services, in-process)."""

from __future__ import annotations

import numpy as np
import pytest

from services.orchestrator.backend import InProcessBackend
from services.orchestrator.session import Orchestrator
from wana.arrays import from_wire

pytestmark = [pytest.mark.integration, pytest.mark.slow]


@pytest.fixture(scope="module")
def orchestrator(tmp_path_factory):
    orch = Orchestrator(tmp_path_factory.mktemp("db") / "s.db", InProcessBackend())
    yield orch
    orch.close()


def test_walking_to_another_character_ends_near_them(orchestrator):
    result = orchestrator.create(
        "A sofa is near a window$.\nEve walks to the window.\nTom walks to Eve.\n"
    ).compute()
    eve = from_wire(result.motions["Eve"].root_position)[-1]
    tom = from_wire(result.motions["Tom"].root_position)[-1]
    assert np.hypot(*(eve - tom)[[0, 2]]) < 1.2


def test_a_later_sentence_starts_no_earlier_than_the_one_before(orchestrator):
    result = orchestrator.create("A chair is near a desk$.\nEve walks to the desk.\nTom waves.\n").compute()
    eve = [s for s in result.motions["Eve"].segments if s.action != "hold"]
    tom = [s for s in result.motions["Tom"].segments if s.action != "hold"]
    assert tom[0].start_frame >= eve[0].start_frame
    assert len(from_wire(result.motions["Eve"].root_position)) == len(
        from_wire(result.motions["Tom"].root_position)
    )


def test_a_story_without_scene_sentences_gets_an_empty_room_with_a_door(orchestrator):
    result = orchestrator.create("Eve walks slowly. Eve waves.").compute()
    assert result.unavailable == {}
    assert result.scene is not None and [o.category for o in result.scene.objects] == ["door"]
    assert [s.action for s in result.motions["Eve"].segments if s.action != "hold"][-1] == "wave"


@pytest.mark.parametrize(
    "text", ["", "   \n\n", "$$$ ... ???", "\x00\x01\x02 binary", "Der Hund läuft schnell."]
)
def test_odd_documents_give_diagnostics_not_crashes(orchestrator, text):
    result = orchestrator.create(text).compute()
    assert result.version == 0
    for sentence in result.sentences:
        assert sentence.id in result.diagnostics


def test_the_optimised_office_keeps_every_object_inside_the_room_and_apart(orchestrator, repo_root):
    from services.retrieval.compose import overlapping_pairs
    from wana.assets.catalog import world_bounds

    result = orchestrator.create((repo_root / "examples" / "office.txt").read_text()).compute()
    assert result.optimisations, "the office story has interactions to optimise"
    room = result.scene.room
    for placed in result.scene.objects:
        lo, hi = world_bounds(placed)
        assert -room.width / 2 - 1e-3 <= lo[0] and hi[0] <= room.width / 2 + 1e-3, placed.id
        assert -room.depth / 2 - 1e-3 <= lo[2] and hi[2] <= room.depth / 2 + 1e-3, placed.id
    assert overlapping_pairs(result.scene) == []
