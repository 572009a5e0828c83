"""Characters on stage are never frozen: the office story through the whole pipeline (issue 23)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from services.orchestrator.backend import InProcessBackend
from services.orchestrator.session import Orchestrator
from wana.arrays import from_wire
from wana.assets.characters import EXPRESSIONS
from wana.domain.skeleton import JOINT_INDEX, forward_kinematics

pytestmark = [pytest.mark.integration, pytest.mark.slow]

OFFICE = (Path(__file__).resolve().parents[2] / "examples" / "office.txt").read_text()


@pytest.fixture(scope="module")
def office(tmp_path_factory):
    orch = Orchestrator(tmp_path_factory.mktemp("db") / "s.db", InProcessBackend())
    try:
        yield orch.create(OFFICE).compute()
    finally:
        orch.close()


def _world(motion):
    return forward_kinematics(
        from_wire(motion.rotations).astype(np.float64), from_wire(motion.root_position).astype(np.float64)
    )


def test_nobody_on_stage_holds_still_for_more_than_a_twentieth_of_the_time(office):
    for name, motion in office.motions.items():
        _, g = _world(motion)
        turn = np.degrees(2 * np.arccos(np.clip(np.abs(np.sum(g[1:] * g[:-1], -1)), 0, 1)))
        on = from_wire(motion.present)[1:] > 0 if motion.present is not None else np.ones(len(turn), bool)
        frozen = turn.max(axis=1) <= 0.1
        assert frozen[on].mean() <= 0.05, name
        # ... and no still stretch lasts longer than half a second
        run = longest = 0
        for f in frozen & on:
            run = run + 1 if f else 0
            longest = max(longest, run)
        assert longest <= 15, (name, longest)


def test_a_waiting_character_shifts_its_weight_with_its_feet_planted(office):
    tom = office.motions["Tom"]
    hold = [s for s in tom.segments if s.action == "hold" and s.end_frame - s.start_frame > 30][-1]
    pos, _ = _world(tom)
    frames = slice(hold.start_frame, hold.end_frame)
    for foot in ("LeftFoot", "RightFoot"):
        assert (
            np.ptp(pos[frames, JOINT_INDEX[foot], 0]) < 0.005
            and np.ptp(pos[frames, JOINT_INDEX[foot], 2]) < 0.005
        )
    assert np.ptp(pos[frames, JOINT_INDEX["Head"]], axis=0).max() > 0.005


def test_the_faces_blink(office):
    for name, motion in office.motions.items():
        if motion.expression is None:
            continue
        eyes = from_wire(motion.expression)[:, EXPRESSIONS.index("eyes_closed")]
        closed = eyes >= 0.99
        blinks = np.flatnonzero(closed[1:] & ~closed[:-1])
        assert len(blinks) >= len(eyes) / 30 / 6, name  # 9 s: at least one blink every 6 s
