"""The `contact` check: an action's contact joints at its target for at least half of its contact window.

Sit: the hips on the seat's point; type: both hands on the keys; drink: the cup in the hand and at the mouth;
tool use: the tool in the hand, and at what it works on when the sentence names a thing in the room ("repairs
the bicycle"); a touch between people: the hand on the other's body; a walk to something:
ending next to it. The target is the object the sentence names, else the fitting object the body came
closest to; with none in the room the check fails and says so (nothing dropped passes silently).
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import partial

import numpy as np

from proto.fidelity import Check
from proto.motion_data import PropTrack
from proto.scene import PlacedObject
from wana.arrays import from_wire
from wana.assets.catalog import asset_for, to_world, world_bounds
from wana.assets.relations import footprint_gap
from wana.assets.vocabulary import CATEGORIES, hypernyms, lookup_room
from wana.domain.actions import names_object
from wana.fidelity.acts import Act, is_entrance, is_locomotion, window_frames
from wana.fidelity.bodies import Body
from wana.fidelity.clips import ClipNeeds, clip_needs
from wana.fidelity.handover import handover, is_handover
from wana.fidelity.solids import depth_inside, rests_on
from wana.fidelity.words import frame_list, joint_words, stays, third_person
from wana.fidelity.world import World, base_id, display

CONTACT_M = 0.05  # the contact joint within this of the object's contact point ...
CONTACT_SHARE = 0.5  # ... on at least this share of the window's frames
POURING = ("pour",)  # held-vessel actions that empty into what the sentence's destination names
POUR_M = 0.25  # metres across from a pouring vessel's axis to the rim it pours into ...
POUR_ABOVE_M = (-0.05, 0.45)  # ... with the vessel's middle this far above that rim (metres)
MOUTH_M = 0.12  # a drink's vessel (its axis, bottom to rim, where it is drawn) within this of the mouth
MOUTH_UP_M = 0.03  # the mouth: this far up the head from the Head joint (the skull's base) ...
MOUTH_FORWARD_M = 0.09  # ... and this far forward, the way the shoulders face
ARRIVE_M = 1.0  # a walk to an object ends within this of its footprint
ARRIVE_PERSON_M = 1.5  # a walk to a character ends within this of them
# Catalog contact-point names that mean each interaction kind, best first (the motion planner's choice).
PREFERRED_POINTS = {
    "seat": ("sit", "sit_0", "sit_2"),
    "bed": ("lie", "sit"),
    "keyboard": ("type", "click", "use", "work", "write", "touch"),
    "instrument": ("play", "work", "touch"),
    "surface": ("write", "work", "eat", "cook", "wash", "touch"),
    "button": ("switch", "use", "touch"),
    "door": ("open", "touch"),
    "container": ("open", "take", "touch", "pick_up"),
    "tool": ("work", "saw", "hammer", "drill", "screw", "cut", "touch"),
    "bag": ("punch", "touch"),
    "floor_item": ("pick_up", "lift", "carry", "touch"),
    "handheld": ("drink", "call", "read", "play", "sing", "pick_up", "carry", "lift", "touch"),
}
KIND_WORDS = {
    "seat": "seat",
    "bed": "bed",
    "keyboard": "keyboard",
    "handheld": "thing to hold",
    "tool": "tool",
    "surface": "surface",
    "door": "door",
    "container": "container",
    "button": "switch",
    "instrument": "instrument",
    "bag": "bag",
    "floor_item": "thing to pick up",
}
HELD = ("handheld", "tool")
# Objects an action works across (writing on a board or a desk, painting): the hand is on the object when it
# is on its face anywhere, not only at the one contact point the catalog names (seen on the contact sheets:
# a teacher's hand moving over the blackboard read as 18 cm from its middle).
ACROSS = ("surface",)
HOLDABLE_M = 0.6  # metres: the largest side of a surface thing one holds in a hand
# A tool's hand works on what the sentence names ("repairs the bicycle") within this of its surface, on at least
# CONTACT_SHARE of the frames: a forearm and the tool, what the eye reads as working at it (on the sheets: a
# screwdriver held over a cabinet 0.99 m from the bicycle to repair read as contact, duo-garage-14 s7; a hammer
# swung over the bench 0.55 m from the nail looks like hammering it, solo-workshop-05 s8).
WORK_M = 0.6


@dataclass(frozen=True)
class Reach:
    """Where an action's contact joints went relative to the object point they were meant for."""

    placed: PlacedObject
    point: str  # contact point name on the object
    targets: dict[str, np.ndarray]  # body joint -> (3,) world target
    distance: dict[str, np.ndarray]  # body joint -> (W,) metres over the window frames


