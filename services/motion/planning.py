"""Plan a character's actions (from the SSG) into locomotion and action segments.

Target objects' stand points and contact points come from the asset catalog
(wana.assets.catalog); routes from route_fn(scene, start_xz, goal_xz[, ignore]) -> (N, 2)
waypoints. The default is the domain library's A* (wana.domain.routes) around the furniture
(services.motion.routing, on cached occupancy grids), ignoring the object walked to and what rests on it so that a goal inside
its clearance is reachable; where no route exists the character walks the straight line and the
plan carries a diagnostic.

Actions aimed at another character use where that character is (``others``: name -> x, z when the
first planned action starts; held there for the rest of the plan): "walks to Eve" stops
PERSON_DISTANCE short of her, "shakes hands with / hugs / high-fives Eve" walks up to her first, and
every action aimed at her ("waves at Eve") turns to face her.

Props: the hand holds at most one small object (``holding`` when planning resumes mid-story). A handheld or
tool action whose prop is not in the hand walks up to it, reaches for it (an arm's reach for one on a table,
a bend for one on the floor) and takes it at the reach; it stays in the hand through every later segment
(PlannedSegment.prop_span "whole") until a put-down sets it on what the sentence names, else the nearest
surface in reach, else back where it was; taking a second prop sets the first one down first.

Over 400 lines because the posture, seat, person and prop rules all read and change the one running plan
(position, facing, posture, hand) inside plan_actions; split apart they would pass that state around.
"""

from __future__ import annotations

import dataclasses
import functools
import inspect
from collections.abc import Callable, Sequence

import numpy as np

from proto.scene import PlacedObject, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.elbow_room import reaching_sides
from services.motion.gait_style import NEUTRAL as NEUTRAL_GAIT
from services.motion.gait_style import gait_style
from services.motion.style import mood_of, style_of
from services.motion.synthesis import RISE_MAX_M, MotionPlan, PlannedSegment
from wana.domain.actions import ActionClip, contact_targets, get_clip, load_library, names_object
from wana.domain.hiding import HIDE_ACTIONS, hiding_spots
from wana.domain.object_geometry import find_object
from wana.domain.skeleton import JOINT_INDEX, forward_kinematics, rest_offsets

RouteFn = Callable[..., np.ndarray]  # (scene, start_xz, goal_xz[, ignore: frozenset[str]]) -> (N, 2)
SPEEDS = {
    "walk": 1.3,
    "walk_slowly": 0.8,
    "run": 3.2,
    "jog": 2.2,
    "tiptoe": 0.7,
    "march": 1.2,
    "limp": 0.7,
    "walk_backward": 0.8,
    "sidestep_left": 0.8,
    "sidestep_right": 0.8,
}
SEAT_BACK = 0.22  # metres the hips travel backwards while sitting down (sit clip)
# Getting up from a seat ends with the shins this far in front of the seat's front edge (not in it: the
# catalog chair's front edge is 0.22 m from its sit point, an office chair's 0.29 m, a sofa's 0.40 m); the
# stand-up moves forward the rest (synthesis). Sitting down still starts SEAT_BACK in front of the seat point:
# a farther approach moved the optimiser's layouts at tables (quick subset 0.890 -> 0.873).
LEG_CLEAR_M = 0.10
SEAT_APPROACH_MAX = 0.6  # metres: the farthest stand-off from a seat point (a deep sofa)
APPROACH_CLEAR_M = 0.2  # metres from the standing hips to other furniture's footprint (belly, toes)
APPROACH_LOW_M = 0.1  # metres: furniture boxes lower than this (a rug) do not limit the stand-off
SIDE_CLEAR_M = 0.2  # metres from hips standing beside a tucked-in seat to the seat's side (the legs clear it)
SIDE_ROOM_M = 0.15  # ... and at least to other furniture's footprint (a desk top the thighs pass under)
# metres before the seat point (along its facing) a spot beside it is tried at, best first
SIDE_FORWARD_M = (0.1, 0.0, -0.1, 0.2)
REACH = 0.42  # metres from the contact points to where the character stands
PERSON_DISTANCE = 0.8  # metres between two characters after one walks up to the other
HANDOVER_VERB = "give"  # ActionNode.verb the orchestrator keeps on an action that hands an object over
HANDOVER_DISTANCE = 0.75  # metres between the two hips while one hands the other an object
HANDOVER_STEP_BACK = 1.2  # metres between the two hips once the giver has let go and stepped back
HANDOVER_HEIGHT = 1.0  # metres above the floor where the object passes from hand to hand
HANDOVER_GESTURE_S = 1.2  # seconds of the presenting gesture after letting go
# metres between the two hips, per touching action: a hand on the other's shoulder or chest needs them
# within an arm's reach of it (at PERSON_DISTANCE the straight arm stops 0.2 m short of the shoulder)
SEATED_PARTNER_M = 0.75  # metres from a seated partner's hips at least that one standing touches it from
CLOSE_DISTANCE = {
    "hug": 0.45,
    "shake_hands": 0.75,
    "high_five": 0.75,
    "comfort": 0.55,
    "kiss_cheek": 0.45,
    "push_person": 0.6,
}
REACH_SIDES = 8  # directions round a point tried for the nearest spot to reach it from
BODY_CLEAR_M = 0.6  # metres from another character's hips a spot to stand and reach from keeps
BODY_SHIFT_M = 0.4  # metres farther from the contacts such a spot may be than the one another stands on
CLEAR_DIRECTIONS = 16  # ... tried in this many directions round them
WALK_WEIGHT = 0.15  # metres of reach one metre more of walking is worth, choosing that spot
POUR_INTO = ("pour",)  # actions whose held vessel empties into what the sentence names
BETWEEN_HANDS_M = 0.12  # metres from the line between two hand targets a thing worked on lies between them
HAND_TARGETS = ("LeftHand", "RightHand", "LeftHandMiddle1", "RightHandMiddle1")
SEATED_POUR_M = 0.75  # metres (horizontal) from a seated character's position to a vessel it pours into
POUR_BACK_M = 0.12  # metres from the hand on a kettle's handle to its spout
POUR_ABOVE_M = 0.15  # metres above the vessel's rim where the pouring hand holds the kettle
TOO_CLOSE_M = 0.1  # metres closer than the wanted distance to another character that make one step back
SOLO_BODY_M = 0.25  # metres: the other's body and a margin beyond one's hands' reach, gesturing at nobody
ARMS_CLEAR_M = 0.05  # metres left between two characters' hands gesturing at each other at their farthest
SEATING = ("sit", "lie_down", "sleep")  # clips that leave the character on a seat or a bed
TURN_TOLERANCE = 0.3  # radians off the wanted facing before the character turns in place
REACH_BODY = 0.18  # metres: the clearance of a body standing at furniture to reach over it (feet, belly)
STEP_IN = 0.5  # metres (horizontal): a point the hand must reach farther than this is stepped up to
PICK_REACH = 0.9  # metres (horizontal) from where the character stands to a prop it can pick up
SEATED_AS = {"sit": "sit", "lie_down": "lie", "sleep": "lie", "sit_on_floor": "sit_floor", "stand": "stand"}
STAND_AT_M = 0.8  # metres from a thing's footprint beyond which "stands at/in front of it" walks there first
STAY_S = 1.0  # seconds a "sits" while seated or a "stands" while standing holds the posture
SLEEP_S = 4.0  # seconds "falls asleep" holds the lying pose of one already in bed
NEAR_NAMED = 1.6  # metres from a named non-seat ("sits at the desk") to the seat used with it
NEAR_ANY = 4.0  # metres from the character to the seat a bare "sits down" uses
TAKEN = 0.4  # metres from another character to a seat slot that counts as theirs
# A seated character whose prop is out of reach gets up, fetches it and sits back down. Off for now: getting
# up from a chair at a table and sitting back down brings the legs through the chair and the table (the
# story checks' penetration, +6 sentences on the quick subset), which costs more than the prop in the hand.
FETCH_WHEN_SEATED = False
SEAT_FOUND = 0.6  # metres from a seated character's position to the seat slot it sits on
SAME_SEAT = 0.35  # metres between the hips and a seat point for a character to count as sitting on it
SAME_BED = 1.1  # metres between a lying body's root and the bed's lie point for it to count as lying there
HELD_KINDS = ("handheld", "tool")  # interactions played with an object in the hand
GRASP_TABLE = (
    "press_switch"  # the clip that reaches out with the right hand (upper body) for a prop on a table
)
TABLE_GRASP_M = 0.45  # metres: a grip point this high is reached for; lower, the character bends down for it
# metres: a pick-up this high (above tables and counters: a filing cabinet's top, a shelf) plays its arm alone,
# upright; lower, its own bend and dip reach the table (the trunk within 30 degrees, synthesis)
SHELF_GRASP_M = 1.1
# A seated character takes a prop whose grip is this near its hips (horizontally) and at most SEATED_GRASP_BELOW_M
# below them (the seat's top beside it, not the floor) with an arm's reach where it sits (the box of chocolates on the bench beside it), not by getting up and
# bending over the seat from behind it, its shins through the bench (gump-lobby-1 s7).
SEATED_REACH_M = 0.7
SEATED_GRASP_BELOW_M = 0.25


def straight_route(scene: Scene, start: tuple[float, float], goal: tuple[float, float]) -> np.ndarray:
    """The straight line (for callers that want no route planning)."""
    return np.array([start, goal], dtype=np.float64)


def resting_on(scene: Scene, obj_id: str) -> frozenset[str]:
    """The object and everything resting on it, directly or on something that rests on it."""
    out = {obj_id}
    grew = True
    while grew:
        more = {o.id for o in scene.objects if o.support in out} - out
        out |= more
        grew = bool(more)
    return frozenset(out)


def _takes_ignore(fn: Callable) -> bool:
    try:
        return "ignore" in inspect.signature(fn).parameters
    except (TypeError, ValueError):
        return False


def _object_geometry(placed: PlacedObject):
    """(stand point xz, contact points name -> [(joint, world xyz)]) or None when the catalog lacks it."""
    try:
        from wana.assets.catalog import asset_for, to_world
    except Exception:  # noqa: BLE001 - the catalog is optional for synthesis
        return None
    try:
        obj = asset_for(placed)
    except Exception:  # noqa: BLE001 - unknown category: plan without contacts
        return None
    stand = to_world(placed, np.asarray(obj.stand_point, float))
    points: dict[str, list[tuple[str, np.ndarray]]] = {}
    for name, cp in obj.contact_points.items():
        lst = [(cp.joint, to_world(placed, np.asarray(cp.position, float)))]
        lst += [(j, to_world(placed, np.asarray(p, float))) for j, p in cp.extra.items()]
        points[name] = lst
    return stand[[0, 2]], points


def _fallback_geometry(placed: PlacedObject):
    front = np.array([np.sin(placed.yaw), np.cos(placed.yaw)])
    stand = np.array([placed.position[0], placed.position[2]]) + front * 0.6
    return stand, {}


