"""The motion stage: drafts, the layout optimised around each interaction, then every character's motion.

Nodes: `draft:<name>:<k>` (action k on the composed layout, what the optimiser starts from),
`optimise:<name>:<k>` (the layout around an action that touches an object), `segment:<name>:<k>` (action
k on the final layout from the end state of action k-1), `<kind>:<name>:idle` for a character with no
action. Story timing (services/orchestrator/timeline.py) then places the segments on one time line.

Who is on stage when and where each starts (the door, entrances, exits: services/orchestrator/staging.py)
and which seat or stand slot each action takes (services/orchestrator/slotting.py) are decided here, in
story order, and reach the motion service as each segment's start, routes, seats and spots; after timing,
each motion gets its presence track (Motion.present) and waits outside the room while off stage.
Each pass over the story (drafts, segments) resumes from the checkpoints of the last one
(services/orchestrator/stages/replay.py), so an edit walks only the actions from the first it changes.
This module is over 400 lines because the passes, the interactions and the time line share one walk.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import msgspec
import numpy as np

from proto.common import Span
from proto.motion import PairedAction, SegmentEndState, SynthesizeReply, SynthesizeRequest
from proto.motion_data import Motion
from proto.optimizer import Interaction, OptimiseReply, OptimiseRequest, OptimiseSettings
from proto.scene import Scene
from proto.social import SocialPlan
from proto.ssg import ActionNode, CharacterNode, Command, Diagnostic, RelationNode, SentenceGraph
from services.orchestrator.backend import StageFailed
from services.orchestrator.document import Sentence
from services.orchestrator.queries import content_hash
from services.orchestrator.slotting import Slotting, matched
from services.orchestrator.stages import StageContext, content_of
from services.orchestrator.stages.props import (
    POURED_FROM,
    aimed,
    brought_notes,
    carried,
    made_for,
    provide,
    worked_at,
)
from services.orchestrator.stages.reach import within_reach
from services.orchestrator.stages.replay import (
    Carried,
    Outputs,
    PassTrace,
    resume_at,
    same_from,
    step_key,
)
from services.orchestrator.stages.scene import kept_relations
from services.orchestrator.stages.seats import furnish, seat_at_instruments
from services.orchestrator.stages.social import fit_cast, frame_count, paired_actions
from services.orchestrator.stages.states import with_states
from services.orchestrator.staging import (
    Doorway,
    doorway,
    first_spot,
    is_entrance,
    is_exit,
    kept_clear,
    presence,
    route,
    spot_near,
    with_door,
)
from services.orchestrator.timeline import Beat, assemble, schedule
from services.orchestrator.views import (
    characters_of,
    geometry_view,
    others,
    scene_part,
    scene_view,
    social_distances,
    social_moods,
    with_looks,
)
from wana.arrays import from_wire, to_wire
from wana.domain.actions import get_clip
from wana.domain.idle import attention, enliven_motion
from wana.domain.object_geometry import find_object
from wana.domain.style import MANNER_MOOD, restyle_motion
from wana.fidelity.handover import HANDOVER_VERBS

HANDS_WHAT_HELD = (
    "hand",
    "pass",
)  # hand-over verbs that always pass an object ("gives her a smile" need not)
HANDOVER_VERB = "give"  # the verb an action that hands an object over keeps for the motion service (planning)

LEGS_OUT_M = 0.4  # metres in front of a seated character's hips where its knees and shins are
GESTURE_NEAR_M = 1.0  # metres: the standing others a gesture aimed at nobody may step back from
TRAIL_STEP = 8  # frames between the points kept of a character's last walk
TRAIL_MIN_M = 0.3  # metres: an action that moves its character less than this leaves no trail
Characters = dict[str, tuple[CharacterNode, list[str]]]  # name -> (its actions in order, their sentence ids)
Distances = dict[tuple[str, int], dict[str, float]]  # (name, k) -> {other: metres}


@dataclass
class Animated:
    """The motion stage's output: the final layout, one motion per character, and what happened on the way."""

    scene: Scene
    motions: dict[str, Motion] = field(default_factory=dict)
    optimisations: list[OptimiseReply] = field(default_factory=list)
    diagnostics: list[tuple[str, Diagnostic]] = field(default_factory=list)  # (sentence id, diagnostic)


def synthesise(
    ctx: StageContext,
    character: CharacterNode,
    scene: Scene,
    state: SegmentEndState | None,
    start: tuple[float, float, float],
    others: dict[str, tuple[float, float]] | None = None,
    distances: dict[str, float] | None = None,
    routes: list[list[tuple[float, float]]] | None = None,
    seats: dict[int, str] | None = None,
    spots: dict[int, tuple[float, float]] | None = None,
    occupied: list[tuple[float, float]] | None = None,
    bodies: list[tuple[float, float]] | None = None,
) -> SynthesizeReply:
    request = SynthesizeRequest(
        header=ctx.header(),
        character=character,
        scene=scene,
        start=start,
        start_state=state,
        others=others or {},
        distances=distances or {},
        routes=routes or [],
        seats=seats or {},
        spots=spots or {},
        occupied=occupied or [],
        bodies=bodies or [],
    )
    return content_of(ctx.backend.call(request))


def seated_others(
    action: ActionNode, name: str, states: dict[str, SegmentEndState]
) -> list[tuple[float, float]]:
    """Where the other characters sit by the time a sit / lie action starts (their seat slots are taken), or
    a two-person action (a hug: one seated is hugged from beyond its legs); [] for any other action, so that
    its recompute does not depend on them."""
    try:
        clip = get_clip(action.action) if action.action else None
    except KeyError:
        clip = None
    if clip is None or clip.interaction is None or clip.interaction.object not in ("seat", "bed", "person"):
        return []
    return sorted(
        (round(st.x, 3), round(st.z, 3)) for c, st in states.items() if c != name and st.posture != "stand"
    )


