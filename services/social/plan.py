"""The social model's public API: ``plan_social`` (graphs -> SocialPlan) and ``expression_track``
(plan + a character's motion segments -> Motion.expression).

Faces: each of a character's actions gets two keys, the previous emotion at the action's first frame and
the emotion of its sentence ONSET_S later (a facial onset of a few hundred milliseconds); a character an
action is aimed at gets a reaction key on the actor's action, REACTION_LAG_S + the response delay after it
starts. Between keys the weights are linear in time; before the first key the face is ``rest_weights``;
after the last one it holds.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import msgspec
import numpy as np

from proto.motion_data import Segment
from proto.social import (
    ActionDistance,
    CharacterSocial,
    ExpressionKey,
    PairSocial,
    ProposedResponse,
    ResponseTiming,
    SocialPlan,
    StepEmotion,
)
from proto.ssg import SentenceGraph, SocialNode
from services.social.energy import build_model
from services.social.face import expression_names, face_weights
from services.social.relations import inverse_label
from services.social.sampler import sample
from services.social.story import Story, read_story
from services.social.windows import merge_windows, plan_window, relations_before, story_windows
from wana.domain.units import FPS

ONSET_S = 0.4
REACTION_LAG_S = 0.3
MAX_MH_STEPS = 100_000


def _r(v: float, nd: int = 4) -> float:
    return round(float(v), nd)


def _vad(x: list[float], i: int) -> tuple[float, float, float]:
    return (_r(x[i]), _r(x[i + 1]), _r(x[i + 2]))


def _weights(vad: tuple[float, float, float]) -> list[float]:
    return [_r(v) for v in face_weights(vad).tolist()]


def plan_social(graphs: list[SentenceGraph], *, seed: int = 0, steps: int = 0) -> SocialPlan:
    """Sample faces, response timing, distances and open reactions for a document's characters.

    Args:
        graphs: the document's sentence graphs in order (pronouns resolved, as the NLP stage returns them).
        seed: the sampler's seed; the same graphs and seed give the same plan.
        steps: Metropolis-Hastings steps; 0 = scaled to the story (bounded by sampler.MAX_STEPS).

    Returns:
        The SocialPlan (empty lists when the text has no characters).

    Raises:
        services.social.story.StoryError (a ValueError): too many characters or sentences, or bad ``steps``.
    """
    if not 0 <= steps <= MAX_MH_STEPS:
        raise ValueError(f"steps must be in 0..{MAX_MH_STEPS}, got {steps}")
    groups = social_groups(graphs)
    if len(groups) <= 1:
        return _plan_windows(graphs, seed, steps)
    return _merge([_plan_windows(_only(graphs, group), seed, steps) for group in groups], seed)


def _plan_windows(graphs: list[SentenceGraph], seed: int, steps: int) -> SocialPlan:
    """One group's plan, window by window (services/social/windows.py: an edit re-plans its window only)."""
    windows = story_windows(graphs)
    plans = [
        plan_window(win, relations_before(windows, w), seed, steps, _plan_group)
        for w, win in enumerate(windows)
    ]
    return merge_windows(windows, plans, seed)


def social_groups(graphs: list[SentenceGraph]) -> list[list[str]]:
    """The characters that never meet split into groups, each in order of first appearance.

    Two characters are in one group when they act in one sentence, when an action of one aims at the
    other, or when a social node names both. Groups are planned apart (same seed), so what one group
    does never changes another's faces or timing.
    """
    parent: dict[str, str] = {}

    def find(n: str) -> str:
        parent.setdefault(n, n)
        while parent[n] != n:
            parent[n] = parent[parent[n]]
            n = parent[n]
        return n

    def join(names: list[str]) -> None:
        for n in names[1:]:
            parent[find(n)] = find(names[0])

    order: list[str] = []
    for g in graphs:
        names = [c.name for c in g.characters]
        order += names + [n for node in g.social for n in node.subjects]
        join(names)
        for node in g.social:
            join(node.subjects)
    known = set(order)
    for g in graphs:
        for c in g.characters:
            join([c.name] + [a.target for a in c.actions if a.target in known])
    groups: dict[str, list[str]] = {}
    for n in dict.fromkeys(order):
        groups.setdefault(find(n), []).append(n)
    return list(groups.values())


def _only(graphs: list[SentenceGraph], group: list[str]) -> list[SentenceGraph]:
    """The graphs with only the characters and social nodes of one group."""
    members = set(group)
    return [
        msgspec.structs.replace(
            g,
            characters=[c for c in g.characters if c.name in members],
            social=[n for n in g.social if members.intersection(n.subjects)],
        )
        for g in graphs
    ]


