"""Handing an object over: the giver takes it, walks up to the receiver and lets go of it between the two;
the receiver's hand takes it there, at that frame, and keeps it for its next action ("Anna drinks the tea")."""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np
import pytest

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.planning import plan_actions
from services.orchestrator.backend import InProcessBackend
from services.orchestrator.session import Orchestrator
from wana.arrays import from_wire
from wana.fidelity.handover import HANDOFF_FRAMES, HANDOFF_M

SCENE = Scene(
    room=Room(room_type="kitchen", width=7, depth=7, height=3),
    objects=[
        PlacedObject(id="table", category="dining_table", position=(0.0, 0.0, 0.0), yaw=0.0),
        PlacedObject(id="cup", category="cup", position=(0.0, 0.76, 0.5), yaw=0.0, support="table"),
    ],
)


def test_the_giver_takes_the_cup_walks_up_to_the_receiver_and_lets_go_between_them():
    john = CharacterNode(name="John", actions=[ActionNode(verb="give", action="present", target="cup", destination="Anna")])  # fmt: skip
    plan = plan_actions(john, SCENE, (0.0, 1.5, np.pi), others={"Anna": (2.0, 2.0)})
    actions = [(s.action, s.prop, s.prop_span) for s in plan.segments if s.kind == "action"]
    assert actions[0][:2] == ("press_switch", "cup") and actions[0][2] == "grasp"  # taken from the table
    assert actions[-2][1:] == ("cup", "release") and actions[-1][:2] == ("present", "")
    release = [s for s in plan.segments if s.prop_span == "release"][0]
    ((joint, point),) = release.targets
    assert abs(point[1] - 1.0) < 1e-6
    at = plan.segments.index(release)
    walk = [s for s in plan.segments[:at] if s.kind == "locomotion"][-1]
    stop = np.asarray(walk.waypoints[-1])
    assert abs(np.linalg.norm(stop - np.array([2.0, 2.0])) - 0.75) < 0.05  # arm's length from Anna


def test_the_giver_steps_back_after_letting_go_still_facing_the_receiver():
    john = CharacterNode(name="John", actions=[ActionNode(verb="give", action="present", target="cup", destination="Anna")])  # fmt: skip
    plan = plan_actions(john, SCENE, (0.0, 1.5, np.pi), others={"Anna": (2.0, 2.0)})
    present = max(i for i, s in enumerate(plan.segments) if s.action == "present")
    (back,) = [s for s in plan.segments[present:] if s.kind == "locomotion"]
    stop = np.asarray(back.waypoints[-1])
    assert np.linalg.norm(stop - np.array([2.0, 2.0])) >= 1.1  # no longer at arm's length
    to_anna = np.array([2.0, 2.0]) - stop
    assert (
        abs(
            np.arctan2(
                np.sin(back.face_yaw - np.arctan2(*to_anna)), np.cos(back.face_yaw - np.arctan2(*to_anna))
            )
        )
        < 0.2
    )


def test_a_give_gesture_with_no_object_hands_nothing_over():
    john = CharacterNode(name="John", actions=[
        ActionNode(verb="pick up", action="pick_up", target="cup"),
        ActionNode(verb="give", action="present", target="Anna"),  # "gives her a thumbs up"
    ])  # fmt: skip
    plan = plan_actions(john, SCENE, (0.0, 1.5, np.pi), others={"Anna": (2.0, 2.0)})
    assert not [s for s in plan.segments if s.prop_span == "release"]


@pytest.mark.slow
def test_the_cup_passes_from_the_givers_hand_to_the_receivers_and_stays_there():
    text = (
        "In the kitchen there is a table$. A cup is on the table$.\n"
        "John walks to the table.\nAnna walks in.\nJohn gives the cup to Anna.\nAnna drinks the tea.\n"
    )
    with tempfile.TemporaryDirectory() as tmp:
        orchestrator = Orchestrator(Path(tmp) / "s.db", InProcessBackend(), seed=0)
        try:
            result = orchestrator.create(text, doc_id="handover").compute()
        finally:
            orchestrator.close()
    john, anna = result.motions["John"], result.motions["Anna"]
    gave = max((t for t in john.props if t.object_id == "cup"), key=lambda t: t.end_frame)
    taken = sorted((t for t in anna.props if t.object_id == "cup"), key=lambda t: t.start_frame)
    assert taken and abs(taken[0].start_frame - gave.end_frame) <= HANDOFF_FRAMES
    jump = np.linalg.norm(from_wire(gave.position)[-1] - from_wire(taken[0].position)[0])
    assert jump <= HANDOFF_M
    drink = next(s for s in anna.segments if s.action == "drink")
    held = np.zeros(int(anna.root_position.shape[0]), bool)
    for t in taken:
        held[t.start_frame : t.end_frame] = True
    assert held[drink.start_frame : drink.end_frame].all()  # the cup John gave her, not one from the table
    assert drink.start_frame >= gave.end_frame


def test_handing_someone_what_is_in_the_hand_when_the_sentence_names_only_them():
    """ "Lily hands him the book": the parse has only him; she hands over the book she holds."""
    from proto.motion import SegmentEndState
    from services.orchestrator.stages.motion import _staged

    states = {"Lily": SegmentEndState(holding="cup"), "Max": SegmentEndState()}
    hand = ActionNode(verb="hand", action="present", target="Max")
    ((sent,), _) = _staged(SCENE, None, "Lily", hand, states["Lily"], states, set())
    assert sent.instrument == "cup" and sent.verb == "give"
    plan = plan_actions(CharacterNode(name="Lily", actions=[ActionNode(verb="pick up", action="pick_up", target="cup"), sent]),
                        SCENE, (0.0, 1.5, np.pi), others={"Max": (2.0, 2.0)})  # fmt: skip
    (release,) = [s for s in plan.segments if s.prop_span == "release"]
    assert release.prop == "cup"
    smile = ActionNode(
        verb="give", action="present", target="Max"
    )  # "gives him a smile": nothing named, no hand-over
    ((sent,), _) = _staged(SCENE, None, "Lily", smile, states["Lily"], states, set())
    assert sent.instrument == ""