def standing_others(
    action: ActionNode, name: str, states: dict[str, SegmentEndState], hidden: set[str]
) -> list[tuple[float, float]]:
    """Where the other characters on stage stand when an action that may walk starts (its route goes round
    them, services/motion/routing.py), and for a walk or an action aimed at something the legs of those
    seated (LEGS_OUT_M in front of their hips); [] for an action that stays put, so its recompute does not
    depend on them."""
    try:
        clip = get_clip(action.action) if action.action else None
    except KeyError:
        clip = None
    walks = clip is not None and "locomotion" in clip.tags
    aimed = walks or action.target or action.destination or action.instrument
    me = states.get(name)
    if not aimed and (clip is None or clip.interaction is not None or me is None):
        return []
    # a gesture aimed at nobody ("They dance") steps away from those within GESTURE_NEAR_M (planning)
    standing = sorted(
        (round(st.x, 3), round(st.z, 3))
        for c, st in states.items()
        if c != name
        and c not in hidden
        and st.posture == "stand"
        and (aimed or (me is not None and math.hypot(st.x - me.x, st.z - me.z) < GESTURE_NEAR_M))
    )
    if not aimed:
        return standing
    # a seated one's legs reach out into the floor in front of the seat: a walk goes round them too (Mei
    # getting up walked past Raj's desk chair through his shins, office2 s8)
    legs = sorted(
        (round(st.x + math.sin(st.yaw) * LEGS_OUT_M, 3), round(st.z + math.cos(st.yaw) * LEGS_OUT_M, 3))
        for c, st in states.items()
        if c != name and c not in hidden and st.posture in ("sit", "sit_floor")
    )
    return standing + legs


def optimise(
    ctx: StageContext, scene: Scene, motion: Motion, character: str, action: ActionNode
) -> OptimiseReply:
    targets = [t for t in (action.target, action.instrument) if t]
    request = OptimiseRequest(
        header=ctx.header(),
        scene=scene,
        motion=motion,
        interaction=Interaction(character=character, action=action.action, targets=targets),
        settings=OptimiseSettings(seed=ctx.seed),
    )
    return content_of(ctx.backend.call(request))


def story_order(characters: Characters, sentences: Sequence[Sentence]) -> list[tuple[str, int]]:
    """(name, k) of every action in story order: by sentence, then by character, then by k (one pass over
    the actions, not one per sentence: a long story's edit should not pay actions x sentences)."""
    by_sentence: dict[str, list[tuple[str, int]]] = {}
    for name, (_, sids) in characters.items():
        for k, sid in enumerate(sids):
            by_sentence.setdefault(sid, []).append((name, k))
    return [x for s in sentences for x in by_sentence.get(s.id, [])]


