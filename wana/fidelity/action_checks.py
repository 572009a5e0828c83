"""Checks of one action: done by its character in story order, at its target, on something that holds it up,
and, for a character's first sentence, entering rather than standing there from the first frame.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from functools import partial

import numpy as np

from proto.fidelity import Check
from proto.scene import PlacedObject
from wana.assets.catalog import world_bounds
from wana.fidelity.acts import SEATING, Act, is_locomotion, window_frames
from wana.fidelity.bodies import Body
from wana.fidelity.clips import ClipNeeds, clip_needs
from wana.fidelity.world import World, display

CONTACT_M = 0.05  # the contact joint within this of the object's contact point ...
CONTACT_SHARE = 0.5  # ... on at least this share of the window's frames
MOUTH_M = 0.15  # a drink's cup within this of the head's centre
ARRIVE_M = 1.0  # a walk to an object ends within this of its footprint
ARRIVE_PERSON_M = 1.5  # a walk to a character ends within this of them
SEAT_BELOW_M = 0.06  # hips at most this far below a supporting surface ...
SEAT_ABOVE_M = 0.30  # ... and at most this far above it
SUPPORT_MARGIN_M = 0.08  # hips may overhang a surface's edge by this much
UNSUPPORTED_FRAMES = 3  # frames on air allowed (the moment of sitting down)
LEAN_M = 0.08  # a leaning hand within this of a wall or a piece of furniture
DOOR_M = 1.0  # an entrance starts within this of a door
ENTRANCE_VERBS = ("walk in", "enter", "come in", "run in", "step in", "burst in", "walk into", "come into")
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


def joint_words(joints: list[str] | tuple[str, ...]) -> str:
    limbs = {j.replace("Middle1", "") for j in joints}
    if limbs == {"LeftHand", "RightHand"}:
        return "hands"
    if limbs == {"Hips"}:
        return "hips"
    return " and ".join(
        sorted({"left hand" if "Left" in j else "right hand" if "Right" in j else j.lower() for j in limbs})
    )


def stays(parts: str) -> str:
    return "stay" if parts.endswith("s") or " and " in parts else "stays"


def third_person(verb: str) -> str:
    """ "hammer" -> "hammers", "watch" -> "watches", "carry" -> "carries" (the first word of a phrase)."""
    head, _, rest = verb.partition(" ")
    if head.endswith(("s", "sh", "ch", "x", "z", "o")):
        head += "es"
    elif head.endswith("y") and head[-2:-1] not in "aeiou":
        head = head[:-1] + "ies"
    else:
        head += "s"
    return f"{head} {rest}".strip()


def frame_list(frames: np.ndarray | range | list[int], limit: int = 120) -> list[int]:
    """Story frames for a check, at most `limit` of them (evenly spread, first and last kept)."""
    arr = np.asarray(list(frames) if isinstance(frames, range) else frames, dtype=np.int64)
    if len(arr) > limit:
        arr = arr[np.linspace(0, len(arr) - 1, limit).round().astype(np.int64)]
    return [int(f) for f in arr]


def span_words(frames: np.ndarray | list[int]) -> str:
    frames = list(frames)
    if not frames:
        return ""
    return f"frame {frames[0]}" if len(frames) == 1 else f"frames {frames[0]}-{frames[-1]}"


# -- performed -----------------------------------------------------------------------------------


def performed(act: Act, has_motion: bool, previous_start: int) -> Check:
    """The right character plays the asked clip, no earlier than the action the text puts before it."""
    who, verb = act.character, act.node.verb or act.node.action
    base = partial(Check, name="performed", character=who)
    if not has_motion:
        return base(ok=False, essential=True, reason=f"{who} does not appear in the animation")
    shown = sorted({s.action for s in act.segments if s.action not in ("hold",)})
    if not act.node.action:
        instead = f"{who} {'does ' + ', '.join(shown) if shown else 'stands still'} instead"
        return base(
            ok=False,
            essential=True,
            reason=f"'{verb}' is not an action wana knows: {instead}",
            frames=frame_list(range(act.start, act.end)) if act.start >= 0 else [],
        )
    seg = act.clip
    if seg is None:
        instead = f"{who} does {', '.join(shown)} instead" if shown else f"{who} never does it"
        return base(
            ok=False,
            essential=True,
            reason=f"the animation does not show {who} {verb}: {instead}",
            frames=frame_list(range(act.start, act.end)) if act.start >= 0 else [],
        )
    if act.start < previous_start:
        return base(
            ok=False,
            reason=f"{who} starts to {verb} at frame {act.start}, before the action the text tells earlier "
            f"(frame {previous_start})",
            frames=[seg.start_frame],
        )
    return base(
        ok=True,
        reason=f"{who} {third_person(act.node.action.replace('_', ' '))} ({span_words([seg.start_frame, seg.end_frame - 1])})",
    )


# -- contact -------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Reach:
    """Where an action's contact joints went relative to the object point they were meant for."""

    placed: PlacedObject
    point: str  # contact point name on the object
    targets: dict[str, np.ndarray]  # body joint -> (3,) world target
    distance: dict[str, np.ndarray]  # body joint -> (W,) metres over the window frames


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
            out.append((name, {by_limb[w][0]: by_limb[w][1] for w in wanted}))
        elif clip.object in HELD and wanted & set(by_limb):
            j, p = by_limb[next(iter(wanted & set(by_limb)))]
            out.append((name, {j: p}))
    return out


