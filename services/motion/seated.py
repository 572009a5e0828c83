"""Re-synthesise an action done seated, from sitting down on its seat, in any layout.

The optimiser asks this when it moves the furniture around an action a character does sitting
(typing at a desk after "sits on the chair"): the character stands where the sit's approach walk
would stop, facing away from the seat, sits down on it and does the action, exactly as the full
plan would from that point on (services.motion.planning + synthesis), without the walk there.

The result depends on the scene only through the objects the two actions name (the seat and the
action's target, instrument or destination): the approach is a straight line and the synthesis sees
the plan, not the scene. So results are memoised by those objects' placements and the action: the
optimiser re-synthesises the same seat and laptop poses again and again across the edits of one
document (an edit elsewhere in the room leaves them where they were).
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Callable

import msgspec

from proto.motion_data import Motion
from proto.scene import Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.planning import plan_actions, straight_route
from services.motion.synthesis import MotionPlan, synthesise

SIT = "sit"
CACHE_SIZE = 64  # seated re-syntheses kept (each ~150 kB for 5 s of motion)

_cache: OrderedDict[bytes, Motion] = OrderedDict()
_cache_lock = threading.Lock()
_encode = msgspec.msgpack.Encoder().encode


def clear_cache() -> None:
    """Forget every memoised seated re-synthesis (tests, or after the motion library changed)."""
    with _cache_lock:
        _cache.clear()


def cache_size() -> int:
    """How many seated re-syntheses are memoised."""
    with _cache_lock:
        return len(_cache)


def _key(character: str, seat_id: str, action: ActionNode, scene: Scene) -> bytes | None:
    """The memo key: the actions and the placements of the objects they name; None when one of
    those names no object id of the scene (the planner then looks it up by category, which any
    object may answer)."""
    by_id = {o.id: o for o in scene.objects}
    named = [seat_id] + [r for r in (action.target, action.instrument, action.destination) if r]
    if any(r not in by_id for r in named):
        return None
    return _encode((character, seat_id, action, [by_id[r] for r in dict.fromkeys(named)]))


def seated_action_fn(character: str, seat_id: str, action: ActionNode) -> Callable[[Scene], Motion]:
    """scene -> Motion: sit down on ``seat_id`` from its approach point, then do ``action``.

    Args:
        character: the character's name (the Motion's).
        seat_id: id of the seat object (a chair, a bench) in the scenes given.
        action: the seated action (its target, manner and duration as the story gives them).

    Returns:
        A function from a scene holding ``seat_id`` to the Motion of the sit and the action, whose
        segments are the sit's and the action's (no walk). Raises KeyError when the scene lacks
        the seat. Results are memoised (see the module docstring); the same Motion object may be
        returned for equal inputs, so callers must not change it.
    """
    node = CharacterNode(name=character, actions=[ActionNode(verb=SIT, action=SIT, target=seat_id), action])

    def synthesise_seated(scene: Scene) -> Motion:
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

    def motion_fn(scene: Scene) -> Motion:
        if not any(o.id == seat_id for o in scene.objects):
            raise KeyError(f"the scene has no seat {seat_id!r}")
        key = _key(character, seat_id, action, scene)
        if key is not None:
            with _cache_lock:
                hit = _cache.get(key)
                if hit is not None:
                    _cache.move_to_end(key)
                    return hit
        motion = synthesise_seated(scene)
        if key is not None:
            with _cache_lock:
                _cache[key] = motion
                while len(_cache) > CACHE_SIZE:
                    _cache.popitem(last=False)
        return motion

    return motion_fn
