"""The story's actions lined up with the motion that plays them: which frames serve which sentence.

An action node k of a character is served by the motion segments whose `action_index` is k (an approach
walk, a turn, then the clip itself); holds belong to the action before them.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from proto.motion_data import Motion, Segment
from proto.ssg import ActionNode, SentenceGraph
from wana.fidelity.clips import clip_needs

SEATING = ("sit", "lie_down", "sleep", "sit_on_floor", "kneel")  # clips after which the character stays down
LOCOMOTION = (
    "walk",
    "walk_slowly",
    "walk_backward",
    "run",
    "jog",
    "tiptoe",
    "march",
    "limp",
    "crawl",
    "stand",
)


def is_locomotion(action: str) -> bool:
    clip = clip_needs(action)
    return action in LOCOMOTION or (clip is not None and "locomotion" in clip.tags)


ENTRANCE_VERBS = ("walk in", "enter", "come in", "run in", "step in", "burst in", "walk into", "come into")


def is_entrance(act: Act) -> bool:
    """ "walks in", "enters", "comes into" (the verb as written)."""
    verb = act.node.verb.lower()
    return any(verb == v or verb.startswith(v + " ") for v in ENTRANCE_VERBS)


@dataclass
class Act:
    """One action node of one character and the segments that play it."""

    sentence_id: str
    character: str
    k: int  # index among the character's actions (Segment.action_index)
    node: ActionNode
    segments: list[Segment] = field(default_factory=list)
    objects: tuple[str, ...] = ()  # ids of the objects the sentence names (a handover's "the book")
    words: dict[str, str] = field(default_factory=dict)  # object id -> the word the sentence used for it
    text: str = ""  # the sentence

    @property
    def clip(self) -> Segment | None:
        """The segment that plays the asked clip (the last one, after any approach), None when absent."""
        playing = [s for s in self.segments if s.action == self.node.action]
        return playing[-1] if playing else None

    @property
    def start(self) -> int:
        return min((s.start_frame for s in self.segments), default=-1)

    @property
    def end(self) -> int:
        return max((s.end_frame for s in self.segments), default=-1)


def story_acts(
    sentences: Sequence[tuple[str, str]], graphs: Mapping[str, SentenceGraph], motions: Mapping[str, Motion]
) -> list[Act]:
    """Every action node in document order (the k of each character counts as the pipeline counts it)."""
    counters: dict[str, int] = {}
    acts = []
    for sid, _ in sentences:
        graph = graphs.get(sid)
        if graph is None:
            continue
        for c in graph.characters:
            for node in c.actions:
                k = counters.get(c.name, 0)
                counters[c.name] = k + 1
                motion = motions.get(c.name)
                segs = [s for s in motion.segments if s.action_index == k] if motion is not None else []
                ids = tuple(o.id for o in graph.objects)
                words = {o.id: o.word or o.category for o in graph.objects}
                acts.append(Act(sid, c.name, k, node, segs, ids, words, graph.text))
    return acts


def window_frames(act: Act) -> range:
    """The frames of the clip's contact window (the whole clip when it loops), story frames."""
    seg = act.clip
    clip = clip_needs(act.node.action)
    if seg is None:
        return range(0)
    length = seg.end_frame - seg.start_frame
    if clip is None or clip.looping or clip.duration_s <= 0 or clip.window[1] <= clip.window[0]:
        if clip is not None and not clip.looping and clip.duration_s > 0 and clip.window[1] <= clip.window[0]:
            at = seg.start_frame + min(length - 1, round(clip.window[0] / clip.duration_s * length))
            return range(at, at + 1)
        return range(seg.start_frame, seg.end_frame)
    a = seg.start_frame + round(clip.window[0] / clip.duration_s * length)
    b = seg.start_frame + round(clip.window[1] / clip.duration_s * length)
    return range(a, max(b, a + 1))


