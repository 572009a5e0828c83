"""Which standing others the motion service hears of for an action (services/orchestrator/stages/motion.py)."""

from __future__ import annotations

from proto.motion import SegmentEndState
from proto.ssg import ActionNode
from services.orchestrator.stages.motion import standing_others

STATES = {
    "Lily": SegmentEndState(x=0.0, z=0.0),
    "Dad": SegmentEndState(x=0.45, z=0.0),  # they just hugged
    "Sam": SegmentEndState(x=3.0, z=0.0),
    "Zoe": SegmentEndState(x=0.3, z=0.3, posture="sit"),
}


def test_a_gesture_aimed_at_nobody_hears_of_the_standing_ones_near_it_only():
    dance = ActionNode(verb="dance", action="dance")
    assert standing_others(dance, "Lily", STATES, set()) == [(0.45, 0.0)]


def test_a_walk_hears_of_every_one_standing_on_stage_and_of_the_legs_of_those_seated():
    walk = ActionNode(verb="walk", action="walk", destination="door")
    # Zoe sits facing +z: her shins are in front of her hips, in the way of a walk past her chair
    assert standing_others(walk, "Lily", STATES, set()) == [(0.45, 0.0), (3.0, 0.0), (0.3, 0.7)]
    assert standing_others(walk, "Lily", STATES, {"Zoe"}) == [(0.45, 0.0), (3.0, 0.0)]  # outside
