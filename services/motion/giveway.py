"""Walkers give way to each other: a space-time reservation over the story's time line.

Each character's route is planned around the furniture and the others where they stand, but two characters
walking at the same time ("They walk to the desk", one coming in while another walks out) can still meet
on the way. Once the cast shares one time line, every character's trajectory is reserved frame by frame
(wana.domain.routes.Reservations); a walker whose trajectory enters another's reserved disc at the same
frame waits: it stops a few frames before (on a frame with both feet down, so the wait looks like a paused
step) for as long as it takes the other to pass, then walks on; where no stop on the way clears it (two
setting off together whose ways cross), it waits before setting off and walks behind the other. Of two walkers the one whose walk began
later waits. The time spent waiting is taken back from the walker's next hold (the gap before its next
action), so the rest of the story keeps its timing; where no hold is long enough the story grows and the
others hold their last pose. A walker blocked by someone standing still is not helped by waiting and is
left as it is (the route planner goes around standing characters).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import msgspec
import numpy as np

from proto.motion_data import Motion, PropTrack, Segment
from wana.arrays import from_wire, to_wire
from wana.domain.actions import get_clip
from wana.domain.routes import Reservations

LEAD_FRAMES = 6  # a waiting walker stops this many frames before it would touch the other
STEP_FRAMES = 4  # waits are tried in steps of this many frames ...
MAX_WAIT_FRAMES = 150  # ... up to 5 s
STILL_M = 0.05  # metres: another who moves less than this over the wait is standing still
MAX_ROUNDS = 16  # conflicts resolved per story at most (each resolution re-reserves every track)
LOCOMOTION = ("walk", "walk_slowly", "walk_backward", "run", "jog", "tiptoe", "march", "limp")


def is_walk(action: str) -> bool:
    """True for a locomotion segment (a walk, a run, ...)."""
    if action in LOCOMOTION:
        return True
    try:
        return "locomotion" in get_clip(action).tags
    except KeyError:
        return False


@dataclass
class Track:
    """One character's motion as editable arrays (frames can be inserted and removed)."""

    motion: Motion
    root: np.ndarray  # (T, 3)
    rotations: np.ndarray  # (T, J, 4)
    foot: np.ndarray  # (T, 2)
    present: np.ndarray | None  # (T,)
    expression: np.ndarray | None  # (T, E)
    segments: list[Segment]
    props: list[PropTrack] = field(default_factory=list)

    @staticmethod
    def of(motion: Motion) -> Track:
        root = from_wire(motion.root_position).astype(np.float32)
        foot = (
            from_wire(motion.foot_contact).astype(np.uint8)
            if motion.foot_contact is not None
            else np.ones((len(root), 2), np.uint8)
        )
        return Track(
            motion=motion,
            root=root,
            rotations=from_wire(motion.rotations).astype(np.float32),
            foot=foot,
            present=from_wire(motion.present).astype(np.uint8).reshape(-1)
            if motion.present is not None
            else None,
            expression=from_wire(motion.expression) if motion.expression is not None else None,
            segments=list(motion.segments),
            props=list(motion.props),
        )

    @property
    def frames(self) -> int:
        return len(self.root)

    def on_stage(self) -> np.ndarray:
        if self.present is None or not len(self.present):
            return np.ones(self.frames, bool)
        on = self.present.astype(bool)
        return np.pad(on, (0, max(0, self.frames - len(on))), mode="edge")[: self.frames]

    def xz(self) -> np.ndarray:
        """(T, 2) hips on the floor, NaN while off stage."""
        out = self.root[:, [0, 2]].astype(np.float64)
        out[~self.on_stage()] = np.nan
        return out

    def _arrays(self) -> list[str]:
        return [
            n for n in ("root", "rotations", "foot", "present", "expression") if getattr(self, n) is not None
        ]

    def insert(self, at: int, count: int, before: bool = False) -> None:
        """``count`` copies of frame ``at`` before it (a held pose, both feet down); with ``before`` they
        belong to the segment that ends at ``at`` (the segment starting there starts later)."""
        for name in self._arrays():
            a = getattr(self, name)
            if at >= len(a):
                continue
            held = np.repeat(a[at : at + 1], count, axis=0)
            if name == "foot":
                held[:] = 1
            setattr(self, name, np.concatenate([a[:at], held, a[at:]]))
        self.segments = [_shift_segment(s, at - 1 if before else at, count) for s in self.segments]
        self.props = [_insert_prop(p, at, count) for p in self.props]

    def remove(self, at: int, count: int) -> None:
        """Frames ``at`` .. ``at + count`` taken out (they lie in a hold: nothing moves there)."""
        for name in self._arrays():
            a = getattr(self, name)
            setattr(self, name, np.concatenate([a[:at], a[at + count :]]))
        kept: list[Segment] = []
        for s in self.segments:
            start = s.start_frame - _overlap_before(s.start_frame, at, count)
            end = s.end_frame - _overlap_before(s.end_frame, at, count)
            if end > start:
                kept.append(msgspec.structs.replace(s, index=len(kept), start_frame=start, end_frame=end))
        self.segments = kept
        self.props = [p for p in (_remove_prop(p, at, count) for p in self.props) if p is not None]

    def pad(self, frames: int) -> None:
        """Hold the last pose until ``frames``."""
        extra = frames - self.frames
        if extra <= 0:
            return
        for name in self._arrays():
            a = getattr(self, name)
            setattr(self, name, np.concatenate([a, np.repeat(a[-1:], extra, axis=0)]))
        if self.segments and self.segments[-1].action == "hold":
            self.segments[-1] = msgspec.structs.replace(self.segments[-1], end_frame=frames)
        else:
            start = self.segments[-1].end_frame if self.segments else 0
            self.segments.append(
                Segment(index=len(self.segments), action="hold", start_frame=start, end_frame=frames)
            )

    def to_motion(self) -> Motion:
        return msgspec.structs.replace(
            self.motion,
            root_position=to_wire(self.root.astype(np.float32)),
            rotations=to_wire(self.rotations.astype(np.float32)),
            foot_contact=to_wire(self.foot.astype(np.uint8)),
            present=to_wire(self.present.astype(np.uint8)) if self.present is not None else None,
            expression=to_wire(self.expression.astype(np.float32)) if self.expression is not None else None,
            segments=self.segments,
            props=self.props,
        )


