"""Checks of one action: done by its character in story order, on something that holds it up, and, for a
character's first sentence, entering rather than standing there from the first frame (its `contact` check is
in wana.fidelity.contact_checks).
"""

from __future__ import annotations

from functools import partial

import numpy as np

from proto.fidelity import Check
from wana.fidelity.acts import SEATING, Act, is_entrance, window_frames
from wana.fidelity.bodies import Body
from wana.fidelity.clips import clip_needs
from wana.fidelity.contact_checks import CONTACT_SHARE, HEAD_OFF_M, head_beyond
from wana.fidelity.solids import rests_on
from wana.fidelity.words import frame_list, joint_words, span_words, third_person
from wana.fidelity.world import World, display, point_box_distance

SEAT_BELOW_M = 0.06  # hips at most this far below a supporting surface ...
SEAT_ABOVE_M = 0.30  # ... and at most this far above it
SUPPORT_MARGIN_M = 0.08  # hips may overhang a surface's edge by this much
UNSUPPORTED_FRAMES = 3  # frames on air allowed (the moment of sitting down)
STANDING_HIPS_M = 0.7  # hips at least this far above the lowest foot: the body stands on its feet ...
FOOT_DOWN_M = 0.12  # ... when that foot is within this of the floor or a surface's top
FEET = ("LeftFoot", "LeftToeBase", "RightFoot", "RightToeBase")
LEAN_M = 0.08  # a leaning hand within this of a wall or a piece of furniture
DOOR_M = 1.0  # an entrance starts within this of a door


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
    posture = "sits" if action == "sit" else "lies"
    upright = _standing(body, frames, world)
    standing = ~held & upright
    held |= standing  # upright on its feet: nothing on air (whether it sat is the contact check's)
    off = _off_stated(act, body, world, frames[~upright]) if action != "sit" else None
    air = frames[~held]
    if off is not None and len(air) <= UNSUPPORTED_FRAMES:
        return off
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
    if standing.sum() > UNSUPPORTED_FRAMES:
        return Check(
            name="supported", character=who, ok=True,
            reason=f"{who} stands on their feet ({span_words(frames[standing])}), not on air",
        )  # fmt: skip
    return Check(
        name="supported", character=who, ok=True, reason=f"{who} {posture} on a surface that holds them"
    )


def _off_stated(act: Act, body: Body, world: World, frames: np.ndarray) -> Check | None:
    """A failing check when a body lying on the object the sentence names has its head off that object.

    The hips on the bed's or the tub's lie point with the rest of the body on the floor or through a wall is
    lying beside it, not on it (solo-bathroom-23 s10: "He lies in the bathtub" played across the tub, the
    head through its side and out at the wall; hips and back were "on a surface", the floor's); the head is
    over the object's footprint when the body lies on it.
    """
    ref = act.node.target or act.node.destination
    named = [o for o in world.find(ref) if any(s[0].id == o.id for s in world.surfaces)] if ref else []
    if not named:
        return None
    gaps = [head_beyond(body, placed, frames) for placed in named]
    gap = np.min(gaps, axis=0)
    beyond = gap > HEAD_OFF_M
    if beyond.sum() <= UNSUPPORTED_FRAMES:
        return None
    name = display(named[int(np.argmin([g.mean() for g in gaps]))].id)
    return Check(
        name="supported",
        character=act.character,
        ok=False,
        essential=True,
        reason=f"{act.character} lies half off the {name}: the head is {float(np.median(gap[beyond])):.2f} m "
        f"beyond it ({span_words(frames[beyond])})",
        frames=frame_list(frames[beyond]),
    )


def _standing(body: Body, frames: np.ndarray, world: World) -> np.ndarray:
    """(W,) whether the body stands upright on each frame: its lowest foot down on the floor or on a
    surface's top (a mattress stood on) and its hips a standing height above that foot."""
    feet = np.stack([body.joint(j)[frames] for j in FEET], axis=1)  # (W, 4, 3)
    low = feet[np.arange(len(frames)), np.argmin(feet[:, :, 1], axis=1)]  # (W, 3) the lowest foot point
    down = np.abs(low[:, 1]) <= FOOT_DOWN_M
    for _, height, lo, hi in world.surfaces:
        over = np.all((low[:, [0, 2]] >= lo) & (low[:, [0, 2]] <= hi), axis=1)
        down |= over & (np.abs(low[:, 1] - height) <= FOOT_DOWN_M)
    return down & (body.joint("Hips")[frames][:, 1] - low[:, 1] >= STANDING_HIPS_M)


def _on_surface(points: np.ndarray, world: World, above: float = SEAT_ABOVE_M) -> np.ndarray:
    """(T,) whether each (T, 3) point rests on some support surface (or, low enough, on the floor).

    A catalog support rectangle can cover less than the object (a bunk bed's only one spans half its
    mattress), so a point also rests on an object when one of its solid parts is right under it.
    """
    held = points[:, 1] <= above * 0.5  # on the floor itself
    for _, height, lo, hi in world.surfaces:
        inside = np.all(
            (points[:, [0, 2]] >= lo - SUPPORT_MARGIN_M) & (points[:, [0, 2]] <= hi + SUPPORT_MARGIN_M),
            axis=1,
        )
        dy = points[:, 1] - height
        held |= inside & (dy >= -SEAT_BELOW_M) & (dy <= above)
    return held | _on_solid(points, world, above) if not held.all() else held


PROBE_STEP_M = 0.03


def _on_solid(points: np.ndarray, world: World, above: float) -> np.ndarray:
    """(T,) whether some object's solid part lies under each point within `above` (probed every 3 cm)."""
    out = np.zeros(len(points), bool)
    for placed, _, outer in world.solids:
        near = (
            np.all((points[:, [0, 2]] >= outer[0, [0, 2]]) & (points[:, [0, 2]] <= outer[1, [0, 2]]), axis=1)
            & (points[:, 1] - above <= outer[1, 1])
            & (points[:, 1] + SEAT_BELOW_M >= outer[0, 1])
            & ~out
        )
        if not near.any():
            continue
        out[np.nonzero(near)[0]] = rests_on(placed, points[near], SEAT_BELOW_M, above, PROBE_STEP_M)
    return out


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


def entrance(
    act: Act, body: Body, world: World, first: bool, present: np.ndarray | None = None
) -> Check | None:
    """An entrance starts outside or at a door; nobody is on stage before their first sentence.

    Args:
        present: (T,) bool, the frames the character is on stage (shown); None means always.
    """
    who = act.character
    if act.start < 0:
        return None
    problems: list[str] = []
    frames: list[int] = []
    hips = body.joint("Hips")[:, [0, 2]]
    shown = np.ones(body.frames, bool) if present is None else present[: body.frames]
    if first and act.start > 0:
        early = np.nonzero(world.inside_room(hips[: act.start]) & shown[: act.start])[0]
        if len(early):
            problems.append(f"{who} is in the room from {span_words(early)}, before {who}'s first sentence")
            frames.extend(int(f) for f in early)
    if is_entrance(act):
        later = np.nonzero(shown[act.start :])[0]  # where the character is first seen, from its sentence on
        at = hips[min(act.start + (int(later[0]) if len(later) else 0), body.frames - 1)]
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


__all__ = ["entrance", "is_entrance", "performed", "supported"]
