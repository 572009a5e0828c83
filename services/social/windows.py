"""A long story planned window by window, so that an edit re-samples only the window it touches.

One Metropolis-Hastings run over a whole document makes every verb edit re-sample every character
sentence, and a re-sampled plan moves faces, distances and response timing all over the story (each of
them re-runs motion downstream). So a group's story is cut into windows of character sentences, each
planned on its own (``plan_window``) and memoised by its content (``_MEMO``): an edit re-plans the one
window that holds it, and every other window's part of the plan comes back exactly as it was.

A cut falls only after a *quiet* character sentence (no action aimed at a character and no social node,
so no response and no emotion label crosses it), once the window holds WINDOW_MIN_STEPS character
sentences, where the sentence id's hash says so (content-defined, like rsync's chunks: an insertion
moves no cut outside its own window); at WINDOW_MAX_STEPS it cuts at the next quiet sentence whatever the
hash. A story shorter than WINDOW_MIN_STEPS character sentences is one window, planned exactly as before.
Relations the text states hold for every later window (``context``: the relation nodes before it).
Action and step numbers are each window's own; ``merge_windows`` moves them to the document's.
"""

from __future__ import annotations

import hashlib
import zlib
from collections import OrderedDict
from collections.abc import Callable

import msgspec

from proto.social import CharacterSocial, ExpressionKey, SocialPlan, StepEmotion
from proto.ssg import SentenceGraph, SocialNode

WINDOW_MIN_STEPS = 24  # character sentences a window holds before it may be cut
WINDOW_MAX_STEPS = 96  # past this, the next quiet character sentence cuts
CUT_EVERY = 4  # a quiet sentence past the minimum cuts when its id hashes to 0 mod this
MEMO_SIZE = 512  # windows remembered (a window's plan is a few kB)

_MEMO: OrderedDict[bytes, SocialPlan] = OrderedDict()
_encoder = msgspec.msgpack.Encoder(order="deterministic")


def _is_step(g: SentenceGraph) -> bool:
    """A character sentence (services/social/story.py's step)."""
    return g.kind == "action" and bool(g.characters or g.social)


def _quiet(g: SentenceGraph, names: set[str]) -> bool:
    """No act aimed at a character (which the next sentence could answer) and no social node."""
    if g.social:
        return False
    return not any((a.target in names or a.destination in names) for c in g.characters for a in c.actions)


def story_windows(graphs: list[SentenceGraph]) -> list[list[SentenceGraph]]:
    """The graphs cut into windows (every graph in exactly one, in order)."""
    names = {c.name for g in graphs for c in g.characters}
    names |= {n for g in graphs for s in g.social for n in s.subjects}
    out: list[list[SentenceGraph]] = [[]]
    steps = 0
    for g in graphs:
        out[-1].append(g)
        if not _is_step(g):
            continue
        steps += 1
        if steps < WINDOW_MIN_STEPS or not _quiet(g, names):
            continue
        if steps >= WINDOW_MAX_STEPS or zlib.crc32(g.sentence_id.encode()) % CUT_EVERY == 0:
            out.append([])
            steps = 0
    if not out[-1]:
        out.pop()
    if len(out) > 1 and sum(_is_step(g) for g in out[-1]) == 0:  # a tail of scene sentences only
        tail = out.pop()
        out[-1].extend(tail)
    return out or [[]]


def relations_before(windows: list[list[SentenceGraph]], w: int) -> list[SocialNode]:
    """The relation nodes stated before window w (they hold on in it)."""
    return [s for win in windows[:w] for g in win for s in g.social if s.kind == "relation"]


def plan_window(
    graphs: list[SentenceGraph],
    context: list[SocialNode],
    seed: int,
    steps: int,
    plan: Callable[[list[SentenceGraph], list[SocialNode], int, int], SocialPlan],
) -> SocialPlan:
    """``plan(graphs, context, seed, steps)``, memoised by the window's content."""
    key = hashlib.blake2b(_encoder.encode([graphs, context, seed, steps]), digest_size=16).digest()
    hit = _MEMO.get(key)
    if hit is not None:
        _MEMO.move_to_end(key)
        return hit
    out = plan(graphs, context, seed, steps)
    _MEMO[key] = out
    if len(_MEMO) > MEMO_SIZE:
        _MEMO.popitem(last=False)
    return out


def _action_counts(graphs: list[SentenceGraph]) -> dict[str, int]:
    """Each character's actions in these graphs (story.py counts an actor's acts the same way)."""
    out: dict[str, int] = {}
    for g in graphs:
        if not _is_step(g):
            continue
        for c in g.characters:
            out[c.name] = out.get(c.name, 0) + len(c.actions)
    return out


def merge_windows(windows: list[list[SentenceGraph]], plans: list[SocialPlan], seed: int) -> SocialPlan:
    """One plan from the windows' plans, action and step numbers moved to the whole document's."""
    if len(plans) == 1:
        return plans[0]
    before: dict[str, int] = {}  # actions of each character in the windows so far
    step0 = 0
    chars: dict[str, CharacterSocial] = {}
    keys_of: dict[str, list[ExpressionKey]] = {}  # (joined once: not a copy of a long story's list a window)
    emotions_of: dict[str, list[StepEmotion]] = {}
    pairs: dict[tuple[str, str], object] = {}
    responses, proposals, distances, notes = [], [], [], []
    for win, p in zip(windows, plans, strict=True):
        off = dict(before)

        def at(name: str, k: int, off: dict[str, int] = off) -> int:
            return k + off.get(name, 0)

        for c in p.characters:
            keys = [
                msgspec.structs.replace(k, action_index=at(k.anchor_character, k.action_index))
                for k in c.keys
            ]
            emotions = [msgspec.structs.replace(e, step=e.step + step0) for e in c.emotions]
            chars.setdefault(c.name, c)  # the first window's entry, its keys and emotions joined at the end
            keys_of.setdefault(c.name, []).extend(keys)
            emotions_of.setdefault(c.name, []).extend(emotions)
        for x in p.pairs:
            pairs.setdefault((x.character, x.other), x)
        responses += [
            msgspec.structs.replace(
                r,
                action_index=at(r.actor, r.action_index),
                response_index=at(r.responder, r.response_index) if r.response_index >= 0 else -1,
            )
            for r in p.responses
        ]
        proposals += [
            msgspec.structs.replace(x, after_action_index=at(x.after, x.after_action_index))
            for x in p.proposals
        ]
        distances += [
            msgspec.structs.replace(d, action_index=at(d.character, d.action_index))
            for d in p.action_distances
        ]
        notes += p.notes
        for name, n in _action_counts(win).items():
            before[name] = before.get(name, 0) + n
        step0 += sum(_is_step(g) for g in win)
    return SocialPlan(
        expression_names=plans[0].expression_names,
        characters=[
            msgspec.structs.replace(c, keys=keys_of[name], emotions=emotions_of[name])
            for name, c in chars.items()
        ],
        pairs=list(pairs.values()),  # type: ignore[arg-type]
        responses=responses,
        proposals=proposals,
        action_distances=distances,
        energy_initial=round(sum(p.energy_initial for p in plans), 6),
        energy_final=round(sum(p.energy_final for p in plans), 6),
        steps=sum(p.steps for p in plans),
        accepted=sum(p.accepted for p in plans),
        seed=seed,
        notes=list(dict.fromkeys(notes)),
    )