def _overlap_before(frame: int, at: int, count: int) -> int:
    """How many of the removed frames at .. at + count lie before ``frame``."""
    return max(0, min(frame, at + count) - at)


def _shift_segment(s: Segment, at: int, count: int) -> Segment:
    start = s.start_frame + (count if s.start_frame > at else 0)
    end = s.end_frame + (count if s.end_frame > at else 0)
    return msgspec.structs.replace(s, start_frame=start, end_frame=end)


def _insert_prop(p: PropTrack, at: int, count: int) -> PropTrack:
    if p.end_frame <= at:
        return p
    if p.start_frame >= at:
        return msgspec.structs.replace(p, start_frame=p.start_frame + count, end_frame=p.end_frame + count)
    k = at - p.start_frame
    pos, rot = from_wire(p.position), from_wire(p.rotation)
    pos = np.concatenate([pos[:k], np.repeat(pos[k : k + 1], count, 0), pos[k:]])
    rot = np.concatenate([rot[:k], np.repeat(rot[k : k + 1], count, 0), rot[k:]])
    return msgspec.structs.replace(
        p,
        end_frame=p.end_frame + count,
        position=to_wire(pos.astype(np.float32)),
        rotation=to_wire(rot.astype(np.float32)),
    )


def _remove_prop(p: PropTrack, at: int, count: int) -> PropTrack | None:
    start = p.start_frame - _overlap_before(p.start_frame, at, count)
    end = p.end_frame - _overlap_before(p.end_frame, at, count)
    if end <= start:
        return None
    lo, hi = max(at, p.start_frame) - p.start_frame, min(at + count, p.end_frame) - p.start_frame
    pos, rot = from_wire(p.position), from_wire(p.rotation)
    if hi > lo:
        pos, rot = np.delete(pos, range(lo, hi), 0), np.delete(rot, range(lo, hi), 0)
    return msgspec.structs.replace(
        p,
        start_frame=start,
        end_frame=end,
        position=to_wire(pos.astype(np.float32)),
        rotation=to_wire(rot.astype(np.float32)),
    )


def _waited(xz: np.ndarray, at: int, count: int) -> np.ndarray:
    """The trajectory (T, 2) with frame ``at`` held ``count`` frames (cut to the same length)."""
    return np.concatenate([xz[:at], np.repeat(xz[at : at + 1], count, 0), xz[at:]])[: len(xz)]


def _stop_frame(track: Track, start: int, conflict: int) -> int:
    """Where to wait: LEAD_FRAMES before the conflict, on the latest frame with both feet down near it."""
    at = max(start, conflict - LEAD_FRAMES)
    for f in range(at, max(start, at - 10) - 1, -1):
        if track.foot[f].all():
            return f
    return at


