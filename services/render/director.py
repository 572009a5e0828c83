"""The director: shots planned per sentence from what happens in it, and camera commands for their scope.

Without camera commands the video is cut on sentence boundaries (the frame where a sentence's first
segment starts) into shots:

- the first action gets an establishing wide shot (the room, everyone in it);
- three or more characters acting at once: wide;
- two characters acting at once: a two-shot, square to the line between them;
- one character: a tracking shot while it walks, a close-up when its face changes (an emotion action or
  a change of the expression weights), over the shoulder of the nearest idle character when it talks to
  them, else a medium shot;
- a shot shorter than MIN_SHOT_FRAMES (1.5 s) joins the shot before it (the subjects of both framed
  together); sentences in a row with the same type and subjects are one shot up to LONGEST_HOLD (5 s),
  and past that the cut must turn the view by JUMP_TURN or change its distance (no jump cut).

Each shot is framed by measuring: among candidate sides, turns, heights and distances
(SHOT_CHOICES; a commanded view only rises, turns a little or comes closer: COMMAND_CHOICES) the one
whose camera shows the shot's acting characters best over sample frames wins, measured as the
``in_view`` check measures the video (services.render.coverage: body points in the picture, unhidden by
furniture, walls seen from inside and other bodies), per sentence: each (sentence, acting character)
in the shot counts by its own frames and counts double once it would pass the check, so a short action
inside a long shot is not averaged away (services.render.camera_checks judges each one alone). A closer
shot whose best framing still leaves one of them unseen becomes a wide shot when that shows more; when no
candidate lets every sentence pass, a few high angles looking down over what stands in front are measured
too (RESCUE_CHOICES: a sitter hemmed in by the table, a partner's back). A seated character is measured
by its head, trunk and arms, as the check judges it (services.render.visibility.judged_view). The
planned camera is played as it is, commands framed by measuring included (they cut in). Walls
between the camera and the room are cut away (one-sided, culled from behind), so a camera may stand
outside the room; a small cost per metre outside keeps views inside when they see as well.

Every two-person shot of a pair stays on the side of the line between them that the pair's first shot
chose (the 180° rule), whatever a candidate on the other side would show.

A camera command replaces the director from its frame until the next camera command; ``close`` and
``follow`` only until their subject's next action ends (at least MIN_SHOT_FRAMES), then the director
resumes; they also cut away when someone else begins a sentence in their scope (after MIN_SHOT_FRAMES),
so that a close-up of Ben does not leave Anna's wave off-screen; one that named nobody ("camera close")
also frames that other character when it acts within those first MIN_SHOT_FRAMES (a named subject is
the user's choice and is held alone). A view command (front, back, left, right, top) that named nobody turns to whoever acts in each
sentence of its scope (a pair: their middle). Shots are what ``report.json`` lists.

This module is over 400 lines because the shot rules, the framing search and the command scopes are
one plan: each step reads the one before.

    shots = plan_shots(motions, tracks, commands, n_frames, room, Coverage.from_rigs(rigs, scene))
    keys = shot_keys(shots)  # services.render.camera.camera_at plays them
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Any, Protocol

import numpy as np

from proto.motion_data import Motion
from proto.render import Shot as RenderShot
from proto.render import TimedCommand
from proto.scene import Room
from services.render.camera import (
    OVERVIEW_ADJUSTMENTS,
    CameraKey,
    CameraPose,
    CharacterTrack,
    shot_pose,
    view_pose,
    wide_pose,
)
from services.render.framing import Adjust
from services.render.timeline import camera_mode

MIN_SHOT_FRAMES = 45  # 1.5 s at 30 fps
WALKS = frozenset(
    {"walk", "run", "jog", "walk_slowly", "walk_backward", "march", "skip", "tiptoe", "limp", "crawl"}
)
EMOTIONS = frozenset(
    {
        "laugh", "cry", "cover_face", "facepalm", "celebrate", "fist_pump", "shrug", "shiver", "yawn",
        "scratch_head", "think", "surrender", "wipe_sweat", "blow_kiss", "get_hit", "stumble", "fall_down",
    }
)  # fmt: skip
TALKS = frozenset(
    {"talk", "whisper", "shout", "argue", "quarrel", "apologize", "criticize", "comfort", "introduce",
     "threaten", "present", "listen_with_headphones", "nod", "shake_head", "greet_bow", "bow"}
)  # fmt: skip
NEAR_PARTNER = 3.0  # metres: an idle character this close is who a speaker talks to
EXPRESSION_CHANGE = 0.3  # largest change of one face weight within a shot that makes it a close-up
DIRECTIONS = ("front", "back", "left", "right", "top")  # commands that name a view, not a subject
COMMAND_VIEWS = (*DIRECTIONS, "follow", "close")
SCOPED_COMMANDS = ("close", "follow")  # commands that end with their subject's next action


@dataclass(frozen=True)
class Shot:
    """Frames [start, end) of one shot.

    Attributes:
        kind: wide, medium, tracking, close_up, two_shot, over_shoulder (director), or the commanded
            mode (front, back, left, right, top, follow, close).
        subject: who the shot is on ("" for a wide shot).
        partner: the second character of a two-person shot ("" otherwise).
        sentence_id: the sentence whose start cut to it (or whose command it is).
        source: "director" or "command".
        side: +1/-1, which side the camera stands (see services.render.shots).
        acting: who acts during the shot (who the framing must show).
        adjust: the framing chosen among candidates by what it shows (None: not measured).
    """

    start: int
    end: int
    kind: str
    subject: str = ""
    partner: str = ""
    sentence_id: str = ""
    source: str = "director"
    side: int = 1
    acting: tuple[str, ...] = ()
    adjust: Adjust | None = None


@dataclass(frozen=True)
class _Beat:
    """A stretch between two sentence starts: who acts in it and what they do."""

    start: int
    end: int
    sentence_id: str
    lead: str  # the character whose sentence starts the beat
    acting: tuple[str, ...]  # everyone with a sentence's segment in the beat, lead first
    actions: tuple[str, ...]  # the lead's segment actions in the beat


def _beats(motions: Mapping[str, Motion], n_frames: int) -> list[_Beat]:
    segs = [
        (s.start_frame, s.end_frame, name, s)
        for name, m in motions.items()
        for s in m.segments
        if s.sentence_id
    ]
    starts: dict[int, tuple[str, str]] = {}
    for lo, _, name, s in sorted(segs, key=lambda t: (t[0], t[2])):
        first_of_sentence = min(x[0] for x in segs if x[3].sentence_id == s.sentence_id)
        if lo == first_of_sentence and lo not in starts:
            starts[max(0, lo)] = (s.sentence_id, name)
    cuts = sorted(starts)
    if not cuts:
        return []
    edges = [0, *cuts[1:], n_frames] if cuts[0] > 0 else [*cuts, n_frames]
    out = []
    for i in range(len(edges) - 1):
        lo, hi = edges[i], edges[i + 1]
        if hi <= lo:
            continue
        sid, lead = starts.get(lo, starts[cuts[0]])
        acting = {name for a, b, name, _ in segs if a < hi and b > lo}
        actions = tuple(s.action for a, b, name, s in segs if name == lead and a < hi and b > lo)
        order = (lead, *sorted(acting - {lead}))
        out.append(_Beat(lo, hi, sid, lead, order if lead in acting else tuple(sorted(acting)), actions))
    return out


def _expression_changes(motion: Motion | None, lo: int, hi: int) -> bool:
    if motion is None or motion.expression is None:
        return False
    from wana.arrays import from_wire

    e = np.asarray(from_wire(motion.expression), dtype=np.float64)
    if e.ndim != 2 or not len(e) or lo >= len(e):
        return False
    part = e[lo : min(hi, len(e))]
    return bool(len(part) and np.abs(part - part[0]).max() > EXPRESSION_CHANGE)


def _nearest_idle(beat: _Beat, tracks: Mapping[str, CharacterTrack]) -> str:
    me = tracks.get(beat.lead)
    if me is None:
        return ""
    mid = (beat.start + beat.end) // 2
    best, best_d = "", NEAR_PARTNER
    for name, t in sorted(tracks.items()):
        if name in beat.acting:
            continue
        d = float(np.linalg.norm((t.at(mid)[0] - me.at(mid)[0])[[0, 2]]))
        if d < best_d:
            best, best_d = name, d
    return best


def _nearest(who: str, tracks: Mapping[str, CharacterTrack], frame: int) -> str:
    """The other character nearest to ``who`` at a frame ("" when alone)."""
    if who not in tracks:
        return ""
    here = tracks[who].at(frame)[0]
    others = [
        (float(np.linalg.norm((t.at(frame)[0] - here)[[0, 2]])), n) for n, t in tracks.items() if n != who
    ]
    return min(others)[1] if others else ""


def _kind(
    beat: _Beat, first: bool, motions: Mapping[str, Motion], tracks: Mapping[str, CharacterTrack]
) -> Shot:
    shot = _kind_of(beat, first, motions, tracks)
    return replace(shot, acting=beat.acting)


def _kind_of(
    beat: _Beat, first: bool, motions: Mapping[str, Motion], tracks: Mapping[str, CharacterTrack]
) -> Shot:
    lead = beat.lead
    if first or len(beat.acting) >= 3 or lead not in tracks:
        return Shot(beat.start, beat.end, "wide", "", "", beat.sentence_id)
    if len(beat.acting) == 2:
        return Shot(beat.start, beat.end, "two_shot", lead, beat.acting[1], beat.sentence_id)
    acts = set(beat.actions)
    if acts and acts <= WALKS:
        return Shot(beat.start, beat.end, "tracking", lead, "", beat.sentence_id)
    if acts & EMOTIONS or _expression_changes(motions.get(lead), beat.start, beat.end):
        return Shot(beat.start, beat.end, "close_up", lead, "", beat.sentence_id)
    if acts & TALKS and (partner := _nearest_idle(beat, tracks)):
        return Shot(beat.start, beat.end, "over_shoulder", lead, partner, beat.sentence_id)
    return Shot(beat.start, beat.end, "medium", lead, "", beat.sentence_id)


def _joined(a: Shot, b: Shot) -> Shot:
    """One shot over both (the later one is too short to stand alone): everyone of both in it."""
    people = [p for p in dict.fromkeys([a.subject, a.partner, b.subject, b.partner]) if p]
    acting = tuple(dict.fromkeys([*a.acting, *b.acting]))
    if a.kind == "wide" or len(people) >= 3 or len(acting) >= 3:
        return Shot(a.start, b.end, "wide", "", "", a.sentence_id, acting=acting)
    if len(people) == 2:
        kind = a.kind if a.kind in ("two_shot", "over_shoulder") and a.partner else "two_shot"
        return Shot(a.start, b.end, kind, people[0], people[1], a.sentence_id, acting=acting)
    return Shot(a.start, b.end, a.kind, a.subject, a.partner, a.sentence_id, acting=acting)


def _same_framing(a: Shot, b: Shot) -> bool:
    """Cutting from a to b would be a jump cut: the same type on the same people (a two-shot of a pair
    either way round; an over-the-shoulder reversed is the reverse shot, a different framing)."""
    if a.kind != b.kind:
        return False
    if a.kind in ("two_shot", "wide"):
        return {a.subject, a.partner} == {b.subject, b.partner}
    return (a.subject, a.partner) == (b.subject, b.partner)


def director_shots(
    motions: Mapping[str, Motion], tracks: Mapping[str, CharacterTrack], n_frames: int
) -> list[Shot]:
    """The director's shots over [0, n_frames), before sides are chosen (see plan_shots)."""
    shots: list[Shot] = []
    for i, beat in enumerate(_beats(motions, n_frames)):
        shot = _kind(beat, i == 0, motions, tracks)
        same = shots and _same_framing(shots[-1], shot) and shot.end - shots[-1].start <= LONGEST_HOLD
        if shots and (shot.end - shot.start < MIN_SHOT_FRAMES or same):
            shots[-1] = _joined(shots[-1], shot)
        elif shots and shots[-1].end - shots[-1].start < MIN_SHOT_FRAMES:
            shots[-1] = _joined(shots[-1], shot)  # the first beat was short: it opens the next
        else:
            shots.append(shot)
    if not shots:
        return [Shot(0, max(1, n_frames), "wide")]
    return shots