def _merge(plans: list[SocialPlan], seed: int) -> SocialPlan:
    """One plan from the plans of groups that never meet (no pair spans two groups)."""
    return SocialPlan(
        expression_names=plans[0].expression_names,
        characters=[c for p in plans for c in p.characters],
        pairs=[x for p in plans for x in p.pairs],
        responses=[x for p in plans for x in p.responses],
        proposals=[x for p in plans for x in p.proposals],
        action_distances=[x for p in plans for x in p.action_distances],
        energy_initial=_r(sum(p.energy_initial for p in plans), 6),
        energy_final=_r(sum(p.energy_final for p in plans), 6),
        steps=sum(p.steps for p in plans),
        accepted=sum(p.accepted for p in plans),
        seed=seed,
        notes=list(dict.fromkeys(n for p in plans for n in p.notes)),
    )


def _plan_group(
    graphs: list[SentenceGraph], context: Sequence[SocialNode], seed: int, steps: int
) -> SocialPlan:
    """plan_social for characters that all belong to one group (``context``: relations stated before)."""
    story = read_story(graphs, context)
    model = build_model(story)
    result = sample(model, seed=seed, steps=steps)
    x = result.x
    # emotions per character and step
    characters = []
    emotion_at: dict[tuple[str, int], tuple[float, float, float]] = {}
    for c in story.characters:
        emotions = []
        for s, sid in enumerate(story.steps):
            i = model.e_index.get((c, s))
            if i is not None:
                emotion_at[(c, s)] = _vad(x, i)
                emotions.append(StepEmotion(step=s, sentence_id=sid, vad=emotion_at[(c, s)]))
        characters.append((c, emotions))
    delays = [math.exp(x[i]) for i in model.delay_index]
    keys: dict[str, list[ExpressionKey]] = {c: [] for c in story.characters}
    for a in story.acts:
        prev = emotion_at.get((a.actor, a.step - 1), emotion_at[(a.actor, a.step)])
        now = emotion_at[(a.actor, a.step)]
        keys[a.actor].append(
            ExpressionKey(
                anchor_character=a.actor, action_index=a.k, at_s=0.0, weights=_weights(prev), vad=prev
            )
        )
        keys[a.actor].append(
            ExpressionKey(
                anchor_character=a.actor, action_index=a.k, at_s=ONSET_S, weights=_weights(now), vad=now
            )
        )
    aimed_delay = {id(r.act): delays[q] for q, r in enumerate(story.responses)}
    for a in story.acts:
        if not a.target:
            continue
        now = emotion_at[(a.target, a.step)]
        lag = REACTION_LAG_S + aimed_delay.get(id(a), 0.0)
        keys[a.target].append(
            ExpressionKey(
                anchor_character=a.actor,
                action_index=a.k,
                at_s=_r(lag),
                weights=_weights(now),
                vad=now,
                reaction=True,
            )
        )
    out_chars = []
    for c, emotions in characters:
        first = story.first_step.get(c)
        rest = emotion_at.get((c, first), (0.0, 0.0, 0.0)) if first is not None else (0.0, 0.0, 0.0)
        if first is not None and _only_acted_on(story, c, first):
            rest = (0.0, 0.0, 0.0)  # first seen as someone's target: neutral until the reaction key
        out_chars.append(
            CharacterSocial(name=c, rest_weights=_weights(rest), keys=keys[c], emotions=emotions)
        )
    pairs = []
    for (ca, cb), (p, sign) in sorted(
        model.pair_index.items(),
        key=lambda kv: (story.characters.index(kv[0][0]), story.characters.index(kv[0][1])),
    ):
        ri = model.r0[p]
        label = story.relations.get((ca, cb), story.relations.get((cb, ca), ("default", (0.0, 0.0))))[0]
        if label != "default" and (ca, cb) not in story.relations:
            label = inverse_label(label)
        pairs.append(
            PairSocial(
                character=ca,
                other=cb,
                relation=label,
                dominance=_r(sign * x[ri]),
                intimacy=_r(x[ri + 1]),
                distance_m=_r(x[model.dpair[p]], 3),
            )
        )
    distances = [
        ActionDistance(
            character=story.acts[n].actor,
            action_index=story.acts[n].k,
            other=story.acts[n].target,
            distance_m=_r(x[i], 3),
        )
        for n, i in model.act_distance
    ]
    responses = [
        ResponseTiming(
            actor=r.act.actor,
            action_index=r.act.k,
            responder=r.responder,
            response_index=r.answer.k if r.answer else -1,
            delay_s=_r(delays[q], 3),
        )
        for q, r in enumerate(story.responses)
    ]
    proposals = []
    for q, mi in model.slots:
        r = story.responses[q]
        cand = model.candidates[int(x[mi])]
        fit = sum((a - b) ** 2 for a, b in zip(emotion_at[(r.responder, r.act.step)], cand.vad, strict=True))
        proposals.append(
            ProposedResponse(
                character=r.responder,
                after=r.act.actor,
                after_action_index=r.act.k,
                action=cand.name,
                vad=tuple(_r(v) for v in cand.vad),  # type: ignore[arg-type]
                delay_s=_r(delays[q], 3),
                fit=_r(fit),
            )
        )
    return SocialPlan(
        expression_names=expression_names(),
        characters=out_chars,
        pairs=pairs,
        responses=responses,
        proposals=proposals,
        action_distances=distances,
        energy_initial=_r(result.energy_initial, 6),
        energy_final=_r(result.energy_final, 6),
        steps=result.steps,
        accepted=result.accepted,
        seed=seed,
        notes=list(dict.fromkeys(story.notes)),
    )