def reach(act: Act, body: Body, world: World, candidates: list[PlacedObject]) -> Reach | None:
    """The candidate object and contact point the body came closest to during the window, None if none fits."""
    clip = clip_needs(act.node.action)
    frames = window_frames(act)
    if clip is None or not len(frames):
        return None
    idx = np.clip(np.asarray(frames), 0, body.frames - 1)
    best: Reach | None = None
    best_score = np.inf
    for placed in candidates:
        for name, targets in _fitting(clip, world.contact_points(placed)):
            dist = {j: np.linalg.norm(body.joint(j)[idx] - p, axis=1) for j, p in targets.items()}
            score = float(np.mean([d.mean() for d in dist.values()]))
            if score < best_score:
                best, best_score = Reach(placed, name, targets, dist), score
    return best


def _candidates(act: Act, world: World, characters: set[str]) -> tuple[list[PlacedObject], str]:
    """The objects the action may use, and the word the text used for them ("" when it named none).

    With no object named, a held object must be one made for the action (a hammer has a "hammer" point, a cup
    a "drink" point); anything else must offer the interaction's own point, not just a place to touch.
    """
    clip = clip_needs(act.node.action)
    for ref in (act.node.instrument, act.node.target, act.node.destination):
        if ref and ref not in characters:
            return world.find(ref), ref
    if clip is None:
        return [], ""
    action = act.node.action
    if clip.object in HELD:
        meant = {action, action.split("_")[0]}
    else:
        meant = {action, *PREFERRED_POINTS.get(clip.object, ())} - {"touch", "pick_up"}
    return [o for o in world.scene.objects if meant & set(world.contact_points(o))], ""