# Changes of a shot's pose the director measures, most preferred first (see services.render.framing.Adjust).
SHOT_CHOICES = (
    Adjust(),
    *(Adjust(turn=np.radians(a) * sg) for a in (30, 60) for sg in (1, -1)),
    Adjust(rise=0.6),
    Adjust(rise=1.2),
    *(Adjust(turn=np.radians(a) * sg, rise=0.8) for a in (30, 60) for sg in (1, -1)),
    Adjust(scale=1.3),
    Adjust(scale=0.8),
    *(Adjust(turn=np.radians(a) * sg) for a in (90, 140) for sg in (1, -1)),
    *(Adjust(turn=np.radians(a) * sg, rise=1.3, scale=1.2) for a in (45, 100) for sg in (1, -1)),
)
OVERVIEW_CHOICES = OVERVIEW_ADJUSTMENTS + tuple(
    Adjust(turn=np.radians(a) * sg, rise=0.8) for a in (135, 180) for sg in (1, -1)
)  # the room seen from its other sides too
# A commanded view keeps its side: only small turns, rising and coming closer (a window in the way).
COMMAND_CHOICES = (
    Adjust(),
    Adjust(rise=0.6),
    *(Adjust(turn=np.radians(a) * sg) for a in (20, 40) for sg in (1, -1)),
    Adjust(rise=1.2),
    Adjust(scale=0.75),
    *(Adjust(turn=np.radians(a) * sg, rise=0.8) for a in (20, 40) for sg in (1, -1)),
    Adjust(rise=1.0, scale=0.7),
    *(Adjust(turn=np.radians(60) * sg, rise=0.8) for sg in (1, -1)),  # last: a three-quarter view
)
# Last resorts, measured only when no candidate above lets every sentence in the shot pass: a high angle
# looking down over what stands in front (a sitter hemmed in by the table, a partner's back, a chair),
# from the shot's own side or turned a little; a wide shot from high above the middle of the room.
RESCUE_CHOICES = tuple(
    Adjust(turn=np.radians(a) * sg, rise=r, scale=k)
    for r, k in ((1.6, 0.6), (2.2, 0.45))
    for a in (0, 35)
    for sg in ((1,) if a == 0 else (1, -1))
)
WIDE_RESCUE_CHOICES = tuple(
    Adjust(turn=np.radians(a), rise=r, scale=k)
    for r, k in ((1.0, 0.45), (1.6, 0.3))
    for a in (0, 90, 180, 270)
)
LINE_CHOICE_TURN = np.radians(60.0)  # two-person shots keep to their side of the line
SAMPLES = 8  # frames of a shot measured per candidate, at least
SAMPLE_STEP = 15  # frames between measured frames of a long shot (at most MAX_SAMPLES)
MAX_SAMPLES = 24
UNIT_SAMPLES = 12  # frames measured per sentence's part of a shot, at most
PASS_SHARE = 0.95  # a sentence's sampled frames shown at least this much pass its check with a margin
PASS_BONUS = 1.0  # what passing a sentence's check is worth beyond its share of frames shown
WIDE_GAIN = 0.02  # how much more a wide shot must show to replace a closer shot that leaves someone unseen
LONGEST_HOLD = (
    150  # frames: same-framing sentences join into one shot up to 5 s; beyond, the cut changes angle
)
JUMP_TURN = np.radians(30.0)  # a cut on the same subject must turn the view at least this much
JUMP_SCALE = 0.25  # ... or change the distance by this share
PREFERENCE = 0.004  # score given up per step down the candidate list (ties go to the preferred one)
REPLAN_STEP = 5  # frames between the frames a failing shot is checked on for where it loses someone
REPLAN_GAIN = 0.05  # how much more a new framing of a shot's rest must show to cut there
OUTSIDE = 0.02  # score per metre the eye stands outside the room (readable views are from inside)
LINE_KEPT_COS = np.cos(np.radians(45.0))  # a pair's line turned further than this is a new line (180° rule)
FACES = 0.06  # score for seeing the acting characters' faces, not the backs of their heads (ties of what is shown)
FACES_ENOUGH = 0.3  # how frontal the preferred framing must be to stop looking at the other side


