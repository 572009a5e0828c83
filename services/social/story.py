"""Sentence graphs -> the social story: characters, steps, acts, labels, and who responds to whom.

A step is one sentence that involves characters (graph kind "action"). An act is one ActionNode; its
``k`` is the actor's action number in document order, the same count as ``Segment.action_index``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

from proto.ssg import SentenceGraph, SocialNode
from services.social.lexicon import action_vad, word_vad, word_variants
from services.social.relations import DEFAULT_RELATION, canonical_label, relation_of

MAX_CHARACTERS = 8
MAX_STEPS = 200

Vad = tuple[float, float, float]


class StoryError(ValueError):
    """The graphs cannot be planned (too large, malformed); the message says why."""


@dataclass
class Act:
    actor: str
    k: int  # actor's action number in document order
    step: int
    sentence_id: str
    action: str  # action-library name ("" when unknown)
    verb: str
    vad: Vad | None  # None: no VAD for this action or verb
    target: str = ""  # character aimed at ("" = none)
    mutual: bool = False  # "They quarrel": aimed at each other without a stated target


@dataclass
class Response:
    act: Act  # A's act aimed at B
    responder: str  # B
    answer: Act | None  # B's act in the text that answers, or None (a reaction is proposed)


@dataclass
class Story:
    characters: list[str]
    steps: list[str]  # sentence ids
    acts: list[Act] = field(default_factory=list)
    emotion_labels: list[tuple[str, int, Vad]] = field(default_factory=list)  # (character, step, VAD)
    relations: dict[tuple[str, str], tuple[str, tuple[float, float]]] = field(default_factory=dict)
    responses: list[Response] = field(default_factory=list)
    first_step: dict[str, int] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)

    def pairs(self) -> list[tuple[str, str]]:
        """Every unordered pair of characters, in character order."""
        cs = self.characters
        return [(cs[i], cs[j]) for i in range(len(cs)) for j in range(i + 1, len(cs))]


def _same_verb(label: str, act: Act) -> bool:
    forms = set(word_variants(label))
    return bool(forms & (set(word_variants(act.verb)) | {act.action}))


def read_story(graphs: list[SentenceGraph], context: Sequence[SocialNode] = ()) -> Story:
    """Collect the social story of a document (``context``: relation nodes stated before these graphs,
    services/social/windows.py, which hold between the characters they name).

    Raises:
        StoryError: more than MAX_CHARACTERS characters or MAX_STEPS character sentences.
    """
    names: list[str] = []
    for g in graphs:
        for c in g.characters:
            if c.name and c.name not in names:
                names.append(c.name)
        for s in g.social:
            for n in s.subjects:
                if n and n[:1].isupper() and n not in names:
                    names.append(n)
        object_ids = {o.id for o in g.objects}
        for c in g.characters:
            for a in c.actions:
                t = a.target
                if t and t[:1].isupper() and t not in object_ids and t not in names:
                    names.append(t)  # "Tom waves at Eve": Eve is a character even if she never acts
    if len(names) > MAX_CHARACTERS:
        raise StoryError(
            f"the social model plans at most {MAX_CHARACTERS} characters, the text has {len(names)}"
        )
    story = Story(characters=names, steps=[])
    counts = dict.fromkeys(names, 0)
    for s in context:
        if s.kind == "relation":
            _add_relation(story, [n for n in s.subjects if n in counts], s.label)
    for g in graphs:
        if g.kind != "action" or not (g.characters or g.social):
            continue
        step = len(story.steps)
        story.steps.append(g.sentence_id)
        step_acts: list[Act] = []
        for c in g.characters:
            if c.name not in counts:
                continue
            story.first_step.setdefault(c.name, step)
            for a in c.actions:
                vad = action_vad(a.action, a.verb)
                if vad is None:
                    story.notes.append(f"no VAD for the action {a.verb or a.action!r} ({g.sentence_id})")
                # "Tom walks to Mary" approaches her as much as "Tom waves at Mary" addresses her
                aimed = a.target if a.target in counts else a.destination
                target = aimed if aimed in counts and aimed != c.name else ""
                if target:
                    story.first_step.setdefault(target, step)
                step_acts.append(
                    Act(c.name, counts[c.name], step, g.sentence_id, a.action, a.verb, vad, target)
                )
                counts[c.name] += 1
        # "They quarrel": two characters doing the same untargeted action in one sentence act on each other
        untargeted = [act for act in step_acts if not act.target and act.action]
        for act in untargeted:
            partners = [o for o in untargeted if o.actor != act.actor and o.action == act.action]
            if len(partners) == 1:
                act.target, act.mutual = partners[0].actor, True
        story.acts.extend(step_acts)
        for s in g.social:
            subjects = [n for n in s.subjects if n in counts]
            for n in subjects:
                story.first_step.setdefault(n, step)
            if s.kind == "relation":
                _add_relation(story, subjects, s.label)
            elif subjects:
                if any(_same_verb(s.label, a) for a in step_acts if a.actor == subjects[0]):
                    continue  # "Tom hugs Mary": the act already carries it
                vad = word_vad(s.label)
                if vad is None:
                    story.notes.append(f"no VAD for the emotion {s.label!r} ({g.sentence_id})")
                    continue
                for n in subjects:  # "Tom and Mary are happy": both
                    story.emotion_labels.append((n, step, vad))
        if len(story.steps) > MAX_STEPS:
            raise StoryError(f"the social model plans at most {MAX_STEPS} character sentences")
    _link_responses(story)
    return story


def _add_relation(story: Story, subjects: list[str], label: str) -> None:
    rel = relation_of(label)
    if rel is None:
        vad = word_vad(label)
        if vad is None:
            story.notes.append(f"unknown relation {label!r}: the default ({DEFAULT_RELATION}) is kept")
            return
        rel = (0.0, vad[0])  # an unknown relation word: intimacy from its valence
        story.notes.append(f"relation {label!r} scored by its valence")
    if len(subjects) < 2:
        return
    a, b = subjects[0], subjects[1]
    for x, y in ((a, b), (b, a)):
        if (x, y) in story.relations or (y, x) in story.relations:
            story.relations.pop((x, y), None)
            story.relations.pop((y, x), None)
    story.relations[(a, b)] = (canonical_label(label), rel)
    # "They are friends" with three or more subjects: every pair
    for i, x in enumerate(subjects):
        for y in subjects[i + 1 :]:
            if (x, y) != (a, b) and (x, y) not in story.relations and (y, x) not in story.relations:
                story.relations[(x, y)] = (canonical_label(label), rel)


def _link_responses(story: Story) -> None:
    """Each act aimed at B gets B's answer: B's first act in the same or the next character sentence."""
    by_actor: dict[str, list[Act]] = {}
    for a in story.acts:
        by_actor.setdefault(a.actor, []).append(a)
    order = {id(a): i for i, a in enumerate(story.acts)}
    aimed = [a for a in story.acts if a.target and not a.mutual]
    for i, a in enumerate(aimed):
        later = [
            b
            for b in by_actor.get(a.target, [])
            if b.step == a.step + 1 or (b.step == a.step and order[id(b)] > order[id(a)])
        ]
        # of several acts of A at B in one sentence, only the last one is answered
        if any(c.actor == a.actor and c.target == a.target and c.step == a.step for c in aimed[i + 1 :]):
            continue
        story.responses.append(Response(a, a.target, later[0] if later else None))
