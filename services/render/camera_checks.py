"""The story checks only the render service can make, because only it knows the camera (issue 13).

- ``in_view``: for each action sentence, each acting character is inside the picture and at least
  VISIBLE_SHARE unoccluded (services.render.visibility) on at least FRAME_SHARE of its action's frames. A
  character is judged by its head, trunk and arms: legs under a table, behind a chair or cut off by a
  medium shot leave a person plainly seen (a standing woman behind a meeting table read as 37 % hidden).
  The seat it sits on and the thing its hands are on hide nothing of it (a sofa's back seen from behind
  hides what sitting hides; a typist is seen across her laptop's screen).
- ``command_visible``: each camera or light/weather command is in force for at least
  MIN_COMMAND_FRAMES of the video (until a later command of the same kind replaces it, or the end).

Both read the same ``Staging`` the renderer draws from, so they judge the camera the MP4 shows.

    checks = camera_checks(scene, motions, commands, sentences, width=640, height=480)
    checks["s8"]  # [Check(name="in_view", ok=False, reason="Tom is out of frame for 2.1 s of ...")]
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from msgspec.structs import replace

from proto.fidelity import Check
from proto.motion_data import Motion
from proto.render import TimedCommand
from proto.scene import Scene
from services.render.camera import intrinsics, project
from services.render.director import Shot
from services.render.sightlines import Furniture
from services.render.staging import CameraTrack, Staging
from services.render.timeline import (
    COMMAND_HOLD_FRAMES,
    SentenceRef,
    as_motion_list,
    as_sentences,
    place_commands,
)
from services.render.video import FPS
from services.render.visibility import (
    LEGS,
    SEATED_HIPS_M,
    VISIBLE_SHARE,
    BodyView,
    capsule_radii,
    held_under,
    judged_view,
    seat_under,
    shown_share,
    unhide_own_seat,
)
from wana.domain.skeleton import JOINT_INDEX

__all__ = [
    "LEGS",
    "SEATED_HIPS_M",
    "VISIBLE_SHARE",
    "held_under",
    "seat_under",
    "shown_share",
    "unhide_own_seat",
]

FRAME_SHARE = 0.9  # of the action's frames that must show the character
MIN_COMMAND_FRAMES = COMMAND_HOLD_FRAMES  # 1.5 s: what the render timeline holds the last command for
# "camera close" is judged by the picture: someone's head top to chest spans at least this share of the
# frame's height: more than a full figure can (a whole body with headroom spans at most a fifth; the render's
# own close shot of a standing person, knees up, about 27 %; a head and shoulders half).
CLOSE_SPAN = 0.22
HEAD_TOP_M = 0.18  # metres above the Head joint (the skull's base) to the top of the head


@dataclass(frozen=True)
class ViewTally:
    """Frame counts behind one in_view check, for shares over a corpus (eval/story.py).

    Attributes:
        sentence_id, character: the check's sentence and acting character.
        frames: the character's action frames in the sentence.
        in_frame: frames with at least VISIBLE_SHARE of its body points inside the picture.
        occluded: of those, frames where less than VISIBLE_SHARE of its body points is unhidden.
    """

    sentence_id: str
    character: str
    frames: int
    in_frame: int
    occluded: int


def camera_checks(
    scene: Scene,
    motions: Iterable[Motion] | Mapping[str, Motion],
    commands: Iterable[Any] | None,
    sentences: Iterable[Any] | None,
    *,
    width: int = 640,
    height: int = 480,
    tally: list[ViewTally] | None = None,
) -> dict[str, list[Check]]:
    """The in_view and command_visible checks of the video ``write_outputs`` would make.

    Args:
        scene: the composed scene.
        motions: one Motion per character (list or name -> Motion).
        commands: as ``write_outputs`` takes them (``Command``, ``(sentence_id, Command)`` or ``TimedCommand``).
        sentences: the document's sentences in order (see services.render.timeline.as_sentences).
        width, height: the video's size in pixels.
        tally: when given, one ViewTally per in_view check is appended (frame counts for corpus shares).

    Returns:
        Sentence id -> its checks (sentences with no action and no command have none).
    """
    mlist = as_motion_list(motions)
    sents = list(sentences or [])
    stage = Staging.build(scene, mlist, place_commands(commands, sents, mlist))
    return staged_checks(stage, sents, width=width, height=height, tally=tally)


def staged_checks(
    stage: Staging,
    sentences: Iterable[Any] | None,
    *,
    width: int,
    height: int,
    track: CameraTrack | None = None,
    tally: list[ViewTally] | None = None,
) -> dict[str, list[Check]]:
    """The camera checks of a staged video (the renderer's own ``staging``); ``track`` when already planned."""
    track = track if track is not None else stage.camera_track(width, height)
    out = in_view_checks(stage, track, sentences, width=width, height=height, tally=tally)
    joints = {name: rig.joint_positions for name, rig in stage.rigs.items()}
    for sid, checks in command_checks(stage.commands, stage.n_frames, stage.shots).items():
        out.setdefault(sid, []).extend(close_in_picture(c, joints, track) for c in checks)
    return out


def close_span(joints: Mapping[str, np.ndarray], track: CameraTrack, frames: Sequence[int]) -> np.ndarray:
    """(F,) on each frame the largest share of the picture's height any character's head top to chest
    takes at its depth in the rendered camera: its length as the lens scales it there, whichever way the
    camera looks at it (a close shot from above foreshortens the head-to-chest line to nothing on screen
    while the two fill the picture: gump-living_room-3 s9). 0 for one behind the camera or off the
    picture's sides."""
    out = np.zeros(len(frames))
    head_i, chest_i = JOINT_INDEX["Head"], JOINT_INDEX["Spine2"]
    for k, f in enumerate(frames):
        pose = track.pose(int(f))
        fy = intrinsics(pose.fov_deg, track.width, track.height)[1]
        for pos in joints.values():
            if not len(pos):
                continue
            g = min(int(f), len(pos) - 1)  # the held end of the video repeats the final pose
            top = pos[g, head_i] + (0.0, HEAD_TOP_M, 0.0)
            uv, z = project(np.stack([top, pos[g, chest_i]]), pose, track.width, track.height)
            if np.any(z <= 0.05) or not (0.0 <= float(uv[:, 0].mean()) <= track.width):
                continue
            length = float(np.linalg.norm(top - pos[g, chest_i]))
            out[k] = max(out[k], fy * length / float(z.mean()) / track.height)
    return out


def close_in_picture(check: Check, joints: Mapping[str, np.ndarray], track: CameraTrack) -> Check:
    """A passing "camera close" check, judged again by the picture: on at least MIN_COMMAND_FRAMES of the
    frames it is in force someone's head to chest fills CLOSE_SPAN of the frame's height (labelled
    duo-kitchen-03 s8: the close shot was in force for 1.5 s while Anna stayed full-figure, the camera
    moving back and up)."""
    if not check.ok or not check.reason.startswith("camera close ") or not check.frames:
        return check
    frames = [f for f in check.frames if f < len(track)]
    span = close_span(joints, track, frames)
    close = int((span >= CLOSE_SPAN).sum())
    if close >= MIN_COMMAND_FRAMES:
        return replace(
            check, reason=f"{check.reason}; a head and chest fill {float(np.max(span)):.0%} of the frame"
        )
    return replace(
        check,
        ok=False,
        reason=f"camera close is in force but the picture never comes close: a head to chest spans at most "
        f"{float(np.max(span, initial=0.0)):.0%} of the frame's height (close on {close / FPS:.1f} s, needs "
        f"{CLOSE_SPAN:.0%} for {MIN_COMMAND_FRAMES / FPS:.1f} s)",
        frames=[int(f) for f, v in zip(frames, span, strict=True) if v < CLOSE_SPAN],
    )


def action_frames(motions: Iterable[Motion], n_frames: int) -> dict[str, dict[str, np.ndarray]]:
    """Sentence id -> character -> (F,) sorted frames of that character's segments for the sentence."""
    spans: dict[str, dict[str, set[int]]] = {}
    for m in motions:
        for seg in m.segments:
            if not seg.sentence_id:
                continue
            frames = range(max(0, seg.start_frame), min(seg.end_frame, n_frames))
            spans.setdefault(seg.sentence_id, {}).setdefault(m.character, set()).update(frames)
    return {
        sid: {c: np.array(sorted(f), dtype=np.int64) for c, f in chars.items() if f}
        for sid, chars in spans.items()
    }


def _quote(ref: SentenceRef | None, fallback: str) -> str:
    text = ref.text.strip().rstrip(".!?;$ ") if ref is not None else ""
    return f"'{text}'" if text else fallback


def in_view_checks(
    stage: Staging,
    track: CameraTrack,
    sentences: Iterable[Any] | None,
    *,
    width: int,
    height: int,
    tally: list[ViewTally] | None = None,
) -> dict[str, list[Check]]:
    """One ``in_view`` check per (action sentence, acting character), sentence id -> checks (and, with
    ``tally``, its frame counts appended there)."""
    refs = {s.id: s for s in as_sentences(sentences)}
    joints = {name: rig.joint_positions for name, rig in stage.rigs.items()}
    furniture = Furniture.from_scene(stage.scene)
    radii = {
        name: capsule_radii(rig.character.rest_joint_positions(), rig.character.vertices)
        for name, rig in stage.rigs.items()
    }
    out: dict[str, list[Check]] = {}
    for sid, chars in action_frames(stage.motions.values(), stage.n_frames).items():
        for who in sorted(chars):
            frames = chars[who]
            view, part = judged_view(
                who, frames, joints, track, furniture, stage.scene.room, width, height, radii
            )
            shown = part >= VISIBLE_SHARE
            share = float(shown.mean())
            if tally is not None:
                framed = view.in_frame.mean(axis=1) >= VISIBLE_SHARE
                tally.append(
                    ViewTally(
                        sentence_id=sid,
                        character=who,
                        frames=len(frames),
                        in_frame=int(framed.sum()),
                        occluded=int((framed & ~shown).sum()),
                    )
                )
            what = _quote(refs.get(sid), f"its action in sentence {sid}")
            ok = share >= FRAME_SHARE
            if ok:
                reason = (
                    f"{who} is in view and at least {VISIBLE_SHARE:.0%} unoccluded for {share:.0%} of {what}"
                )
            else:
                reason = _in_view_failure(who, what, view, shown, share)
            out.setdefault(sid, []).append(
                Check(
                    name="in_view",
                    ok=ok,
                    reason=reason,
                    frames=[int(f) for f in (frames if ok else frames[~shown])],
                    character=who,
                    essential=share < 0.25,
                )
            )
    return out


def _in_view_failure(who: str, what: str, view: BodyView, shown: np.ndarray, share: float) -> str:
    """'Tom is out of frame for 2.1 s of ...; Tom is 60 % hidden behind the bookshelf for 0.5 s'."""
    failing = ~shown
    out_of_frame = failing & (view.in_frame.mean(axis=1) < VISIBLE_SHARE)
    hidden = failing & ~out_of_frame
    parts = []
    if out_of_frame.any():
        parts.append(f"{who} is out of frame for {out_of_frame.sum() / FPS:.1f} s of {what}")
    if hidden.any():
        covered = 1.0 - view.visible[hidden][:, ~LEGS].mean()
        blockers = Counter(int(k) for k in view.hidden_by[hidden].reshape(-1) if k >= 0)
        total = sum(blockers.values())
        top = [view.occluders[k] for k, n in blockers.most_common(2) if n >= 0.25 * total]
        behind = " and ".join(top) if top else "something"
        lead = f"{who} is" if not parts else "and"
        tail = "" if parts else f" of {what}"
        parts.append(f"{lead} {covered:.0%} hidden behind {behind} for {hidden.sum() / FPS:.1f} s{tail}")
    return (" ".join(parts) if len(parts) == 2 else parts[0]) + (
        f" (shown on {int(share * 100)}% of its frames, needs {FRAME_SHARE:.0%})"
    )


def command_word(tc: TimedCommand) -> str:
    """'camera close', 'night'."""
    c = tc.command
    return f"camera {c.value}" if c.kind == "camera" else c.value


def command_checks(
    commands: Iterable[TimedCommand], n_frames: int, shots: Sequence[Shot] | None = None
) -> dict[str, list[Check]]:
    """One ``command_visible`` check per camera or weather command with a sentence id.

    A command is in force from its frame until the next command of the same kind (camera; weather and
    light) or the end of the video. With the director's shots, a camera command is in force on the frames
    of its own shots only: "camera close" ends with its subject's next action, and the video then cuts
    back to the director's framing however long the timeline holds the command.

    Args:
        commands: timed commands in frame order (timeline.place_commands).
        n_frames: the video's length.
        shots: the director's plan (Staging.shots); None or empty: the timeline alone.
    """
    timed = [tc for tc in commands if tc.command.kind in ("camera", "weather")]
    out: dict[str, list[Check]] = {}
    for i, tc in enumerate(timed):
        if not tc.sentence_id:
            continue
        nxt = next((t for t in timed[i + 1 :] if t.command.kind == tc.command.kind), None)
        start = min(max(0, tc.frame), n_frames)
        end = min(nxt.frame, n_frames) if nxt is not None else n_frames
        shown = max(0, end - start)
        word = command_word(tc)
        own = _own_shots(tc, shots) if tc.command.kind == "camera" else None
        if own is not None:
            frames = sorted({f for s in own for f in range(max(s.start, 0), min(s.end, n_frames))})
            if len(frames) < shown:
                shown, end = len(frames), (frames[-1] + 1 if frames else start)
                start = frames[0] if frames else start
                nxt = None if nxt is None or nxt.frame > end else nxt
        ok = shown >= MIN_COMMAND_FRAMES
        if ok:
            reason = f"{word} is in force for {shown / FPS:.1f} s from {start / FPS:.1f} s"
        elif own is not None and end < n_frames and (nxt is None or nxt.frame > end):
            reason = (
                f"{word} is shown for only {shown / FPS:.1f} s before the director cuts away "
                f"(needs {MIN_COMMAND_FRAMES / FPS:.1f} s)"
            )
        elif nxt is not None and nxt.frame < n_frames:
            reason = (
                f"{word} is in force for only {shown / FPS:.1f} s before {command_word(nxt)} replaces it "
                f"(needs {MIN_COMMAND_FRAMES / FPS:.1f} s)"
            )
        else:
            reason = (
                f"{word} takes effect {shown / FPS:.1f} s before the end of the video "
                f"(needs {MIN_COMMAND_FRAMES / FPS:.1f} s)"
            )
        frames_named = list(range(start, start + shown)) if shown else [max(0, n_frames - 1)]
        out.setdefault(tc.sentence_id, []).append(
            Check(name="command_visible", ok=ok, reason=reason, frames=frames_named, essential=shown == 0)
        )
    return out


def _own_shots(tc: TimedCommand, shots: Sequence[Shot] | None) -> list[Shot] | None:
    """The director's shots of one camera command (source "command", its sentence), None without a plan."""
    if not shots:
        return None
    return [s for s in shots if s.source == "command" and s.sentence_id == tc.sentence_id]
