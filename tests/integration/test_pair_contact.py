"""Two-person actions in whole stories (the real pipeline, in-process services): the two hands of a handshake
or a high five meet at the clip's contact frames, also when the partner sits and was busy typing."""

from __future__ import annotations

import numpy as np
import pytest

from services.motion.pairs import _window
from services.orchestrator.backend import InProcessBackend
from services.orchestrator.session import Orchestrator
from wana.fidelity import story_checks
from wana.fidelity.bodies import body_of

pytestmark = [pytest.mark.integration, pytest.mark.slow]

CONTACT_M = 0.03  # the target: hands within 3 cm at the contact frames
SEATED_HIPS_M = 0.75

GREETING = (
    "In the office there is a desk with a computer on it$. An office chair is in front of the desk$.\n"
    "Eve sits on the office chair and types on the keyboard.\n"
    "Tom walks in.\n"
    "He walks to Eve and shakes her hand.\n"
)
HIGH_FIVE = (
    "In the gym there is a bench$.\n"
    "Mary walks to the bench.\n"
    "Lily walks to the bench.\n"
    "Mary gives Lily a high five.\n"
)


@pytest.fixture(scope="module")
def orchestrator(tmp_path_factory):
    orch = Orchestrator(tmp_path_factory.mktemp("db") / "s.db", InProcessBackend())
    yield orch
    orch.close()


def _meeting(result, actor: str, partner: str, action: str, joint: str) -> tuple[np.ndarray, range]:
    """(W,) metres between the actor's and the partner's ``joint`` over the action's contact frames."""
    seg = next(s for s in result.motions[actor].segments if s.action == action)
    w0, w1 = _window(seg, action)
    a, b = body_of(result.motions[actor]), body_of(result.motions[partner])
    frames = range(w0, w1)
    return np.linalg.norm(a.joint(joint)[w0:w1] - b.joint(joint)[w0:w1], axis=1), frames


def _contact_ok(result, text: str) -> bool:
    sid = next(s.id for s in result.sentences if s.text == text)
    every = story_checks(
        [(s.id, s.kind) for s in result.sentences],
        result.graphs,
        result.scene,
        result.motions,
        result.unavailable,
    )
    checks = [c for c in every[sid] if c.name == "contact"]
    assert checks
    return all(c.ok for c in checks)


@pytest.fixture(scope="module")
def greeting(orchestrator):
    return orchestrator.create(GREETING).compute()


def test_a_seated_partner_reaches_up_and_the_two_right_hands_meet(greeting):
    gaps, frames = _meeting(greeting, "Tom", "Eve", "shake_hands", "RightHand")
    eve = body_of(greeting.motions["Eve"])
    assert (eve.joint("Hips")[frames.start : frames.stop, 1] < SEATED_HIPS_M).all()  # she stays seated
    assert float(gaps.max()) <= CONTACT_M
    assert _contact_ok(greeting, "He walks to Eve and shakes her hand.")


def test_the_handshake_waits_till_the_partner_has_done_typing(greeting):
    typing = next(s for s in greeting.motions["Eve"].segments if s.action == "type")
    shake = next(s for s in greeting.motions["Tom"].segments if s.action == "shake_hands")
    assert shake.start_frame >= typing.end_frame
    assert _contact_ok(greeting, "Eve sits on the office chair and types on the keyboard.")


def test_a_high_five_in_a_story_meets_palm_to_palm(orchestrator):
    result = orchestrator.create(HIGH_FIVE).compute()
    gaps, _ = _meeting(result, "Mary", "Lily", "high_five", "RightHandMiddle1")
    assert float(gaps.max()) <= CONTACT_M
    assert _contact_ok(result, "Mary gives Lily a high five.")