def segments(
    ctx: StageContext,
    kind: str,
    characters: Characters,
    sentences: Sequence[Sentence],
    scene: Scene,
    starts: dict[str, tuple[float, float, float]],
    upto: dict[str, int] | None = None,
    distances: Distances | None = None,
    door: Doorway | None = None,
    hidden: set[str] | None = None,
    notes: list[tuple[str, str]] | None = None,
    handovers: list[PairedAction] | None = None,
    holding: dict[str, str] | None = None,
) -> dict[str, list[Motion]]:
    """Every character's motion, one query node `<kind>:<name>:<k>` per action, in document order.

    Action k starts from the end state of action k-1 and sees only what it can touch: the objects on the
    floor (which routes go around), the objects it names with what they rest on, and where a character it
    names stands by then. So an edit that leaves an end state unchanged stops there (early cutoff), and
    moving a lamp on a desk re-runs only the actions that use the lamp. ``distances``: (name, k) -> how
    far action k stops from the characters it walks up to (the social plan's, views.social_distances).
    ``hidden``: the characters waiting outside ``door`` (services/orchestrator/staging.py): their next action
    comes in through it, and an exit walks out through it.
    ``notes`` collects (sentence id, what the motion service said) ("no free seat ...: Zoe stands instead").
    ``handovers`` collects the actions that hand an object to another character (their next actions hold it).
    ``holding``: name -> the object in the character's hand from its first frame (props.carried: a bag it brings).
    """
    held = holding or {}
    states = {
        name: SegmentEndState(x=st[0], z=st[1], yaw=st[2], holding=held.get(name, ""))
        for name, st in starts.items()
    }
    outside = set(hidden or ())
    slotting = Slotting(scene)  # who holds which seat and stand slot, as the story runs
    exit_lanes: dict[str, list[tuple[float, float]]] = {}  # sentence id -> the door's lanes still free
    sentence_index = {s.id: i for i, s in enumerate(sentences)}
    trails: dict[
        str, tuple[int, list[tuple[float, float]]]
    ] = {}  # name -> (sentence, where its last walk went)
    out = Outputs({name: [] for name in characters})
    pieces = out.pieces
    object_ids = {o.id for o in scene.objects}
    order = story_order(characters, sentences)
    for name, k in order:
        slotting.expect(name, characters[name][0].actions[k])
    ends = _sentence_ends(order, characters)
    # Checkpoints (stages/replay.py): what each step reads besides the carried state, and the whole pass's.
    skipped = [upto is not None and k > upto.get(name, -1) for name, k in order]
    keys = [
        step_key(
            name,
            k,
            characters[name][0].actions[k],
            characters[name][1][k],
            sentence_index.get(characters[name][1][k], 0),
            [[o, j, characters[o][0].actions[j]] for o, j in order[i + 1 : ends[i]]],
            sorted((distances or {}).get((name, k), {}).items()),
        )
        if not skipped[i]
        else "skipped"
        for i, (name, k) in enumerate(order)
    ]
    context = content_hash(
        [scene, list(starts.items()), sorted(held.items()), door, sorted(hidden or ()), list(characters)]
        + [sorted((o, sorted(w)) for o, w in slotting.sitters.items())]
        + [sorted((o, sorted(w)) for o, w in slotting.standers.items())]
    )
    last: PassTrace | None = ctx.engine.traces.pop(kind, None)  # put back only when this pass finishes
    begin = resume_at(last, context, keys)
    tail = same_from(last, context, keys)
    after: list[Carried] = []
    digests: list[str] = []
    counts: list[tuple[dict[str, int], int, int]] = []
    if begin and last is not None:  # the steps before the first changed one: as the last pass left them
        live = last.after[begin - 1].copy()
        states, outside, exit_lanes, trails = live.states, live.outside, live.exit_lanes, live.trails
        slotting.book.held = live.held
        out = last.outputs.upto(last.counts[begin - 1])
        pieces = out.pieces
        after, digests, counts = last.after[:begin], last.digests[:begin], last.counts[:begin]
        ctx.engine.mark_reused(
            f"{kind}:{n}:{j}" for (n, j), skip in zip(order[:begin], skipped[:begin], strict=True) if not skip
        )
    for i, (name, k) in enumerate(order):
        if i < begin:
            continue
        if skipped[i]:
            if after:
                after.append(after[-1])
                digests.append(digests[-1])
            else:
                carried = Carried(states, outside, slotting.book.held, exit_lanes, trails).copy()
                after.append(carried)
                digests.append(carried.digest())
            counts.append(out.counts())
            continue
        node, sids = characters[name]
        action = node.actions[k]
        state = states[name]
        later = order[i + 1 : ends[i]]  # the actions of this sentence after this one
        company = [
            (states[o].x, states[o].z)
            for o, j in later
            if o != name and _same_goal(characters[o][0].actions[j], action)
        ]
        went = {  # others of this sentence who went there before it
            o
            for o, j in order[_sentence_start(ends, i) : i]
            if o != name and _same_goal(characters[o][0].actions[j], action)
        }
        joined = bool(went)  # it takes what they left nearest
        lane = None
        if door is not None and is_exit(action):  # "They leave": each its own lane through the door
            going = [
                (states[o].x, states[o].z)
                for o, j in later
                if o != name and is_exit(characters[o][0].actions[j])
            ]
            lanes = exit_lanes.setdefault(sids[k], [door.inside(beside=b) for b in range(len(going) + 1)])
            pick = matched([(state.x, state.z), *going], lanes) if going and lanes else 0
            lane = lanes.pop(pick or 0) if lanes else None  # ("gets out and leaves": one lane, two exits)
        asked, routes = _staged(scene, door, name, action, state, states, outside, lane)
        # those walking there with it are no bystanders: they stand side by side there on purpose ("They walk
        # to the statue": the second kept off the first's spot, 0.65 m beside it, stood in the row behind);
        # those who work there with it are ("Ben and Nora eat at the counter": their arms need the room)
        company_at = went if _walks(action) else set()
        crowd = [
            (st.x, st.z)
            for o, st in states.items()
            if o != name
            and o not in outside
            and o not in company_at
            and st.posture == "stand"
            and (st.x, st.z) not in company
        ]
        here_at = sentence_index.get(sids[k], 0)
        for o, (at, trail) in trails.items():  # the ways the others walk meanwhile are no place to stand
            if o != name and o not in company_at and at >= here_at - 1:
                crowd.extend(trail)
        claim = slotting.claim(name, asked[-1], (state.x, state.z), company, crowd, joined)
        asked[-1] = claim.action
        at = len(asked) - 1
        seats = {at: claim.seat} if claim.seat else {}
        spots = {at: claim.spot} if claim.spot is not None else {}
        if door is not None:
            if is_exit(action):
                outside.add(name)
            else:
                outside.discard(name)
        single = CharacterNode(name=name, actions=asked)
        view = _with_props(scene, _with_held(scene, scene_view(scene, action), state.holding), action)
        in_other_hands = {st.holding for other, st in states.items() if other != name and st.holding}
        if in_other_hands:  # one prop, one hand: what another character holds is not there to take
            view = msgspec.structs.replace(
                view, objects=[o for o in view.objects if o.id not in in_other_hands]
            )
        near_them = others(action, name, states, object_ids)
        near = {o: d for o, d in (distances or {}).get((name, k), {}).items() if o in near_them}
        seated = seated_others(action, name, states)
        standing = standing_others(action, name, states, outside) if not routes else []

        def run(
            single: CharacterNode = single,
            view: Scene = view,
            state: SegmentEndState = state,
            near_them: dict[str, tuple[float, float]] = near_them,
            near: dict[str, float] = near,
            routes: list[list[tuple[float, float]]] = routes,
            seats: dict[int, str] = seats,
            spots: dict[int, tuple[float, float]] = spots,
            seated: list[tuple[float, float]] = seated,
            standing: list[tuple[float, float]] = standing,
        ) -> SynthesizeReply:
            start = (state.x, state.z, state.yaw)
            return synthesise(
                ctx, single, view, state, start, near_them, near, routes, seats, spots, seated, standing
            )

        inputs = [single, view, state, near_them, near] if near else [single, view, state, near_them]
        if routes or seats or spots:
            inputs.append([routes, sorted(seats.items()), sorted(spots.items())])
        if seated:  # only a seat-taking action depends on where the others sit
            inputs.append(seated)
        if standing:  # only an action that may walk goes round the others standing
            inputs.append(["standing", standing])
        reply = ctx.engine.query(f"{kind}:{name}:{k}", inputs, run)
        placed = [
            msgspec.structs.replace(seg, action_index=k, sentence_id=sids[k]) for seg in reply.motion.segments
        ]
        pieces[name].append(msgspec.structs.replace(reply.motion, segments=placed))
        # (unknown actions the parse already reported)
        out.notes.extend((sids[k], d) for d in reply.diagnostics if not d.startswith("unknown action"))
        states[name] = reply.end_states[-1] if reply.end_states else state
        to = recipient(action, name, states)
        if to and states[name].holding == "" and reply.motion.props:
            # "gives the cup to Anna": let go of here, in Anna's hand from now on (services.motion.handover)
            given = reply.motion.props[-1].object_id
            states[to] = msgspec.structs.replace(states[to], holding=given)
            out.handovers.append(PairedAction(actor=name, action_index=k, action="present", partner=to))
        walked = from_wire(reply.motion.root_position)[::TRAIL_STEP, [0, 2]]
        if len(walked) > 1 and float(np.linalg.norm(walked[-1] - walked[0])) > TRAIL_MIN_M:
            trails[name] = (sentence_index.get(sids[k], 0), [(float(x), float(z)) for x, z in walked[:-1]])
        else:
            trails.pop(name, None)
        carried = Carried(states, outside, slotting.book.held, exit_lanes, trails).copy()
        after.append(carried)
        digests.append(carried.digest())
        counts.append(out.counts())
        if i + 1 >= tail and last is not None and last.digests[i] == digests[-1]:
            # early cutoff: the same state as the last pass's here, and the same steps after it
            rest = [
                f"{kind}:{n}:{j}"
                for (n, j), skip in zip(order[i + 1 :], skipped[i + 1 :], strict=True)
                if not skip
            ]
            ctx.engine.mark_reused(rest)
            out.extended(last.outputs, last.counts[i])
            after += last.after[i + 1 :]
            digests += last.digests[i + 1 :]
            counts += last.counts[i + 1 :]
            break
    ctx.engine.traces[kind] = PassTrace(context, keys, after, digests, counts, out)
    if notes is not None:
        notes.extend(out.notes)
    if handovers is not None:
        handovers.extend(out.handovers)
    pieces = {name: list(p) for name, p in out.pieces.items()}  # the trace keeps its own lists
    for name, (node, _) in characters.items():
        if not node.actions and upto is None:
            view = scene_view(scene, None)
            st = starts[name]

            def idle(
                name: str = name, view: Scene = view, st: tuple[float, float, float] = st
            ) -> SynthesizeReply:
                return synthesise(ctx, CharacterNode(name=name), view, None, st)

            pieces[name] = [ctx.engine.query(f"{kind}:{name}:idle", [name, view, st], idle).motion]
    return pieces


