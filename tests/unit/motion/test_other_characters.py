"""Actions aimed at another character use where that character is (SynthesizeRequest.others)."""

from __future__ import annotations

import msgspec
import numpy as np
import pytest

from proto.common import Header
from proto.motion import SynthesizeRequest
from proto.scene import Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.handlers import CONTRACT
from services.motion.planning import PERSON_DISTANCE, plan_actions
from wana.arrays import from_wire
from wana.bus.service import InvalidInput, call_in_process

EMPTY = Scene(room=Room(room_type="office", width=8, depth=8, height=3), objects=[])
EVE = (2.0, 1.5)  # x, z metres
START = (-1.0, -1.5, 0.0)  # x, z, yaw: Tom faces +Z, Eve is ahead and to his left (+X)


def _tom(*actions: ActionNode) -> CharacterNode:
    return CharacterNode(name="Tom", actions=list(actions))


def _synthesise(character: CharacterNode, others: dict[str, tuple[float, float]]):
    req = SynthesizeRequest(header=Header(), character=character, scene=EMPTY, start=START, others=others)
    reply = call_in_process(CONTRACT, req)
    assert reply.status == "ok"
    return reply


def _bearing_error(reply, target: tuple[float, float]) -> float:
    """Radians between the final facing and the direction from the final position to the target."""
    end = reply.end_states[-1]
    want = np.arctan2(target[0] - end.x, target[1] - end.z)
    return float(abs(np.arctan2(np.sin(want - end.yaw), np.cos(want - end.yaw))))


def test_waving_at_a_character_turns_towards_her_without_walking():
    reply = _synthesise(_tom(ActionNode(verb="wave", action="wave", target="Eve")), {"Eve": EVE})
    assert _bearing_error(reply, EVE) < 0.15
    end = reply.end_states[-1]
    assert np.hypot(end.x - START[0], end.z - START[1]) < 0.3  # turned in place
    assert reply.motion.segments[-1].action == "wave"


def test_without_her_position_waving_keeps_the_old_facing():
    reply = _synthesise(_tom(ActionNode(verb="wave", action="wave", target="Eve")), {})
    assert abs(reply.end_states[-1].yaw - START[2]) < 0.05
    assert _bearing_error(reply, EVE) > 0.5


def test_walking_to_a_character_stops_short_of_her_facing_her():
    reply = _synthesise(_tom(ActionNode(verb="walk", action="walk", destination="Eve")), {"Eve": EVE})
    end = reply.end_states[-1]
    gap = np.hypot(end.x - EVE[0], end.z - EVE[1])
    assert abs(gap - PERSON_DISTANCE) < 0.2
    assert _bearing_error(reply, EVE) < 0.2
    root = from_wire(reply.motion.root_position)
    walked = np.hypot(root[-1, 0] - START[0], root[-1, 2] - START[1])
    assert walked > 2.5  # the body moved, not only the end state


@pytest.mark.parametrize(
    "action,target,most", [("shake_hands", "Eve", 1.0), ("hug", "Eve", 0.7), ("shake_hands", "hand", 1.0)]
)
def test_touching_actions_walk_up_to_the_character_first(action, target, most):
    reply = _synthesise(_tom(ActionNode(verb=action, action=action, target=target)), {"Eve": EVE})
    end = reply.end_states[-1]
    assert np.hypot(end.x - EVE[0], end.z - EVE[1]) < most
    assert _bearing_error(reply, EVE) < 0.2
    kinds = [
        (s.action, s.target_id)
        for s in plan_actions(
            _tom(ActionNode(verb=action, action=action, target=target)), EMPTY, START, others={"Eve": EVE}
        ).segments
    ]
    assert kinds == [("walk", "Eve"), (action, "Eve")]


def test_a_character_never_targets_itself_and_the_request_round_trips():
    req = SynthesizeRequest(
        header=Header(),
        character=_tom(ActionNode(verb="wave", action="wave", target="Tom")),
        scene=EMPTY,
        start=START,
        others={"Tom": (3.0, 3.0), "Eve": EVE},
    )
    again = msgspec.msgpack.decode(msgspec.msgpack.encode(req), type=SynthesizeRequest)
    assert again.others == {"Tom": (3.0, 3.0), "Eve": EVE}
    plan = plan_actions(req.character, EMPTY, START, others=dict(req.others))
    assert [s.action for s in plan.segments] == ["wave"]


def test_a_non_finite_position_of_another_character_is_invalid_input():
    req = SynthesizeRequest(
        header=Header(),
        character=_tom(ActionNode(verb="wave", action="wave", target="Eve")),
        scene=EMPTY,
        start=START,
        others={"Eve": (float("nan"), 0.0)},
    )
    with pytest.raises(InvalidInput, match="others"):
        call_in_process(CONTRACT, req)