def slack(track: Track, after: int, action_index: int) -> int:
    """Frames of hold after frame ``after`` and before the character's next action (other than ``action_index``,
    the one walking): what a wait can be taken back from without starting that next action late, which
    would put it after actions the text tells later. With no next action, any wait fits."""
    total = 0
    for s in sorted(track.segments, key=lambda s: s.start_frame):
        if s.start_frame < after:
            continue
        if s.action == "hold":
            total += s.end_frame - s.start_frame
        elif s.action_index != action_index:
            return total
    return MAX_WAIT_FRAMES  # nothing after it: the story may grow (the others hold their last pose)


def take_back(track: Track, after: int, count: int) -> int:
    """Remove up to ``count`` frames from the holds after frame ``after``; returns how many are left over."""
    while count > 0:
        holds = [s for s in track.segments if s.action == "hold" and s.start_frame >= after]
        if not holds:
            break
        hold = holds[0]
        take = min(count, hold.end_frame - hold.start_frame)
        track.remove(hold.end_frame - take, take)  # a hold taken whole is gone: the next one is first then
        count -= take
    return count


def give_way(motions: Mapping[str, Motion]) -> tuple[dict[str, Motion], list[str]]:
    """The motions with walkers waiting for each other where they would meet (see the module docstring).

    Args:
        motions: name -> whole motion, all on one time line (same length).

    Returns:
        the motions (changed ones replaced, all of one length again), and one note per wait.
    """
    tracks = {n: Track.of(m) for n, m in motions.items()}
    if len(tracks) < 2:
        return dict(motions), []
    notes: list[str] = []
    hopeless: set[tuple[str, int, str]] = set()  # (walker, walk start, other): waiting does not help
    changed: set[str] = set()
    for _ in range(MAX_ROUNDS):
        table = Reservations()
        paths = {n: t.xz() for n, t in tracks.items()}
        for n, xz in paths.items():
            table.reserve(n, xz)
        found: tuple[int, int, str, str, Segment] | None = None  # (frame, -walk start, walker, other, walk)
        for name, track in tracks.items():
            for seg in track.segments:
                if not is_walk(seg.action) or seg.end_frame <= seg.start_frame:
                    continue
                skip = {name} | {o for (w, s, o) in hopeless if w == name and s == seg.start_frame}
                hit = table.first_conflict(paths[name], range(seg.start_frame, seg.end_frame), skip)
                if hit is None:
                    continue
                key = (hit[0], -seg.start_frame, name, hit[1], seg)
                if found is None or key[:2] < found[:2]:
                    found = key
        if found is None:
            break
        frame, _, walker, other, seg = found
        track = tracks[walker]
        theirs = paths[other]
        horizon = theirs[frame : min(len(theirs), frame + MAX_WAIT_FRAMES)]
        moving = horizon[np.isfinite(horizon).all(axis=1)]
        if len(moving) < 2 or float(np.linalg.norm(moving - moving[0], axis=1).max()) < STILL_M:
            hopeless.add((walker, seg.start_frame, other))  # standing still: waiting will not clear the way
            continue
        table_others = Reservations(clearance=table.clearance)
        for n, xz in paths.items():
            if n != walker:
                table_others.reserve(n, xz)
        skip = {walker} | {o for (w, s, o) in hopeless if w == walker and s == seg.start_frame}
        wait, stop = 0, seg.start_frame
        # Stop just before the meeting, or earlier when the other passes through that spot too.
        stops = [frame - back for back in range(0, 6 * LEAD_FRAMES + 1, LEAD_FRAMES)] + [seg.start_frame]
        for at in stops:  # at the last, wait before setting off and walk behind the other
            stop = _stop_frame(track, seg.start_frame, at)
            for count in range(STEP_FRAMES, MAX_WAIT_FRAMES + 1, STEP_FRAMES):
                trial = _waited(paths[walker], stop, count)
                tested = range(stop, min(len(trial), seg.end_frame + count))
                if table_others.first_conflict(trial, tested, skip) is None:
                    wait = count
                    break
            if wait or stop == seg.start_frame:
                break
        if not wait or slack(track, seg.end_frame, seg.action_index) < wait:
            hopeless.add((walker, seg.start_frame, other))  # no wait clears the way, or none fits the story
            continue
        track.insert(stop, wait)
        left = take_back(track, seg.end_frame + wait, wait)
        del left  # the story grows by what no hold could give back (padded below)
        changed.add(walker)
        notes.append(f"{walker} waits {wait / track.motion.fps:.1f} s for {other} to pass")
    if not changed:
        return dict(motions), []
    length = max(t.frames for t in tracks.values())
    out = {}
    for name, track in tracks.items():
        if track.frames < length:
            track.pad(length)
            changed.add(name)
        out[name] = track.to_motion() if name in changed else motions[name]
    return out, notes


__all__ = ["Track", "give_way", "is_walk", "slack", "take_back"]