def _sentence_start(ends: Sequence[int], i: int) -> int:
    """Where the actions of action ``i``'s sentence begin in story order (``ends`` from `_sentence_ends`)."""
    while i > 0 and ends[i - 1] == ends[i]:
        i -= 1
    return i


def _sentence_ends(order: Sequence[tuple[str, int]], characters: Characters) -> list[int]:
    """For each place in ``order`` (story_order: a sentence's actions side by side), where its sentence's
    actions end: the actions of one sentence after an action are ``order[i + 1 : ends[i]]``, found without
    a pass over the rest of the story for every action."""
    ends = [len(order)] * len(order)
    for i in range(len(order) - 2, -1, -1):
        (a, k), (b, j) = order[i], order[i + 1]
        same = characters[a][1][k] == characters[b][1][j]
        ends[i] = ends[i + 1] if same else i + 1
    return ends


def _walks(action: ActionNode) -> bool:
    """Whether an action is a walk (a locomotion clip)."""
    try:
        return "locomotion" in get_clip(action.action or action.verb).tags
    except KeyError:
        return False


def _same_goal(a: ActionNode, b: ActionNode) -> bool:
    """Two actions of one sentence that go to the same object ("They sit at the table")."""
    goal_a = a.destination or a.target or a.instrument
    return bool(goal_a) and a.action == b.action and goal_a == (b.destination or b.target or b.instrument)


def _with_held(scene: Scene, view: Scene, holding: str) -> Scene:
    """The view with the object the character holds (it keeps holding it through actions that do not name it)."""
    if not holding or any(o.id == holding for o in view.objects):
        return view
    held = [o for o in scene.objects if o.id == holding]
    return msgspec.structs.replace(view, objects=[*view.objects, *held]) if held else view


def _taken_after(
    beats: Sequence[Beat], handovers: Sequence[PairedAction]
) -> dict[tuple[str, int], tuple[tuple[str, int], float]]:
    """(receiver, k) -> ((giver, j), 0): the receiver's next action after a hand-over starts once it is done
    ("Anna drinks the tea" with the cup John gave her), as timeline responses."""
    out = {}
    keys = [(b.character, b.k) for b in beats]
    for pair in handovers:
        given = (pair.actor, pair.action_index)
        if given not in keys:
            continue
        later = keys[keys.index(given) + 1 :]
        nxt = next((key for key in later if key[0] == pair.partner), None)
        if nxt is not None:
            out[nxt] = (given, 0.0)
    return out


def _partner_free(
    beats: Sequence[Beat], touches: Sequence[PairedAction]
) -> dict[tuple[str, int], tuple[tuple[str, int], float]]:
    """(actor, k) -> ((partner, j), 0): a touching action starts once the partner's action before it in the
    text is done, as timeline responses: Eve types, then Tom shakes her hand (not her hand taken off the keys
    mid-typing, duo-office-01 s6); Mr Van Loon sits down, then Eddie shakes his hand (not while he drops onto
    the chair, limitless-meeting_room-3 s7)."""
    out = {}
    keys = [(b.character, b.k) for b in beats]
    for pair in touches:
        mine = (pair.actor, pair.action_index)
        if not pair.partner or mine not in keys:
            continue
        before = [key for key in keys[: keys.index(mine)] if key[0] == pair.partner]
        if before:
            out[mine] = (before[-1], 0.0)
    return out


