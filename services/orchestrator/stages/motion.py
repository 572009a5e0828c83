"""The motion stage: drafts, the layout optimised around each interaction, then every character's motion.

Nodes: `draft:<name>:<k>` (action k on the composed layout, what the optimiser starts from),
`optimise:<name>:<k>` (the layout around an action that touches an object), `segment:<name>:<k>` (action
k on the final layout from the end state of action k-1), `<kind>:<name>:idle` for a character with no
action. Story timing (services/orchestrator/timeline.py) then places the segments on one time line.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import msgspec

from proto.common import Span
from proto.motion import SegmentEndState, SynthesizeReply, SynthesizeRequest
from proto.motion_data import Motion
from proto.optimizer import Interaction, OptimiseReply, OptimiseRequest, OptimiseSettings
from proto.scene import Scene
from proto.social import SocialPlan
from proto.ssg import ActionNode, CharacterNode, Command, Diagnostic, SentenceGraph
from services.orchestrator.backend import StageFailed
from services.orchestrator.document import Sentence
from services.orchestrator.stages import StageContext, content_of
from services.orchestrator.stages.seats import furnish
from services.orchestrator.stages.social import frame_count
from services.orchestrator.timeline import Beat, assemble, schedule
from services.orchestrator.views import characters_of, others, scene_view, social_distances, start_positions
from wana.domain.actions import get_clip

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
    occupied: list[tuple[float, float]] | None = None,
) -> SynthesizeReply:
    request = SynthesizeRequest(
        header=ctx.header(),
        character=character,
        scene=scene,
        start=start,
        start_state=state,
        others=others or {},
        distances=distances or {},
        occupied=occupied or [],
    )
    return content_of(ctx.backend.call(request))


def seated_others(
    action: ActionNode, name: str, states: dict[str, SegmentEndState]
) -> list[tuple[float, float]]:
    """Where the other characters sit by the time a sit / lie action starts (their seat slots are taken);
    [] for any other action, so that its recompute does not depend on them."""
    try:
        clip = get_clip(action.action) if action.action else None
    except KeyError:
        clip = None
    if clip is None or clip.interaction is None or clip.interaction.object not in ("seat", "bed"):
        return []
    return sorted(
        (round(st.x, 3), round(st.z, 3)) for c, st in states.items() if c != name and st.posture != "stand"
    )


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


def segments(
    ctx: StageContext,
    kind: str,
    characters: Characters,
    sentences: Sequence[Sentence],
    scene: Scene,
    starts: dict[str, tuple[float, float, float]],
    upto: dict[str, int] | None = None,
    distances: Distances | None = None,
    notes: list[tuple[str, str]] | None = None,
) -> dict[str, list[Motion]]:
    """Every character's motion, one query node `<kind>:<name>:<k>` per action, in document order.

    Action k starts from the end state of action k-1 and sees only what it can touch: the objects on the
    floor (which routes go around), the objects it names with what they rest on, and where a character it
    names stands by then. So an edit that leaves an end state unchanged stops there (early cutoff), and
    moving a lamp on a desk re-runs only the actions that use the lamp. ``distances``: (name, k) -> how
    far action k stops from the characters it walks up to (the social plan's, views.social_distances).
    ``notes`` collects (sentence id, what the motion service said) ("no free seat ...: Zoe stands instead").
    """
    states = {name: SegmentEndState(x=st[0], z=st[1], yaw=st[2]) for name, st in starts.items()}
    pieces: dict[str, list[Motion]] = {name: [] for name in characters}
    object_ids = {o.id for o in scene.objects}
    order = [
        (name, k)
        for s in sentences
        for name, (_, sids) in characters.items()
        for k, sid in enumerate(sids)
        if sid == s.id
    ]
    for name, k in order:
        if upto is not None and k > upto.get(name, -1):
            continue
        node, sids = characters[name]
        action = node.actions[k]
        single = CharacterNode(name=name, actions=[msgspec.structs.replace(action, verb="")])
        view = scene_view(scene, action)
        near_them = others(action, name, states, object_ids)
        near = {o: d for o, d in (distances or {}).get((name, k), {}).items() if o in near_them}
        state = states[name]
        seated = seated_others(action, name, states)

        def run(
            single: CharacterNode = single,
            view: Scene = view,
            state: SegmentEndState = state,
            near_them: dict[str, tuple[float, float]] = near_them,
            near: dict[str, float] = near,
            seated: list[tuple[float, float]] = seated,
        ) -> SynthesizeReply:
            return synthesise(
                ctx, single, view, state, (state.x, state.z, state.yaw), near_them, near, seated
            )

        inputs = [single, view, state, near_them, near] if near else [single, view, state, near_them]
        if seated:  # only a seat-taking action depends on where the others sit
            inputs.append(seated)
        reply = ctx.engine.query(f"{kind}:{name}:{k}", inputs, run)
        placed = [
            msgspec.structs.replace(seg, action_index=k, sentence_id=sids[k]) for seg in reply.motion.segments
        ]
        pieces[name].append(msgspec.structs.replace(reply.motion, segments=placed))
        if notes is not None:
            # (unknown actions the parse already reported)
            notes.extend((sids[k], d) for d in reply.diagnostics if not d.startswith("unknown action"))
        states[name] = reply.end_states[-1] if reply.end_states else state
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
    characters = characters_of(graphs, [s.id for s in sentences])
    scene, added = furnish(ctx, scene, graphs, sentences)  # a chair where a sit has no free seat
    starts = start_positions(scene, list(characters))
    ids = {o.id for o in scene.objects}
    out = Animated(scene=scene, diagnostics=list(added))
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
    drafts = segments(ctx, "draft", characters, sentences, scene, starts, upto=last, distances=near)
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
        scene = reply.scene
        out.optimisations.append(reply)
        done += 1
    out.scene = scene
    tick("motion", done, total)
    notes: list[tuple[str, str]] = []
    pieces = segments(ctx, "segment", characters, sentences, scene, starts, distances=near, notes=notes)
    spans = {s.id: Span(s.start, s.end) for s in sentences}
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
        Beat(sid, name, k, frame_count(pieces[name][k]))
        for s in sentences
        for name, (node, sids) in characters.items()
        for k, sid in enumerate(sids)
        if sid == s.id
    ]
    waits = {sid: c.seconds for sid, c in commands if c.kind == "wait"}
    responses = {
        (r.responder, r.response_index): ((r.actor, r.action_index), r.delay_s)
        for r in (plan.responses if plan is not None else [])
        if r.response_index >= 0
    }
    start_frames = schedule(beats, waits, [s.id for s in sentences], responses)
    length = max([start_frames[(b.character, b.k)] + b.frames for b in beats] or [1])
    for name, (node, _) in characters.items():
        firsts = [start_frames[(name, k)] for k in range(len(node.actions))] or [0]
        out.motions[name] = assemble(name, pieces[name], firsts, total=length)
    return out
