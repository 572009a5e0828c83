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
others hold their last pose. Where no wait clears the way (two walking head on, each through where the other
waits; someone standing still on the way, who came there after the walk was planned) and the scene is known,
the walker steps aside instead: its path bends sideways round the other for the frames they pass (``sidestep``),
as far as it needs and the furniture lets it, and joins its own path again before the walk ends, so the walk
keeps its timing, its start and its end. Otherwise the walker is left as it is. Two who stand close when a
walk begins (they hugged, then walk off) do not meet while the walker is still on its spot and the other no
closer (``first_meeting``): the one who waits there is not walked into; nor does one who gets up from beside
someone seated walk into them while it moves no closer.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

import msgspec
import numpy as np

from proto.motion_data import Motion, PropTrack, Segment
from proto.scene import Scene
from wana.arrays import from_wire, to_wire
from wana.domain.actions import get_clip
from wana.domain.routes import Reservations

LEAD_FRAMES = 6  # a waiting walker stops this many frames before it would touch the other
STEP_FRAMES = 4  # waits are tried in steps of this many frames ...
MAX_WAIT_FRAMES = 150  # ... up to 5 s
STILL_M = 0.05  # metres: another who moves less than this over the wait is standing still
MAX_ROUNDS = 16  # conflicts resolved per story at most (each resolution re-reserves every track)
# metres a sidestepping walker's path bends aside, tried in turn
ASIDE_M = (0.15, 0.25, 0.35, 0.45, 0.55, 0.7)
RAMP_FRAMES = 15  # frames over which a sidestep bends away from the path and back onto it
RAMP_MIN_FRAMES = 6  # ... at least (a pass near the walk's start or end)
PASS_MARGIN_FRAMES = 4  # frames the path stays aside before and after the frames the two would touch
SET_OFF_M = 0.05  # metres from its spot a walker has set off
NO_CLOSER_M = 0.02  # metres a bend may come closer than the walk was (rounding)
MOVED_M = 0.03  # metres: points bent less than this are where the walk was and need no new room
ASIDE_BODY_M = 0.2  # metres: the sidestepping body's clearance from furniture and walls
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


def _set_off_beside(
    xz: np.ndarray, theirs: np.ndarray, start: int, lo: int, hi: int, clearance: float
) -> np.ndarray:
    """(hi - lo,) bool: the frames lo .. hi where a walker that began at ``start`` within ``clearance`` of the
    other gets no closer to it than it stood, while the walker is still on its spot (they hugged, then the
    other walks off) or, until the two are first apart, while the other stays on its own (it gets up from
    beside someone seated): nobody walks into anyone there."""
    n = min(len(xz), len(theirs))
    if not 0 <= start < n or hi <= lo:
        return np.zeros(max(0, hi - lo), bool)
    stood = float(np.linalg.norm(theirs[start] - xz[start]))
    d = np.linalg.norm(theirs[lo:hi] - xz[lo:hi], axis=1)
    frames = np.arange(lo, hi)
    apart = np.flatnonzero(~(np.linalg.norm(theirs[start:hi] - xz[start:hi], axis=1) < clearance))
    together = frames < (start + int(apart[0]) if len(apart) else hi)
    moved = np.flatnonzero(np.linalg.norm(xz[start:hi] - xz[start], axis=1) > SET_OFF_M)
    not_yet = frames < (start + int(moved[0]) if len(moved) else hi)
    theirs_still = np.linalg.norm(theirs[lo:hi] - theirs[start], axis=1) <= SET_OFF_M
    return (d >= stood - NO_CLOSER_M) & (not_yet | (theirs_still & together))


def first_meeting(
    table: Reservations, xz: np.ndarray, start: int, frames: range, exclude: set[str]
) -> tuple[int, str] | None:
    """``table.first_conflict`` of a walk that began at frame ``start``, but for the frames before it sets off
    from beside someone who walks away (``_set_off_beside``): the one who waits there is not walked into."""
    best: tuple[int, str] | None = None
    for name, track in (table.tracks or {}).items():
        if name in exclude:
            continue
        lo, hi = max(frames.start, 0), min(frames.stop, len(track), len(xz))
        if hi <= lo:
            continue
        d = np.linalg.norm(track[lo:hi] - xz[lo:hi], axis=1)
        beside = _set_off_beside(xz, track, start, lo, hi, table.clearance)
        hit = (d < table.clearance) & ~beside  # NaN: off stage, no hit
        found = np.flatnonzero(hit)
        if len(found) and (best is None or lo + int(found[0]) < best[0]):
            best = (lo + int(found[0]), name)
    return best


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