def _only_acted_on(story: Story, c: str, step: int) -> bool:
    acts = [a for a in story.acts if a.step == step]
    labelled = any(n == c and s == step for n, s, _ in story.emotion_labels)
    return any(a.target == c for a in acts) and not any(a.actor == c for a in acts) and not labelled


def _spans(segments: list[Segment]) -> dict[int, tuple[int, int]]:
    """action_index -> (first frame, end frame) over the segments that serve it."""
    out: dict[int, tuple[int, int]] = {}
    for s in segments:
        if s.action_index < 0:
            continue
        lo, hi = out.get(s.action_index, (s.start_frame, s.end_frame))
        out[s.action_index] = (min(lo, s.start_frame), max(hi, s.end_frame))
    return out


def expression_track(
    plan: SocialPlan,
    character: str,
    segments: list[Segment],
    fps: int = FPS,
    *,
    frames: int | None = None,
    others: dict[str, list[Segment]] | None = None,
) -> np.ndarray:
    """Face blendshape weights of one character over its motion.

    Args:
        plan: from ``plan_social``.
        character: the character's name.
        segments: the character's Motion.segments (their action_index and frame ranges).
        fps: frames per second of the motion.
        frames: T; default the segments' last end_frame (at least 1).
        others: other characters' segments by name, to place reactions to their actions (without it, reaction
            keys are left out and the character's own keys and rest face remain).

    Returns:
        (T, E) float32 weights in [0, 1], E = len(plan.expression_names).

    Raises:
        ValueError: unknown character, fps < 1, frames < 1 or a segment with end_frame < start_frame.
    """
    if fps < 1:
        raise ValueError(f"fps must be at least 1, got {fps}")
    for s in segments:
        if s.end_frame < s.start_frame or s.start_frame < 0:
            raise ValueError(f"segment {s.index} has frames {s.start_frame}..{s.end_frame}")
    entry = next((c for c in plan.characters if c.name == character), None)
    if entry is None:
        raise ValueError(
            f"{character!r} is not a character of this plan: {[c.name for c in plan.characters]}"
        )
    T = frames if frames is not None else max([s.end_frame for s in segments] or [1])
    if T < 1:
        raise ValueError(f"frames must be at least 1, got {T}")
    E = len(plan.expression_names)
    spans = {character: _spans(segments)}
    for name, segs in (others or {}).items():
        if name != character:
            spans[name] = _spans(segs)
    timed: list[tuple[float, int, list[float]]] = []
    for n, key in enumerate(entry.keys):
        span = spans.get(key.anchor_character, {}).get(key.action_index)
        if span is None:
            continue
        frame = (
            min(float(span[0] + key.at_s * fps), float(T - 1))
            if key.anchor_character != character
            else min(span[0] + key.at_s * fps, max(span[0], span[1] - 1))
        )
        timed.append((frame, n, key.weights))
    rest = np.asarray(entry.rest_weights, dtype=np.float32)
    out = np.empty((T, E), dtype=np.float32)
    out[:] = rest
    if not timed:
        return out
    timed.sort(key=lambda t: (t[0], t[1]))
    times = np.array([t[0] for t in timed], dtype=np.float64)
    values = np.array([t[2] for t in timed], dtype=np.float32)
    f = np.arange(T, dtype=np.float64)
    for j in range(E):
        out[:, j] = np.interp(f, times, values[:, j], left=np.nan, right=values[-1, j])
    before = f < times[0]
    out[before] = rest
    return np.clip(out, 0.0, 1.0).astype(np.float32)