def hands_over(action: ActionNode) -> bool:
    """Whether an action hands an object to someone ("gives the cup to Anna", "hands him the book")."""
    verb = action.verb.lower()
    return action.action == "present" and any(verb == v or verb.startswith(v + " ") for v in HANDOVER_VERBS)


def recipient(action: ActionNode, name: str, states: dict[str, SegmentEndState]) -> str:
    """The character a hand-over action gives to ("" for any other action)."""
    if not (action.verb == HANDOVER_VERB or hands_over(action)):
        return ""
    return next((r for r in (action.target, action.destination) if r in states and r != name), "")


def _with_props(scene: Scene, view: Scene, action: ActionNode) -> Scene:
    """The view with the props a held action can use when it names none that is in the view ("drinks
    water": the cups on the table, with what they rest on), so that it walks up to one and takes it; when
    it names one, the others of its kind ("drinks from her mug" with two mugs on the table: the planner
    takes the one nearest her, services.motion.planning.prop_grip, so it must see both); a pour, the vessels
    like the one it pours into; an action at a surface naming nothing, the small things made for it ("Lucy
    eats": the plates, the planner eats at one in her reach when she sits)."""
    tools = made_for(scene, action.action) or worked_at(action, scene)
    ids = {t.id for t in tools}
    # the bottle in the hand after pouring does not hide the glasses ("They drink": from a glass)
    poured_from = POURED_FROM if action.action != "pour" else ()
    in_view = {o.category for o in view.objects if o.id in ids and o.category not in poured_from}
    if in_view:
        tools = [t for t in tools if t.category in in_view]
    into = find_object(scene, action.destination) if action.action == "pour" and action.destination else None
    if into is not None:  # "pours wine into the glasses": into the one nearest the pourer, so all of them
        tools += [o for o in scene.objects if o.category == into.category]
    if not tools:
        return view
    by_id = {o.id: o for o in scene.objects}
    wanted = {o.id for o in view.objects}
    for t in tools:
        ref = t.id
        while ref and ref in by_id and ref not in wanted:
            wanted.add(ref)
            ref = by_id[ref].support
    return msgspec.structs.replace(view, objects=[o for o in scene.objects if o.id in wanted])


def _staged(
    scene: Scene,
    door: Doorway | None,
    name: str,
    action: ActionNode,
    state: SegmentEndState,
    states: dict[str, SegmentEndState],
    hidden: set[str],
    lane: tuple[float, float] | None = None,
) -> tuple[list[ActionNode], list[list[tuple[float, float]]]]:
    """The actions sent to motion for one story action, and the routes their walks take.

    A character waiting at the door (shown from the threshold on) walks in to a free spot: an entrance
    does only that, any other action walks in to a spot near where it acts first. An exit walks to the
    door's threshold (``lane``: its own place there when several leave together; the character is gone once
    there). Walks go around the others on stage (``hidden``:
    who is off stage now).
    """
    waiting = name in hidden
    plain = msgspec.structs.replace(action, verb=HANDOVER_VERB if hands_over(action) else "")
    named = [r for r in (action.target, action.instrument, action.destination) if r and r not in states]
    if hands_over(action) and state.holding and not named and action.verb.lower().startswith(HANDS_WHAT_HELD):
        # "hands him the book": the parse keeps only him; what is handed is what is in the hand
        plain = msgspec.structs.replace(plain, instrument=state.holding)
    if door is None:
        return [plain], []
    here = (state.x, state.z)
    taken = [(st.x, st.z) for other, st in states.items() if other != name and other not in hidden]
    walk = msgspec.structs.replace(
        plain, action=action.action or "walk", target="", destination="", instrument=""
    )
    if is_exit(action):
        return [walk], [route(scene, here, lane or door.inside(), taken)]
    if not waiting:
        return [plain], []
    towards = states.get(action.target) or states.get(action.destination)
    if towards is not None and not is_entrance(action):
        goal = spot_near(scene, (towards.x, towards.z), taken)
    else:
        goal = spot_near(scene, door.way_in(here), taken, radii=(0.0, 0.6, 1.0, 1.5))
    way_in = [route(scene, here, (goal[0], goal[1]), taken)]
    if is_entrance(action):
        return [walk], way_in
    return [ActionNode(verb="", action="walk"), plain], way_in


def animate(
    ctx: StageContext,
    scene: Scene,
    graphs: Sequence[SentenceGraph],
    sentences: Sequence[Sentence],
    commands: Sequence[tuple[str, Command]],
    plan: SocialPlan | None,
    tick: Callable[[str, int, int], None],
) -> Animated:
    """Drafts on the composed layout, the layout optimised around each interaction, then the final motion."""
    scene, added = furnish(ctx, scene, graphs, sentences)  # a chair where a sit has no free seat
    scene = with_door(scene)  # furnishing composes the room again, without the door the scene stage added
    # props named only in action sentences, after furnishing (which composes the room again from the scene
    # sentences and so dropped what was added before it: the bag "put on the teacher's desk")
    there = {o.id for o in scene.objects}
    scene, provided = provide(scene, graphs, sentences, ctx.seed)
    characters = aimed(characters_of(graphs, [s.id for s in sentences]), scene)
    # an added bag the character puts down came in with them: in the hand from the first frame
    texts = {s.id: s.text for s in sentences}  # "his phone": his own, in the hand from the first frame
    characters, brought = carried(characters, scene, {o.id for o in scene.objects} - there, texts)
    scene, stools = seat_at_instruments(scene, characters, sentences)  # the stool to the drum kit's place
    added = [*provided, *brought_notes(characters, brought, scene, sentences), *stools, *added]
    looks, scene = scene, geometry_view(scene)  # the nodes below read shapes, not paint
    stated = scene_part(graphs).relations  # kept true through every optimisation
    # The story is played on the sentences' order alone (their ids): the text was read into the graphs, and
    # the offsets only place diagnostics on their sentence, put back after. So an edit elsewhere (a colour,
    # a word that shifts the text) re-plays nothing: the `motion` node's inputs are unchanged.
    order = [Sentence(id=s.id, start=0, end=1, text="") for s in sentences]
    social = ctx.engine.hash_of("social", plan) if plan is not None else ""
    waits = [(sid, c) for sid, c in commands if c.kind == "wait"]  # the only commands motion reads
    inputs = [scene, characters, brought, [s.id for s in sentences], waits, social, stated]

    def run() -> Animated:
        return _played(ctx, scene, characters, order, waits, plan, brought, stated, tick)

    played = ctx.engine.query_unhashed("motion", inputs, run)
    spans = {s.id: Span(s.start, s.end) for s in sentences}
    out = Animated(
        scene=with_looks(played.scene, looks),
        motions=played.motions,
        optimisations=played.optimisations,
        diagnostics=[*added, *(_on_sentence(sid, d, spans) for sid, d in played.diagnostics)],
    )
    out.scene = with_states(out.scene, characters, out.motions, sentences)  # doors opened, lamps on
    return out