FINGERTIP_M = 0.07  # metres from the middle finger's first joint (the skeleton's last hand joint) to its tip


def _tip(joint: str) -> float:
    """How far beyond the joint the body reaches: a finger joint's tip touches the board, not its knuckle."""
    return FINGERTIP_M if joint.endswith("HandMiddle1") else 0.0


def surface_gap(placed: PlacedObject, points: np.ndarray) -> np.ndarray:
    """(n,) metres from each point to the object's solid surface (0 on or inside it)."""
    return np.maximum(-depth_inside(placed, points, np.zeros(len(points))), 0.0)


def _limb(joint: str) -> str:
    return joint.replace("Middle1", "")


def _fitting(
    clip: ClipNeeds, points: Mapping[str, list[tuple[str, np.ndarray]]]
) -> list[tuple[str, dict[str, np.ndarray]]]:
    """(point name, joint -> world target) for each contact point that serves the clip's contact joints."""
    wanted = {_limb(j) for j in clip.contacts}
    names = list(
        dict.fromkeys([n for n in PREFERRED_POINTS.get(clip.object, ()) if n in points] + sorted(points))
    )
    out = []
    for name in names:
        pairs = points[name]
        if clip.object in ("seat", "bed"):
            hips = [p for j, p in pairs if j == "Hips"]
            if hips:
                out.append((name, {"Hips": hips[0]}))
            continue
        by_limb = {_limb(j): (j, p) for j, p in pairs}
        if wanted and wanted <= set(by_limb):
            out.append(
                (name, {by_limb[w][0]: by_limb[w][1] for w in sorted(wanted)})
            )  # sorted: the same in every process
        elif (clip.object in HELD or name in (clip.name, clip.name.split("_")[0])) and wanted & set(by_limb):
            # a held thing, or the object's own point for this action serving one of its hands (the
            # shower's one-handed "wash" point for washing the hands: solo-bathroom-23 s6 read "the shower
            # has no place to wash" while Ben washed at it)
            j, p = by_limb[sorted(wanted & set(by_limb))[0]]
            out.append((name, {j: p}))
    return out


def carried(tracks: Sequence[PropTrack], object_id: str, frames: np.ndarray) -> np.ndarray:
    """(W,) whether the object is in one of the character's hands (a PropTrack of it) on each frame."""
    out = np.zeros(len(frames), bool)
    for t in tracks:
        if t.object_id == object_id:
            out |= (frames >= t.start_frame) & (frames < t.end_frame)
    return out


def reach(
    act: Act, body: Body, world: World, candidates: list[PlacedObject], tracks: Sequence[PropTrack] = ()
) -> Reach | None:
    """The candidate object and contact point the body came closest to during the window, None if none fits.

    An object the character carries (a PropTrack of it: a cup, a hammer, the can it sets down) is in the hand
    on those frames whatever the action's kind: its placed position is where it was picked up from, not where
    it is (greenhouse s5: "sets the can back on the stool" read the can as 3.40 m off, at the stool it left).
    """
    clip = clip_needs(act.node.action)
    frames = window_frames(act)
    if clip is None or not len(frames):
        return None
    idx = np.clip(np.asarray(frames), 0, body.frames - 1)
    best: Reach | None = None
    best_score = np.inf
    for placed in candidates:
        held = carried(tracks, placed.id, np.asarray(frames))
        for name, targets in _fitting(clip, world.contact_points(placed)):
            dist = {j: np.linalg.norm(body.joint(j)[idx] - p, axis=1) for j, p in targets.items()}
            if clip.object in ACROSS:  # writing moves over the board: any point of its face is the contact
                dist = {
                    j: np.minimum(d, np.maximum(surface_gap(placed, body.joint(j)[idx]) - _tip(j), 0.0))
                    for j, d in dist.items()
                }
            if held.any():
                dist = {j: np.where(held, 0.0, d) for j, d in dist.items()}
            score = float(np.mean([d.mean() for d in dist.values()]))
            if score < best_score:
                best, best_score = Reach(placed, name, targets, dist), score
    return best


def _hypernyms(category: str) -> tuple[str, ...]:
    try:
        return tuple(hypernyms(category))
    except KeyError:
        return ()


def _mount(category: str) -> str:
    info = CATEGORIES.get(category)
    return info.mount if info is not None else ""


def _holdable(world: World, placed: PlacedObject, tool: bool = False) -> bool:
    """A tool, or a small thing that rests on a surface (a cup, a book): not a plank or a stand microphone.

    For an action that is no tool use, also anything the catalog lets a hand pick up (a "pick_up" point):
    the dumbbell lifted from the floor, the guitar played in the arms (the motion planner takes exactly
    those into the hand; the check read them as "nothing in the room to lift with").
    """
    if "tool" in _hypernyms(placed.category):
        return True
    b = world_bounds(placed)
    if _mount(placed.category) == "surface" and float(np.max(b[1] - b[0])) <= HOLDABLE_M:
        return True
    return not tool and "pick_up" in world.contact_points(placed)