def contact(
    act: Act, body: Body, world: World, bodies: Mapping[str, Body]
) -> tuple[Check | None, dict[str, bool]]:
    """The `contact` check of one action and the objects it touches on purpose (exempt from `penetration`):
    object id -> True when the whole body may touch it, False for the arms only."""
    clip = clip_needs(act.node.action)
    who, verb = act.character, act.node.verb or act.node.action
    base = partial(Check, name="contact", character=who)
    if clip is None or act.clip is None:
        return None, {}
    if is_locomotion(act.node.action):
        return _arrival(act, body, world, bodies), {}
    if not clip.object:
        return None, {}
    frames = window_frames(act)
    if clip.object == "person":
        return _touch_person(act, body, bodies, frames), {}
    candidates, word = _candidates(act, world, set(bodies))
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
    got = reach(act, body, world, candidates)
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
    if act.node.action == "drink":
        head = body.points[np.clip(fr, 0, body.frames - 1), -1]
        hand = body.joint(worst)[np.clip(fr, 0, body.frames - 1)]
        at_mouth = np.linalg.norm(head - hand, axis=1) <= MOUTH_M + CONTACT_M
        if np.mean(at_mouth) < CONTACT_SHARE:
            return (
                base(
                    ok=False,
                    reason=f"the {name} never reaches {who}'s mouth",
                    frames=frame_list(fr[~at_mouth]),
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


def _other_character(act: Act, bodies: Mapping[str, Body]) -> str:
    for ref in (act.node.target, act.node.destination, act.node.instrument):
        if ref in bodies and ref != act.character:
            return ref
    others = [n for n in bodies if n != act.character]
    return others[0] if len(others) == 1 else ""


def _touch_person(act: Act, body: Body, bodies: Mapping[str, Body], frames: range) -> Check:
    clip = clip_needs(act.node.action)
    assert clip is not None
    who, verb = act.character, act.node.verb or act.node.action
    other = _other_character(act, bodies)
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
    share = float(np.mean(gap <= CONTACT_M))
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
    found = world.find(dest)
    if not found:
        return Check(
            name="contact",
            character=who,
            ok=False,
            reason=f"there is no {display(dest)} in the room for {who} to walk to",
        )
    gaps = []
    for placed in found:
        b = world_bounds(placed)
        d = np.maximum(0.0, np.maximum(b[0, [0, 2]] - hips, hips - b[1, [0, 2]]))
        gaps.append(float(np.hypot(*d)))
    gap = min(gaps)
    ok = gap <= ARRIVE_M
    return Check(
        name="contact",
        character=who,
        ok=ok,
        reason=f"{who} stops {gap:.1f} m from the {display(dest)}"
        + ("" if ok else f" (at most {ARRIVE_M} m)"),
        frames=[] if ok else [end],
    )


# -- supported -----------------------------------------------------------------------------------


def supported(act: Act, body: Body, world: World, until: int) -> Check | None:
    """Sitting, lying and leaning rest on something: a surface under the hips (and back), a wall under the hand."""
    action = act.node.action
    who = act.character
    seg = act.clip
    if seg is None:
        return None
    clip = clip_needs(action)
    if action == "lean_on_wall" and clip is not None:
        return _leaning(act, body, world)
    if action not in SEATING or action in ("sit_on_floor", "kneel"):
        return None
    frames = np.arange(window_frames(act).start, max(until, window_frames(act).stop))
    frames = frames[frames < body.frames]
    if not len(frames):
        return None
    held = _on_surface(body.joint("Hips")[frames], world)
    if action != "sit":
        held &= _on_surface(body.joint("Spine1")[frames], world, above=0.45)
    air = frames[~held]
    posture = "sits" if action == "sit" else "lies"
    if len(air) > UNSUPPORTED_FRAMES:
        hips = body.joint("Hips")[air]
        return Check(
            name="supported",
            character=who,
            ok=False,
            essential=True,
            reason=f"{who} {posture} on air: " + _nearest_seat_words(hips, world),
            frames=frame_list(air),
        )
    return Check(
        name="supported", character=who, ok=True, reason=f"{who} {posture} on a surface that holds them"
    )


def _on_surface(points: np.ndarray, world: World, above: float = SEAT_ABOVE_M) -> np.ndarray:
    """(T,) whether each (T, 3) point rests on some support surface (or, low enough, on the floor)."""
    held = points[:, 1] <= above * 0.5  # on the floor itself
    for _, height, lo, hi in world.surfaces:
        inside = np.all(
            (points[:, [0, 2]] >= lo - SUPPORT_MARGIN_M) & (points[:, [0, 2]] <= hi + SUPPORT_MARGIN_M),
            axis=1,
        )
        dy = points[:, 1] - height
        held |= inside & (dy >= -SEAT_BELOW_M) & (dy <= above)
    return held


def _nearest_seat_words(hips: np.ndarray, world: World) -> str:
    at = np.median(hips, axis=0)
    best, best_gap = None, np.inf
    for placed, height, lo, hi in world.surfaces:
        if not 0.2 <= height <= 0.9:
            continue
        d = np.maximum(0.0, np.maximum(lo - at[[0, 2]], at[[0, 2]] - hi))
        gap = float(np.hypot(*d))
        if gap < best_gap:
            best, best_gap = placed, gap
    hips_words = f"hips {at[1]:.2f} m above the floor"
    if best is None:
        return f"no seat in the room ({hips_words})"
    if best_gap < 0.02:
        return f"{hips_words}, off the {display(best.id)}'s seat height"
    return f"{best_gap:.2f} m beside the {display(best.id)} ({hips_words})"


def _leaning(act: Act, body: Body, world: World) -> Check:
    clip = clip_needs(act.node.action)
    assert clip is not None
    frames = np.asarray(window_frames(act))
    frames = frames[frames < body.frames]
    joint = clip.contacts[0] if clip.contacts else "LeftHand"
    hand = body.joint(joint)[frames]
    room = world.room
    wall = np.minimum(room.width / 2 - np.abs(hand[:, 0]), room.depth / 2 - np.abs(hand[:, 2])) <= LEAN_M
    for _, boxes, outer in world.solids:
        near = np.all((hand >= outer[0] - LEAN_M) & (hand <= outer[1] + LEAN_M), axis=1)
        if near.any():
            from wana.fidelity.world import point_box_distance

            wall[near] |= point_box_distance(hand[near], boxes).min(axis=1) <= LEAN_M
    who = act.character
    if np.mean(wall) < CONTACT_SHARE:
        return Check(
            name="supported",
            character=who,
            ok=False,
            essential=True,
            reason=f"{who} leans on air: the {joint_words([joint])} touches no wall",
            frames=frame_list(frames[~wall]),
        )
    return Check(name="supported", character=who, ok=True, reason=f"{who} leans on something solid")


# -- entrance ------------------------------------------------------------------------------------


def is_entrance(act: Act) -> bool:
    verb = act.node.verb.lower()
    return any(verb == v or verb.startswith(v + " ") for v in ENTRANCE_VERBS)


def entrance(act: Act, body: Body, world: World, first: bool) -> Check | None:
    """An entrance starts outside or at a door; nobody is on stage before their first sentence."""
    who = act.character
    if act.start < 0:
        return None
    problems: list[str] = []
    frames: list[int] = []
    hips = body.joint("Hips")[:, [0, 2]]
    if first and act.start > 0:
        early = np.nonzero(world.inside_room(hips[: act.start]))[0]
        if len(early):
            problems.append(f"{who} is in the room from {span_words(early)}, before {who}'s first sentence")
            frames.extend(int(f) for f in early)
    if is_entrance(act):
        at = hips[min(act.start, body.frames - 1)]
        inside = bool(world.inside_room(at[None])[0])
        doors = [o for o in world.scene.objects if o.category == "door"]
        door_gap = min(
            (float(np.hypot(at[0] - d.position[0], at[1] - d.position[2])) for d in doors), default=np.inf
        )
        if inside and door_gap > DOOR_M:
            wall = min(world.room.width / 2 - abs(at[0]), world.room.depth / 2 - abs(at[1]))
            where = "with no door in the room" if not doors else f"{door_gap:.1f} m from the door"
            problems.append(f"{who} starts {wall:.1f} m inside the room, {where}, instead of coming in")
            frames.append(act.start)
    if not first and not is_entrance(act):
        return None
    if problems:
        return Check(
            name="entrance",
            character=who,
            ok=False,
            reason="; ".join(problems),
            frames=frame_list(sorted(set(frames))),
        )
    why = (
        f"{who} comes in from outside or a door"
        if is_entrance(act)
        else f"{who} appears with the first sentence"
    )
    return Check(name="entrance", character=who, ok=True, reason=why)


__all__ = [
    "CONTACT_M",
    "contact",
    "entrance",
    "frame_list",
    "joint_words",
    "performed",
    "span_words",
    "supported",
]