def _aside_window(seg: Segment, near: np.ndarray) -> tuple[int, int, int, int] | None:
    """(bend from, aside from, aside to, back by) frames of a sidestep inside the walk ``seg`` round the frames
    ``near`` (sorted) where the two would touch; None when the walk has no room to bend away and back."""
    lo, hi = int(near[0]) - PASS_MARGIN_FRAMES, int(near[-1]) + PASS_MARGIN_FRAMES
    lo, hi = max(lo, seg.start_frame + RAMP_MIN_FRAMES), min(hi, seg.end_frame - 1 - RAMP_MIN_FRAMES)
    if hi < lo or hi < near[-1]:
        return None
    return max(seg.start_frame, lo - RAMP_FRAMES), lo, hi, min(seg.end_frame - 1, hi + RAMP_FRAMES)


def sidestep(
    xz: np.ndarray,
    seg: Segment,
    theirs: np.ndarray,
    clearance: float,
    free: Callable[[np.ndarray], np.ndarray],
    others: Sequence[np.ndarray] = (),
) -> np.ndarray | None:
    """The offset (T, 2) metres that bends the walk ``seg`` of the trajectory ``xz`` (T, 2) aside round another's
    trajectory ``theirs`` (T, 2) wherever the two come within ``clearance`` during the walk; None when no bend
    of at most ASIDE_M[-1] metres keeps them apart (and the walker clear of ``others``' trajectories) with every
    point bent aside where ``free`` (N, 2) -> (N,) bool says the body fits, or, where the walk already brushed
    the furniture, fits no worse than it did.

    The bend is sideways to the walker's heading at the closest frame, away from the other, smooth (a cosine
    ramp in, aside while they pass, a ramp out) and zero at the walk's first and last frames.
    """
    end = min(seg.end_frame, len(xz), len(theirs))
    frames = np.arange(seg.start_frame, end)
    if end - seg.start_frame < 2 * RAMP_MIN_FRAMES + 1 or not len(frames):
        return None
    gap = np.linalg.norm(theirs[frames] - xz[frames], axis=1)
    stood = float(gap[0])
    near = frames[
        (gap < clearance) & ~_set_off_beside(xz, theirs, seg.start_frame, frames[0], end, clearance)
    ]
    if not len(near):
        return None
    window = _aside_window(seg, near)
    if window is None:
        return None
    f0, lo, hi, f1 = window
    closest = int(near[np.argmin(gap[near - frames[0]])])
    ahead = xz[min(closest + 3, len(xz) - 1)] - xz[max(closest - 3, 0)]
    if float(np.linalg.norm(ahead)) < 1e-6:  # standing: aside from the other
        ahead = theirs[closest] - xz[closest]
        ahead = np.array([ahead[1], -ahead[0]])
    heading = ahead / max(float(np.linalg.norm(ahead)), 1e-9)
    normal = np.array([-heading[1], heading[0]])
    away = 1.0 if float(np.dot(xz[closest] - theirs[closest], normal)) >= 0 else -1.0
    weight = np.zeros(len(xz))
    weight[lo : hi + 1] = 1.0
    if lo > f0:
        weight[f0:lo] = 0.5 - 0.5 * np.cos(np.linspace(0.0, np.pi, lo - f0, endpoint=False))
    if f1 > hi:
        weight[hi + 1 : f1 + 1] = 0.5 + 0.5 * np.cos(np.linspace(0.0, np.pi, f1 - hi + 1)[1:])
    span = np.arange(f0, f1 + 1)
    # Bending away from someone one set off beside (a walk that starts within a body of them) may not get
    # closer than they stood; from the bend's full width on, the two keep the clearance.
    need = np.where(
        span < lo, min(clearance, stood if np.isfinite(stood) else clearance) - NO_CLOSER_M, clearance
    )
    for side in (away, -away):
        for metres in ASIDE_M:
            offset = weight[:, None] * (side * metres * normal)[None]
            trial = xz + offset
            if np.any(np.linalg.norm(theirs[span] - trial[span], axis=1) < need):
                continue
            was = [np.linalg.norm(t[span] - xz[span], axis=1) for t in others]
            if any(
                np.any(np.linalg.norm(t[span] - trial[span], axis=1) < np.minimum(w, clearance) - NO_CLOSER_M)
                for t, w in zip(others, was, strict=True)
            ):  # the others: no closer than before where the walk came near them anyway
                continue
            moved = span[np.linalg.norm(offset[span], axis=1) > MOVED_M]  # the ends stay where the walk was
            if not (free(trial[moved]) | ~free(xz[moved])).all():  # no point newly in the furniture
                continue
            return offset
    return None