def _fixed_for(world: World, meant: set[str]) -> list[PlacedObject]:
    """Objects that stay put and offer the held action's own point where the hand goes (the microphone on its
    stand: one sings into it with the hand on it, it is not taken off the stand)."""
    return [
        o
        for o in world.scene.objects
        if meant & set(world.contact_points(o)) and "pick_up" not in world.contact_points(o)
    ]


def _made_for(world: World, placed: PlacedObject, action: str, meant: set[str]) -> bool:
    """Whether an object offers the held action's own point, or the action's name names it (the phone one
    texts with: its one held point is "call"; the planner holds it the same way, planning.made_for_action)."""
    return bool(meant & set(world.contact_points(placed))) or (
        "pick_up" in world.contact_points(placed) and names_object(action, placed.category)
    )


# The actor's own body named as the object ("snaps his fingers", "washes her hands", "checks his watch"): no
# thing in the room is meant, the hand or the clip's own object (the sink) is.
BODY_PARTS = frozenset(
    "finger fingers hand hands head face arm arms leg legs foot feet knee knees shoulder shoulders eye eyes "
    "nose tooth teeth hair chin brow forehead neck back chest belly stomach lip lips mouth ear ears toe toes "
    "wrist wrists watch".split()
)
OWN_PART = re.compile(
    r"\b(?:his|her|their|my|your|its)\s+(?:own\s+)?(" + "|".join(sorted(BODY_PARTS)) + r")\b"
)


def is_body_part(ref: str) -> bool:
    """An object word that is a part of the body (or worn on it), not a thing in the room."""
    return ref.lower().replace("_", " ").split(" ")[-1] in BODY_PARTS


def names_own_body(act: Act) -> bool:
    """The sentence names the actor's own body part ("Ted snaps his fingers at Walter")."""
    return OWN_PART.search(act.text.lower()) is not None


def _candidates(act: Act, world: World, characters: set[str]) -> tuple[list[PlacedObject], str]:
    """The objects the action may use, and the word the text used for them ("" when it named none).

    With no object named, a held object must be one made for the action (a hammer has a "hammer" point, a cup
    a "drink" point); anything else must offer the interaction's own point, not just a place to touch. A held
    action's named object that is not made for it is what is worked on ("hammers a nail", "sweeps the floor"):
    the tool is then still the one made for the action, in the hand.
    """
    clip = clip_needs(act.node.action)
    action = act.node.action
    held = clip is not None and clip.object in HELD
    tool = clip is not None and clip.object == "tool"
    meant = {action, action.split("_")[0]}
    missing = ""  # a named object the room lacks ("drinks from the cup" with no cup)
    for ref in (act.node.instrument, act.node.target, act.node.destination):
        if ref and ref not in characters and not (is_body_part(ref) and names_own_body(act)):
            found = world.find(ref)
            alike = len(found) == 1 and "/" not in found[0].id
            if not held:
                if alike and _holdable(world, found[0], False):
                    # "They eat dinner" with a plate at each place: any plate, the one in front of each
                    # (the planner eats from the nearest alike as it drinks from one)
                    found += [
                        o
                        for o in world.scene.objects
                        if o.category == found[0].category and o is not found[0]
                    ]
                return found, ref
            if alike:
                # "drinks from her mug" with two mugs on the table: any of them, the one the hand came to (the
                # planner takes the nearest alike, planning.prop_grip; duo-cafe-04 s8 read the mug in her
                # hand as 0.88 m off, measuring to the first one, which stayed by Dr. Jones)
                found += [
                    o for o in world.scene.objects if o.category == found[0].category and o is not found[0]
                ]
            tools = [o for o in found if _made_for(world, o, action, meant) and _holdable(world, o, tool)]
            if not tools and not tool:  # the microphone on its stand: the hand on its own point
                tools = [o for o in found if o in _fixed_for(world, meant)]
            if tools or (not found and ref == act.node.instrument):  # the tool it names ("with a hammer")
                return tools, ref
            kind = base_id(ref)  # a held thing the room lacks (a cup), not a surface worked on (the floor)
            if not found and not missing and (_mount(kind) == "surface" or "tool" in _hypernyms(kind)):
                missing = ref
    if clip is None:
        return [], ""
    if held:
        made_for = [
            o for o in world.scene.objects if _made_for(world, o, action, meant) and _holdable(world, o, tool)
        ]
        if not made_for and not tool:
            made_for = _fixed_for(world, meant)
        return made_for, "" if made_for else missing
    meant = {action, *PREFERRED_POINTS.get(clip.object, ())} - {"touch", "pick_up"}
    return [o for o in world.scene.objects if meant & set(world.contact_points(o))], ""


