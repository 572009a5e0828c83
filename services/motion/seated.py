"""Re-synthesise an action done seated, from sitting down on its seat, in any layout.

The optimiser asks this when it moves the furniture around an action a character does sitting
(typing at a desk after "sits on the chair"): the character stands where the sit's approach walk
would stop, facing away from the seat, sits down on it and does the action, exactly as the full
plan would from that point on (services.motion.planning + synthesis), without the walk there.
"""

from __future__ import annotations

from collections.abc import Callable

from proto.motion_data import Motion
from proto.scene import Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.planning import plan_actions, straight_route
from services.motion.synthesis import MotionPlan, synthesise

SIT = "sit"


def seated_action_fn(character: str, seat_id: str, action: ActionNode) -> Callable[[Scene], Motion]:
    """scene -> Motion: sit down on ``seat_id`` from its approach point, then do ``action``.

    Args:
        character: the character's name (the Motion's).
        seat_id: id of the seat object (a chair, a bench) in the scenes given.
        action: the seated action (its target, manner and duration as the story gives them).

    Returns:
        A function from a scene holding ``seat_id`` to the Motion of the sit and the action, whose
        segments are the sit's and the action's (no walk). Raises KeyError when the scene lacks
        the seat.
    """
    node = CharacterNode(name=character, actions=[ActionNode(verb=SIT, action=SIT, target=seat_id), action])

    def motion_fn(scene: Scene) -> Motion:
        if not any(o.id == seat_id for o in scene.objects):
            raise KeyError(f"the scene has no seat {seat_id!r}")
        plan = plan_actions(node, scene, (0.0, 0.0, 0.0), route_fn=straight_route)
        sit = next(i for i, s in enumerate(plan.segments) if s.kind == "action" and s.action == SIT)
        walk = plan.segments[sit - 1] if sit > 0 else None
        if walk is None or walk.kind != "locomotion" or not walk.waypoints:
            return synthesise(plan)[0]
        # Start where the approach walk stops, facing as it ends (away from the seat).
        x, z = walk.waypoints[-1]
        yaw = walk.face_yaw if walk.face_yaw is not None else 0.0
        rest = MotionPlan(
            character=character,
            start=(float(x), float(z), float(yaw)),
            segments=plan.segments[sit:],
            diagnostics=plan.diagnostics,
        )
        return synthesise(rest)[0]

    return motion_fn
