"""The incremental pipeline over one document: parse -> resolve -> scene -> optimise -> motion.

Query nodes (DESIGN §3), each keyed by the content hash of its inputs:
- `parse:<sentence id>`   the sentence's whitespace-normalised text  -> its SSG fragment (sentence offsets)
- `resolve`               the parse results in order                 -> names and pronouns resolved
- `scene`                 every scene sentence's objects + relations -> the composed room
- `draft:<name>:<k>`      actions, layout before optimising action k -> the motion the optimiser starts from
- `optimise:<name>:<k>`   layout, draft motion, action k             -> layout (+ motion) around action k
- `segment:<name>:<k>`    action k, the final layout, end state k-1  -> frames of action k + its end state
- `social`                characters, actions and social nodes       -> faces, distances, response timing
- `face:<name>`           the social plan, every character's timing  -> the character's face track
A stage whose service is not in this build is reported in `unavailable`; nothing is faked.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import partial
from typing import Any

import msgspec
import numpy as np

from proto.common import ErrorCode, Header, Span
from proto.motion_data import Motion
from proto.scene import Room, Scene
from proto.ssg import ActionNode, CharacterNode, Command, Diagnostic, ObjectNode, RelationNode, SentenceGraph
from services.orchestrator.backend import Backend, StageFailed, StageUnavailable
from services.orchestrator.document import Document
from services.orchestrator.queries import QueryEngine, content_hash
from services.orchestrator.timeline import Beat, assemble, schedule
from wana.arrays import from_wire, to_wire

STAGES = ("parse", "scene", "motion")


@dataclass(frozen=True)
class SentenceView:
    id: str
    start: int
    end: int
    text: str
    kind: str


@dataclass
class PipelineResult:
    doc_id: str
    version: int
    sentences: list[SentenceView] = field(default_factory=list)
    graphs: dict[str, SentenceGraph] = field(default_factory=dict)  # resolved, sentence-relative spans
    diagnostics: dict[str, list[Diagnostic]] = field(default_factory=dict)  # sentence id -> doc offsets
    scene: Scene | None = None
    scene_report: Any = None
    motions: dict[str, Motion] = field(default_factory=dict)
    commands: list[tuple[str, Command]] = field(default_factory=list)  # (sentence id, command)
    ran: list[str] = field(default_factory=list)
    reused: list[str] = field(default_factory=list)
    unavailable: dict[str, str] = field(default_factory=dict)  # stage -> why
    optimisations: list[Any] = field(default_factory=list)  # OptimiseReply per optimised interaction


def _messages(service: str, module: str, *names: str) -> list[Any]:
    """Import a service's message types; a missing module means the stage is not in this build."""
    try:
        mod = __import__(f"proto.{module}", fromlist=list(names))
        return [getattr(mod, n) for n in names]
    except (ImportError, AttributeError) as exc:
        raise StageUnavailable(service, str(exc)) from exc


def _shift(span: Span, by: int) -> Span:
    return Span(span.start + by, span.end + by)


def _stage_diag(stage: str, why: str, span: Span) -> Diagnostic:
    return Diagnostic(
        code=ErrorCode.UNAVAILABLE,
        message=f"the {stage} stage is not available yet: {why}",
        span=span,
        severity="info",
    )