def seat_approach(scene: Scene, placed: PlacedObject, hips: tuple[float, float, float]) -> float:
    """Metres in front of a seat point (along the seat's facing) where the hips stand once up from it: the
    seat's front edge plus LEG_CLEAR_M, at least SEAT_BACK (the sit clip's own travel), and no closer than
    APPROACH_CLEAR_M to other furniture (a chair tucked in at a table keeps SEAT_BACK: the body does not stand
    inside the table's edge)."""
    try:
        from wana.assets.catalog import asset_for
    except Exception:  # noqa: BLE001 - the catalog is optional for synthesis
        return SEAT_BACK
    try:
        half_depth = float(asset_for(placed).dims[2]) / 2.0 * float(placed.scale[2])
    except Exception:  # noqa: BLE001 - unknown category: the clip's own travel
        return SEAT_BACK
    fwd = np.array([np.sin(placed.yaw), np.cos(placed.yaw)])
    seat = np.array([hips[0], hips[2]])
    along = float(fwd @ (seat - np.array([placed.position[0], placed.position[2]])))
    want = float(np.clip(half_depth - along + LEG_CLEAR_M, SEAT_BACK, SEAT_APPROACH_MAX))
    if want <= SEAT_BACK:
        return SEAT_BACK
    from wana.domain.object_geometry import object_shape, scene_footprints
    from wana.domain.routes import point_rect_distance

    skip = set(resting_on(scene, placed.id)) | {placed.id}
    for o in scene.objects:  # a category the catalog lacks has no known footprint to step around
        try:
            object_shape(o)
        except (KeyError, ValueError):
            skip.add(o.id)
    fp = scene_footprints(scene, ignore=skip)
    fp = fp.select(fp.y_max > APPROACH_LOW_M)
    if not len(fp):
        return want
    steps = np.arange(SEAT_BACK, want + 1e-9, 0.02)
    clear = point_rect_distance(seat[None] + steps[:, None] * fwd[None], fp).min(axis=1) >= APPROACH_CLEAR_M
    free = steps[np.cumprod(clear).astype(bool)]
    return float(free[-1]) if len(free) else SEAT_BACK


def seat_stand_spot(
    scene: Scene,
    placed: PlacedObject,
    hips: tuple[float, float, float],
    others: Sequence[tuple[float, float]] = (),
) -> np.ndarray:
    """(2,) world x, z where the hips stand once up from a seat point.

    In front of the seat (seat_approach) when the legs have room there. A chair tucked in at a table or a
    desk has none: its front edge touches the table's, so a body standing up in front of it stands in both
    and turns away through the chair. A person then gets up beside the seat, the hips sliding sideways off
    it; so the spot is SIDE_CLEAR_M clear of the seat's side, on the side with more room (other furniture at
    least SIDE_ROOM_M away, the characters at ``others`` TAKEN), or in front as before when neither side is
    free. (Sitting down still starts SEAT_BACK in front: a side approach moved the optimiser's layouts at
    tables, test-split seating stories 15 -> 18 penetration failures.)
    """
    fwd = np.array([np.sin(placed.yaw), np.cos(placed.yaw)])
    seat = np.array([hips[0], hips[2]])
    ahead = seat_approach(scene, placed, hips)
    front = seat + fwd * ahead
    try:
        from wana.assets.catalog import asset_for

        dims = np.asarray(asset_for(placed).dims, float) * np.asarray(placed.scale, float)
    except Exception:  # noqa: BLE001 - unknown category: the clip's own travel
        return front
    centre = np.array([placed.position[0], placed.position[2]])
    along = float(fwd @ (seat - centre))
    if ahead >= min(dims[2] / 2.0 - along + LEG_CLEAR_M, SEAT_APPROACH_MAX) - 1e-6:
        return front  # the legs stand clear of its front edge
    if len(seat_slots(placed, "seat")) != 1:
        return front  # a sofa or a bench: its side is a neighbour's seat, or too far to slide along
    from wana.domain.object_geometry import object_shape, scene_footprints
    from wana.domain.routes import point_rect_distance

    skip = set(resting_on(scene, placed.id)) - {placed.id}
    for o in scene.objects:  # a category the catalog lacks has no known footprint to step around
        try:
            object_shape(o)
        except (KeyError, ValueError):
            skip.add(o.id)
    fp = scene_footprints(scene, ignore=skip)
    fp = fp.select(fp.y_max > APPROACH_LOW_M)
    side = np.array([np.cos(placed.yaw), -np.sin(placed.yaw)])
    across = float(side @ (seat - centre))
    people = np.asarray(others, float).reshape(-1, 2)
    best, room = front, -1.0
    for sign in (1.0, -1.0):
        for f in SIDE_FORWARD_M:
            spot = seat + side * sign * (dims[0] / 2.0 - sign * across + SIDE_CLEAR_M) + fwd * f
            if np.linalg.norm(spot - (seat + fwd * SEAT_BACK)) > RISE_MAX_M:
                continue  # farther than a stand-up moves (synthesis)
            clear = float(point_rect_distance(spot[None], fp).min()) if len(fp) else np.inf
            if len(people):
                clear = min(clear, float(np.linalg.norm(people - spot, axis=1).min()) - TAKEN + SIDE_ROOM_M)
            if clear >= SIDE_ROOM_M - 1e-6 and clear > room + 1e-6:
                best, room = spot, clear
                break
    return best


def seat_slots(placed: PlacedObject, kind: str) -> list[tuple[float, float, float]]:
    """World hips points of an object's seat slots ("sit", "sit_0", ...; a bed's "lie" for lying)."""
    geo = _object_geometry(placed)
    if geo is None:
        return []
    prefix = ("lie",) if kind == "bed" else ("sit",)
    return [
        (float(p[0]), float(p[1]), float(p[2]))
        for name, pairs in sorted(geo[1].items())
        if name.startswith(prefix)
        for j, p in pairs
        if j == "Hips"
    ]


def _slot_on_it(scene: Scene, placed: PlacedObject, slot: tuple[float, float, float]) -> bool:
    """Whether a seat slot lies over the object's own footprint (a chair's seat), not beside it (a drum
    kit's "sit" point: the place its player's stool goes)."""
    from wana.domain.object_geometry import object_shape, scene_footprints
    from wana.domain.routes import point_rect_distance

    try:
        object_shape(placed)
    except (KeyError, ValueError):
        return True  # no known footprint: taken at its word
    fp = scene_footprints(Scene(room=scene.room, objects=[placed]))
    return bool(len(fp)) and float(point_rect_distance(np.array([[slot[0], slot[2]]]), fp).min()) <= 1e-6


def seat_under(scene: Scene, pos: np.ndarray) -> tuple[PlacedObject, tuple[float, float, float]] | None:
    """The seat a seated character sits on (the slot nearest its position, within SEAT_FOUND) and its hips
    point, None when no seat is there (on the floor).

    A slot over its object's own footprint comes before one beside it: the stool moved to a drum kit's place
    to sit has its slot where the kit's is, and getting up "in front of" the kit's (the kit faces its
    player) walked Leo backwards through the stool (duo-music_studio-12 s11)."""
    cands = [(o, p) for o in scene.objects for p in seat_slots(o, "seat")]
    ok = [(o, p) for o, p in cands if np.hypot(p[0] - pos[0], p[2] - pos[1]) <= SEAT_FOUND]

    def order(c: tuple[PlacedObject, tuple[float, float, float]]) -> tuple[bool, float]:
        return not _slot_on_it(scene, *c), float(np.hypot(c[1][0] - pos[0], c[1][2] - pos[1]))

    return min(ok, key=order, default=None)


def pick_seat(
    scene: Scene,
    kind: str,
    named: PlacedObject | None,
    pos: np.ndarray,
    others: dict[str, tuple[float, float]],
    me: str,
    occupied: list[tuple[float, float]] | tuple[()] = (),
) -> tuple[PlacedObject, tuple[float, float, float]] | None:
    """The seat (bed) an action sits (lies) on and the hips point of its slot, or None.

    The named object's free slot nearest the character when it has one; else the free slot of any
    object nearest the named object ("sits at the desk": a chair at the desk, within NEAR_NAMED) or,
    with nothing named, nearest the character (within NEAR_ANY: "walks to the bench. sits down").
    A slot within TAKEN of another character (``others``, ``occupied``: those seated by then) is not free.
    """
    taken = [np.asarray(xz, float) for n, xz in others.items() if n != me]
    taken += [np.asarray(xz, float) for xz in occupied]

    def free(p: tuple[float, float, float]) -> bool:
        return all(np.hypot(p[0] - o[0], p[2] - o[1]) > TAKEN for o in taken)

    def nearest(cands: list[tuple[PlacedObject, tuple[float, float, float]]], ref: np.ndarray, limit: float):
        ok = [(o, p) for o, p in cands if free(p) and np.hypot(p[0] - ref[0], p[2] - ref[1]) <= limit]
        return min(ok, key=lambda c: np.hypot(c[1][0] - ref[0], c[1][2] - ref[1]), default=None)

    if named is not None:
        own = nearest([(named, p) for p in seat_slots(named, kind)], pos, np.inf)
        if own is not None:
            return own
    kinds = ("bed",) if kind == "bed" else ("seat",)
    cands = [(o, p) for o in scene.objects for k in kinds for p in seat_slots(o, k)]
    if kind == "bed":  # a bed first; a sofa's lie slot too
        cands = [(o, p) for o in scene.objects for p in seat_slots(o, "bed")]
    if named is not None:
        return nearest(cands, np.array([named.position[0], named.position[2]]), NEAR_NAMED)
    return nearest(cands, pos, NEAR_ANY)


def prop_grip(
    scene: Scene, action: str, named: PlacedObject | None, pos: np.ndarray
) -> tuple[PlacedObject, str, tuple[float, float, float]] | None:
    """The small object a handheld action holds, the joint holding it and its grip point (object frame).

    Small objects are those the catalog lets a hand pick up (a "pick_up" contact point); the grip is the
    point named for the action ("drink", "call", "read"...: the action's name or its first word), else the
    pick-up point. The named object when it is one; else the nearest one made for the action.
    """

    def grip(placed: PlacedObject) -> tuple[str, tuple[float, float, float]] | None:
        try:
            from wana.assets.catalog import asset_for

            points = asset_for(placed).contact_points
        except Exception:  # noqa: BLE001 - unknown category or no catalog: nothing to hold
            return None
        if "pick_up" not in points:
            return None
        for key in (action, action.split("_")[0], "pick_up"):
            if key in points:
                cp = points[key]
                joint = cp.joint.replace("Middle1", "")
                return joint, (float(cp.position[0]), float(cp.position[1]), float(cp.position[2]))
        return None

    def nearest(objs: list[PlacedObject]) -> PlacedObject:
        return min(objs, key=lambda o: float(np.hypot(o.position[0] - pos[0], o.position[2] - pos[1])))

    made_for = [o for o in scene.objects if made_for_action(o, action)]
    if named is not None and not made_for_action(named, action) and (made_for or _is_tool_action(action)):
        # "hammers a nail into the plank", "sweeps the floor": what is worked on; the tool is the one made
        # for the action (none in reach: nothing is taken, the plank is not swung as a hammer)
        named = None
    if named is not None:
        # "drinks from her mug" with two mugs on the table: the one nearest the character
        alike = [o for o in scene.objects if o.category == named.category and grip(o) is not None]
        if "/" not in named.id and len(alike) > 1:
            named = nearest(alike)
        g = grip(named)
        return (named, *g) if g is not None else None
    if not made_for:
        return None
    # "They drink" after pouring the wine: from a glass, not the bottle poured from (the last choice)
    best = nearest([o for o in made_for if not _poured_from(o, action)] or made_for)
    g = grip(best)
    return (best, *g) if g is not None else None