class Scorer(Protocol):
    """What a candidate camera shows (services.render.coverage.Coverage), over sample frames."""

    def shown(self, poses: Sequence[CameraPose], frames: Sequence[int], who: Sequence[str]) -> float: ...

    def shown_each(
        self, poses: Sequence[CameraPose], frames: Sequence[int], who: Sequence[str]
    ) -> np.ndarray: ...


@dataclass(frozen=True)
class _Unit:
    """One sentence's frames of one acting character: what one ``in_view`` check judges."""

    who: str
    frames: np.ndarray  # (F,) sorted story frames
    key: int = 0  # its place in the story's list of units (what the frames it has missed are kept under)


def _units(motions: Mapping[str, Motion], n_frames: int) -> list[_Unit]:
    """Every (sentence, acting character) with its frames, as services.render.camera_checks counts them."""
    spans: dict[tuple[str, str], set[int]] = {}
    for name, m in motions.items():
        for seg in m.segments:
            if seg.sentence_id:
                lo, hi = max(0, seg.start_frame), min(seg.end_frame, n_frames)
                spans.setdefault((seg.sentence_id, name), set()).update(range(lo, hi))
    kept = [(who, f) for (_, who), f in sorted(spans.items()) if f]
    return [_Unit(who, np.array(sorted(f), dtype=np.int64), k) for k, (who, f) in enumerate(kept)]


