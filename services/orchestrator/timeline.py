"""When each character's actions happen: story order, then one motion per character.

Characters act at the same time, but the text is a story: an action sentence starts no earlier than the
previous action sentence did (so "Eve sits. Tom walks in." has Tom enter once Eve begins to sit), the
characters of one sentence start together, and a character's actions follow one another. A response (the
social model's ResponseTiming: "Tom criticizes Mary. Mary apologizes.") starts once the action it answers
is over plus the sampled delay. `wait N seconds` holds every later sentence until all earlier actions are
over, plus N seconds. Gaps are filled by holding the pose; nothing here re-synthesises motion.
"""

from __future__ import annotations

from dataclasses import dataclass

import msgspec
import numpy as np

from proto.motion_data import Motion, PropTrack, Segment
from wana.arrays import from_wire, to_wire
from wana.domain.units import FPS


@dataclass(frozen=True)
class Beat:
    """One action in document order."""

    sentence_id: str
    character: str
    k: int  # index of the action among the character's actions
    frames: int  # length of its motion


def schedule(
    beats: list[Beat],
    waits: dict[str, float] | None = None,
    order: list[str] | None = None,
    responses: dict[tuple[str, int], tuple[tuple[str, int], float]] | None = None,
) -> dict[tuple[str, int], int]:
    """Start frame of every (character, k).

    Args:
        beats: the actions in document order.
        waits: sentence id of a `wait` command -> seconds.
        order: every sentence id in document order (needed to place the waits); defaults to the beats' order.
        responses: (character, k) -> ((other, j), delay seconds): action k answers the other's action j
            and starts no earlier than its end plus the delay (when that action comes earlier in the text).

    Returns:
        (character, k) -> start frame.
    """
    waits = waits or {}
    responses = responses or {}
    ends: dict[tuple[str, int], int] = {}
    order = order or list(dict.fromkeys(b.sentence_id for b in beats))
    by_sentence: dict[str, list[Beat]] = {}
    for b in beats:
        by_sentence.setdefault(b.sentence_id, []).append(b)
    free: dict[str, int] = {}  # character -> first free frame
    floor = 0  # no sentence starts before this frame
    latest_end = 0
    starts: dict[tuple[str, int], int] = {}
    for sid in order:
        if sid in waits:
            floor = max(floor, latest_end + int(round(waits[sid] * FPS)))
            continue
        group = by_sentence.get(sid, [])
        if not group:
            continue
        # Everyone in the sentence starts together, once each of them is free ("They shake hands").
        begin = max([floor] + [free.get(b.character, 0) for b in group])
        for b in group:
            answered = responses.get((b.character, b.k))
            if answered is not None and answered[0] in ends:
                begin = max(begin, ends[answered[0]] + int(round(answered[1] * FPS)))
        for b in group:
            start = max(free.get(b.character, 0), begin)
            starts[(b.character, b.k)] = start
            free[b.character] = start + b.frames
            ends[(b.character, b.k)] = start + b.frames
            latest_end = max(latest_end, start + b.frames)
        floor = begin
    return starts


def _still_held(props: list[PropTrack], frame: int, gap: int) -> list[PropTrack]:
    """A prop in the hand when a hold begins stays there, still, for the hold's ``gap`` frames."""
    last = [p for p in props if p.end_frame == frame]
    out = []
    for p in last:
        pos, rot = from_wire(p.position), from_wire(p.rotation)
        out.append(
            msgspec.structs.replace(
                p,
                start_frame=frame,
                end_frame=frame + gap,
                position=to_wire(np.repeat(pos[-1:], gap, 0).astype(np.float32)),
                rotation=to_wire(np.repeat(rot[-1:], gap, 0).astype(np.float32)),
            )
        )
    return out


def assemble(name: str, pieces: list[Motion], starts: list[int], total: int | None = None) -> Motion:
    """Join per-action motions at their start frames, holding the pose through the gaps.

    Args:
        name: the character.
        pieces: one Motion per action, in order.
        starts: start frame of each piece (non-decreasing, each at or after the previous piece's end).
        total: pad the end (holding the last pose) to this many frames.
    """
    roots: list[np.ndarray] = []  # (n_i, 3) float root positions per piece or hold
    rots: list[np.ndarray] = []  # (n_i, J, 4) float joint rotations
    contacts: list[np.ndarray] = []  # (n_i, 2) uint8 foot contacts
    segments: list[Segment] = []
    props: list[PropTrack] = []  # held objects, frames moved with their piece
    frame = 0
    for piece, start in zip(pieces, starts, strict=True):
        root, rot = from_wire(piece.root_position), from_wire(piece.rotations)
        foot = (
            from_wire(piece.foot_contact)
            if piece.foot_contact is not None
            else np.ones((len(root), 2), np.uint8)
        )
        gap = start - frame
        if gap > 0:
            props += _still_held(props, frame, gap)
            hold_root, hold_rot = (roots[-1][-1], rots[-1][-1]) if roots else (root[0], rot[0])
            roots.append(np.repeat(hold_root[None], gap, 0))
            rots.append(np.repeat(hold_rot[None], gap, 0))
            contacts.append(np.ones((gap, 2), np.uint8))
            segments.append(Segment(index=len(segments), action="hold", start_frame=frame, end_frame=start))
            frame = start
        for seg in piece.segments:
            segments.append(
                msgspec.structs.replace(
                    seg,
                    index=len(segments),
                    start_frame=seg.start_frame + frame,
                    end_frame=seg.end_frame + frame,
                )
            )
        props += [
            msgspec.structs.replace(p, start_frame=p.start_frame + frame, end_frame=p.end_frame + frame)
            for p in piece.props
        ]
        roots.append(root)
        rots.append(rot)
        contacts.append(foot)
        frame += len(root)
    if total is not None and total > frame and roots:
        gap = total - frame
        props += _still_held(props, frame, gap)
        roots.append(np.repeat(roots[-1][-1][None], gap, 0))
        rots.append(np.repeat(rots[-1][-1][None], gap, 0))
        contacts.append(np.ones((gap, 2), np.uint8))
        segments.append(Segment(index=len(segments), action="hold", start_frame=frame, end_frame=total))
    first = pieces[0]
    return Motion(
        character=name,
        fps=first.fps,
        joint_names=list(first.joint_names),
        root_position=to_wire(np.concatenate(roots).astype(np.float32)),
        rotations=to_wire(np.concatenate(rots).astype(np.float32)),
        foot_contact=to_wire(np.concatenate(contacts).astype(np.uint8)),
        segments=segments,
        props=props,
    )