AT_M = 1.6  # metres: how far a chair may stand from the table it is "at"


def _fitting_at(act: Act, world: World, named: list[PlacedObject]) -> list[PlacedObject]:
    """Objects that offer the action's own point and stand at one of the named objects ("at the table")."""
    clip = clip_needs(act.node.action)
    if clip is None or clip.object in HELD:
        return []
    meant = {act.node.action, *PREFERRED_POINTS.get(clip.object, ())} - {"touch", "pick_up"}
    ids = {o.id for o in named}
    return [
        o
        for o in world.scene.objects
        if o.id not in ids
        and meant & set(world.contact_points(o))
        and min(footprint_gap(o, n) for n in named) <= AT_M
    ]


def contact(
    act: Act,
    body: Body,
    world: World,
    bodies: Mapping[str, Body],
    props: Mapping[str, Sequence[PropTrack]] | None = None,
) -> tuple[Check | None, dict[str, bool]]:
    """The `contact` check of one action and the objects it touches on purpose (exempt from `penetration`):
    object id -> True when the whole body may touch it, False for the arms only.

    Args:
        props: character -> the objects it carries (Motion.props), for held objects and handing over.
    """
    props = props or {}
    clip = clip_needs(act.node.action)
    who, verb = act.character, act.node.verb or act.node.action
    base = partial(Check, name="contact", character=who)
    if act.clip is not None and is_handover(act, set(bodies)):
        return handover(act, world, bodies, props), {}
    if clip is None or act.clip is None:
        return None, {}
    if is_locomotion(act.node.action):
        return _arrival(act, body, world, bodies), {}
    if not clip.object:
        return None, {}
    frames = window_frames(act)
    if clip.object == "person":
        hugged = _held_instead(act, world, bodies)
        if hugged is not None:  # "picks up the teddy bear and hugs it": the arms round the thing held
            return _in_arms(act, hugged, frames, props.get(who, ())), {}
        return _touch_person(act, body, bodies, frames), {}
    candidates, word = _candidates(act, world, set(bodies))
    if not candidates and clip.object in HELD and names_own_body(act):
        return None, {}  # a gesture of the body itself ("snaps his fingers"): no tool is asked for
    if not candidates:
        if clip.object in HELD:
            what = f"no {display(word)} in the room" if word else f"nothing in the room to {verb} with"
            reason = f"there is {what}: {who} {third_person(verb)} with an empty hand"
        else:
            what = display(word) if word else KIND_WORDS.get(clip.object, clip.object)
            reason = f"there is no {what} in the room for {who} to {verb}"
        return (
            base(
                ok=False,
                essential=True,
                reason=reason,
            ),
            {},
        )
    got = reach(act, body, world, candidates, props.get(who, ()))
    if got is None and word:  # "sits at the table": a fitting object at the named one (a chair at it)
        at = _fitting_at(act, world, candidates)
        got = reach(act, body, world, at) if at else None
    if got is None:
        name = display(candidates[0].id)
        return base(ok=False, reason=f"the {name} has no place for {who} to {verb} with"), {}
    name = display(got.placed.id)
    # the object itself with the whole body; what it rests on (the desk under the laptop) with the arms only
    touching = {oid: oid == got.placed.id for oid in world.supports_chain(got.placed)}
    shares = {j: float(np.mean(d <= CONTACT_M)) for j, d in got.distance.items()}
    worst = min(shares, key=lambda j: shares[j])
    fr = np.asarray(frames)
    far = fr[got.distance[worst] > CONTACT_M]
    if shares[worst] < CONTACT_SHARE:
        gap = float(np.median(got.distance[worst]))
        if clip.object in HELD:
            reason = f"the {name} is not in {who}'s hand: it stays {gap:.2f} m from it"
        else:
            reason = (
                f"{who}'s {joint_words([worst])} {stays(joint_words([worst]))} {gap:.2f} m from the {name} "
                f"(within 5 cm on {shares[worst]:.0%} of the frames, needs half)"
            )
        return base(ok=False, reason=reason, frames=frame_list(far)), touching
    if clip.object == "bed":  # the hips on the lie point and the head over the floor: across it, not on it
        off = head_beyond(body, got.placed, fr) > HEAD_OFF_M
        if np.mean(off) > 1.0 - CONTACT_SHARE:
            return (
                base(
                    ok=False,
                    reason=f"{who}'s hips are on the {name} but the head is "
                    f"{float(np.median(head_beyond(body, got.placed, fr[off]))):.2f} m beyond it: {who} lies "
                    f"across it, not on it",
                    frames=frame_list(fr[off]),
                ),
                touching,
            )
    if act.node.action == "drink":
        idx = np.clip(fr, 0, body.frames - 1)
        gaps = mouth_gap(*vessel_axis(got.placed, props.get(who, ()), fr), mouth(body)[idx])
        at_mouth = gaps <= MOUTH_M
        if np.mean(at_mouth) < CONTACT_SHARE:
            gap = float(np.min(gaps))
            return (
                base(
                    ok=False,
                    reason=f"the {name} never reaches {who}'s mouth (at best {gap:.2f} m from it)",
                    frames=frame_list(fr[~at_mouth]),
                ),
                touching,
            )
    into = world.find(act.node.destination or act.node.target) if act.node.action in POURING else []
    into = [o for o in into if o.id != got.placed.id]
    if into:  # "pours tea into the mug": the kettle held over the mug's rim, not anywhere in the room
        over, vessel = _poured_over(got.placed, into, props.get(who, ()), fr)
        if np.mean(over) < CONTACT_SHARE:
            return (
                base(
                    ok=False,
                    reason=f"{who} pours from the {name} away from the {display(vessel.id)}: over its rim on "
                    f"{np.mean(over):.0%} of the frames (needs half)",
                    frames=frame_list(fr[~over]),
                ),
                touching,
            )
    worked = _worked_on(act, world, set(bodies), got.placed) if clip.object == "tool" else []
    if worked:  # "repairs the bicycle": the tool in the hand and the hand at the bicycle, not anywhere
        idx = np.clip(fr, 0, body.frames - 1)
        gaps = np.min(
            [[surface_gap(o, body.joint(j)[idx]) for o in worked] for j in got.distance], axis=(0, 1)
        )
        at = gaps <= WORK_M
        if np.mean(at) < CONTACT_SHARE:
            return (
                base(
                    ok=False,
                    reason=f"{who} holds the {name} {float(np.median(gaps)):.2f} m from the "
                    f"{display(worked[0].id)}: at it on {np.mean(at):.0%} of the frames (needs half)",
                    frames=frame_list(fr[~at]),
                ),
                touching,
            )
    return (
        base(
            ok=True,
            reason=f"{who}'s {joint_words(list(got.distance))} on the {name} ({shares[worst]:.0%} of the frames within 5 cm)",
        ),
        touching,
    )


