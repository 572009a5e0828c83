"""Walking up to another character stops at the distance the social model asks for."""

from __future__ import annotations

import numpy as np
import pytest

from proto.common import Header
from proto.motion import SynthesizeRequest
from proto.scene import Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.handlers import handle_synthesize
from wana.arrays import from_wire
from wana.bus.service import InvalidInput

SCENE = Scene(room=Room(room_type="room", width=8, depth=8, height=3))
TOM = CharacterNode(name="Tom", actions=[ActionNode(verb="walk", action="walk", destination="Mary")])


def _gap(distances: dict[str, float]) -> float:
    reply = handle_synthesize(
        SynthesizeRequest(
            header=Header(),
            character=TOM,
            scene=SCENE,
            start=(-2.0, 0.0, 0.0),
            others={"Mary": (2.0, 0.0)},
            distances=distances,
        )
    )
    end = from_wire(reply.motion.root_position)[-1]
    return float(np.hypot(end[0] - 2.0, end[2]))


def test_a_walk_up_to_a_character_stops_at_the_given_distance():
    assert _gap({}) == pytest.approx(0.8, abs=0.05)  # the default
    assert _gap({"Mary": 1.4}) == pytest.approx(1.4, abs=0.05)
    assert _gap({"Mary": 0.6}) == pytest.approx(0.6, abs=0.05)


def test_an_impossible_distance_is_refused():
    with pytest.raises(InvalidInput, match="distances"):
        _gap({"Mary": 0.0})


def _apart(verb: str, action: str, start_x: float) -> float:
    """Hips distance at the end of Tom's ``action`` aimed at Mary (at x = 0), starting at ``start_x``."""
    reply = handle_synthesize(
        SynthesizeRequest(
            header=Header(),
            character=CharacterNode(
                name="Tom", actions=[ActionNode(verb=verb, action=action, target="Mary")]
            ),
            scene=SCENE,
            start=(start_x, 0.0, 1.57),
            others={"Mary": (0.0, 0.0)},
        )
    )
    end = from_wire(reply.motion.root_position)[-1]
    return float(np.hypot(end[0], end[2]))


def test_talking_to_someone_nose_to_nose_steps_back_to_room_for_the_hands():
    """Talking gestures sweep the hands 0.45 m ahead: at 0.4 m they would go through Mary."""
    from services.motion.planning import arms_room

    assert arms_room("talk") > 0.6
    assert _apart("talk", "talk", -0.4) >= arms_room("talk") - 0.05
    assert _apart("talk", "talk", -1.2) == pytest.approx(1.2, abs=0.05)  # far enough already: it stays
    assert arms_room("nod") == 0.0


def test_a_handshake_too_close_steps_back_to_arms_length():
    assert _apart("shake", "shake_hands", -0.4) == pytest.approx(0.75, abs=0.06)


def test_a_way_round_furniture_that_passes_the_person_stops_there_not_through_them():
    """The route to the point short of Mary (on Tom's side) goes round a table and arrives from her far side:
    Tom stops where the way first comes within the hug's distance, on the side he arrives from."""
    from services.motion.planning import CLOSE_DISTANCE, plan_actions

    def detour(scene, a, b, ignore=frozenset()):  # noqa: ANN001, ANN202 - round a table north of them
        del scene, ignore
        return np.array([a, (0.0, 1.0), (-0.8, 0.0), b])

    tom = CharacterNode(name="Tom", actions=[ActionNode(verb="hug", action="hug", target="Mary")])
    plan = plan_actions(tom, SCENE, (2.0, 0.0, -1.57), route_fn=detour, others={"Mary": (0.0, 0.0)})
    walk = next(s for s in plan.segments if s.kind == "locomotion")
    way = np.asarray(walk.waypoints, float)
    assert np.allclose(way[-1], (-CLOSE_DISTANCE["hug"], 0.0), atol=0.02)
    points = np.concatenate([np.linspace(p, q, 20) for p, q in zip(way[:-1], way[1:], strict=True)])
    assert np.linalg.norm(points, axis=1).min() >= CLOSE_DISTANCE["hug"] - 0.02  # never through Mary


def test_dancing_right_after_a_hug_steps_back_from_the_one_still_there():
    """Tom dances with nobody named while Mary stands 0.45 m away (they just hugged): the dance's hands
    would go into her, so he steps back first; someone 2 m off is no reason to."""
    from services.motion.planning import arms_room

    def apart(mary_x: float) -> float:
        reply = handle_synthesize(
            SynthesizeRequest(
                header=Header(),
                character=CharacterNode(name="Tom", actions=[ActionNode(verb="dance", action="dance")]),
                scene=SCENE,
                start=(0.0, 0.0, 1.57),
                bodies=[(mary_x, 0.0)],
            )
        )
        end = from_wire(reply.motion.root_position)[-1]
        return float(np.hypot(end[0] - mary_x, end[2]))

    assert apart(0.45) >= arms_room("dance") / 2 + 0.2
    assert apart(2.0) == pytest.approx(2.0, abs=0.05)


def test_one_seated_is_hugged_from_beyond_her_knees():
    """Mary sits (she is among the seated others): Tom walking up to hug her stops past her knees and feet,
    not at the standing hug's distance with his toes in her shins."""
    from services.motion.planning import CLOSE_DISTANCE, SEATED_PARTNER_M

    def apart(occupied: list[tuple[float, float]]) -> float:
        reply = handle_synthesize(
            SynthesizeRequest(
                header=Header(),
                character=CharacterNode(
                    name="Tom", actions=[ActionNode(verb="hug", action="hug", target="Mary")]
                ),
                scene=SCENE,
                start=(-2.0, 0.0, 1.57),
                others={"Mary": (0.0, 0.0)},
                occupied=occupied,
            )
        )
        end = from_wire(reply.motion.root_position)[-1]
        return float(np.hypot(end[0], end[2]))

    assert apart([]) == pytest.approx(CLOSE_DISTANCE["hug"], abs=0.05)
    assert apart([(0.0, 0.0)]) == pytest.approx(SEATED_PARTNER_M, abs=0.05)