class Pipeline:
    def __init__(self, backend: Backend, *, doc_id: str = "", seed: int = 0) -> None:
        self.backend = backend
        self.doc_id = doc_id
        self.seed = seed

    def _header(self, version: int) -> Header:
        return Header(doc_id=self.doc_id, revision=version)

    # -- stages --------------------------------------------------------------------------------------
    def _parse(self, sid: str, text: str, version: int) -> SentenceGraph:
        ParseRequest, ParseReply = _messages("nlp", "nlp", "ParseRequest", "ParseReply")

        reply = self.backend.call(
            "nlp",
            ParseRequest(header=self._header(version), sentence_id=sid, text=text, offset=0),
            ParseReply,
        )
        return reply.graph  # type: ignore[no-any-return]

    def _resolve(self, graphs: list[SentenceGraph], version: int) -> list[SentenceGraph]:
        ResolveRequest, ResolveReply = _messages("nlp", "nlp", "ResolveRequest", "ResolveReply")

        reply = self.backend.call(
            "nlp", ResolveRequest(header=self._header(version), graphs=graphs), ResolveReply
        )
        return list(reply.graphs)

    def _compose(self, part: dict[str, Any], version: int) -> tuple[Scene, Any]:
        if not part["objects"]:  # nothing to retrieve: an empty room for the characters
            return Scene(
                room=Room(room_type=part["room_type"] or "room", width=5.0, depth=5.0, height=2.8),
                seed=self.seed,
            ), None
        ComposeRequest, ComposeReply = _messages("retrieval", "retrieval", "ComposeRequest", "ComposeReply")

        reply = self.backend.call(
            "retrieval",
            ComposeRequest(
                header=self._header(version),
                objects=part["objects"],
                relations=part["relations"],
                room_type=part["room_type"],
                seed=self.seed,
            ),
            ComposeReply,
        )
        return reply.scene, reply

    def _synthesise(
        self,
        character: CharacterNode,
        scene: Scene,
        start: tuple[float, float, float],
        version: int,
        start_state: Any = None,
        others: dict[str, tuple[float, float]] | None = None,
        distances: dict[str, float] | None = None,
    ) -> Any:
        SynthesizeRequest, SynthesizeReply = _messages(
            "motion", "motion", "SynthesizeRequest", "SynthesizeReply"
        )
        return self.backend.call(
            "motion",
            SynthesizeRequest(
                header=self._header(version),
                character=character,
                scene=scene,
                start=start,
                start_state=start_state,
                others=others or {},
                distances=distances or {},
            ),
            SynthesizeReply,
        )

    def _optimise(
        self, scene: Scene, motion: Motion, character: str, action: ActionNode, version: int
    ) -> Any:
        OptimiseRequest, OptimiseReply, Interaction, OptimiseSettings = _messages(
            "optimizer", "optimizer", "OptimiseRequest", "OptimiseReply", "Interaction", "OptimiseSettings"
        )
        targets = [t for t in (action.target, action.instrument) if t]
        return self.backend.call(
            "optimizer",
            OptimiseRequest(
                header=self._header(version),
                scene=scene,
                motion=motion,
                interaction=Interaction(character=character, action=action.action, targets=targets),
                settings=OptimiseSettings(seed=self.seed),
            ),
            OptimiseReply,
        )

    def _motion_stage(
        self,
        result: PipelineResult,
        resolved: list[SentenceGraph],
        sentences: list[Any],
        engine: QueryEngine,
        version: int,
        tick: Callable[[str, int, int], None],
    ) -> None:
        """Drafts on the composed layout, the layout optimised around each interaction, then the final motion."""
        assert result.scene is not None
        characters = _characters(resolved, sentences)
        starts = _start_positions(result.scene, list(characters))
        scene = result.scene
        ids = {o.id for o in scene.objects}
        # Interactions: actions that touch an object of the scene; the layout is optimised around each.
        interactions = [
            (name, k, a)
            for name, (node, _) in characters.items()
            for k, a in enumerate(node.actions)
            if a.action and (a.target in ids or a.instrument in ids)
        ]
        done, total = 0, len(interactions) + len(characters)
        last = {name: max([k for n, k, _ in interactions if n == name], default=-1) for name in characters}
        plan = self._social_plan(result, resolved, engine, version)
        near = _social_distances(plan)
        drafts = self._segments(
            "draft", characters, sentences, scene, starts, engine, version, upto=last, distances=near
        )
        for name, k, action in interactions:
            tick("optimise", done, total)
            draft = drafts[name][k]
            try:
                reply = engine.query(
                    f"optimise:{name}:{k}",
                    [scene, draft, action],
                    partial(self._optimise, scene, draft, name, action, version),
                )
            except StageFailed as exc:
                result.diagnostics.setdefault(characters[name][1][k], []).append(
                    Diagnostic(
                        code="W301",
                        message=f"the layout around this action could not be optimised: {exc}",
                        span=Span(0, 0),
                        severity="warning",
                    )
                )
                continue
            scene = reply.scene
            result.optimisations.append(reply)
            done += 1
        result.scene = scene
        tick("motion", done, total)
        pieces = self._segments(
            "segment", characters, sentences, scene, starts, engine, version, distances=near
        )
        tick("motion", total, total)
        # Story timing: sentence order sets when actions start; gaps hold the pose.
        beats = [
            Beat(sid, name, k, _frames(pieces[name][k]))
            for s in sentences
            for name, (node, sids) in characters.items()
            for k, sid in enumerate(sids)
            if sid == s.id
        ]
        waits = {sid: c.seconds for sid, c in result.commands if c.kind == "wait"}
        responses = {
            (r.responder, r.response_index): ((r.actor, r.action_index), r.delay_s)
            for r in (plan.responses if plan is not None else [])
            if r.response_index >= 0
        }
        start_frames = schedule(beats, waits, [s.id for s in sentences], responses)
        length = max([start_frames[(b.character, b.k)] + b.frames for b in beats] or [1])
        for name, (node, _) in characters.items():
            firsts = [start_frames[(name, k)] for k in range(len(node.actions))] or [0]
            result.motions[name] = assemble(name, pieces[name], firsts, total=length)
        if plan is not None:
            try:
                self._faces(result, plan, engine, version)
            except (StageUnavailable, StageFailed) as exc:
                result.unavailable["social"] = str(exc)

    def _social_plan(
        self, result: PipelineResult, graphs: list[SentenceGraph], engine: QueryEngine, version: int
    ) -> Any:
        """The story's social plan (faces, response timing, distances), or None when unavailable."""
        try:
            SocialPlanRequest, SocialPlanReply = _messages(
                "social", "social", "SocialPlanRequest", "SocialPlanReply"
            )
            header = self._header(version)
            return engine.query(
                "social",
                _social_part(graphs),
                lambda: (
                    self.backend.call(
                        "social",
                        SocialPlanRequest(header=header, graphs=graphs, seed=self.seed),
                        SocialPlanReply,
                    ).plan
                ),
            )
        except (StageUnavailable, StageFailed) as exc:
            result.unavailable["social"] = str(exc)
            return None

    def _faces(self, result: PipelineResult, plan: Any, engine: QueryEngine, version: int) -> None:
        """Each character's face track (Motion.expression) from the social plan."""
        ExpressionTrackRequest, ExpressionTrackReply = _messages(
            "social", "social", "ExpressionTrackRequest", "ExpressionTrackReply"
        )
        header = self._header(version)
        if not plan.characters:
            return
        # A face depends on the character's part of the plan and on when its own actions and the actions
        # it reacts to happen; holds and the story's length do not matter (the face holds after its last
        # key), so the track is computed to a length of its own and held or cut to the motion's.
        acting = {
            name: [seg for seg in motion.segments if seg.action_index >= 0]
            for name, motion in result.motions.items()
        }
        for entry in plan.characters:
            motion = result.motions.get(entry.name)
            if motion is None:
                continue
            anchors = sorted({k.anchor_character for k in entry.keys} - {entry.name})
            others = {n: acting[n] for n in anchors if n in acting}
            ends = [seg.end_frame for segs in (acting[entry.name], *others.values()) for seg in segs]
            lag = max([k.at_s for k in entry.keys], default=0.0)
            frames = max(ends, default=0) + int(lag * motion.fps) + 2
            track = engine.query(
                f"face:{entry.name}",
                [plan.expression_names, entry, acting[entry.name], others, frames],
                partial(
                    self.backend.call,
                    "social",
                    ExpressionTrackRequest(
                        header=header,
                        plan=plan,
                        character=entry.name,
                        segments=acting[entry.name],
                        frames=frames,
                        fps=motion.fps,
                        others=others,
                    ),
                    ExpressionTrackReply,
                ),
            )
            face = _fit_frames(from_wire(track.expression), _frames(motion))
            result.motions[entry.name] = msgspec.structs.replace(motion, expression=to_wire(face))

    def _segments(
        self,
        kind: str,
        characters: dict[str, tuple[CharacterNode, list[str]]],
        sentences: list[Any],
        scene: Scene,
        starts: dict[str, tuple[float, float, float]],
        engine: QueryEngine,
        version: int,
        upto: dict[str, int] | None = None,
        distances: dict[tuple[str, int], dict[str, float]] | None = None,
    ) -> dict[str, list[Motion]]:
        """Every character's motion, one query node `<kind>:<name>:<k>` per action, in document order.

        Action k starts from the end state of action k-1 and sees only what it can touch: the objects on the
        floor (which routes go around), the objects it names with what they rest on, and where a character it
        names stands by then. So an edit that leaves an end state unchanged stops there (early cutoff), and
        moving a lamp on a desk re-runs only the actions that use the lamp. ``distances``: (name, k) -> how
        far action k stops from the characters it walks up to (the social plan's, see _social_distances).
        """
        (SegmentEndState,) = _messages("motion", "motion", "SegmentEndState")
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
            view = _scene_view(scene, action)
            others = _others(action, name, states, object_ids)
            near = {o: d for o, d in (distances or {}).get((name, k), {}).items() if o in others}
            state = states[name]
            reply = engine.query(
                f"{kind}:{name}:{k}",
                [single, view, state, others, near] if near else [single, view, state, others],
                partial(
                    self._synthesise,
                    single,
                    view,
                    (state.x, state.z, state.yaw),
                    version,
                    state,
                    others,
                    near,
                ),
            )
            segments = [
                msgspec.structs.replace(seg, action_index=k, sentence_id=sids[k])
                for seg in reply.motion.segments
            ]
            pieces[name].append(msgspec.structs.replace(reply.motion, segments=segments))
            states[name] = reply.end_states[-1] if reply.end_states else state
        for name, (node, _) in characters.items():
            if not node.actions and upto is None:
                view = _scene_view(scene, None)
                st = starts[name]
                idle = engine.query(
                    f"{kind}:{name}:idle",
                    [name, view, st],
                    partial(self._synthesise, CharacterNode(name=name), view, st, version),
                )
                pieces[name] = [idle.motion]
        return pieces

    # -- the run -------------------------------------------------------------------------------------
    def run(
        self,
        doc: Document,
        engine: QueryEngine,
        *,
        stages: tuple[str, ...] | None = None,
        progress: Callable[[str, int, int], None] | None = None,
    ) -> PipelineResult:
        stages = stages or STAGES
        result = PipelineResult(doc_id=doc.doc_id, version=doc.version)
        tick = progress or (lambda stage, done, total: None)
        sentences = list(doc.sentences)

        # parse, one node per sentence
        parsed: dict[str, SentenceGraph] = {}
        try:
            for i, s in enumerate(sentences):
                tick("parse", i, len(sentences))
                try:
                    parsed[s.id] = engine.query(
                        f"parse:{s.id}", s.key_text, partial(self._parse, s.id, s.key_text, doc.version)
                    )
                except StageFailed as exc:  # not memoised: the next compute tries again
                    parsed[s.id] = SentenceGraph(
                        sentence_id=s.id,
                        text=s.key_text,
                        kind="empty",
                        diagnostics=[
                            Diagnostic(
                                code=exc.code,
                                message=f"this sentence could not be parsed: {exc}",
                                span=Span(0, len(s.key_text)),
                                severity="error",
                            )
                        ],
                    )
            tick("parse", len(sentences), len(sentences))
            ordered = [parsed[s.id] for s in sentences]
            try:
                resolved = engine.query(
                    "resolve",
                    [content_hash(g) for g in ordered],
                    lambda: self._resolve(ordered, doc.version),
                )
            except StageFailed as exc:
                resolved = ordered
                result.unavailable["resolve"] = str(exc)
        except StageUnavailable as exc:
            result.unavailable["parse"] = str(exc)
            self._finish(result, engine, sentences)
            return result
        # Spans from the parser are relative to the whitespace-normalised sentence text; map them back.
        for s, g in zip(sentences, resolved, strict=True):
            result.graphs[s.id] = g
            result.sentences.append(SentenceView(s.id, s.start, s.end, s.text, g.kind))
            result.diagnostics[s.id] = [
                msgspec.structs.replace(d, span=_shift(_map_span(d.span, s.text), s.start))
                for d in g.diagnostics
            ]
            result.commands.extend((s.id, c) for c in g.commands)

        if "scene" in stages:
            part = _scene_part(resolved)
            try:
                tick("scene", 0, 1)
                scene, report = engine.query("scene", part, lambda: self._compose(part, doc.version))
                result.scene, result.scene_report = scene, report
                tick("scene", 1, 1)
            except (StageUnavailable, StageFailed) as exc:
                result.unavailable["scene"] = str(exc)

        if "motion" in stages and result.scene is not None:
            try:
                self._motion_stage(result, resolved, sentences, engine, doc.version, tick)
            except (StageUnavailable, StageFailed) as exc:
                result.unavailable["motion"] = str(exc)
        self._finish(result, engine, sentences)
        return result

    def _finish(self, result: PipelineResult, engine: QueryEngine, sentences: list[Any]) -> None:
        result.ran = engine.ran()
        result.reused = engine.reused()
        if sentences and result.unavailable:
            span = Span(sentences[0].start, sentences[0].end)
            first = sentences[0].id
            for stage, why in result.unavailable.items():
                result.diagnostics.setdefault(first, []).append(_stage_diag(stage, why, span))