def _worked_on(act: Act, world: World, characters: set[str], tool: PlacedObject) -> list[PlacedObject]:
    """What a tool action works on, when the sentence names it and the room has it ("repairs the bicycle",
    "saws the plank"): the objects of its target, else its destination, other than the tool and its kind; none
    for a room word, a character, the body's own part, or a thing the room lacks ("screws the pieces")."""
    for ref in (act.node.target, act.node.destination):
        if not ref or ref in characters or _is_room_word(ref) or (is_body_part(ref) and names_own_body(act)):
            continue
        found = [o for o in world.find(ref) if o.id != tool.id and o.category != tool.category]
        if found:
            return found
    return []


# A lying head held by no part of its bed this far beyond the bed's footprint is off it (on the sheets: 16 cm
# past a sofa's back read as lying on it, gump-living_room-3 s13; 27 cm out through a tub's side did not).
HEAD_OFF_M = 0.20
HEAD_DROP_M = 0.45  # a lying head rests on a part of the bed at most this far under it (or sunk into it)


def head_beyond(body: Body, placed: PlacedObject, frames: np.ndarray) -> np.ndarray:
    """(W,) metres the head of a body lying on the object is beyond the object's footprint on each frame
    where no part of the object holds it up (0 where one does, or over the object).

    A body lying on a bed or in a tub has its head on it: the hips on the tub's lie point with the body across
    the tub and the head out through its side over the floor is lying beside it (solo-bathroom-23 s10, a
    person's label); a head on a sofa's backrest or armrest, even sunk into it, is held.
    """
    head = body.joint("Head")[np.clip(frames, 0, body.frames - 1)]
    b = world_bounds(placed)
    d = np.maximum(0.0, np.maximum(b[0, [0, 2]] - head[:, [0, 2]], head[:, [0, 2]] - b[1, [0, 2]]))
    gap = np.hypot(d[:, 0], d[:, 1])
    out = np.zeros(len(head))
    far = gap > 0.0
    out[far] = np.where(rests_on(placed, head[far], 0.06, HEAD_DROP_M, 0.03), 0.0, gap[far])
    return out


