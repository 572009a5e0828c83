"""Which actions the `contact` check reads as handing an object over (wana.fidelity.handover.is_handover)."""

from __future__ import annotations

import pytest

from proto.ssg import ActionNode
from wana.fidelity.acts import Act
from wana.fidelity.handover import is_handover


def act(verb: str, **refs: str) -> Act:
    return Act(sentence_id="s1", character="Mia", k=0, node=ActionNode(verb=verb, action="present", **refs))


@pytest.mark.parametrize(
    "node",
    [
        act("give", target="Sam", instrument="cup"),  # "gives Sam the cup"
        act("hand", target="hammer", destination="Sam"),  # "hands the hammer to Sam"
        act("bring", target="Sam", instrument="cup"),  # "brings the cup to Sam": handed over on arrival
    ],
)
def test_a_thing_given_to_someone_is_a_handover(node):
    assert is_handover(node, {"Mia", "Sam"})


def test_a_give_with_no_thing_or_no_one_is_no_handover():
    assert not is_handover(act("give", target="Sam"), {"Mia", "Sam"})  # "gives Sam a thumbs up"
    assert not is_handover(act("bring", target="cup", destination="table"), {"Mia", "Sam"})