def _map_span(span: Span, original: str) -> Span:
    """Map a span in the whitespace-normalised text back to the sentence as written."""
    mapping: list[int] = []  # normalised index -> original index
    prev_space = False
    started = False
    for i, ch in enumerate(original):
        if ch.isspace():
            if started and not prev_space:
                mapping.append(i)
            prev_space = True
        else:
            mapping.append(i)
            prev_space = False
            started = True
    mapping.append(len(original))

    def at(k: int) -> int:
        return mapping[min(max(k, 0), len(mapping) - 1)]

    return Span(at(span.start), at(span.end - 1) + 1 if span.end > span.start else at(span.start))


def _scene_part(graphs: list[SentenceGraph]) -> dict[str, Any]:
    """Everything the scene depends on: objects, relations and the room kind of the scene sentences."""
    objects: list[ObjectNode] = []
    relations: list[RelationNode] = []
    room_type = ""
    for g in graphs:
        if g.kind != "scene":
            continue
        objects.extend(msgspec.structs.replace(o, span=Span(0, 0)) for o in g.objects)
        relations.extend(msgspec.structs.replace(r, span=Span(0, 0)) for r in g.relations)
        room_type = room_type or g.room_type
    return {"objects": objects, "relations": relations, "room_type": room_type}


def _fit_frames(track: np.ndarray, frames: int) -> np.ndarray:
    """(T, E) -> (frames, E): the last row held, or the end cut."""
    if len(track) >= frames:
        return track[:frames]
    return np.concatenate([track, np.repeat(track[-1:], frames - len(track), axis=0)])