def _on_sentence(sid: str, diagnostic: Diagnostic, spans: dict[str, Span]) -> tuple[str, Diagnostic]:
    """A diagnostic of the played story on its sentence as the text is now: every span `_played` gives is a
    whole sentence's (or Span(0, 0), no span, kept)."""
    if diagnostic.span.end <= diagnostic.span.start or sid not in spans:
        return sid, diagnostic
    return sid, msgspec.structs.replace(diagnostic, span=spans[sid])


def _played(
    ctx: StageContext,
    scene: Scene,
    characters: Characters,
    sentences: Sequence[Sentence],
    commands: Sequence[tuple[str, Command]],
    plan: SocialPlan | None,
    brought: dict[str, str],
    stated: Sequence[RelationNode],
    tick: Callable[[str, int, int], None],
) -> Animated:
    """The story played on the geometry of the furnished layout: drafts, the layout optimised around each
    interaction, every character's motion on one time line, fitted to each other and enlivened (the
    `motion` node: the paint, the states of objects and the diagnostics' spans are put on after).
    ``sentences``: their ids in order (spans and text are placeholders: nothing here may read them);
    ``commands``: the wait commands (the only ones motion reads)."""
    door = doorway(scene)
    wait_ids = {sid for sid, c in commands if c.kind == "wait"}
    answering = {r.responder for r in (plan.responses if plan is not None else []) if r.response_index == 0}
    touches = paired_actions(characters, plan)
    touch_sids = _touch_sentences(characters, sentences, touches)
    starts, hidden = _first_positions(scene, door, characters, sentences, wait_ids, answering, touch_sids)
    waiting_place = {name: i for i, name in enumerate(sorted(characters, key=lambda n: n not in hidden))}
    ids = {o.id for o in scene.objects}
    out = Animated(scene=scene, diagnostics=_door_added(scene, characters, sentences, hidden))
    # Interactions: actions that touch an object of the scene; the layout is optimised around each.
    interactions = [
        (name, k, a)
        for name, (node, _) in characters.items()
        for k, a in enumerate(node.actions)
        if a.action and (a.target in ids or a.instrument in ids)
    ]
    done, total = 0, len(interactions) + len(characters)
    last = {name: max([k for n, k, _ in interactions if n == name], default=-1) for name in characters}
    near = social_distances(plan)
    moods = social_moods(plan, characters)
    drafts = segments(
        ctx,
        "draft",
        characters,
        sentences,
        scene,
        starts,
        upto=last,
        distances=near,
        door=door,
        hidden=hidden,
        holding=brought,
    )
    for name, k, action in interactions:
        tick("optimise", done, total)
        draft = drafts[name][k]

        def run(
            scene: Scene = scene, draft: Motion = draft, name: str = name, action: ActionNode = action
        ) -> OptimiseReply:
            return optimise(ctx, scene, draft, name, action)

        try:
            reply = ctx.engine.query(f"optimise:{name}:{k}", [scene, draft, action], run)
        except StageFailed as exc:
            why = f"the layout around this action could not be optimised: {exc}"
            warning = Diagnostic(code="W301", message=why, span=Span(0, 0), severity="warning")
            out.diagnostics.append((characters[name][1][k], warning))
            continue
        scene = kept_relations(scene, reply.scene, stated)
        out.optimisations.append(reply)
        done += 1
    out.scene = scene
    starts = kept_clear(scene, starts, sorted(hidden))  # furniture the optimiser slid onto a starting spot
    tick("motion", done, total)
    notes: list[tuple[str, str]] = []
    handovers: list[PairedAction] = []

    def final(scene: Scene) -> dict[str, list[Motion]]:
        notes.clear()
        handovers.clear()
        return segments(
            ctx,
            "segment",
            characters,
            sentences,
            scene,
            starts,
            distances=near,
            door=door,
            hidden=hidden,
            notes=notes,
            handovers=handovers,
            holding=brought,
        )

    pieces = final(scene)
    # a prop out of reach of where its user sits is put in front of that place (stages/reach.py), and the
    # story played again on that room: the seats are the ones this pass took, known only now
    scene, moved = within_reach(
        scene, characters, *_before_each(ctx, characters, sentences, starts, brought), stated
    )
    if moved:
        out.scene = scene
        pieces = final(scene)
    spans = {s.id: Span(s.start, s.end) for s in sentences}
    for sid, why in moved:
        note = Diagnostic(code="I202", message=why, span=spans.get(sid, Span(0, 0)), severity="info")
        out.diagnostics.append((sid, note))
    for sid, why in dict.fromkeys(notes):
        span = spans.get(sid, Span(0, 0))
        if "instead" in why:  # something the sentence asks could not be done
            note = Diagnostic(code="W302", message=why, span=span, severity="warning")
        else:
            note = Diagnostic(code="I301", message=why, span=span, severity="info")
        out.diagnostics.append((sid, note))
    tick("motion", total, total)
    # Story timing: sentence order sets when actions start; gaps hold the pose.
    beats = [
        Beat(characters[name][1][k], name, k, frame_count(pieces[name][k]))
        for name, k in story_order(characters, sentences)
    ]
    waits = {sid: c.seconds for sid, c in commands if c.kind == "wait"}
    responses = {
        (r.responder, r.response_index): ((r.actor, r.action_index), r.delay_s)
        for r in (plan.responses if plan is not None else [])
        if r.response_index >= 0
    }
    responses.update(_taken_after(beats, handovers))
    for key, answered in _partner_free(beats, touches).items():
        responses.setdefault(key, answered)
    start_frames = schedule(beats, waits, [s.id for s in sentences], responses)
    length = max([start_frames[(b.character, b.k)] + b.frames for b in beats] or [1])
    for name, (node, _) in characters.items():
        firsts = [start_frames[(name, k)] for k in range(len(node.actions))] or [0]
        motion = assemble(name, pieces[name], firsts, total=length)
        lengths = [frame_count(p) for p in pieces[name]] if node.actions else []
        on = presence(length, firsts if node.actions else [], lengths, node.actions, name not in hidden)
        motion = msgspec.structs.replace(motion, present=to_wire(on))
        if door is not None and not on.all():
            motion = _wait_outside(motion, on, door.outside(waiting_place[name]))
        out.motions[name] = motion
    fitted = fit_cast(ctx, out.motions, [*touches, *handovers], out.scene)  # give way, touch on both bodies
    touching: dict[str, list[tuple[int, int]]] = {}  # name -> frames its hands were solved onto another
    if fitted is not None:
        out.motions = dict(fitted.motions)
        for c in fitted.contacts:
            for who in (c.actor, c.partner):
                touching.setdefault(who, []).append((c.start_frame, c.end_frame))
    out.motions = set_down_props(out.scene, out.motions, length)
    out.motions = _enlivened(out.scene, characters, _in_moods(characters, out.motions, moods), touching)
    return out


