"""A story that opens a door, turns on a lamp and closes the door, through the real pipeline (in-process
services): the scene's state tracks start inside the acting segments and carry across sentences."""

from __future__ import annotations

import pytest

from services.orchestrator.backend import InProcessBackend
from services.orchestrator.session import Orchestrator
from wana.domain.object_state import state_at

pytestmark = [pytest.mark.integration, pytest.mark.slow]

STORY = (
    "There is a desk with a lamp and a laptop in the office. There is a door.\n"
    "Tom opens the door. Eve turns on the lamp. Eve closes the laptop. Tom closes the door.\n"
)


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    orch = Orchestrator(tmp_path_factory.mktemp("db") / "s.db", InProcessBackend())
    try:
        yield orch.create(STORY).compute()
    finally:
        orch.close()


def _segment(result, name, action):
    return next(s for s in result.motions[name].segments if s.action == action)


def test_the_door_opens_while_tom_opens_it_and_stays_open_until_he_closes_it(result):
    tracks = {(t.object_id, t.state): t for t in result.scene.states}
    door = tracks[("door", "open")]
    opening, closing = _segment(result, "Tom", "open_door"), _segment(result, "Tom", "close_door")
    assert opening.start_frame < door.frames[0] < opening.end_frame  # from the touch, not the sentence start
    assert state_at(result.scene.states, "door", "open", 0.0, opening.start_frame) == 0.0
    assert state_at(result.scene.states, "door", "open", 0.0, closing.start_frame) == 1.0  # carried on
    assert state_at(result.scene.states, "door", "open", 0.0, closing.end_frame) == 0.0


def test_the_lamp_is_on_after_eve_presses_it_and_the_laptop_lid_is_shut_at_the_end(result):
    press = _segment(result, "Eve", "press_switch")
    states = result.scene.states
    assert state_at(states, "lamp", "on", 0.0, press.start_frame) == 0.0
    assert state_at(states, "lamp", "on", 0.0, press.end_frame) == 1.0
    last = max(s.end_frame for m in result.motions.values() for s in m.segments) - 1
    assert state_at(states, "lamp", "on", 0.0, last) == 1.0
    assert state_at(states, "laptop", "open", 1.0, last) == 0.0