DISTANCE_STEP = (
    0.05  # metres: social distances are rounded to this, so a re-sampled plan moves no one for less
)


def _social_distances(plan: Any) -> dict[tuple[str, int], dict[str, float]]:
    """(character, action index) -> {other: metres} for actions aimed at another character."""
    out: dict[tuple[str, int], dict[str, float]] = {}
    for d in plan.action_distances if plan is not None else []:
        metres = round(round(d.distance_m / DISTANCE_STEP) * DISTANCE_STEP, 2)
        out.setdefault((d.character, d.action_index), {})[d.other] = metres
    return out


def _social_part(graphs: list[SentenceGraph]) -> list[Any]:
    """What the social model reads of the story (services/social/story.py): the action sentences'
    characters, their actions and the characters those aim at, and the social nodes; no spans."""
    names = {c.name for g in graphs for c in g.characters}
    return [
        [
            g.sentence_id,
            [
                [
                    c.name,
                    [
                        [a.verb, a.action, *(r if r in names else "" for r in (a.target, a.destination))]
                        for a in c.actions
                    ],
                ]
                for c in g.characters
            ],
            [[n.kind, n.subjects, n.label] for n in g.social],
        ]
        for g in graphs
        if g.kind == "action" and (g.characters or g.social)
    ]


def _characters(
    graphs: list[SentenceGraph], sentences: list[Any]
) -> dict[str, tuple[CharacterNode, list[str]]]:
    """Each character's actions over the document in order, with the sentence id of each action."""
    out: dict[str, tuple[list[ActionNode], list[str]]] = {}
    for g, s in zip(graphs, sentences, strict=True):
        for c in g.characters:
            actions, sids = out.setdefault(c.name, ([], []))
            for a in c.actions:
                actions.append(msgspec.structs.replace(a, span=Span(0, 0)))
                sids.append(s.id)
    return {name: (CharacterNode(name=name, actions=acts), sids) for name, (acts, sids) in out.items()}


