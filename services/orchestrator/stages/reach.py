"""Props a seated character's action uses, put within its reach on the table it sits at, before motion.

"Eve, John and Nora sit at the table. John pours wine into the glasses" with the bottle at the far end of
the table (1.4 m from John's chair) and no glass at his place; "They sit around the table. Anna types on the
laptop" with the laptop in front of another chair than the one the slotting gave her: a seated character
takes a prop within an arm's reach of where it sits (the motion planner's PICK_REACH) and types on a laptop
in front of it, and getting up to fetch one brings the legs through the chair and the table. So, as a set
dresser would, the prop is put on a table top in front of the place where it is used, from the story's
start: on the surface it stands on, else (an object no scene sentence placed) on the nearest one at table
height; a thing worked at faces the sitter (a laptop's keys towards it), and a pour gets the vessel it pours
into at that place too. Only a prop no earlier action used, nothing rests on and nobody holds moves; where
no free spot is in reach in front of the sitter (the bowl at the far end of a coffee table, a book on a desk
behind the chair) the room is left as it is, and the action's check says so. The sentence gets an I202.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import msgspec
import numpy as np

from proto.motion import SegmentEndState
from proto.scene import PlacedObject, Scene
from proto.ssg import ActionNode, CharacterNode, RelationNode
from services.orchestrator.stages.props import (
    HELD_KINDS,
    clip_kind,
    holdable,
    made_for,
    offers,
    on_surface,
    table_tops,
)
from wana.domain.object_geometry import find_object

# metres from a seated character's position (its knees) to a prop it takes (motion planning's PICK_REACH)
PICK_REACH = 0.9
AHEAD_M = 0.25  # metres ahead of a seated character's position where a prop brought to it goes
TAKE_M = 0.88  # metres from a seated character's position to a prop put in its reach (a margin in)
AT_HAND_M = 0.4  # metres from the point ahead within which an object worked at seated (a laptop) is in reach
TOP_NEAR_M = 0.8  # metres from the point ahead to a table top a prop may be put on
AT_OBJECT = ("person", "seat", "bed", "")  # interactions that work on no small object
POURS = ("pour",)  # actions that empty the held vessel into the one the sentence names (planning's POUR_INTO)
# metres from a seated character's position to the vessel it pours into: farther, the arm falls short of it
POUR_NEAR_M = 0.55


def used_prop(scene: Scene, action: ActionNode, pos: np.ndarray) -> tuple[PlacedObject, bool] | None:
    """The small object an action works with and whether it is held (a bottle poured from, a book read), or
    worked at where it stands (a laptop typed on); None when it uses none. A held action takes what it names
    when that is made for it (or it names no tool: "drinks from the glass"), else the nearest object made for
    it ("pours wine into the glasses": the bottle), as motion planning's prop_grip does."""
    kind = clip_kind(action)
    named = next(
        (o for r in (action.target, action.instrument, action.destination) if (o := find_object(scene, r))),
        None,
    )
    if kind in HELD_KINDS:
        tools = made_for(scene, action.action)
        if named is not None and named not in tools and (tools or kind == "tool"):
            named = None
        if named is not None:
            return (named, True) if holdable(named) else None
        if not tools:
            return None
        tools = [o for o in tools if not _from_pour(o, action.action)] or tools
        best = min(tools, key=lambda o: float(np.hypot(o.position[0] - pos[0], o.position[2] - pos[1])))
        return best, True
    if (
        kind not in AT_OBJECT
        and named is not None
        and named.support
        and holdable(named)
        and offers(named, action.action)
    ):
        return named, False
    return None


def poured_into(
    scene: Scene, action: ActionNode, pos: np.ndarray, held: PlacedObject | None
) -> PlacedObject | None:
    """The vessel a pour empties into: of those like the one the sentence names, the nearest (the motion
    planner's choice), or None for any other action."""
    into = find_object(scene, action.destination or action.target) if action.action in POURS else None
    if into is None or (held is not None and into.id == held.id):
        return None
    alike = [o for o in scene.objects if o.category == into.category and (held is None or o.id != held.id)]
    return min(alike, key=lambda o: float(np.hypot(o.position[0] - pos[0], o.position[2] - pos[1])))


def _from_pour(placed: PlacedObject, action: str) -> bool:
    """A bottle or a kettle (a "pour" point) for an action that is no pour: drunk from last (planning)."""
    try:
        from wana.assets import catalog

        return action not in POURS and "pour" in catalog.asset_for(placed).contact_points
    except Exception:  # noqa: BLE001 - unknown category
        return False


def _in_reach(prop: PlacedObject, held: bool, pos: np.ndarray, ahead: np.ndarray) -> bool:
    xz = np.array([prop.position[0], prop.position[2]])
    if held:
        return float(np.linalg.norm(xz - pos)) <= PICK_REACH
    return float(np.linalg.norm(xz - ahead)) <= AT_HAND_M