def _poured_from(placed: PlacedObject | None, action: str) -> bool:
    """Whether a small object is one poured from (a bottle, a kettle: a "pour" point) and the action not a
    pour: drunk from only when nothing else in the room is made for drinking."""
    if placed is None or action in POUR_INTO:
        return False
    geo = _object_geometry(placed)
    return geo is not None and "pour" in geo[1]


def _is_tool_action(action: str) -> bool:
    try:
        clip = get_clip(action)
    except KeyError:
        return False
    return clip.interaction is not None and clip.interaction.object == "tool"


def made_for_action(placed: PlacedObject | None, action: str) -> bool:
    """Whether a small object is made for an action: the catalog lets a hand pick it up and names a contact
    point for the action (a cup's "drink", a hammer's "hammer"), or the action's name names it (a phone for
    "text_on_phone")."""
    if placed is None:
        return False
    try:
        from wana.assets.catalog import asset_for

        names = set(asset_for(placed).contact_points)
    except Exception:  # noqa: BLE001 - unknown category or no catalog
        return False
    own = bool({action, action.split("_")[0]} & names) or names_object(action, placed.category)
    if not ("pick_up" in names and own):
        return False
    if not _is_tool_action(action):
        return True
    try:  # a tool action's own point is also on what it works on (the plank's "hammer"): a tool is a tool
        from wana.assets.vocabulary import hypernyms

        return "tool" in hypernyms(placed.category)
    except KeyError:
        return True


WORK_AT_M = 1.6  # metres: how far what an action is done at may stand from the thing the sentence names


def work_place(scene: Scene, obj: PlacedObject, action: str) -> PlacedObject:
    """What a surface action is done at: the named object when it offers the action's own point, else the
    nearest object within WORK_AT_M of it that does ("washes the dishes": the sink they are in, not a plate)."""
    meant = {action, action.split("_")[0]} - {"touch", "pick_up"}  # points every thing has move nothing

    def offers(o: PlacedObject) -> bool:
        geo = _object_geometry(o)
        return geo is not None and bool(meant & set(geo[1]))

    if not meant or offers(obj):
        return obj
    here = np.array([obj.position[0], obj.position[2]])
    near = [
        (float(np.hypot(o.position[0] - here[0], o.position[2] - here[1])), o)
        for o in scene.objects
        if o.id != obj.id
    ]
    fit = [(d, o) for d, o in near if d <= WORK_AT_M and offers(o)]
    return min(fit, key=lambda t: t[0])[1] if fit else obj


OFFER_NEAR_M = 2.5  # metres from a standing character to the object an action naming none is done at
WORK_FRONT_M = 0.4  # metres in front of a seated character's hips where the hands work on a table top
WORK_EDGE_M = 0.08  # metres the hands keep from a table top's edge


def _footprint_gap(placed: PlacedObject, pos: np.ndarray) -> float:
    """Metres (horizontal) from pos to the object's footprint (0 inside it); its position without a catalog."""
    try:
        from wana.assets.catalog import world_bounds

        b = np.asarray(world_bounds(placed), float)[:, [0, 2]]
    except Exception:  # noqa: BLE001 - unknown category: its position stands for it
        b = np.array([[placed.position[0], placed.position[2]]] * 2)
    return float(np.linalg.norm(np.clip(pos, b[0], b[1]) - pos))


def offering(scene: Scene, action: str, pos: np.ndarray, limit: float) -> PlacedObject | None:
    """The object nearest pos (within limit, by footprint) that offers the action's own contact point, for an
    action at an object whose sentence names none ("Zoe washes her hands": the sink; "She takes notes" at
    the table she sits at): without one the clip plays in the air beside it. Not one the character stands
    inside to use (a shower: its stand point within its footprint): the sentence would have named it."""
    meant = {action, action.split("_")[0]} - {"touch", "pick_up"}
    near = []
    for o in scene.objects:
        geo = _object_geometry(o)
        if geo is None or _footprint_gap(o, geo[0]) <= 0.0:
            continue
        if meant & set(geo[1]) and "pick_up" not in geo[1]:
            gap = _footprint_gap(o, pos)
            if gap <= limit:
                near.append((gap, o.id, o))
    return min(near, key=lambda t: t[:2])[2] if near else None


def _small_offering(scene: Scene, action: str, pos: np.ndarray) -> PlacedObject | None:
    """The small object (a "pick_up" point) nearest pos within PICK_REACH that offers the action's own point,
    for a seated action at an object whose sentence names none and whose table offers none ("Lucy eats"
    with a plate on the kitchen table: the hands at the plate, not in the air above her lap)."""
    meant = {action, action.split("_")[0]} - {"touch", "pick_up"}
    near = []
    for o in scene.objects:
        geo = _object_geometry(o)
        if geo is None or "pick_up" not in geo[1] or not meant & set(geo[1]):
            continue
        d = float(np.hypot(o.position[0] - pos[0], o.position[2] - pos[1]))
        if d <= PICK_REACH:
            near.append((d, o.id, o))
    return min(near, key=lambda t: t[:2])[2] if near else None


def slid_to_place(
    placed: PlacedObject, targets: dict[str, tuple[float, float, float]], pos: np.ndarray, yaw: float
) -> dict[str, tuple[float, float, float]]:
    """A seated character's hand targets on a table top moved to the place in front of it: a long table's
    one catalog "write" point can be metres from the chair (the hand stayed 0.23 m short, in the air). The
    targets keep their height and spacing; the object's top nearest WORK_FRONT_M ahead of the hips."""
    try:
        from wana.assets.catalog import world_support_surfaces

        tops = world_support_surfaces(placed)
    except Exception:  # noqa: BLE001 - unknown category: the catalog points as they are
        return targets
    if not tops or not targets:
        return targets
    # seated, the plan's position is SEAT_BACK in front of the hips (where getting up ends)
    ahead = pos + np.array([np.sin(yaw), np.cos(yaw)]) * (WORK_FRONT_M - SEAT_BACK)
    centre = np.mean([[p[0], p[2]] for p in targets.values()], axis=0)
    best = None
    for _, corners in tops:
        lo, hi = corners.min(axis=0) + WORK_EDGE_M, corners.max(axis=0) - WORK_EDGE_M
        if np.any(hi < lo):
            continue
        spot = np.clip(ahead, lo, hi)
        if best is None or np.linalg.norm(spot - ahead) < np.linalg.norm(best - ahead):
            best = spot
    if best is None or np.linalg.norm(best - ahead) >= np.linalg.norm(centre - ahead):
        return targets
    dx, dz = best - centre
    return {j: (p[0] + float(dx), p[1], p[2] + float(dz)) for j, p in targets.items()}


def _grasp(placed: PlacedObject) -> tuple[str, tuple[float, float, float], tuple[float, float, float]] | None:
    """(joint, object-frame point, world point) where a hand takes a small object: its "pick_up" point."""
    try:
        from wana.assets.catalog import asset_for, to_world

        cp = asset_for(placed).contact_points.get("pick_up")
    except Exception:  # noqa: BLE001 - unknown category or no catalog: nothing to take
        return None
    if cp is None:
        return None
    local = tuple(float(v) for v in cp.position)
    world = to_world(placed, np.asarray(cp.position, float))
    return cp.joint, local, (float(world[0]), float(world[1]), float(world[2]))  # type: ignore[return-value]


SET_DOWN_REACH = 1.0  # metres: a surface this near is where a held prop is set down when none is named
SET_DOWN_MARGIN = 0.08  # metres kept from a surface's edge
SET_DOWN_CLEAR = 0.15  # metres kept from what already stands on the surface


def _set_down_point(
    scene: Scene, pos: np.ndarray, dest: PlacedObject | None, prop: PlacedObject, hand: dict
) -> tuple[float, float, float]:
    """World point for the holding joint that leaves the prop standing on a surface: dest's, else the nearest
    one within SET_DOWN_REACH of pos, else the prop's own place in the room."""
    from wana.assets.catalog import world_support_surfaces

    home = _grasp(prop)
    if (
        dest is None
        and home is not None
        and np.hypot(home[2][0] - pos[0], home[2][2] - pos[1]) <= SET_DOWN_REACH
    ):
        return home[2]  # within reach of where it was taken from: back there
    best, best_d = None, np.inf
    for o in [dest] if dest is not None else scene.objects:
        if o is None or o.id == prop.id:
            continue
        try:
            surfs = world_support_surfaces(o)
        except Exception:  # noqa: BLE001 - unknown category: nothing to set down on
            continue
        resting = [
            np.array([r.position[0], r.position[2]])
            for r in scene.objects
            if r.support == o.id and r.id != prop.id
        ]
        for h, corners in surfs:
            if not 0.3 <= h <= 1.3:
                continue
            lo, hi = corners.min(axis=0) + SET_DOWN_MARGIN, corners.max(axis=0) - SET_DOWN_MARGIN
            if np.any(hi < lo):
                lo = hi = (corners.min(axis=0) + corners.max(axis=0)) / 2
            grid = np.stack(
                np.meshgrid(np.linspace(lo[0], hi[0], 7), np.linspace(lo[1], hi[1], 7)), -1
            ).reshape(-1, 2)
            free = [g for g in grid if all(np.linalg.norm(g - r) > SET_DOWN_CLEAR for r in resting)]
            for p in free or [np.clip(pos, lo, hi)]:
                d = float(np.linalg.norm(p - pos))
                if d < best_d:
                    best, best_d = (float(p[0]), float(h), float(p[1])), d
    if best is None or (dest is None and best_d > SET_DOWN_REACH):
        if home is not None:
            return home[2]
        return (float(prop.position[0]), float(prop.position[1]), float(prop.position[2]))
    from wana.domain import quat

    grip = quat.rotate(
        quat.yaw(np.array(float(hand.get("prop_yaw", 0.0)))), np.asarray(hand["prop_grip"], float)
    )
    return (best[0] + float(grip[0]), best[1] + float(grip[1]), best[2] + float(grip[2]))


def _other_character(
    node: ActionNode, clip: ActionClip | None, others: dict[str, tuple[float, float]], scene: Scene, me: str
) -> str:
    """The name of the character an action is aimed at ("" when none).

    The target or destination names a character of ``others``; a touching action (hug, shake hands,
    high five) whose target is no character and no scene object ("shakes hands with Eve" parsed with
    target "hand") goes to the only other character there is.
    """
    for ref in (node.target, node.destination):
        if ref and ref != me and ref in others:
            return ref
    touching = clip is not None and clip.interaction is not None and clip.interaction.object == "person"
    candidates = [n for n in others if n != me]
    if touching and len(candidates) == 1 and find_object(scene, node.target or node.destination) is None:
        return candidates[0]
    return ""


