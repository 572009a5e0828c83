"""The motion stage's story passes resume from their checkpoints (services/orchestrator/stages/replay.py):
an edit walks only the actions it reaches, and gives the results and the query log a full walk gives."""

from __future__ import annotations

import pytest

from services.orchestrator.backend import InProcessBackend
from services.orchestrator.document import TextChange
from services.orchestrator.queries import content_hash
from services.orchestrator.session import Orchestrator, Session
from services.orchestrator.slotting import Slotting

pytestmark = [pytest.mark.integration, pytest.mark.slow]

STORY = (
    "In the office there is a desk near a window$. A chair is in front of the desk$. "
    "A sofa is next to the bookshelf$.\n"
    "Eve walks to the chair. Tom walks to the sofa. Eve sits on the chair. Tom waves.\n"
    "Eve stands up. Tom sits on the sofa. Eve walks to the window. Tom stands up.\n"
    "Eve walks to the desk. Tom walks to the window. Eve waves. Tom walks to the desk.\n"
)
ACTIONS = 12


class _Forgetful(dict):
    """A trace table that keeps nothing: every pass walks the whole story."""

    def __setitem__(self, key, value) -> None:
        pass


@pytest.fixture(scope="module")
def orchestrator(tmp_path_factory):
    orch = Orchestrator(tmp_path_factory.mktemp("db") / "sessions.db", InProcessBackend())
    yield orch
    orch.close()


def replace(session: Session, old: str, new: str, last: bool = False) -> None:
    text = session.doc.text
    at = text.rindex(old) if last else text.index(old)
    session.edit(session.doc.version, [TextChange(start=at, end=at + len(old), text=new)])


def counted_claims(monkeypatch) -> list[str]:
    """The characters Slotting.claim is asked for, one entry a call (a step walked by a pass)."""
    calls: list[str] = []
    claim = Slotting.claim

    def counting(self, who, *args, **kwargs):
        calls.append(who)
        return claim(self, who, *args, **kwargs)

    monkeypatch.setattr(Slotting, "claim", counting)
    return calls


def test_an_edit_of_the_last_action_walks_only_that_action_again(orchestrator, monkeypatch):
    calls = counted_claims(monkeypatch)
    s = orchestrator.create(STORY)
    s.compute()
    assert len(calls) > ACTIONS  # the cold compute walks every action, and the drafts up to the interactions
    calls.clear()
    replace(s, "Tom walks to the desk", "Tom runs to the desk", last=True)
    result = s.compute()
    assert "segment:Tom:5" in result.ran
    assert calls == ["Tom"]  # the segment pass from its last step; the draft pass stops before it


def test_without_checkpoints_the_same_edit_walks_the_whole_story(orchestrator, monkeypatch):
    calls = counted_claims(monkeypatch)
    s = orchestrator.create(STORY)
    s.engine.traces = _Forgetful()
    s.compute()
    calls.clear()
    replace(s, "Tom walks to the desk", "Tom runs to the desk", last=True)
    s.compute()
    assert len(calls) > ACTIONS


@pytest.mark.parametrize(
    "old,new",
    [
        ("Eve sits on the chair", "Eve lies on the chair"),  # an early action: the rest follows from it
        ("Tom waves.", "Tom waves. Eve nods."),  # a sentence more: every step shifts
        ("Eve stands up. ", ""),  # a sentence less
        ("Tom walks to the window", "Eve walks to the window"),  # an action that changes hands
        ("A chair is", "A wooden chair is"),  # a scene edit
    ],
)
def test_a_resumed_pass_gives_the_results_and_log_of_a_full_walk(orchestrator, old, new):
    resumed, walked = orchestrator.create(STORY), orchestrator.create(STORY)
    walked.engine.traces = _Forgetful()
    for s in (resumed, walked):
        s.compute()
        replace(s, "Eve walks to the desk", "Eve runs to the desk")  # a first edit leaves a trace
        s.compute()
        replace(s, old, new)
    a, b = resumed.compute(), walked.compute()
    assert content_hash([a.motions, a.scene, sorted(a.diagnostics.items())]) == content_hash(
        [b.motions, b.scene, sorted(b.diagnostics.items())]
    )
    assert (a.ran, a.reused) == (b.ran, b.reused)