def stays_until(act: Act, motion: Motion, *, through_standing_up: bool = False) -> int:
    """The frame the character leaves the pose an action put it in: the next locomotion, sit or lie down (which
    answer for themselves), or the motion's end.

    Args:
        through_standing_up: count standing up as still in the pose (it starts on the seat: the seat stays the
            stated contact while the character gets up), up to its last frame, not as leaving it. Once up,
            the seat is vacated: legs left in the armchair after "Tom stands up and argues" are inside it
            (duo-living_room-19 s7, a person's label).
    """
    seg = act.clip
    if seg is None:
        return act.end
    later = [
        s.end_frame if through_standing_up and s.action == "stand" else s.start_frame
        for s in motion.segments
        if s.start_frame >= seg.end_frame and (is_locomotion(s.action) or s.action in SEATING)
    ]
    frames = int(motion.root_position.shape[0])
    return min(later, default=frames)


def owned_frames(acts: list[Act], motion: Motion) -> dict[str, range]:
    """Sentence id -> the character's frames that sentence is answerable for (its actions and the holds after)."""
    frames = int(motion.root_position.shape[0])
    starts: dict[str, int] = {}
    for a in acts:
        if a.start >= 0:
            starts[a.sentence_id] = min(starts.get(a.sentence_id, a.start), a.start)
    ordered = sorted(starts.items(), key=lambda kv: kv[1])
    out = {}
    for i, (sid, start) in enumerate(ordered):
        end = ordered[i + 1][1] if i + 1 < len(ordered) else frames
        out[sid] = range(start, max(end, start))
    return out


IDLE = ("hold", "idle")  # segments that play nothing the story asked for


@dataclass(frozen=True)
class Activity:
    """What a character is doing on each frame, to tell who caused a fault two characters share.

    Attributes:
        since: (T,) the start frame of the action segment playing (a sentence's approach walk or clip),
            -1 where the character only holds its pose.
        walking: (T,) a locomotion segment plays (the character moves across the room).
        last: (T,) the start frame of the latest action segment begun by then (-1 before the first).
    """

    since: np.ndarray
    walking: np.ndarray
    last: np.ndarray


def activity(motion: Motion, frames: int) -> Activity:
    """Per frame: which action plays, whether it walks, and when the character last began one."""
    since = np.full(frames, -1, np.int64)
    walking = np.zeros(frames, bool)
    begun = np.full(frames, -1, np.int64)
    for seg in sorted(motion.segments, key=lambda s: s.start_frame):
        a, b = max(seg.start_frame, 0), min(seg.end_frame, frames)
        if b <= a:
            continue
        if is_locomotion(seg.action):
            walking[a:b] = True
        if seg.action in IDLE or (seg.action_index < 0 and not is_locomotion(seg.action)):
            continue
        since[a:b] = a
        begun[a] = max(begun[a], a)
    return Activity(since, walking, np.maximum.accumulate(begun))


def to_blame(a: Activity, b: Activity, frames: int) -> tuple[np.ndarray, np.ndarray]:
    """(frames,) bool per side: the frames on which a fault the two characters share is that side's doing.

    The one acting is blamed, not the one holding its pose (an idle character is not at fault for someone
    walking into them); of two acting, the one walking, else the one whose action began later (the sentence
    being acted at that frame); of two idle, the one who last began an action (who came there last). A tie
    blames both (one sentence that moves both, "Mary and John walk in").
    """
    sa, sb = a.since[:frames], b.since[:frames]
    wa, wb = a.walking[:frames], b.walking[:frames]
    la, lb = a.last[:frames], b.last[:frames]
    act_a, act_b = sa >= 0, sb >= 0
    both = act_a & act_b
    walk_one = both & (wa != wb)
    key_a = np.where(both, sa, la)
    key_b = np.where(both, sb, lb)
    blame_a = np.where(act_a != act_b, act_a, np.where(walk_one, wa, key_a >= key_b))
    blame_b = np.where(act_a != act_b, act_b, np.where(walk_one, wb, key_b >= key_a))
    return blame_a.astype(bool), blame_b.astype(bool)


__all__ = [
    "IDLE",
    "LOCOMOTION",
    "Activity",
    "activity",
    "to_blame",
    "SEATING",
    "Act",
    "is_locomotion",
    "owned_frames",
    "stays_until",
    "story_acts",
    "window_frames",
]