def _yaw_to(frm: np.ndarray, to: np.ndarray, default: float) -> float:
    d = to - frm
    return float(np.arctan2(d[0], d[1])) if np.linalg.norm(d) > 1e-6 else default


def _seat_fronts(scene: Scene) -> list[tuple[float, float]]:
    """(x, z) where one stands to sit on each seat of the scene: SEAT_BACK in front of its sit point."""
    geos = [_object_geometry(o) for o in scene.objects]
    out = []
    for o, geo in zip(scene.objects, geos, strict=True):
        if geo is None or "sit" not in geo[1]:
            continue
        hips = geo[1]["sit"][0][1]
        out.append((float(hips[0] + np.sin(o.yaw) * SEAT_BACK), float(hips[2] + np.cos(o.yaw) * SEAT_BACK)))
    return out


def _pour_point(vessel: PlacedObject, pos: np.ndarray) -> tuple[float, float, float]:
    """Where the hand holding a kettle or a bottle pours into ``vessel``: above its rim, POUR_BACK_M back
    towards the one pouring (x, z ``pos``), so the spout ahead of the hand is over the opening."""
    try:
        from wana.assets.catalog import asset_for

        tall = float(asset_for(vessel).dims[1]) * float(vessel.scale[1])
    except Exception:  # noqa: BLE001 - unknown category: a cup's height
        tall = 0.1
    top = vessel.position[1] + tall
    d = pos - np.array([vessel.position[0], vessel.position[2]])
    n = float(np.linalg.norm(d))
    back = d / n * POUR_BACK_M if n > 1e-6 else np.zeros(2)
    return (
        float(vessel.position[0] + back[0]),
        float(top + POUR_ABOVE_M),
        float(vessel.position[2] + back[1]),
    )


def _onto(
    targets: dict[str, tuple[float, float, float]], small: PlacedObject
) -> dict[str, tuple[float, float, float]]:
    """A surface action's hand targets moved along the surface so the right hand is at the small object the
    sentence names ("makes a coffee": at the cup on the counter, not at the counter's own point 0.4 m away);
    the targets as they are when it is no small object (no "pick_up" point), there is no right hand, or it
    lies between the hands already."""
    grasp = _grasp(small)
    right = next((j for j in ("RightHandMiddle1", "RightHand") if j in targets), None)
    if grasp is None or right is None:
        return targets
    hands = [np.array([p[0], p[2]]) for j, p in targets.items() if j in HAND_TARGETS]
    at = np.array([small.position[0], small.position[2]])
    a, b = hands[0], hands[-1]
    t = float(np.clip(np.dot(at - a, b - a) / max(float(np.dot(b - a, b - a)), 1e-9), 0.0, 1.0))
    if np.linalg.norm(a + t * (b - a) - at) <= BETWEEN_HANDS_M:
        return targets  # already between the hands (the dishes in the sink's basin): both stay at work
    dx, dz = grasp[2][0] - targets[right][0], grasp[2][2] - targets[right][2]
    lift = max(0.0, grasp[2][1] - targets[right][1])  # above the object, never into it
    return {j: (p[0] + dx, p[1] + lift, p[2] + dz) if j in HAND_TARGETS else p for j, p in targets.items()}


def _pours_seated(vessel: PlacedObject, pos: np.ndarray) -> bool:
    """Whether a seated character pours into the vessel where it stands: one within SEATED_POUR_M of its
    position (its own glass at its place); a farther one is poured towards where the clip reaches (an arm
    stretched at a far glass pulled the trunk over the table)."""
    return bool(np.hypot(vessel.position[0] - pos[0], vessel.position[2] - pos[1]) <= SEATED_POUR_M)


def _short_of(pos: np.ndarray, other: np.ndarray, distance: float) -> np.ndarray:
    """The point on the line from pos to other that stops ``distance`` metres short of other."""
    d = other - pos
    n = float(np.linalg.norm(d))
    if n <= distance:
        return pos.copy()
    return other - d / n * distance


def _seated_at(xz: np.ndarray, seated: Sequence[tuple[float, float]]) -> bool:
    """Whether one of the seated others (x, z) is the character at ``xz``."""
    return any(float(np.hypot(xz[0] - s[0], xz[1] - s[1])) < 0.05 for s in seated)


def _at_distance(pos: np.ndarray, other: np.ndarray, distance: float) -> np.ndarray:
    """Where to stand ``distance`` metres from other: short of it on the way there, or a step back from it
    along the same line when TOO_CLOSE_M closer already (two who end up nose to nose after one waited
    behind the other shake hands at arm's length, not through each other)."""
    d = pos - other
    n = float(np.linalg.norm(d))
    if n >= distance - TOO_CLOSE_M:
        return _short_of(pos, other, distance)
    return other + (d / n if n > 1e-6 else np.array([0.0, -1.0])) * distance


@functools.lru_cache(maxsize=256)
def arms_room(clip_name: str) -> float:
    """Metres between two characters' hips a gesture at the other needs: twice its hands' farthest reach
    forward over the clip (a talking gesture sweeps 0.45 m ahead of the hips, and in "They talk" the other's
    hands come as far towards it) and ARMS_CLEAR_M, so neither hand goes into the other. 0 for a clip that
    does not bring a hand ahead of the body."""
    rot, _, _ = get_clip(clip_name).sample()
    pos, _ = forward_kinematics(rot.astype(np.float64), np.zeros((len(rot), 3)), rest_offsets())
    hands = pos[:, [JOINT_INDEX[n] for n in ("LeftHandMiddle1", "RightHandMiddle1")], 2]
    ahead = float(hands.max()) if hands.size else 0.0
    return round(2 * ahead + ARMS_CLEAR_M, 2) if ahead > 0.15 else 0.0


def _first_within(way: np.ndarray, other: np.ndarray, distance: float, goal: np.ndarray) -> np.ndarray:
    """Where a walk along ``way`` (N, 2) first comes ``distance`` metres near ``other``: a way round furniture
    that arrives from the far side would otherwise go through the person to the point short of them on the
    side the walker started. ``goal`` when the way only gets that near at its end."""
    for a, b in zip(way[:-1], way[1:], strict=True):
        d = b - a
        f = a - other
        qa, qb, qc = float(d @ d), 2.0 * float(f @ d), float(f @ f) - distance**2
        if qa < 1e-12:
            continue
        disc = qb * qb - 4 * qa * qc
        if disc < 0:
            continue
        t = (-qb - np.sqrt(disc)) / (2 * qa)  # entering the circle
        if qc <= 0:  # already within it at a: it was not reached walking
            continue
        if 0.0 <= t <= 1.0:
            hit = a + t * d
            return goal if np.linalg.norm(hit - goal) < 0.05 else hit
    return goal


def _free_beside(scene: Scene, pos: np.ndarray, other: np.ndarray, distance: float) -> np.ndarray:
    """A free spot ``distance`` metres from another character (furniture clear of a walking body), the one
    nearest the straight approach from pos; the straight approach's end when none is free."""
    from services.motion.routing import free_spot

    straight = _short_of(pos, other, distance)
    ring = [
        other + distance * np.array([np.sin(a), np.cos(a)])
        for a in np.linspace(0, 2 * np.pi, 24, endpoint=False)
    ]
    free = [
        p
        for p in [straight, *ring]
        if np.allclose(free_spot(scene, (float(p[0]), float(p[1]))), p, atol=0.02)
    ]
    return min(free, key=lambda p: float(np.linalg.norm(p - straight))) if free else straight


def _with_moods(segs: list[PlannedSegment], character: CharacterNode) -> list[PlannedSegment]:
    """Each segment with the mood its action's manner word gives ("angrily": services/motion/style.py)."""
    out = []
    for seg in segs:
        node = character.actions[seg.action_index] if 0 <= seg.action_index < len(character.actions) else None
        mood = mood_of(node.manner if node else "")
        out.append(dataclasses.replace(seg, mood=mood) if mood != (0.0, 0.0) else seg)
    return out


def _walk_speed_factor(manner: str) -> float:
    """The commanded walking speed's factor for a manner word: the captured gaits' for words the gait knows
    ("slowly", "tiredly"), else the mood's tempo ("angrily"), never both (they would count the word twice)."""
    gait = gait_style(manner)
    return gait.speed if gait != NEUTRAL_GAIT else style_of(*mood_of(manner)).tempo


def _puts_another(scene: Scene, target: str, held: str) -> bool:
    """Whether a put names a thing other than the one in the hand ("hangs his coat" with a phone in the hand
    and no coat in the room): the phone stays in the hand, not hung on the coat rack."""
    if not target or target == held or target.lower() in ("it", "them", "this", "that", "everything"):
        return False
    return find_object(scene, target) is None