def mouth(body: Body) -> np.ndarray:
    """(T, 3) the mouth: up the head from the Head joint and forward the way the shoulders face.

    The head's up is from the Head joint to the head's centre sphere (the last body point, placed in the
    head's own frame); forward is across the shoulder line (left minus right) and that up.
    """
    head = body.joint("Head")
    up = body.points[:, -1] - head
    up /= np.maximum(np.linalg.norm(up, axis=1, keepdims=True), 1e-9)
    forward = np.cross(body.joint("LeftShoulder") - body.joint("RightShoulder"), up)
    forward /= np.maximum(np.linalg.norm(forward, axis=1, keepdims=True), 1e-9)
    return head + MOUTH_UP_M * up + MOUTH_FORWARD_M * forward


def vessel_axis(
    placed: PlacedObject, tracks: Sequence[PropTrack], frames: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """(W, 3) twice: the bottom and the top centre of a drinking vessel on each frame, where it is drawn:
    moved with the hand on the frames a PropTrack of it holds it (its pose there), else where the scene
    placed it."""
    from scipy.spatial.transform import Rotation  # scipy.spatial is not needed before the first check

    scale = np.asarray(placed.scale, float)
    ends = []
    for local in (np.zeros(3), np.array([0.0, float(asset_for(placed).dims[1]), 0.0])):
        out = np.tile(to_world(placed, local), (len(frames), 1))
        for t in tracks:
            if t.object_id != placed.id:
                continue
            pos, rot = from_wire(t.position), from_wire(t.rotation)
            inside = (frames >= t.start_frame) & (frames < t.end_frame)
            k = np.clip(frames[inside] - t.start_frame, 0, len(pos) - 1)
            out[inside] = pos[k] + Rotation.from_quat(rot[k]).apply(local * scale)
        ends.append(out)
    return ends[0], ends[1]


def _poured_over(
    held: PlacedObject, into: Sequence[PlacedObject], tracks: Sequence[PropTrack], frames: np.ndarray
) -> tuple[np.ndarray, PlacedObject]:
    """(W,) bool, per frame, whether the held vessel (where it is drawn) is over the rim of the one it pours
    into, POUR_M across and POUR_ABOVE_M above, and which of the alike vessels (the one it is over most)."""
    bottom, top = vessel_axis(held, tracks, frames)
    middle = (bottom + top) / 2.0
    best: tuple[np.ndarray, PlacedObject] | None = None
    for vessel in into:
        rim = to_world(vessel, np.array([0.0, float(asset_for(vessel).dims[1]), 0.0]))
        across = np.hypot(middle[:, 0] - rim[0], middle[:, 2] - rim[2])
        above = middle[:, 1] - rim[1]
        over = (across <= POUR_M) & (above >= POUR_ABOVE_M[0]) & (above <= POUR_ABOVE_M[1])
        if best is None or over.sum() > best[0].sum():
            best = (over, vessel)
    assert best is not None  # into is not empty
    return best


def mouth_gap(bottom: np.ndarray, top: np.ndarray, mouth_at: np.ndarray) -> np.ndarray:
    """(W,) the mouth's distance to the vessel's axis: a cup's rim at the lips, or a bottle held by its
    middle with its body against the mouth (group-dining_room-04 s7: John's bottle crosses his face)."""
    axis = top - bottom
    t = np.einsum("ij,ij->i", mouth_at - bottom, axis) / np.maximum(np.einsum("ij,ij->i", axis, axis), 1e-12)
    nearest = bottom + np.clip(t, 0.0, 1.0)[:, None] * axis
    return np.linalg.norm(mouth_at - nearest, axis=1)


def _held_instead(act: Act, world: World, bodies: Mapping[str, Body]) -> PlacedObject | None:
    """The thing a person-to-person action is done to instead of a person ("hugs the teddy bear"): a named
    object of the room, not a character, that a hand can pick up; None otherwise."""
    ref = act.node.target or act.node.destination
    if not ref or ref in bodies or is_body_part(ref):
        return None
    return next((o for o in world.find(ref) if "pick_up" in world.contact_points(o)), None)


def _in_arms(act: Act, placed: PlacedObject, frames: range, tracks: Sequence[PropTrack]) -> Check:
    """Whether the thing is in the actor's hands (a PropTrack of it) on at least half the action's frames."""
    who, name = act.character, display(placed.id)
    fr = np.asarray(frames)
    held = carried(tracks, placed.id, fr)
    share = float(np.mean(held)) if len(fr) else 0.0
    if share < CONTACT_SHARE:
        return Check(
            name="contact",
            character=who,
            ok=False,
            reason=f"the {name} is not in {who}'s arms: held on {share:.0%} of the frames (needs half)",
            frames=frame_list(fr[~held]),
        )
    return Check(
        name="contact", character=who, ok=True, reason=f"{who} holds the {name} ({share:.0%} of the frames)"
    )


def other_character(act: Act, bodies: Mapping[str, Body]) -> str:
    for ref in (act.node.target, act.node.destination, act.node.instrument):
        if ref in bodies and ref != act.character:
            return ref
    others = [n for n in bodies if n != act.character]
    if len(others) <= 1:
        return others[0] if others else ""
    # "They shake hands": no one named, so the partner is whoever is nearest during the action.
    me = bodies.get(act.character)
    if me is None or act.clip is None:
        return ""
    lo = max(0, min(act.clip.start_frame, me.frames - 1))
    hi = max(lo + 1, min(act.clip.end_frame, me.frames))

    def mean_gap(name: str) -> float:
        them = bodies[name]
        n = min(hi, them.frames)
        if n <= lo:
            return float("inf")
        d = me.joint("Hips")[lo:n, [0, 2]] - them.joint("Hips")[lo:n, [0, 2]]
        return float(np.linalg.norm(d, axis=1).mean())

    return min(others, key=mean_gap)


def _touch_person(act: Act, body: Body, bodies: Mapping[str, Body], frames: range) -> Check:
    clip = clip_needs(act.node.action)
    assert clip is not None
    who, verb = act.character, act.node.verb or act.node.action
    other = other_character(act, bodies)
    if not other:
        return Check(
            name="contact",
            character=who,
            ok=False,
            essential=True,
            reason=f"there is nobody for {who} to {verb}",
        )
    them = bodies[other]
    fr = np.clip(np.asarray(frames), 0, min(body.frames, them.frames) - 1)
    gaps = []
    for j in clip.contacts:
        p = body.joint(j)[fr]  # (W, 3)
        surface = np.linalg.norm(them.points[fr] - p[:, None], axis=2) - them.radii[None]  # (W, P)
        gaps.append(np.maximum(surface.min(axis=1), 0.0))
    gap = np.max(gaps, axis=0)
    touching = gap <= CONTACT_M
    share = float(np.mean(touching))
    if share >= CONTACT_SHARE and act.node.action in ROUND_ACTIONS:
        behind = np.all([round_back(body.joint(j)[fr], them, fr) for j in clip.contacts], axis=0)
        round_share = float(np.mean(touching & behind))
        if round_share < CONTACT_SHARE:
            return Check(
                name="contact",
                character=who,
                ok=False,
                reason=f"{who}'s arms never go round {other}: both hands are behind {other}'s back on "
                f"{round_share:.0%} of the frames (needs half)",
                frames=frame_list(np.asarray(frames)[~(touching & behind)]),
            )
    if share < CONTACT_SHARE:
        return Check(
            name="contact",
            character=who,
            ok=False,
            reason=f"{who}'s {joint_words(clip.contacts)} {stays(joint_words(clip.contacts))} {float(np.median(gap)):.2f} m from {other}",
            frames=frame_list(np.asarray(frames)[gap > CONTACT_M]),
        )
    return Check(
        name="contact", character=who, ok=True, reason=f"{who} touches {other} ({share:.0%} of the frames)"
    )


ROUND_ACTIONS = ("hug",)  # person-to-person actions whose arms go round the other's back
BACK_PLANE_M = 0.05  # a hand at most this far in front of the other's back plane is behind their back


def round_back(hand: np.ndarray, them: Body, frames: np.ndarray) -> np.ndarray:
    """(W,) whether a hand (W, 3) is behind the other's back plane: the plane through their chest (Spine2)
    square to the way their shoulders face, with the hand no further in front of it than BACK_PLANE_M (a
    hug's arms go round the other; hands on their chest or arms are not a hug)."""
    chest = them.joint("Spine2")[frames]
    across = them.joint("LeftShoulder")[frames] - them.joint("RightShoulder")[frames]
    up = them.joint("Neck")[frames] - them.joint("Hips")[frames]
    forward = np.cross(across, up)
    forward /= np.maximum(np.linalg.norm(forward, axis=1, keepdims=True), 1e-9)
    return np.einsum("ij,ij->i", hand - chest, forward) <= BACK_PLANE_M


def _is_room_word(word: str) -> bool:
    """Whether a destination names the room (or a kind of room) rather than an object in it."""
    base = word.split("/")[0].split("#")[0].replace("_", " ")
    return base in ("room", "house", "home", "inside", "outside") or lookup_room(base) is not None


def _gap_to_footprint(placed: PlacedObject, xz: np.ndarray) -> np.ndarray:
    """(N,) metres from each floor point (N, 2) to the object's footprint (its world bounds seen from above)."""
    b = world_bounds(placed)
    d = np.maximum(0.0, np.maximum(b[0, [0, 2]] - xz, xz - b[1, [0, 2]]))
    return np.hypot(d[:, 0], d[:, 1])


def _arrival(act: Act, body: Body, world: World, bodies: Mapping[str, Body]) -> Check | None:
    """A walk to something ends next to it."""
    dest = act.node.destination or act.node.target
    seg = act.clip
    if not dest or seg is None:
        return None
    who = act.character
    end = min(seg.end_frame, body.frames) - 1
    hips = body.joint("Hips")[end, [0, 2]]
    if dest in bodies and dest != who:
        gap = float(
            np.linalg.norm(bodies[dest].joint("Hips")[min(end, bodies[dest].frames - 1), [0, 2]] - hips)
        )
        ok = gap <= ARRIVE_PERSON_M
        return Check(
            name="contact",
            character=who,
            ok=ok,
            reason=f"{who} stops {gap:.1f} m from {dest}" + ("" if ok else f" (at most {ARRIVE_PERSON_M} m)"),
            frames=[] if ok else [end],
        )
    # "walks to a chair" of "eight chairs around the table": any of its copies (the walk goes to one it can
    # reach, services.orchestrator.slotting), not only the first
    found = world.copies(dest) or world.find(dest)
    if not found and _is_room_word(dest):
        return None  # "walks into the room", "goes to the kitchen": the room itself, no object to reach
    if not found and is_entrance(act) and base_id(dest) not in CATEGORIES:
        return None  # "enters the bakery": a place the catalog has no object for is the room it comes into
    if not found:
        return Check(
            name="contact",
            character=who,
            ok=False,
            reason=f"there is no {display(dest)} in the room for {who} to walk to",
        )
    on = [p for p in found if set(world.contact_points(p)) & RUN_ON_POINTS and said_on(act, dest)]
    if on:
        return _on_it(act, body, world, on, end)
    via = passes_through(act, dest)
    # "comes in through the door", "leaves through the back door": the walk passes it, wherever it ends
    at = np.arange(max(0, seg.start_frame), end + 1) if via else np.array([end])
    walked = body.joint("Hips")[np.clip(at, 0, body.frames - 1)][:, [0, 2]]
    gaps = []
    for placed in found:
        gaps.append(_gap_to_footprint(placed, walked))
    each = np.min(gaps, axis=0)
    gap = float(each.min())
    ok = gap <= ARRIVE_M
    where = "passes" if via else "stops"
    return Check(
        name="contact",
        character=who,
        ok=ok,
        reason=f"{who} {where} {gap:.1f} m from the {display(dest)}"
        + ("" if ok else f" (at most {ARRIVE_M} m)"),
        frames=[] if ok else [int(at[int(np.argmin(each))])],
    )


RUN_ON_POINTS = frozenset({"run", "walk", "jog"})  # an object made to be run on (a treadmill's "run" point)
ON_IT_M = 0.1  # metres from its footprint that the hips of one running on it may be


def said_on(act: Act, dest: str) -> bool:
    """Whether the sentence moves on the destination ("runs on the treadmill"), not to it."""
    return _said_with(act, dest, "on")


def _on_it(act: Act, body: Body, world: World, found: list[PlacedObject], end: int) -> Check:
    """ "Ben runs on the treadmill": the hips over the treadmill when the run ends, not beside it (a run to
    its front read "stops 0.5 m from the treadmill" and passed while nobody was on it: duo-gym-05 s5)."""
    who = act.character
    hips = body.joint("Hips")[end, [0, 2]]
    gaps = []
    for placed in found:
        gaps.append(float(_gap_to_footprint(placed, hips[None])[0]))
    gap, name = min(gaps), display(found[int(np.argmin(gaps))].id)
    ok = gap <= ON_IT_M
    return Check(
        name="contact",
        character=who,
        ok=ok,
        reason=f"{who} is on the {name}" if ok else f"{who} ends {gap:.1f} m beside the {name}, not on it",
        frames=[] if ok else [end],
    )


def passes_through(act: Act, dest: str) -> bool:
    """Whether the sentence walks through the destination ("enters through the front door"), not to it."""
    return _said_with(act, dest, "through")


def _said_with(act: Act, dest: str, prep: str) -> bool:
    """Whether the sentence puts ``prep`` before the destination's name ("through the front door")."""
    name = re.escape(display(dest).split(" ")[-1])
    pattern = rf"\b{prep}\s+(?:the|a|an|his|her|their)?\s*(?:\w+\s+)?{name}\b"
    return re.search(pattern, act.text.lower()) is not None


__all__ = ["CONTACT_M", "carried", "contact", "other_character", "reach"]