def give_way(
    motions: Mapping[str, Motion], scene: Scene | None = None
) -> tuple[dict[str, Motion], list[str]]:
    """The motions with walkers waiting for each other where they would meet (see the module docstring).

    Args:
        motions: name -> whole motion, all on one time line (same length).
        scene: the room and its furniture, where a walker that no wait helps may step aside (None: it may not).

    Returns:
        the motions (changed ones replaced, all of one length again), and one note per wait.
    """
    tracks = {n: Track.of(m) for n, m in motions.items()}
    if len(tracks) < 2:
        return dict(motions), []
    free = _free_test(scene)
    stepped: set[tuple[str, int]] = set()  # (walker, walk start): bent aside once already
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
                hit = first_meeting(
                    table, paths[name], seg.start_frame, range(seg.start_frame, seg.end_frame), skip
                )
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
            # standing still: waiting will not clear the way; stepping round may
            if not _stepped_aside(track, seg, paths, walker, other, table.clearance, free, stepped):
                hopeless.add((walker, seg.start_frame, other))
                continue
            changed.add(walker)
            notes.append(f"{walker} steps round {other}")
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
                if first_meeting(table_others, trial, seg.start_frame, tested, skip) is None:
                    wait = count
                    break
            if wait or stop == seg.start_frame:
                break
        if not wait or slack(track, seg.end_frame, seg.action_index) < wait:
            # no wait clears the way, or none fits the story: step aside as they pass
            if not _stepped_aside(track, seg, paths, walker, other, table.clearance, free, stepped):
                hopeless.add((walker, seg.start_frame, other))
                continue
            changed.add(walker)
            notes.append(f"{walker} steps aside for {other}")
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


def _stepped_aside(
    track: Track,
    seg: Segment,
    paths: Mapping[str, np.ndarray],
    walker: str,
    other: str,
    clearance: float,
    free: Callable[[np.ndarray], np.ndarray] | None,
    stepped: set[tuple[str, int]],
) -> bool:
    """Bend the walk ``seg`` of ``walker``'s track aside round ``other`` (``sidestep``), clear of everyone on
    stage; False when it may not (no scene, or this walk was bent once already) or no bend clears the way."""
    if free is None or (walker, seg.start_frame) in stepped:
        return False
    mine = np.nan_to_num(paths[walker], nan=1e6)
    rest = [p for n, p in paths.items() if n not in (walker, other)]
    offset = sidestep(mine, seg, paths[other], clearance, free, rest)
    if offset is None:
        return False
    stepped.add((walker, seg.start_frame))
    track.root[:, 0] += offset[:, 0].astype(np.float32)
    track.root[:, 2] += offset[:, 1].astype(np.float32)
    return True


def _free_test(scene: Scene | None) -> Callable[[np.ndarray], np.ndarray] | None:
    """(N, 2) -> (N,) bool: where a sidestepping body fits among the scene's furniture (None without a scene)."""
    if scene is None:
        return None
    from services.motion.routing import scene_grid

    grid = scene_grid(scene, radius=ASIDE_BODY_M)
    return lambda pts: np.asarray(grid.is_free_xz(np.asarray(pts, float).reshape(-1, 2)), bool).reshape(-1)


__all__ = ["Track", "give_way", "is_walk", "sidestep", "slack", "take_back"]