def _samples(s: Shot, units: Sequence[_Unit] = ()) -> list[int]:
    """Frames a candidate is measured on: spread over the shot, and over each sentence's part of it (a
    short action inside a long shot is judged on its own frames, as the check judges it)."""
    n = min(max(SAMPLES, (s.end - s.start) // SAMPLE_STEP), MAX_SAMPLES, max(1, s.end - s.start))
    out = {int(round(x)) for x in np.linspace(s.start, max(s.start, s.end - 1), n)}
    for u in units:
        inside = u.frames[(u.frames >= s.start) & (u.frames < s.end)]
        if len(inside):
            k = min(UNIT_SAMPLES, len(inside))
            out.update(int(inside[int(round(i))]) for i in np.linspace(0, len(inside) - 1, k))
    return sorted(out)


def _unit_score(
    shown: np.ndarray,
    frames: Sequence[int],
    who: Sequence[str],
    s: Shot,
    units: Sequence[_Unit],
    missed: Mapping[int, float] | None = None,
    out: dict[int, float] | None = None,
) -> tuple[float | None, bool]:
    """How well (F, C) ``shown`` passes the shot's sentences' checks, in [0, 1]: each (sentence,
    character) in the shot counts by the share of its frames the shot holds; its score is the share of
    its sampled frames shown, plus PASS_BONUS when the whole sentence would still pass its check with a
    margin: the frames the shots before missed of it (``missed``, by unit key) and those this one misses
    (written to ``out``) together at most 1 - PASS_SHARE of its frames. None when no sentence acts in
    the shot; and whether every one passes."""
    col = {w: j for j, w in enumerate(who)}
    fr = np.asarray(frames, dtype=np.int64)
    total, weight, passes = 0.0, 0.0, True
    missed = missed or {}
    for u in units:
        if u.who not in col:
            continue
        inside = u.frames[(u.frames >= s.start) & (u.frames < s.end)]
        if not len(inside):
            continue
        mask = np.isin(fr, inside)
        if not mask.any():
            continue
        share = float(shown[mask, col[u.who]].mean())
        w = len(inside) / len(u.frames)
        here = (1.0 - share) * len(inside)
        if out is not None:
            out[u.key] = here
        ok = missed.get(u.key, 0.0) + here <= (1.0 - PASS_SHARE) * len(u.frames) + 1e-9
        passes &= ok
        total += w * (share + PASS_BONUS * ok) / (1.0 + PASS_BONUS)
        weight += w
    return (total / weight if weight > 0 else None), passes


def _candidates(s: Shot, fixed_side: int | None, rescue: bool = False) -> list[tuple[int, Adjust]]:
    """The framings a shot is measured with, preferred first; ``rescue``: the last resorts instead."""
    sides = (fixed_side,) if fixed_side is not None else (1, -1)
    if s.source == "command":
        if s.kind not in COMMAND_VIEWS or (rescue and s.kind == "top"):
            return []
        return [(1, a) for a in (RESCUE_CHOICES if rescue else COMMAND_CHOICES)]
    if s.kind == "wide":
        return [(1, a) for a in (WIDE_RESCUE_CHOICES if rescue else OVERVIEW_CHOICES)]
    choices = RESCUE_CHOICES if rescue else SHOT_CHOICES
    if s.partner:
        choices = tuple(a for a in choices if abs(a.turn) <= LINE_CHOICE_TURN + 1e-9)
    return [(side, a) for a in choices for side in sides]


def _framed(
    shots: list[Shot],
    tracks: Mapping[str, CharacterTrack],
    room: Room,
    scorer: Scorer | None,
    units: Sequence[_Unit] = (),
) -> list[Shot]:
    """Each shot's side and framing: the candidate that shows its acting characters best (with a scorer),
    else the side whose eye stays in the room; a pair keeps the side of its first shot (180° rule), and
    a cut to the same subject never lands on a near-identical view (no jump cut). A director's shot whose
    best framing still leaves a sentence's character unseen becomes a wide shot when one shows more."""
    pair_side: dict[tuple[str, str], tuple[int, np.ndarray]] = {}  # the side kept, the line it was kept on
    track_map = dict(tracks)

    def kept_side(pair: tuple[str, str] | None, frame: int) -> int | None:
        """The side of the line a pair's shot keeps: its last shot's, while the line between them still runs
        the same way (a talk on a sofa after one walked in from the door is a new line, seen afresh)."""
        if pair is None or pair not in pair_side:
            return None
        side, before = pair_side[pair]
        now = _line(pair, track_map, frame)
        return side if float(before @ now) >= LINE_KEPT_COS else None

    out: list[Shot] = []
    last: tuple[Shot, Any] | None = None  # the shot before and its camera on its last frame
    missed: dict[int, float] = {}  # frames of each unit the shots framed so far leave unseen (by key)
    todo = list(reversed(shots))
    while todo:
        s = todo.pop()
        if (s.source == "command" and scorer is None) or (s.kind != "wide" and s.subject not in tracks):
            out.append(s)
            last = None
            continue
        pair = (min(s.subject, s.partner), max(s.subject, s.partner)) if s.partner else None
        found = _search(s, kept_side(pair, s.start), track_map, room, scorer, units, last, missed=missed)
        if scorer is not None and not found.passes and s.source == "director" and s.kind != "wide":
            wide = replace(s, kind="wide", subject="", partner="")
            other = _search(wide, None, track_map, room, scorer, units, last, missed=missed)
            if other.score > found.score + WIDE_GAIN:
                s, found, pair = wide, other, None
        if pair is not None and s.source == "director":  # a command's framing keeps no side of the line
            pair_side[pair] = (found.side, _line(pair, track_map, max(s.start, s.end - 1)))
        framed = replace(s, side=found.side, adjust=found.adjust if scorer is not None else None)
        if scorer is not None and not found.passes:  # a measured command's view too, on its side
            split = _replan(framed, track_map, room, scorer, units, kept_side(pair, s.start), missed)
            if split is not None:
                framed = replace(framed, end=split)
                only = (found.side, found.adjust)
                part = _search(
                    framed, found.side, track_map, room, scorer, units, None, only=only, missed=missed
                )
                found = replace(
                    found, end_pose=_pose(_key(framed), track_map, room, split - 1), missed=part.missed
                )
                todo.append(replace(s, start=split))
        out.append(framed)
        for k, m in found.missed.items():
            missed[k] = missed.get(k, 0.0) + m
        last = (framed, found.end_pose) if found.end_pose is not None else None
    return out


def _line(pair: tuple[str, str], tracks: Mapping[str, CharacterTrack], frame: int) -> np.ndarray:
    """The unit direction (XZ) from a pair's first to its second character at a frame."""
    d = (tracks[pair[1]].at(frame)[0] - tracks[pair[0]].at(frame)[0])[[0, 2]]
    n = float(np.linalg.norm(d))
    return d / n if n > 1e-6 else np.array([1.0, 0.0])


def _key(s: Shot) -> CameraKey:
    """The camera of a framed shot."""
    return CameraKey(
        frame=s.start, mode=s.kind, character=s.subject, partner=s.partner, side=s.side, adjust=s.adjust
    )


def _lost_at(
    s: Shot, tracks: dict[str, CharacterTrack], room: Room, scorer: Scorer, units: Sequence[_Unit]
) -> int | None:
    """The first frame (every REPLAN_STEP) where the framed shot loses a character whose sentence acts
    then (someone walks into the line of sight, or the actor walks out of the picture); None: never."""
    frames = list(range(s.start, s.end, REPLAN_STEP))
    inside = [u for u in units if u.who in tracks and ((u.frames >= s.start) & (u.frames < s.end)).any()]
    who = list(dict.fromkeys(u.who for u in inside))
    if not who:
        return None
    key = _key(s)
    poses = [_pose(key, tracks, room, f) for f in frames]
    if any(p is None for p in poses):
        return None
    seen = scorer.shown_each(poses, frames, who)
    fr = np.asarray(frames, dtype=np.int64)
    lost = np.zeros(len(frames), dtype=bool)
    for u in inside:
        lost |= np.isin(fr, u.frames) & ~seen[:, who.index(u.who)]
    hits = np.flatnonzero(lost)
    return int(fr[hits[0]]) if len(hits) else None


def _replan(
    s: Shot,
    tracks: dict[str, CharacterTrack],
    room: Room,
    scorer: Scorer,
    units: Sequence[_Unit],
    fixed_side: int | None,
    missed: Mapping[int, float] | None = None,
) -> int | None:
    """Where a director's shot whose framing loses an acting character part-way is cut and re-framed:
    at the frame it loses them (held MIN_SHOT_FRAMES first, and the rest at least as long), when another
    framing of the rest (its side of the line kept; no jump cut from this one) shows clearly more of it
    than this one does. None: the shot is kept whole."""
    if s.end - s.start < 2 * MIN_SHOT_FRAMES:
        return None
    lost = _lost_at(s, tracks, room, scorer, units)
    if lost is None:
        return None
    split = min(max(lost, s.start + MIN_SHOT_FRAMES), s.end - MIN_SHOT_FRAMES)
    rest = replace(s, start=split)
    only = (s.side, s.adjust or Adjust())
    kept = _search(rest, s.side, tracks, room, scorer, units, None, only=only, missed=missed)
    if kept.passes:
        return None
    end_pose = _pose(_key(s), tracks, room, split - 1)
    other = _search(
        rest, fixed_side, tracks, room, scorer, units, (replace(s, end=split), end_pose), missed=missed
    )
    return split if other.score > kept.score + REPLAN_GAIN else None


@dataclass(frozen=True)
class _Found:
    """The best candidate of one shot: its side and adjustment, its score, its camera on its last frame,
    and whether it shows every sentence's character in the shot well enough to pass the check."""

    side: int
    adjust: Adjust
    score: float
    end_pose: Any
    passes: bool
    missed: Mapping[int, float] = field(default_factory=dict)  # frames it misses of each unit (by key)


def _search(
    s: Shot,
    fixed_side: int | None,
    tracks: dict[str, CharacterTrack],
    room: Room,
    scorer: Scorer | None,
    units: Sequence[_Unit],
    last: tuple[Shot, Any] | None,
    only: tuple[int, Adjust] | None = None,
    missed: Mapping[int, float] | None = None,
) -> _Found:
    """Measure a shot's candidates (preferred first) and keep the one that shows most (``only``: measure
    just that side and framing; ``missed``: the frames the shots before missed of each unit)."""
    frames = _samples(s, units)
    inside = [u for u in units if u.who in tracks and ((u.frames >= s.start) & (u.frames < s.end)).any()]
    who = list(dict.fromkeys([*(s.acting or (s.subject,)), *(u.who for u in inside)]))
    best = _Found(1, Adjust(), -np.inf, None, False)
    main = [only] if only is not None else _candidates(s, fixed_side)
    for rank, (side, adj) in enumerate(main):
        key = CameraKey(
            frame=s.start, mode=s.kind, character=s.subject, partner=s.partner, side=side, adjust=adj
        )
        poses = [_pose(key, tracks, room, f) for f in frames]
        if any(p is None for p in poses):
            break
        if last is not None and s.start == last[0].end and _jump(last, s, poses[0], tracks):
            continue
        passes = True
        frontal = 1.0
        here: dict[int, float] = {}
        if scorer is None:
            score = -float(np.mean([_outside(room, p.eye) for p in poses]))
        else:
            score, passes, frontal = _measured(
                poses, frames, who, s, inside, tracks, room, scorer, missed, here
            )
        score -= PREFERENCE * rank
        if score > best.score + 1e-12:
            end_pose = _pose(key, tracks, room, max(s.start, s.end - 1))
            best = _Found(side, adj, score, end_pose, passes, here)
        if scorer is None and rank >= 1:
            break  # without measuring, only the side is chosen
        if (
            scorer is not None
            and rank == 0
            and frontal >= FACES_ENOUGH
            and best.score >= 1.0 + FACES * frontal - PREFERENCE * rank - 1e-9
        ):
            break  # the preferred framing shows everyone, from the front: nothing to improve
    if scorer is not None and not best.passes and only is None:
        best = _rescue(s, fixed_side, tracks, room, scorer, frames, who, inside, best, len(main), missed)
    return best


def _measured(
    poses: Sequence[Any],
    frames: list[int],
    who: list[str],
    s: Shot,
    inside: Sequence[_Unit],
    tracks: Mapping[str, CharacterTrack],
    room: Room,
    scorer: Scorer,
    missed: Mapping[int, float] | None = None,
    out: dict[int, float] | None = None,
) -> tuple[float, bool, float]:
    """A candidate's score (what it shows of the shot's sentences, less the eye outside the room, plus
    FACES for faces seen), whether it passes every sentence's check, and how frontal it is (``missed``
    and ``out``: as in _unit_score)."""
    seen = scorer.shown_each(poses, frames, who)
    by_unit, passes = _unit_score(seen, frames, who, s, inside, missed, out)
    acting_names = [w for w in (s.acting or (s.subject,)) if w in who]
    fallback = float(seen[:, [who.index(w) for w in acting_names]].mean()) if acting_names else 1.0
    outside = float(np.mean([_outside(room, p.eye) for p in poses]))
    frontal = _frontal(poses, frames, acting_names, tracks)
    return (fallback if by_unit is None else by_unit) - OUTSIDE * outside + FACES * frontal, passes, frontal


def _frontal(
    poses: Sequence[Any], frames: Sequence[int], who: Sequence[str], tracks: Mapping[str, CharacterTrack]
) -> float:
    """How much the acting characters face the camera over the sampled frames: 1 looking straight into
    it, 0 in profile or from behind (a talk seen from behind a sofa shows two backs of heads)."""
    if not who:
        return 1.0
    total, n = 0.0, 0
    for pose, f in zip(poses, frames, strict=True):
        for w in (w for w in who if w in tracks):
            _, facing, head = tracks[w].at(f)
            to_eye = (pose.eye - head)[[0, 2]]
            dist = float(np.linalg.norm(to_eye))
            face = facing[[0, 2]]
            norm = float(np.linalg.norm(face))
            if dist < 1e-6 or norm < 1e-6:
                continue
            total += max(0.0, float(face @ to_eye) / (dist * norm))
            n += 1
    return total / n if n else 1.0


def _rescue(
    s: Shot,
    fixed_side: int | None,
    tracks: dict[str, CharacterTrack],
    room: Room,
    scorer: Scorer,
    frames: list[int],
    who: list[str],
    inside: list[_Unit],
    best: _Found,
    first_rank: int,
    missed: Mapping[int, float] | None = None,
) -> _Found:
    """The last-resort framings (RESCUE_CHOICES), measured as the others, ranked after them: one wins
    only when it shows more than every preferred framing did."""
    for i, (side, adj) in enumerate(_candidates(s, fixed_side, rescue=True)):
        key = CameraKey(
            frame=s.start, mode=s.kind, character=s.subject, partner=s.partner, side=side, adjust=adj
        )
        poses = [_pose(key, tracks, room, f) for f in frames]
        if any(p is None for p in poses):
            break
        here: dict[int, float] = {}
        score, passes, _ = _measured(poses, frames, who, s, inside, tracks, room, scorer, missed, here)
        score -= PREFERENCE * (first_rank + i)
        if score > best.score + 1e-12:
            end_pose = _pose(key, tracks, room, max(s.start, s.end - 1))
            best = _Found(side, adj, score, end_pose, passes, here)
            if passes:
                break
    return best


def _jump(last: tuple[Shot, Any], s: Shot, first: Any, tracks: Mapping[str, CharacterTrack]) -> bool:
    """Whether cutting from the shot before (its camera on its last frame) to this camera is a jump cut:
    the same people, seen from nearly the same direction and distance."""
    before, pose = last
    if pose is None or {before.subject, before.partner} != {s.subject, s.partner} or s.kind == "wide":
        return False
    centre = tracks[s.subject].at(s.start)[0]
    a, b = (pose.eye - centre)[[0, 2]], (first.eye - centre)[[0, 2]]
    na, nb = float(np.linalg.norm(a)), float(np.linalg.norm(b))
    if na < 1e-6 or nb < 1e-6:
        return False
    turn = float(np.arccos(np.clip(a @ b / (na * nb), -1.0, 1.0)))
    return turn < JUMP_TURN and abs(na - nb) / max(na, nb) < JUMP_SCALE


def _pose(key: CameraKey, tracks: dict[str, CharacterTrack], room: Room, f: int) -> Any:
    if key.mode == "wide":
        return wide_pose(key, room)
    if key.mode in COMMAND_VIEWS:
        return view_pose(key, tracks[key.character], tracks, room, f)
    return shot_pose(key, tracks, f)


def _outside(room: Room, eye: np.ndarray, margin: float = 0.15) -> float:
    """Metres the eye stands outside the room's walls (0 inside)."""
    return float(
        max(0.0, abs(eye[0]) - room.width / 2 + margin) + max(0.0, abs(eye[2]) - room.depth / 2 + margin)
    )


def _command_shots(
    commands: Iterable[TimedCommand],
    motions: Mapping[str, Motion],
    tracks: Mapping[str, CharacterTrack],
    n_frames: int,
    beats: list[_Beat],
) -> list[Shot]:
    """The frames each camera command is in force (see the module doc)."""
    cams = [tc for tc in commands if tc.command.kind == "camera"]
    out = []
    for i, tc in enumerate(cams):
        start = min(max(0, tc.frame), n_frames)
        end = cams[i + 1].frame if i + 1 < len(cams) else n_frames
        mode = camera_mode(tc.command.value)
        who = tc.command.target
        if mode in SCOPED_COMMANDS and who in motions:
            nxt = [s.end_frame for s in motions[who].segments if s.sentence_id and s.end_frame > start]
            if nxt:
                end = min(end, max(min(nxt), start + MIN_SHOT_FRAMES))
            end = min(end, _cut_away(who, start, beats))
        end = min(max(end, start), n_frames)
        if end <= start:
            continue
        acting = tuple(dict.fromkeys(a for b in beats if b.start < end and b.end > start for a in b.acting))
        shot = Shot(start, end, mode, who, "", tc.sentence_id, "command", acting=acting)
        # both in the picture: the pair's middle, closer in ("camera close on Okafor" while Sam walks off: a
        # close shot of Okafor alone left Sam out, and the framing then rose to a top view that showed neither;
        # "follow Mei" while Raj argues with her left Raj out for the 1.5 s the command must hold)
        if mode in SCOPED_COMMANDS and (other := _co_actor(who, start, beats, tracks)):
            shot = replace(shot, partner=other)
        if mode == "over_shoulder":  # over this character's shoulder onto the nearest other one
            other = _nearest(who, tracks, start)
            shot = replace(shot, subject=other or who, partner=who if other else "")
        if mode in DIRECTIONS and tc.implied_target:
            out.extend(_per_beat(shot, beats, tracks))
        else:
            out.append(shot)
    return out


def _co_actor(who: str, start: int, beats: list[_Beat], tracks: Mapping[str, CharacterTrack]) -> str:
    """Who else acts while an unnamed close-up or follow shot of ``who`` from ``start`` must hold (its first
    MIN_SHOT_FRAMES, which no cut-away shortens): the nearest of them, "" when nobody. "camera close"
    before "They sit on the sofa and talk" or "Ted walks in" would otherwise hold on one face for 1.5 s
    while the other character's action happens off-screen; the command then frames both, closer in."""
    hold = start + MIN_SHOT_FRAMES
    others = {a for b in beats if b.start < hold and b.end > start for a in b.acting if a != who}
    if who not in tracks or not (others := {a for a in others if a in tracks}):
        return ""
    here = tracks[who].at(start)[0]
    return min(others, key=lambda a: (float(np.linalg.norm((tracks[a].at(start)[0] - here)[[0, 2]])), a))


def _cut_away(who: str, start: int, beats: list[_Beat]) -> int:
    """Where a close-up or follow shot of ``who`` from ``start`` cuts away: at the first sentence of
    someone else that begins in its scope (held at least MIN_SHOT_FRAMES, so the command shows), since
    the issue wants every acting character seen; a large number when nobody else begins a sentence."""
    others = [b.start for b in beats if b.lead != who and b.start >= start]
    return max(min(others), start + MIN_SHOT_FRAMES) if others else 1 << 30


def _per_beat(shot: Shot, beats: list[_Beat], tracks: Mapping[str, CharacterTrack]) -> list[Shot]:
    """A view command that named nobody, turned to whoever acts in each sentence of its scope (a pair:
    both, from the commanded side of the first)."""
    out: list[Shot] = []
    for b in beats:
        lo, hi = max(shot.start, b.start), min(shot.end, b.end)
        if hi <= lo or b.lead not in tracks:
            continue
        partner = _widest(b.lead, b.acting[1:], tracks, lo, hi)
        piece = replace(shot, start=lo, end=hi, subject=b.lead, partner=partner, acting=b.acting)
        if out and (hi - lo < MIN_SHOT_FRAMES or (out[-1].subject, out[-1].partner) == (b.lead, partner)):
            out[-1] = replace(out[-1], end=hi, acting=tuple(dict.fromkeys([*out[-1].acting, *b.acting])))
        else:
            out.append(piece)
    if not out:
        return [shot]
    out[0] = replace(out[0], start=shot.start)  # the pieces cover the command's whole scope
    out[-1] = replace(out[-1], end=shot.end)
    return out


def _widest(
    lead: str, others: Sequence[str], tracks: Mapping[str, CharacterTrack], lo: int, hi: int | None = None
) -> str:
    """Who a view of ``lead`` pairs with so that everyone acting with them is in the picture: the one
    that gets farthest from the lead over frames [lo, hi) ("" when nobody). Sentences that start together
    ("Nora tells a story.", "Max comes in", "John stands up" at once) all act in the beat; the pair at its
    two ends frames the rest between them, where the first name alone left Nora and Max out of a "camera
    left" two-shot. Measured over the beat, not on its first frame: "Mom kisses Sam and leaves" starts
    beside Sam, and a pair chosen then left her walking out of the picture for 3 s."""
    frames = np.unique(np.linspace(lo, max(lo, (hi or lo + 1) - 1), 9).round().astype(int))

    def farthest(a: str) -> tuple[float, str]:
        d = [float(np.linalg.norm((tracks[a].at(f)[0] - tracks[lead].at(f)[0])[[0, 2]])) for f in frames]
        return max(d), a

    return max((a for a in others if a in tracks), key=farthest, default="")


def _overlay(base: list[Shot], commanded: list[Shot]) -> list[Shot]:
    """The director's shots with the commanded stretches cut out and the commands in their place."""
    out = []
    for s in base:
        pieces = [(s.start, s.end)]
        for c in commanded:
            pieces = [
                part
                for lo, hi in pieces
                for part in ((lo, min(hi, c.start)), (max(lo, c.end), hi))
                if part[1] > part[0]
            ]
        for lo, hi in pieces:
            out.append(replace(s, start=lo, end=hi))
    return sorted(out + list(commanded), key=lambda s: s.start)


def plan_shots(
    motions: Mapping[str, Motion],
    tracks: Mapping[str, CharacterTrack],
    commands: Iterable[TimedCommand],
    n_frames: int,
    room: Room,
    scorer: Scorer | None = None,
) -> list[Shot]:
    """Every frame's shot, in order, covering [0, n_frames).

    Args:
        motions: character -> motion (its segments say which sentence acts when).
        tracks: character -> hips/facing/head track (services.render.skinning.Rig.track).
        commands: timed commands in frame order (timeline.place_commands); camera ones override.
        n_frames: the video's length.
        room: the room (sides are chosen to keep the eye inside it).
        scorer: measures what a candidate camera shows (services.render.coverage.Coverage); None: the
            shots are not measured (the camera moves off boxes in its way instead).
    """
    n = max(1, n_frames)
    beats = _beats(motions, n)
    commanded = _command_shots(commands, motions, tracks, n, beats)
    shots = _overlay(director_shots(motions, tracks, n), commanded)
    return _framed(shots, tracks, room, scorer, _units(motions, n))


def shot_keys(shots: Iterable[Shot]) -> list[CameraKey]:
    """The camera keys that play the shots: the director cuts (and so does a view command turning to the
    next sentence's character, and any command framed by measuring: the framing that was measured is the
    one on screen from its first frame, where an ease from the shot before could swing the lens through a
    whiteboard or out past the character); a command planned without measuring eases in as it always did."""
    shots = list(shots)
    return [
        CameraKey(
            frame=s.start,
            mode=s.kind,
            character=s.subject,
            partner=s.partner,
            side=s.side,
            end=s.end,
            cut=s.source == "director"
            or s.adjust is not None
            or (i > 0 and shots[i - 1].source == "command" and s.sentence_id == shots[i - 1].sentence_id),
            adjust=s.adjust,
        )
        for i, s in enumerate(shots)
    ]


def shot_messages(shots: Iterable[Shot]) -> list[RenderShot]:
    """The shots as the ExportReply and report.json list them."""
    return [
        RenderShot(
            start_frame=s.start,
            end_frame=s.end,
            type=s.kind,
            subject=s.subject,
            partner=s.partner,
            sentence_id=s.sentence_id,
            source="command" if s.source == "command" else "director",
        )
        for s in shots
    ]