def _brought(
    scene: Scene, prop: PlacedObject, held: bool, state: SegmentEndState, stated: set[str], face: bool = True
) -> PlacedObject | None:
    """The prop on a free spot of a table top in front of the seated character (one worked at facing it,
    when ``face``), or None."""
    pos = np.array([state.x, state.z])
    forward = np.array([np.sin(state.yaw), np.cos(state.yaw)])
    ahead = pos + forward * AHEAD_M
    try:
        from wana.assets import catalog

        obj = catalog.make_object(prop.category, dict(prop.attributes), prop.seed)
    except Exception:  # noqa: BLE001 - no mesh: it cannot be placed
        return None
    boxes = np.asarray(obj.collision_boxes, float).reshape(-1, 2, 3)
    fp = np.stack([boxes[:, 0, [0, 2]].min(axis=0), boxes[:, 1, [0, 2]].max(axis=0)])
    height = float(boxes[:, 1, 1].max())
    # what it stands on first; another top only for what no scene sentence put somewhere
    tops = [o for o in scene.objects if o.id == prop.support]
    if prop.id not in stated:
        tops += [o for o in scene.objects if o.id != prop.support and not o.support and o.id != prop.id]
    without = Scene(room=scene.room, objects=[o for o in scene.objects if o.id != prop.id], seed=scene.seed)
    best: tuple[float, tuple, str] | None = None
    for top in tops:
        near = [float(np.linalg.norm(np.clip(ahead, lo, hi) - ahead)) for _, lo, hi in table_tops(top)]
        if not near or min(near) > TOP_NEAR_M:
            continue
        spot = on_surface(without, top, fp, height, toward=ahead)
        if spot is None:
            continue
        d = float(np.hypot(spot[0] - ahead[0], spot[2] - ahead[1]))
        # a held prop is taken with an arm's reach (the planner's PICK_REACH); one worked at is before it
        fits = np.hypot(spot[0] - pos[0], spot[2] - pos[1]) <= TAKE_M if held else d <= AT_HAND_M
        fits = fits and float(np.dot([spot[0] - pos[0], spot[2] - pos[1]], forward)) >= 0.0  # not behind
        if fits and (best is None or d < best[0] - 1e-6):
            best = (d, spot, top.id)
        if best is not None and top.id == prop.support:
            break  # its own table has a place in reach: it stays on it
    if best is None:
        return None
    _, spot, support = best
    yaw = (
        prop.yaw
        if held or not face
        else float(np.arctan2(np.sin(state.yaw + np.pi), np.cos(state.yaw + np.pi)))
    )
    position = (round(spot[0], 5), round(spot[1], 5), round(spot[2], 5))
    return msgspec.structs.replace(prop, position=position, support=support, yaw=round(yaw, 5))


def within_reach(
    scene: Scene,
    characters: Mapping[str, tuple[CharacterNode, list[str]]],
    order: Sequence[tuple[str, int]],
    before: Sequence[Mapping[str, SegmentEndState]],
    stated: Sequence[RelationNode] = (),
) -> tuple[Scene, list[tuple[str, str]]]:
    """The room with each prop a seated character's action uses out of its reach put in front of it.

    Args:
        order: (name, k) of every action in story order.
        before: for each of them, every character's state as the action starts (a pass's checkpoints).
        stated: the scene sentences' relations: what they put on a surface stays on that surface.

    Returns:
        (the room, (sentence id, what was moved) for each prop moved, on the action's sentence).
    """
    objects = {o.id: o for o in scene.objects}
    rests = {o.support for o in scene.objects if o.support}
    placed_by_text = {r.subject for r in stated}
    used: set[str] = set()
    notes: list[tuple[str, str]] = []
    for (name, k), states in zip(order, before, strict=True):
        node, sids = characters[name]
        action = node.actions[k]
        state = states.get(name)
        now = Scene(room=scene.room, objects=list(objects.values()), seed=scene.seed)
        named = {
            o.id for r in (action.target, action.instrument, action.destination) if (o := find_object(now, r))
        }
        if state is None:
            used |= named
            continue
        pos = np.array([state.x, state.z])
        got = used_prop(now, action, pos)
        wanted = [(got[0], got[1], not got[1])] if got is not None else []  # (prop, held, faces the sitter)
        vessel = poured_into(now, action, pos, got[0] if got is not None else None)
        if (
            vessel is not None
            and np.hypot(vessel.position[0] - pos[0], vessel.position[2] - pos[1]) > POUR_NEAR_M
        ):
            # none in reach: the one the sentence names goes to the pourer's place (the others are theirs)
            into = find_object(now, action.destination or action.target)
            wanted.append((into if into is not None and into.id not in used else vessel, False, False))
        for prop, held, face in wanted if state.posture == "sit" else []:
            prop = objects[prop.id]
            ahead = pos + np.array([np.sin(state.yaw), np.cos(state.yaw)]) * AHEAD_M
            free = prop.id not in used and prop.id not in rests
            free = free and not any(st.holding == prop.id for st in states.values())
            if not free or _in_reach(prop, held, pos, ahead):
                continue
            now = Scene(room=scene.room, objects=list(objects.values()), seed=scene.seed)
            moved = _brought(now, prop, held, state, placed_by_text, face=face)
            if moved is not None:
                objects[prop.id] = moved
                what = prop.category.replace("_", " ")
                on = moved.support.split("#")[0].replace("_", " ")
                notes.append(
                    (sids[k], f"moved the {what} on the {on} within {name}'s reach, where {name} sits")
                )
        used |= named | {prop.id for prop, _, _ in wanted}
    if not notes:
        return scene, []
    return Scene(room=scene.room, objects=list(objects.values()), seed=scene.seed), notes


__all__ = ["used_prop", "within_reach"]