def _before_each(
    ctx: StageContext,
    characters: Characters,
    sentences: Sequence[Sentence],
    starts: dict[str, tuple[float, float, float]],
    holding: dict[str, str],
) -> tuple[list[tuple[str, int]], list[dict[str, SegmentEndState]]]:
    """Every action in story order and every character's state as it starts, from the checkpoints of the
    last `segment` pass (stages/replay.py)."""
    order = story_order(characters, sentences)
    trace: PassTrace | None = ctx.engine.traces.get("segment")
    first = {
        name: SegmentEndState(x=st[0], z=st[1], yaw=st[2], holding=holding.get(name, ""))
        for name, st in starts.items()
    }
    if trace is None or len(trace.after) != len(order):
        return [], []
    return order, [first, *(c.states for c in trace.after[:-1])][: len(order)]


def _door_added(
    scene: Scene, characters: Characters, sentences: Sequence[Sentence], hidden: set[str]
) -> list[tuple[str, Diagnostic]]:
    """An info diagnostic on the first sentence that comes in or goes out through a door the text did not
    name (staging.with_door added it): the user sees where the door came from."""
    doors = [o for o in scene.objects if o.category == "door"]
    if len(doors) != 1 or doors[0].from_text or doors[0].id.startswith("ctx_"):  # named, or composed
        return []
    spans = {s.id: s for s in sentences}
    order = {s.id: i for i, s in enumerate(sentences)}
    through = [
        (order.get(sid, 0), sid, name)
        for name, (node, sids) in characters.items()
        for k, (action, sid) in enumerate(zip(node.actions, sids, strict=True))
        if is_entrance(action) or is_exit(action) or (k == 0 and name in hidden)
    ]
    if not through:
        return []
    _, sid, name = min(through)
    s = spans.get(sid)
    message = f"added a door: the room had none for {name} to come in or go out"
    span = Span(s.start, s.end) if s is not None else Span(0, 0)
    return [(sid, Diagnostic(code="I202", message=message, span=span, severity="info"))]


def _in_moods(
    characters: Characters, motions: dict[str, Motion], moods: dict[tuple[str, int], tuple[float, float]]
) -> dict[str, Motion]:
    """Every motion played in the social plan's emotions (wana.domain.style), except for actions whose manner
    word already set their mood (the motion service played those)."""
    out = {}
    for name, motion in motions.items():
        actions = characters[name][0].actions if name in characters else []
        mine = {k: m for (n, k), m in moods.items() if n == name and actions[k].manner not in MANNER_MOOD}
        out[name] = restyle_motion(motion, mine)
    return out


def _enlivened(
    scene: Scene,
    characters: Characters,
    motions: dict[str, Motion],
    touching: dict[str, list[tuple[int, int]]] | None = None,
) -> dict[str, Motion]:
    """Every motion with the idle layer (wana.domain.idle): breathing, weight shifts and a gaze at whoever
    acts, or at what the character's next action uses, wherever the time line holds a pose; not over the
    frames where ``touching`` says its hands were solved onto another character (the cast fit's contacts)."""
    out = {}
    for name, motion in motions.items():
        upcoming: dict[int, tuple[float, float, float] | str] = {}
        for k, action in enumerate(characters[name][0].actions if name in characters else []):
            goal = action.target or action.instrument or action.destination
            placed = find_object(scene, goal) if goal else None
            if placed is not None:
                upcoming[k] = (placed.position[0], max(placed.position[1], 0.5), placed.position[2])
            elif goal in motions:
                upcoming[k] = goal
        out[name] = enliven_motion(
            motion, attention(name, motions, upcoming), touching=(touching or {}).get(name, ())
        )
    return out