def plan_actions(
    character: CharacterNode,
    scene: Scene,
    start: tuple[float, float, float],
    route_fn: RouteFn | None = None,
    posture: str = "stand",
    others: dict[str, tuple[float, float]] | None = None,
    distances: dict[str, float] | None = None,
    seats: dict[int, str] | None = None,
    spots: dict[int, tuple[float, float]] | None = None,
    occupied: list[tuple[float, float]] | None = None,
    holding: str = "",
    bodies: list[tuple[float, float]] | None = None,
) -> MotionPlan:
    """Turn a character's ordered actions into a MotionPlan.

    Args:
        character: the SSG character with its ordered ActionNodes.
        scene: the composed scene (objects placed in the world).
        start: (x, z, yaw) where the character starts.
        route_fn: route planner (scene, start_xz, goal_xz[, ignore]) -> (N, 2); defaults to A* around
            the furniture (services.motion.routing.scene_route), a straight line where there is none.
        posture: the posture the character starts in ("stand", "sit", ...), when planning resumes mid-story.
        others: other characters' (x, z) metres, world, when the first action starts; actions aimed at
            one of them face it, and walking / touching actions go up to it.
        distances: metres a walk up to another character stops short of them (the social model's
            standing distance: friends closer than a boss); touching actions keep their clip's distance.
        seats: action index -> the object's contact point to sit or lie on (its slot: "sit_0" on a sofa).
        spots: action index -> x, z where it stands at or walks to its object (its stand slot).
        occupied: (x, z) metres, world, of other characters already seated: seat slots there are taken.
        holding: id of the scene object already in the hand (picked up by an earlier action): it stays there.
        bodies: (x, z) metres, world, of the other characters standing near: a gesture aimed at nobody steps
            back from one its hands would reach.

    Returns:
        the plan; unknown actions become a 1 s wait and a diagnostic.
    """
    others = dict(others or {})
    seats, spots = dict(seats or {}), dict(spots or {})
    lib = load_library()
    segs: list[PlannedSegment] = []
    diags: list[str] = []
    x, z, yaw = start
    pos = np.array([x, z], float)

    hand: dict = {}  # the prop in the hand between segments (PlannedSegment prop fields), {} when empty
    held_obj = next((o for o in scene.objects if o.id == holding), None) if holding else None
    if held_obj is not None and (g := _grasp(held_obj)) is not None:
        hand.update(prop=held_obj.id, prop_joint=g[0], prop_grip=g[1], prop_yaw=float(held_obj.yaw))

    sat_on: dict[str, tuple] = {}  # "seat": (object id, hips point) of the last sit-down
    if posture == "sit" and (under := seat_under(scene, pos)) is not None:  # resumed seated: on that seat
        sat_on["seat"] = (under[0].id, under[1])
    elsewhere = [xz for n, xz in others.items() if n != character.name]  # kept clear of beside a seat

    def rise_spot() -> np.ndarray | None:
        """Seated on a known seat: where getting up ends, clear of it and of the table (seat_stand_spot)."""
        if now_posture() != "sit" or "seat" not in sat_on:
            return None
        seat = next((o for o in scene.objects if o.id == sat_on["seat"][0]), None)
        if seat is None:
            return None
        return seat_stand_spot(scene, seat, sat_on["seat"][1], elsewhere)

    def add(**kw) -> None:
        nonlocal pos
        if hand and not kw.get("prop"):  # held through every segment until it is put down
            kw.update(hand, prop_span="whole")
        if kw.get("action") == "stand" and kw.get("kind") == "action" and not kw.get("targets"):
            spot = rise_spot()
            if spot is not None:  # getting up onto the spot in front of the seat, the legs out of it
                kw["targets"] = (("Hips", (float(spot[0]), 0.0, float(spot[1]))),)
                pos = spot
        segs.append(PlannedSegment(index=len(segs), **kw))
        targets = dict(kw.get("targets", ()))
        if kw.get("action") == "sit" and kw.get("kind") == "action" and "Hips" in targets:
            sat_on["seat"] = (kw.get("target_id", ""), targets["Hips"])

    def route(a: tuple[float, float], b: tuple[float, float], ignore: frozenset[str]) -> np.ndarray:
        if route_fn is not None:
            return route_fn(scene, a, b, ignore=ignore) if custom_ignores else route_fn(scene, a, b)
        from services.motion.routing import scene_route

        wps, why = scene_route(scene, a, b, ignore)
        if why:
            diags.append(why)
        return wps

    custom_ignores = route_fn is not None and _takes_ignore(route_fn)

    def walk_to(
        goal: np.ndarray,
        speed: float,
        face: float | None,
        action: str,
        ai: int,
        target: str = "",
        manner: str = "",
    ) -> None:
        nonlocal pos, yaw
        if np.linalg.norm(goal - pos) < 0.05 and face is None:
            return
        spot = rise_spot()
        if spot is not None and np.linalg.norm(goal - pos) > 1e-6:
            pos = spot  # a walk from a seat gets up first (synthesis), onto the spot in front of it
        a, b = (float(pos[0]), float(pos[1])), (float(goal[0]), float(goal[1]))
        if np.linalg.norm(goal - pos) < 1e-6:  # turning in place
            wps = np.array([a, b])
        else:
            ignore = resting_on(scene, target) if target and target not in others else frozenset()
            wps = np.asarray(route(a, b, ignore), float).reshape(-1, 2)
        add(
            kind="locomotion",
            action=action,
            waypoints=tuple(map(tuple, np.round(wps, 4))),
            speed=speed,
            face_yaw=face,
            target_id=target,
            action_index=ai,
            manner=manner,
        )
        if len(wps) > 1:
            d = wps[-1] - wps[-2]
            yaw = float(np.arctan2(d[0], d[1])) if np.linalg.norm(d) > 1e-6 else yaw
        pos = wps[-1].copy()
        if face is not None:
            yaw = face

    def reach_spot(want: np.ndarray, here: np.ndarray, target: str) -> np.ndarray:
        """Where to stand to reach ``here`` from about ``want``: the free spot nearest ``want`` for a body
        reaching over furniture (REACH_BODY) when the route from where the character is arrives there
        and it is nearer ``here``, else the free spot for a walking body."""
        from services.motion.routing import RADIUS, free_spot, scene_route

        a = (float(pos[0]), float(pos[1]))
        ignore = resting_on(scene, target) if target and target not in others else frozenset()
        spots = []
        for radius in (REACH_BODY, RADIUS):
            spot = np.asarray(free_spot(scene, (float(want[0]), float(want[1])), radius=radius), float)
            b = (float(spot[0]), float(spot[1]))
            if radius != RADIUS:  # a tight spot counts only when the walk gets there
                ends = route(a, b, ignore) if route_fn is not None else scene_route(scene, a, b, ignore)[0]
                if np.linalg.norm(np.asarray(ends, float).reshape(-1, 2)[-1] - spot) > 0.05:
                    continue
            spots.append(spot)
        return min(spots, key=lambda p: float(np.linalg.norm(here - p)))

    def step_up_to(here: np.ndarray, ai: int, target: str, front: np.ndarray | None = None) -> None:
        """Standing farther than STEP_IN from a point the hand must reach (a prop to take or set down):
        step to REACH from it (reach_spot), so the arm arrives without a deep bend; from the ``front`` side
        when given (x, z direction), else from where the character is."""
        if np.linalg.norm(here - pos) <= STEP_IN:
            return
        away = pos - here if front is None else np.asarray(front, float)
        n = float(np.linalg.norm(away))
        spot = reach_spot(here + (away / n if n > 1e-6 else np.array([0.0, 1.0])) * REACH, here, target)
        if np.linalg.norm(here - spot) < np.linalg.norm(here - pos) - 0.05:  # only a step that closes in
            walk_to(spot, 1.2, _yaw_to(spot, here, yaw), "walk", ai, target)

    def poured_into(held: str) -> PlacedObject | None:
        """The vessel a pouring action (POUR_INTO) empties the held one into: the sentence's destination."""
        into = node.destination or node.target  # "pours juice into the glass": no juice, the glass its target
        if name not in POUR_INTO or not into:
            return None
        kind = into.split("#")[0].split("/")[0]
        alike = [
            o
            for o in scene.objects
            if o.id != held and (o.id == into or o.category == kind or o.id.split("/")[0] == kind)
        ]
        return min(
            alike, key=lambda o: np.hypot(o.position[0] - pos[0], o.position[2] - pos[1]), default=None
        )

    def step_up_close(here: np.ndarray, ai: int, target: str) -> None:
        """step_up_to from the side nearest the point whichever that is (REACH_SIDES tried, the approach
        among them): a cup in the middle of a kitchen island is poured into from the side it is nearest,
        not from across the island; a longer walk counts WALK_WEIGHT against the nearer spot."""
        if np.linalg.norm(here - pos) <= STEP_IN:
            return
        # the others (seated, aimed at, standing by), and the fronts of seats where one steps to sit (someone
        # may be sitting down there): the bass guitar beside the drum kit is not taken from inside the drummer
        people = [*(occupied or []), *others.values(), *(bodies or []), *_seat_fronts(scene)]
        sides = [pos - here] + [
            np.array([np.sin(a), np.cos(a)]) for a in np.arange(REACH_SIDES) * 2 * np.pi / REACH_SIDES
        ]

        def cost(side: np.ndarray) -> float:
            spot = reach_spot(here + side / np.linalg.norm(side) * REACH, here, target)
            crowded = any(np.hypot(spot[0] - b[0], spot[1] - b[1]) < BODY_CLEAR_M for b in people)
            return (  # beside the one seated at the cup, not in their lap
                float(np.linalg.norm(here - spot))
                + WALK_WEIGHT * float(np.linalg.norm(spot - pos))
                + 10.0 * crowded
            )

        sides = [side for side in sides if np.linalg.norm(side) > 1e-6]
        if sides:
            step_up_to(here, ai, target, front=min(sides, key=cost))

    def clear_of_bodies(stand: np.ndarray, centre: np.ndarray) -> np.ndarray:
        """``stand``, or where another already stands there (the bass guitar lies where the drummer plays),
        the free spot nearest it as far from the contacts at ``centre`` or up to BODY_SHIFT_M farther (rings
        round them) and at least BODY_CLEAR_M from everyone standing; ``stand`` when there is none."""
        from services.motion.routing import RADIUS, scene_grid

        people = np.asarray(bodies or [], float).reshape(-1, 2)
        if not len(people) or np.linalg.norm(people - stand, axis=1).min() >= BODY_CLEAR_M:
            return stand
        r0 = float(np.linalg.norm(stand - centre))
        a = np.arange(CLEAR_DIRECTIONS) * 2 * np.pi / CLEAR_DIRECTIONS
        rings = r0 + np.arange(0.0, BODY_SHIFT_M + 1e-9, 0.1)
        spots = (centre + rings[:, None, None] * np.stack([np.sin(a), np.cos(a)], -1)[None]).reshape(-1, 2)
        clear = np.linalg.norm(spots[:, None] - people[None], axis=2).min(axis=1) >= BODY_CLEAR_M
        free = np.asarray(scene_grid(scene, frozenset(), RADIUS).is_free_xz(spots), bool).reshape(-1)
        spots = spots[clear & free]
        if not len(spots):
            return stand
        return spots[int(np.argmin(np.linalg.norm(spots - stand, axis=1)))]

    def front_of(obj_id: str) -> np.ndarray | None:
        """The side a piece of furniture is used from (its catalog stand point from its centre), None if unknown:
        papers on a filing cabinet are taken standing in front of it, not from beside its drawers."""
        under = next((o for o in scene.objects if o.id == obj_id), None)
        geo = _object_geometry(under) if under is not None else None
        if geo is None:
            return None
        side = geo[0] - np.array([under.position[0], under.position[2]])  # type: ignore[union-attr]
        return side if np.linalg.norm(side) > 1e-6 else None

    def make_room(
        name: str,
        ai: int,
        target: str = "",
        at: np.ndarray | None = None,
        face_to: np.ndarray | None = None,
        ignore: frozenset[str] = frozenset(),
        reaching: frozenset[str] = frozenset(),
        within: float = np.inf,
    ) -> tuple[np.ndarray, float] | None:
        """Standing, the spot and facing nearest ``at`` (default: here) where the clip's arms keep out of the
        furniture beside it (services.motion.elbow_room), None when they are clear there already. Without
        ``at`` the character steps there."""
        nonlocal pos, yaw
        if now_posture() != "stand" or name in SEATED_AS or "locomotion" in lib[name].tags:
            return None
        from services.motion.elbow_room import roomy_spot
        from services.motion.routing import RADIUS

        skip = ignore | (resting_on(scene, target) if target and target not in others else frozenset())
        if hand:
            skip |= {hand["prop"]}
        here = pos if at is None else np.asarray(at, float)
        got = roomy_spot(scene, name, here, yaw if at is None or face_to is None else _yaw_to(here, face_to, yaw),
                         ignore=skip, reaching=reaching, body_radius=RADIUS if at is None else REACH_BODY,
                         face_to=face_to, within=within)  # fmt: skip
        if got is not None and at is None:
            walk_to(got[0], 1.0, got[1], "walk", ai, target)
        return got

    def now_posture() -> str:
        """The posture the plan so far leaves the character in."""
        for s in reversed(segs):
            if s.kind == "locomotion":
                return "stand"
            if s.kind == "wait":
                continue  # held where it was ("dozes off in the armchair": still sitting)
            if s.action in SEATED_AS:
                return SEATED_AS[s.action]
            if s.kind == "action" and not s.upright and s.action in lib and lib[s.action].drives_lower_body:
                return "stand"  # an upright segment plays the clip's arms alone: the posture holds
        return posture

    def now_seat() -> str:
        """The seat (bed) the plan so far sat the character on ("" when unknown or standing)."""
        for s in reversed(segs):
            if s.action in SEATED_AS:
                return s.target_id
            if s.kind == "locomotion" or (s.kind == "action" and s.action == "stand"):
                return ""
        return ""

    def set_down(dest: PlacedObject | None, ai: int, clip_name: str = "put_down") -> None:
        """Put the held prop down (reach, release) on dest's surface, else the nearest one, else its place."""
        nonlocal pos
        prop_obj = next((o for o in scene.objects if o.id == hand["prop"]), None)
        if prop_obj is None:
            hand.clear()
            return
        target = _set_down_point(scene, pos, dest, prop_obj, hand)
        here = np.array([target[0], target[2]])
        if now_posture() == "stand":
            step_up_to(here, ai, (dest or prop_obj).id)
        face = _yaw_to(pos, here, yaw)
        if (
            now_posture() == "stand"
            and abs(np.arctan2(np.sin(face - yaw), np.cos(face - yaw))) > TURN_TOLERANCE
        ):
            walk_to(pos.copy(), 1.0, face, "turn", ai, prop_obj.id)
        if clip_name != "put_down" and target[1] < TABLE_GRASP_M:
            clip_name = "put_down"  # down to the floor: a bend, not an arm's reach
        add(kind="action", action=clip_name, targets=((hand["prop_joint"], target),),
            target_id=(dest or prop_obj).id, action_index=ai, **hand, prop_span="release")  # fmt: skip
        hand.clear()

    def set_down_in_reach() -> bool:
        """Whether a seated character can set the held prop down without getting up (a table in front)."""
        prop_obj = next((o for o in scene.objects if o.id == hand.get("prop")), None)
        if prop_obj is None:
            return False
        target = _set_down_point(scene, pos, None, prop_obj, hand)
        return bool(np.hypot(target[0] - pos[0], target[2] - pos[1]) <= PICK_REACH)

    def take(prop_obj: PlacedObject, ai: int, shows: str = "") -> bool:
        """Walk up to a small object and take it with an arm's reach (standing); False when out of reach.
        ``shows``: the action the segment plays instead, upright (a "pick_up" at shelf height: its arm only)."""
        reach = _grasp(prop_obj)
        if reach is None or now_posture() != "stand":
            return False
        here = np.array([prop_obj.position[0], prop_obj.position[2]])
        step_up_to(here, ai, prop_obj.id, front_of(prop_obj.support) if shows else None)
        if np.linalg.norm(here - pos) > PICK_REACH:
            return False
        taker = GRASP_TABLE if reach[2][1] >= TABLE_GRASP_M else "pick_up"
        if hand and hand["prop"] != prop_obj.id:
            set_down(None, ai, GRASP_TABLE)
        face = _yaw_to(pos, here, yaw)
        if abs(np.arctan2(np.sin(face - yaw), np.cos(face - yaw))) > TURN_TOLERANCE:
            walk_to(pos.copy(), 1.0, face, "turn", ai, prop_obj.id)
        grasp = {"prop": prop_obj.id, "prop_joint": reach[0], "prop_grip": reach[1],
                 "prop_yaw": float(prop_obj.yaw)}  # fmt: skip
        played = {"action": shows, "upright": True} if shows and shows != taker else {"action": taker}
        add(kind="action", targets=((reach[0], reach[2]),), target_id=prop_obj.id, action_index=ai,
            prop_span="grasp", **played, **grasp)  # fmt: skip
        hand.update(grasp)
        return True

    def take_seated(prop_obj: PlacedObject, ai: int, shows: str) -> bool:
        """Seated on a known seat, take a small object in arm's reach of the hips (SEATED_REACH_M) where one
        sits, with the arms of ``shows`` (its upright variant) on the seated pose; False when there is none,
        it is out of reach or on the floor."""
        reach = _grasp(prop_obj)
        if reach is None or now_posture() != "sit" or "seat" not in sat_on:
            return False
        hips = sat_on["seat"][1]
        point = reach[2]
        if (
            point[1] < hips[1] - SEATED_GRASP_BELOW_M
            or np.hypot(point[0] - hips[0], point[2] - hips[2]) > SEATED_REACH_M
        ):
            return False
        if hand and hand["prop"] != prop_obj.id:
            if not set_down_in_reach():
                return False
            set_down(None, ai, GRASP_TABLE)
        grasp = {"prop": prop_obj.id, "prop_joint": reach[0], "prop_grip": reach[1],
                 "prop_yaw": float(prop_obj.yaw)}  # fmt: skip
        played = {"action": shows, "upright": True}
        add(kind="action", targets=((reach[0], point),), target_id=prop_obj.id, action_index=ai,
            prop_span="grasp", **played, **grasp)  # fmt: skip
        hand.update(grasp)
        return True

    def step_back(back: np.ndarray, there: np.ndarray, ai: int, person: str) -> None:
        """A step back to ``back``, still facing the character at ``there``."""
        face = _yaw_to(back, there, yaw)
        walk_to(back, 0.8, face, "walk_backward" if "walk_backward" in lib else "walk", ai, person)

    def clear_of_others(name: str, ai: int) -> None:
        """Standing, a step back from the nearest other character when a gesture aimed at nobody would put
        a hand into them: to half the room two need gesturing at each other (arms_room) and a body more, so
        that one gesturing clears the other, and two who both step back clear each other's hands."""
        room = arms_room(name)
        people = [(np.asarray(xz, float), n) for n, xz in others.items() if n != character.name]
        people += [(np.asarray(xz, float), "") for xz in bodies or ()]
        if not room or not people or now_posture() != "stand":
            return
        there, who = min(people, key=lambda p_n: float(np.linalg.norm(p_n[0] - pos)))
        need = room / 2 + SOLO_BODY_M
        if float(np.linalg.norm(there - pos)) < need - TOO_CLOSE_M:
            step_back(_free_beside(scene, _at_distance(pos, there, need), there, need), there, ai, who)

    def hand_over(gift: PlacedObject | None, person: str, ai: int, duration_s: float) -> bool:
        """ "Gives the cup to Anna": take the cup (unless it is in the hand already), walk up to Anna, hold it
        out to the point between the two (the reach releases it there, at HANDOVER_HEIGHT) and finish with
        the presenting gesture. The receiver's hand meets it there (services.motion.handover)."""
        if gift is None or (hand.get("prop") != gift.id and not take(gift, ai)):
            return False  # "gives him a thumbs up": a gesture, nothing changes hands
        if not hand or now_posture() != "stand":
            return False
        there = np.asarray(others[person], dtype=float)
        goal = _free_beside(scene, pos, there, HANDOVER_DISTANCE)
        face = _yaw_to(goal, there, yaw)
        if np.linalg.norm(goal - pos) > 0.1:
            walk_to(goal, 1.2, face, "walk", ai, person)
        elif abs(np.arctan2(np.sin(face - yaw), np.cos(face - yaw))) > TURN_TOLERANCE:
            walk_to(pos.copy(), 1.0, face, "turn", ai, person)
        mid = (pos + there) / 2
        point = (float(mid[0]), HANDOVER_HEIGHT, float(mid[1]))
        add(kind="action", action=GRASP_TABLE, targets=((hand["prop_joint"], point),), target_id=person,
            action_index=ai, **hand, prop_span="release")  # fmt: skip
        hand.clear()
        add(kind="action", action="present", duration_s=duration_s or HANDOVER_GESTURE_S, target_id=person,
            action_index=ai)  # fmt: skip
        # then a step back, still facing the receiver: the two do not stay bunched at arm's length
        off = pos - there
        away = there + off / max(float(np.linalg.norm(off)), 1e-6) * HANDOVER_STEP_BACK
        back = _free_beside(scene, away, there, HANDOVER_STEP_BACK)
        if np.linalg.norm(back - there) > np.linalg.norm(pos - there) + 0.1:
            walk_to(back, 0.8, face, "walk_backward" if "walk_backward" in lib else "walk", ai, person)
        return True

    node: ActionNode
    for ai, node in enumerate(character.actions):
        name = node.action
        if not name or name not in lib:
            try:
                name = get_clip(node.action or node.verb).name
            except KeyError:
                diags.append(f"unknown action {node.action or node.verb!r}: waiting 1 s instead")
                add(kind="wait", action="idle", duration_s=1.0, action_index=ai)
                continue
        clip = lib[name]
        speed_k = _walk_speed_factor(node.manner)
        person = _other_character(node, clip, others, scene, character.name)
        sitting_by = ""  # "sits next to her": a seat near that character, not the floor beside her
        if person and clip.interaction is not None and clip.interaction.object in ("seat", "bed"):
            sitting_by, person = person, ""
        if person and name == "present" and node.verb == HANDOVER_VERB:
            gift = next(
                (o for r in (node.target, node.instrument, node.destination) if r != person
                 and (o := find_object(scene, r)) is not None),
                None,
            )  # fmt: skip
            if hand_over(gift, person, ai, float(node.duration_s)):
                continue
        if person:
            there = np.asarray(others[person], dtype=float)
            touching = clip.interaction is not None and clip.interaction.object == "person"
            seated = now_posture() != "stand"
            if "locomotion" in clip.tags or name in CLOSE_DISTANCE or touching:
                near = CLOSE_DISTANCE.get(name) or (
                    (distances or {}).get(person, PERSON_DISTANCE)
                    if "locomotion" in clip.tags
                    else PERSON_DISTANCE
                )
                if touching and not seated and _seated_at(there, occupied or []):
                    # a seated one's knees and feet are in front of its hips: stand beyond them and bend
                    # down (Leo's toes in Marta's shins as he hugged her on the sofa, livingroom s9)
                    near = max(near, SEATED_PARTNER_M)
                goal = _at_distance(pos, there, near)
                if np.linalg.norm(goal - there) > np.linalg.norm(pos - there) + 0.05:  # a step back
                    step_back(_free_beside(scene, goal, there, near), there, ai, person)
                    goal = pos.copy()
                from services.motion.routing import reachable_short_of

                around = reachable_short_of(scene, (pos[0], pos[1]), (there[0], there[1]), near)
                goal = goal if around is None else np.asarray(around)  # not the far side of the armchair
                if np.linalg.norm(goal - pos) > 0.1:  # a way round the table that passes them stops there
                    way = np.asarray(route((pos[0], pos[1]), (goal[0], goal[1]), frozenset()), float)
                    goal = _first_within(way.reshape(-1, 2), there, near, goal)
                face = _yaw_to(goal, there, yaw)
                if "locomotion" in clip.tags:
                    walk_to(goal, SPEEDS.get(name, 1.3) * speed_k, face, name, ai, person, node.manner)
                    continue
                if np.linalg.norm(goal - pos) > 0.1:
                    walk_to(goal, 1.2, face, "walk", ai, person)
                elif abs(np.arctan2(np.sin(face - yaw), np.cos(face - yaw))) > TURN_TOLERANCE:
                    walk_to(pos.copy(), 1.0, face, "turn", ai, person)
            elif not seated:
                room = arms_room(name)
                if room and np.linalg.norm(there - pos) < room - TOO_CLOSE_M:  # the hands need room
                    step_back(
                        _free_beside(scene, _at_distance(pos, there, room), there, room), there, ai, person
                    )
                face = _yaw_to(pos, there, yaw)
                if abs(np.arctan2(np.sin(face - yaw), np.cos(face - yaw))) > TURN_TOLERANCE:
                    walk_to(pos.copy(), 1.0, face, "turn", ai, person)
            if not touching:  # a gesture at someone: its arms out of the furniture beside the character
                make_room(name, ai, face_to=there)
            add(
                kind="action",
                action=name,
                duration_s=float(node.duration_s),
                target_id=person,
                action_index=ai,
            )
            continue
        if "locomotion" in clip.tags:
            obj = find_object(scene, node.destination or node.target)
            if obj is not None:
                geo = _object_geometry(obj) or _fallback_geometry(obj)
                goal = geo[0]
                # Stop beside the object, not inside it or other furniture (a chair tucked under a desk).
                from services.motion.routing import free_spot

                goal = np.asarray(free_spot(scene, (float(goal[0]), float(goal[1]))), float)
                if ai in spots:
                    goal = np.asarray(spots[ai], float)
            else:
                fwd = np.array([np.sin(yaw), np.cos(yaw)])
                goal = pos + fwd * (2.0 if node.destination or not node.target else 1.5)
            walk_to(goal, SPEEDS.get(name, 1.3) * speed_k, None, name, ai, obj.id if obj else "", node.manner)
            continue
        if name == "stand" and now_posture() == "stand":
            # Already standing: a short hold, not a get-up from a seat that is not there; "stands in front
            # of the mirror" from across the room walks there first.
            stood_at = find_object(scene, node.target or node.destination)
            geo = _object_geometry(stood_at) if stood_at is not None else None
            if stood_at is not None and geo is not None and _footprint_gap(stood_at, pos) > STAND_AT_M:
                from services.motion.routing import free_spot

                goal = np.asarray(free_spot(scene, (float(geo[0][0]), float(geo[0][1]))), float)
                walk_to(goal, SPEEDS.get("walk", 1.3) * speed_k, None, "walk", ai, stood_at.id, node.manner)
            add(kind="wait", action=name, duration_s=STAY_S, action_index=ai)
            continue
        if name in ("turn_left", "turn_right", "turn_around") and now_posture() != "stand":
            # Seated or lying, the body does not spin on the seat: the posture holds.
            add(kind="wait", action=name, duration_s=STAY_S, action_index=ai)
            continue
        if name in ("turn_left", "turn_right", "turn_around"):
            add(kind="action", action=name, action_index=ai)
            yaw += {"turn_left": np.pi / 2, "turn_right": -np.pi / 2, "turn_around": np.pi}[name]
            continue
        if name == "pick_up" and now_posture() == "sit":
            prop_obj = next(
                (o for r in (node.target, node.instrument, node.destination) if (o := find_object(scene, r))),
                None,
            )
            if prop_obj is not None and take_seated(prop_obj, ai, name):
                continue  # in reach where one sits: taken seated, not by getting up and bending over the seat
        if (
            clip.drives_lower_body
            and name not in SEATED_AS
            and name not in ("turn_left", "turn_right", "turn_around")
            and now_posture() != "stand"
        ):
            add(kind="action", action="stand", action_index=ai)  # a whole-body action needs standing
        # The first of target, instrument, destination that names an object ("falls asleep on the sofa":
        # a target word that is no object leaves the sofa).
        obj = next(
            (o for r in (node.target, node.instrument, node.destination) if (o := find_object(scene, r))),
            None,
        )
        at_object = clip.interaction is not None and clip.interaction.object not in (
            *HELD_KINDS,
            "person",
            "seat",
            "bed",
        )
        if obj is None and at_object and not clip.drives_lower_body:
            # "washes her hands", "takes notes": at the nearest object made for it (seated: in reach only)
            obj = offering(scene, name, pos, PICK_REACH if now_posture() != "stand" else OFFER_NEAR_M)
            if obj is None and now_posture() == "sit":
                # "Lucy eats" at the table with a plate in front of her: at the plate (its "eat" point)
                obj = _small_offering(scene, name, pos)
        if (
            name == "sleep"
            and now_posture() == "sit"
            and (obj is None or obj.id == now_seat() or not seat_slots(obj, "bed"))
        ):
            # "She sits in the armchair ... falls asleep in the armchair": dozes off where she sits
            dur = float(node.duration_s) if node.duration_s > 0 else SLEEP_S
            add(kind="wait", action=name, duration_s=dur, target_id=now_seat(), action_index=ai)
            continue
        seat_pick: tuple[PlacedObject, tuple[float, float, float]] | None = None
        if clip.interaction and clip.interaction.object in ("seat", "bed"):
            near_xz = np.asarray(others[sitting_by], float) if sitting_by and obj is None else pos
            seat_pick = pick_seat(
                scene, clip.interaction.object, obj, near_xz, others, character.name, occupied or []
            )
            if seat_pick is None:
                what = "bed" if clip.interaction.object == "bed" else "seat"
                where = f" near the {obj.id.split('#')[0].replace('_', ' ')}" if obj is not None else ""
                diags.append(
                    f"no free {what}{where} for {character.name} to {name.replace('_', ' ')} on: "
                    f"{character.name} stands instead"
                )
                add(kind="wait", action="idle", duration_s=STAY_S, action_index=ai)
                continue
            if obj is not None and seat_pick[0].id != obj.id:
                asked = f"the {obj.id.split('#')[0].replace('_', ' ')}"
                diags.append(
                    f"{character.name} {name.replace('_', ' ')}s on the nearest free "
                    f"{seat_pick[0].category.replace('_', ' ')} ({asked} named)"
                )
            obj = seat_pick[0]
            if name == "sleep" and now_posture() != "lie":
                # Sleeping from standing: lie down on the bed first, then sleep there.
                lie = lib.get("lie_down")
                if lie is not None:
                    bed_xz = np.array([seat_pick[1][0], seat_pick[1][2]])
                    face = float(obj.yaw)
                    approach = bed_xz + np.array([np.sin(face), np.cos(face)]) * SEAT_BACK
                    walk_to(approach, 1.2, face, "walk", ai, obj.id)
                    pos, yaw = approach.copy(), face
                    add(
                        kind="action",
                        action="lie_down",
                        targets=(("Hips", seat_pick[1]),),
                        target_id=obj.id,
                        action_index=ai,
                    )
        targets: dict[str, tuple[float, float, float]] = {}
        held: dict = {}
        kind = clip.interaction.object if clip.interaction else ""
        in_hand = next((o for o in scene.objects if hand and o.id == hand["prop"]), None)
        # a screwdriver in the hand does not sweep the floor when a broom is there to take
        any_made_for = kind in HELD_KINDS and any(made_for_action(o, name) for o in scene.objects)
        # the bottle just poured from is set down for a glass to drink from, when the room has one
        fits_hand = made_for_action(in_hand, name) and not (
            _poured_from(in_hand, name)
            and any(made_for_action(o, name) and not _poured_from(o, name) for o in scene.objects)
        )
        if (
            kind in HELD_KINDS
            and hand
            and (
                (obj is None and (fits_hand or not any_made_for))
                or (obj is not None and obj.id == hand["prop"])
                or (fits_hand and not made_for_action(obj, name))
            )
        ):
            # Already in the hand (picked up before): the action plays with it, no new reach; its arms may go
            # to what it works on (the nail, the plank and the bench under them), not into other furniture.
            worked = frozenset() if obj is None else resting_on(scene, obj.support or obj.id) | {obj.id}
            poured = poured_into(hand["prop"])
            if poured is not None and now_posture() == "stand":
                # what it pours into is elsewhere ("pours tea into the mug" on the table, the kettle in hand
                # at the counter): up to it first, as a prop is walked up to before it is taken
                step_up_close(np.array([poured.position[0], poured.position[2]]), ai, poured.id)
            obj = next((o for o in scene.objects if o.id == hand["prop"]), obj)
            if poured is None:
                make_room(name, ai, ignore=worked)
            # seated, the vessel is poured into where the clip reaches: an arm stretched at a far glass
            # pulled the trunk over the table
            aim = (
                ((hand["prop_joint"], _pour_point(poured, pos)),)
                if poured is not None and (now_posture() == "stand" or _pours_seated(poured, pos))
                else ()
            )
            add(kind="action", action=name, duration_s=float(node.duration_s), target_id=hand["prop"],
                targets=aim, action_index=ai)  # fmt: skip
            continue
        grip = prop_grip(scene, name, obj, pos) if kind in HELD_KINDS else None
        back_to = None  # seated with the prop out of reach: get up, fetch it, and sit back down
        if FETCH_WHEN_SEATED and grip is not None and now_posture() == "sit":
            far = np.hypot(grip[0].position[0] - pos[0], grip[0].position[2] - pos[1]) > PICK_REACH
            back_to = seat_under(scene, pos) if far else None
            if back_to is not None:
                add(kind="action", action="stand", action_index=ai)
        taking = grip[0].id if grip is not None else obj.id if name == "pick_up" and obj is not None else ""
        if hand and taking and taking != hand["prop"] and (now_posture() == "stand" or set_down_in_reach()):
            set_down(None, ai, GRASP_TABLE)  # one hand, one prop: the one held goes down first
        if grip is not None:
            prop_obj, joint, local = grip
            here = np.array([prop_obj.position[0], prop_obj.position[2]])
            if now_posture() == "stand":  # walk up to the prop first (it is picked up where it lies), from
                # the side it is nearest: coming from the bench's end, the nearest free spot on the way in
                # was 0.7 m from a saw near the front edge, and the reach bent the chest into the bench
                step_up_close(here, ai, prop_obj.id)
            if back_to is None and take_seated(prop_obj, ai, GRASP_TABLE):
                # seated with it in arm's reach (the bowl on the low coffee table): taken with the arm where
                # one sits, not by getting up and bending over the table (a floor-height pick-up)
                add(kind="action", action=name, duration_s=float(node.duration_s), target_id=prop_obj.id,
                    action_index=ai)  # fmt: skip
                continue
            if np.linalg.norm(here - pos) <= PICK_REACH:  # within reach: it is held from now on
                reach = _grasp(prop_obj)
                # A prop on a table is taken with an arm's reach (upper body: seated too), one on the floor
                # with a bend down; either way the hand gets there before the prop leaves its place.
                taker = "" if reach is None else GRASP_TABLE if reach[2][1] >= TABLE_GRASP_M else "pick_up"
                standing = now_posture() == "stand"
                if taker in lib and (standing or not lib[taker].drives_lower_body):
                    rj, rlocal, rworld = reach  # type: ignore[misc]
                    grasp = {"prop": prop_obj.id, "prop_joint": rj, "prop_grip": rlocal,
                             "prop_yaw": float(prop_obj.yaw)}  # fmt: skip
                    face = _yaw_to(pos, here, yaw)
                    turn = abs(np.arctan2(np.sin(face - yaw), np.cos(face - yaw))) > TURN_TOLERANCE
                    if standing and turn:
                        walk_to(pos.copy(), 1.0, face, "turn", ai, prop_obj.id)
                    add(kind="action", action=taker, targets=((rj, rworld),), target_id=prop_obj.id,
                        action_index=ai, prop_span="grasp", **grasp)  # fmt: skip
                    hand.update(grasp)
                    if back_to is not None:  # the prop in hand: back to the seat it was fetched from
                        seat_obj, hips = back_to
                        face = float(seat_obj.yaw)
                        approach = (
                            np.array([hips[0], hips[2]]) + np.array([np.sin(face), np.cos(face)]) * SEAT_BACK
                        )
                        walk_to(approach, 1.2, face, "walk", ai, seat_obj.id)
                        pos, yaw = approach.copy(), face
                        add(kind="action", action="sit", targets=(("Hips", hips),), target_id=seat_obj.id,
                            action_index=ai)  # fmt: skip
                    vessel = poured_into(prop_obj.id)
                    if vessel is not None and standing:  # taken from the counter, poured into the cup
                        step_up_close(np.array([vessel.position[0], vessel.position[2]]), ai, vessel.id)
                    else:
                        make_room(
                            name, ai
                        )  # the prop in hand: where its use has room (a sweep, a saw stroke)
                    aims = vessel is not None and (standing or _pours_seated(vessel, pos))
                    aim = ((rj, _pour_point(vessel, pos)),) if aims and vessel is not None else ()
                    add(kind="action", action=name, duration_s=float(node.duration_s),
                        target_id=prop_obj.id, targets=aim, action_index=ai)  # fmt: skip
                    continue
                if reach is not None:  # held where a later action (or the put-down) finds it
                    joint, local = reach[0], reach[1]
                held = {
                    "prop": prop_obj.id,
                    "prop_joint": joint,
                    "prop_grip": local,
                    "prop_yaw": float(prop_obj.yaw),
                }
                obj = prop_obj
                hand.update(held)
                held["prop_span"] = "grasp"
                kind = "handheld"
        elif kind in HELD_KINDS and obj is not None:
            kind = "reach"  # a prop that stays put (a microphone on its stand): the hand goes to its point
        if name == "pick_up" and obj is not None and now_posture() == "stand" and _grasp(obj) is not None:
            rj, rlocal, rworld = _grasp(obj)  # type: ignore[misc]
            if rworld[1] >= SHELF_GRASP_M and take(obj, ai, shows=name):
                continue  # at table or shelf height an arm's reach takes it: no bend down into the furniture
            held = {"prop": obj.id, "prop_joint": rj, "prop_grip": rlocal, "prop_yaw": float(obj.yaw),
                    "prop_span": "grasp"}  # fmt: skip
        put = find_object(scene, node.target) if name == "put_down" and node.target else None
        put_on = find_object(scene, node.destination) if put is not None and node.destination else None
        if (
            put is not None
            and put.id not in (hand.get("prop"), put_on.id if put_on is not None else "")
            and _grasp(put) is not None
            and take(put, ai)
        ):
            # "Dan puts the plate on the table" with empty hands: the plate is taken first, then put there
            # (where the parse kept no surface: back down where it was, the nearest surface in reach)
            set_down(put_on, ai)
            continue
        if name == "put_down" and hand and not _puts_another(scene, node.target, hand["prop"]):
            # Set down on what the sentence names, else the nearest surface in reach, else where it was.
            dest = find_object(scene, node.destination) or (
                obj if obj is not None and obj.id != hand["prop"] else None
            )
            set_down(dest, ai)
            continue
        worked_on = obj  # "makes a coffee" (the cup) at the counter: the hands on the cup, not its far end
        if obj is not None and clip.interaction and kind not in ("handheld", "person", "seat", "bed"):
            obj = work_place(scene, obj, name)
        if obj is not None and kind == "surface" and "/" not in obj.id and _grasp(obj) is not None:
            # "They eat dinner" with a plate at each place: each eats from the one nearest, as a cup is drunk
            # from (prop_grip), not both from the first plate (0.84 m across the table)
            alike = [o for o in scene.objects if o.category == obj.category and _grasp(o) is not None]
            obj = min(alike, key=lambda o: float(np.hypot(o.position[0] - pos[0], o.position[2] - pos[1])))
        if obj is not None and clip.interaction and kind not in ("handheld", "person"):
            geo = _object_geometry(obj) or _fallback_geometry(obj)
            stand, points = geo
            targets = contact_targets(clip, points)
            slot = seats.get(ai, "")
            if slot in points:  # the orchestrator's slot book gave this action its own slot
                targets = {j: (float(p[0]), float(p[1]), float(p[2])) for j, p in points[slot]}
            elif seat_pick is not None:
                targets = {"Hips": seat_pick[1]}
            if kind == "surface" and worked_on is not None and worked_on.id != obj.id and _grasp(obj) is None:
                targets = _onto(targets, worked_on)
            if clip.interaction.object in ("seat", "bed") and "Hips" in targets:
                face = float(obj.yaw)
                seat = np.array([targets["Hips"][0], targets["Hips"][2]])
                approach = seat + np.array([np.sin(face), np.cos(face)]) * SEAT_BACK
                near = SAME_BED if now_posture() == "lie" else SAME_SEAT
                on_it = now_posture() in ("sit", "lie") and (
                    now_seat() == obj.id or (not now_seat() and np.linalg.norm(seat - pos) < near)
                )
                if on_it and name in SEATED_AS and name != "stand" and SEATED_AS[name] == now_posture():
                    # Already sitting (lying) there: keep the posture, no replayed sit-down ("lies down on
                    # the bed. He falls asleep": asleep where he lies, not up on the bed and down again).
                    hold_s = SLEEP_S if name == "sleep" else STAY_S
                    dur = float(node.duration_s) if node.duration_s > 0 and name != "sit" else hold_s
                    add(kind="wait", action=name, duration_s=dur, target_id=obj.id, action_index=ai)
                    continue
                if not on_it:  # already sitting / lying there ("lies down on the bed and sleeps"): stay
                    walk_to(approach, 1.2, face, "walk", ai, obj.id)
                    # Sitting brings the hips onto the seat wherever the walk stopped; getting up ends here.
                    pos = approach.copy()
                    yaw = face
            elif clip.interaction.object not in ("seat", "bed"):
                centre = np.array([obj.position[0], obj.position[2]])
                if (
                    targets
                ):  # stand within arm's reach of the contact points (catalog stand points can be far)
                    centre = np.mean([[p[0], p[2]] for p in targets.values()], axis=0)
                    away = stand - centre
                    if np.linalg.norm(away) > 1e-6:
                        stand = centre + away / np.linalg.norm(away) * min(np.linalg.norm(away), REACH)
                    from services.motion.routing import free_spot

                    # Other furniture there (a chair in front of the desk): the free spot nearest the contacts.
                    stand_xz = (float(stand[0]), float(stand[1]))
                    if free_spot(scene, stand_xz) != stand_xz:
                        stand = np.asarray(free_spot(scene, (float(centre[0]), float(centre[1]))), float)
                if ai in spots:
                    stand = np.asarray(spots[ai], float)
                elif targets:  # the arm that does not reach (hanging, swinging) out of the furniture beside
                    stand = clear_of_bodies(stand, centre)
                    keep = float(np.linalg.norm(stand - centre)) + 0.02  # no farther off: no deeper lean
                    roomy = make_room(name, ai, obj.id, at=stand, face_to=centre,
                                      reaching=reaching_sides(targets), within=keep)  # fmt: skip
                    if roomy is not None:
                        stand = roomy[0]
                d = centre - stand
                face = float(np.arctan2(d[0], d[1])) if np.linalg.norm(d) > 1e-6 else yaw
                # near the stand and no farther from the contacts than it (farther off, the trunk leans deeper)
                already_there = np.linalg.norm(stand - pos) < 0.35 and (
                    not targets or np.linalg.norm(centre - pos) <= np.linalg.norm(centre - stand) + 0.05
                )
                seated = now_posture() != "stand"
                if seated and clip.interaction.object == "surface" and targets:
                    targets = slid_to_place(obj, targets, pos, yaw)
                if not already_there and not seated:
                    walk_to(stand, 1.2, face, "walk", ai, obj.id)
                elif not seated and abs(np.arctan2(np.sin(face - yaw), np.cos(face - yaw))) > 0.3:
                    walk_to(
                        pos.copy(), 1.0, face, "turn", ai, obj.id
                    )  # close enough, but facing away: turn in place
        elif obj is not None and name in HIDE_ACTIONS and now_posture() == "stand":
            # "hides behind the door": beside it against its wall, or behind what stands free (its slot)
            hide_at = (
                [np.asarray(spots[ai], float)]
                if ai in spots
                else [np.asarray(p) for p in hiding_spots(obj, scene)]
            )
            if hide_at:
                from services.motion.routing import free_spot

                goal = min(hide_at, key=lambda p: float(np.linalg.norm(p - pos)))
                goal = np.asarray(free_spot(scene, (float(goal[0]), float(goal[1])), max_move=0.4), float)
                d = np.array([obj.position[0], obj.position[2]]) - goal
                face = float(np.arctan2(d[0], d[1])) if np.linalg.norm(d) > 1e-6 else yaw
                walk_to(goal, SPEEDS.get("walk", 1.3) * speed_k, face, "walk", ai, obj.id, node.manner)
        elif obj is not None and clip.interaction is None and name in ("look_at", "point", "wave", "talk"):
            d = np.array([obj.position[0], obj.position[2]]) - pos
            if np.linalg.norm(d) > 0.3 and now_posture() == "stand":  # seated: no standing up to turn
                face = float(np.arctan2(d[0], d[1]))
                if abs(np.arctan2(np.sin(face - yaw), np.cos(face - yaw))) > 0.3:
                    walk_to(pos.copy(), 1.0, face, "turn", ai, obj.id)
        if obj is None and not held and clip.interaction is None:
            clear_of_others(name, ai)  # "They dance" right after a hug: a step apart first
        if (
            not targets
            and not held
            and (kind in HELD_KINDS or clip.interaction is None)
            and name not in HIDE_ACTIONS
        ):
            make_room(name, ai, obj.id if obj else "")  # a gesture or a tool swung where it stands
        add(
            kind="action",
            action=name,
            duration_s=float(node.duration_s),
            targets=tuple(sorted(targets.items())),
            target_id=obj.id if obj else node.target,
            action_index=ai,
            **held,
        )
        if held.get("prop_span") == "release":
            hand.clear()
        elif held:
            hand.update({k: v for k, v in held.items() if k != "prop_span"})
    segs = _with_moods(segs, character)
    return MotionPlan(
        character=character.name,
        start=(float(x), float(z), float(start[2])),
        segments=tuple(segs),
        diagnostics=tuple(diags),
    )