def _start_positions(scene: Scene, names: list[str]) -> dict[str, tuple[float, float, float]]:
    """Characters enter along the front wall (-Z side), facing into the room, 0.9 m apart."""
    room = scene.room
    z = -room.depth / 2 + 0.6
    x0 = -min(room.width / 2 - 0.6, 0.45 * (len(names) - 1))
    return {name: (round(x0 + 0.9 * i, 3), round(z, 3), 0.0) for i, name in enumerate(names)}


def _frames(motion: Motion) -> int:
    return int(motion.root_position.shape[0])


def _scene_view(scene: Scene, action: ActionNode | None) -> Scene:
    """The part of the layout an action can depend on: floor objects, plus what it names and their supports."""
    by_id = {o.id: o for o in scene.objects}
    wanted = {o.id for o in scene.objects if not o.support}
    named = [] if action is None else [action.target, action.instrument, action.destination]
    for name in named:
        if not name:
            continue
        # An action names an object by id ("chair", "chair/2") or, failing that, by category.
        refs = (
            [name]
            if name in by_id
            else [
                o.id for o in scene.objects if o.category == name or o.id.split("/")[0].split("#")[0] == name
            ]
        )
        for ref in refs:
            while ref and ref in by_id and ref not in wanted:
                wanted.add(ref)
                ref = by_id[ref].support
    return msgspec.structs.replace(scene, objects=[o for o in scene.objects if o.id in wanted])


def _others(
    action: ActionNode, name: str, states: dict[str, Any], object_ids: set[str]
) -> dict[str, tuple[float, float]]:
    """Where the characters an action is aimed at stand (by the time it starts); {} when it names none.

    An action aimed at something that is neither an object nor a known character ("shakes hands") gets
    every other character, so that planning can pick the only one.
    """
    named = [r for r in (action.target, action.destination, action.instrument) if r]
    people = {c: (round(st.x, 3), round(st.z, 3)) for c, st in states.items() if c != name}
    chosen = {c: p for c, p in people.items() if c in named}
    if chosen:
        return chosen
    if action.target and action.target not in object_ids and action.target not in states:
        return people
    return {}