REST_M = 0.02  # metres: a prop released farther than this from its place in the room stays where it was put


def set_down_props(scene: Scene, motions: dict[str, Motion], length: int) -> dict[str, Motion]:
    """Each motion with a still track for every prop it set down away from its place in the room: from the
    release until someone takes it again (or the story's end), it stays where it was put."""
    homes = {o.id: np.asarray(o.position, float) for o in scene.objects}
    tracks = sorted(
        ((t.start_frame, t.end_frame, name, t) for name, m in motions.items() for t in m.props),
        key=lambda x: (x[3].object_id, x[0]),
    )
    extra: dict[str, list] = {}
    for i, (_, end, name, t) in enumerate(tracks):
        later = [s for s, _, _, u in tracks[i + 1 :] if u.object_id == t.object_id and s >= end]
        if any(s < end and e > end for s, e, _, u in tracks if u.object_id == t.object_id):
            continue  # held on (the next piece's track starts where this one ends)
        until = min(later, default=length)
        pos, rot = from_wire(t.position), from_wire(t.rotation)
        home = homes.get(t.object_id)
        if until <= end or not len(pos) or home is None or np.linalg.norm(pos[-1] - home) <= REST_M:
            continue
        extra.setdefault(name, []).append(
            msgspec.structs.replace(
                t,
                start_frame=end,
                end_frame=until,
                position=to_wire(np.repeat(pos[-1:], until - end, 0).astype(np.float32)),
                rotation=to_wire(np.repeat(rot[-1:], until - end, 0).astype(np.float32)),
            )
        )
    return {
        name: msgspec.structs.replace(m, props=[*m.props, *extra[name]]) if name in extra else m
        for name, m in motions.items()
    }


def _wait_outside(motion: Motion, on: np.ndarray, spot: tuple[float, float]) -> Motion:
    """The motion with its off-stage frames (on == 0) moved to the character's place outside the door."""
    root = from_wire(motion.root_position).copy()
    root[on == 0, 0], root[on == 0, 2] = spot
    return msgspec.structs.replace(motion, root_position=to_wire(root.astype(np.float32)))


def _touch_sentences(
    characters: Characters, sentences: Sequence[Sentence], touches: Sequence[PairedAction]
) -> set[str]:
    """Sentences with a touching action that waits for its partner's action in an earlier sentence (as
    ``_partner_free`` times it): the sentence starts when that action ends, not with the one before it."""
    order = {s.id: i for i, s in enumerate(sentences)}
    out: set[str] = set()
    for pair in touches:
        if not pair.partner or pair.actor not in characters or pair.partner not in characters:
            continue
        sids = characters[pair.actor][1]
        if pair.action_index >= len(sids):
            continue
        mine = order.get(sids[pair.action_index], -1)
        if any(order.get(sid, mine) < mine for sid in characters[pair.partner][1]):
            out.add(sids[pair.action_index])
    return out


def _late_comers(
    characters: Characters,
    sentences: Sequence[Sentence],
    waits: set[str],
    answering: set[str],
    answered: set[str] | None = None,
) -> tuple[set[str], dict[str, str]]:
    """The characters whose first sentence starts after frame 0 (timeline.schedule's rule, before timing), and
    per sentence the sentence it starts together with (the last one that had to start later).

    A sentence starts with the one before it unless one of its characters is still busy with an earlier
    action, its first action answers another's (the social plan's response delay: ``answering``) or a
    `wait` holds it, or a touch in it waits for the partner's earlier action (``answered``: sentence ids); from
    the first sentence that starts later, every later one does too.
    """
    answered = answered or set()
    group: dict[str, set[str]] = {}
    for name, (_, sids) in characters.items():
        for sid in sids:
            group.setdefault(sid, set()).add(name)
    seen: set[str] = set()
    late: set[str] = set()
    delayed = False
    together: dict[str, str] = {}
    current = ""
    for s in sentences:
        names = group.get(s.id, set())
        if (s.id in waits and seen) or names & seen or (names & answering and seen) or s.id in answered:
            delayed = True
            current = s.id
        if delayed:
            late |= names - seen
        together[s.id] = current
        seen |= names
    return late, together


def _first_positions(
    scene: Scene,
    door: Doorway | None,
    characters: Characters,
    sentences: Sequence[Sentence],
    waits: set[str] | None = None,
    answering: set[str] | None = None,
    answered: set[str] | None = None,
) -> tuple[dict[str, tuple[float, float, float]], set[str]]:
    """Where each character is at frame 0, and who waits outside the door until their first sentence.

    Characters on stage from frame 0 start at free spots near what they first act on; an entrance and every
    character whose first sentence starts later wait at the door (hidden until their first sentence), those
    who come in at the same time side by side on its threshold.
    """
    late, together_with = _late_comers(characters, sentences, waits or set(), answering or set(), answered)
    starts: dict[str, tuple[float, float, float]] = {}
    hidden: set[str] = set()
    taken: list[tuple[float, float]] = []
    together: dict[str, int] = {}  # sentence id -> characters coming in with it so far
    for name, (node, sids) in characters.items():
        first = node.actions[0] if node.actions else None
        if door is not None and first is not None and (name in late or is_entrance(first)):
            # "": with the story's first frame; else the first sentence of those starting at the same time
            when = together_with.get(sids[0], sids[0]) if name in late else ""
            beside = together.get(when, 0)
            together[when] = beside + 1
            starts[name] = (*door.inside(beside=beside), door.yaw_in)
            hidden.add(name)
            continue
        spot = first_spot(scene, first, taken)
        taken.append((spot[0], spot[1]))
        starts[name] = spot
    return starts, hidden
