"""Object states from the timed actions: "Tom opens the door", "Eve turns on the lamp", "closes the laptop".

After story timing each character's motion says which action plays in which frames; an action aimed at a
stateful object (wana.domain.object_state.STATEFUL) changes that object's state from the frame the hand
touches it (the clip's contact window) over CHANGE_S, and the state holds for the rest of the story, so
a door opened in one sentence stays open until a later sentence closes it. The result is one
ObjectStateTrack per changed (object, state) on the final scene; the renderer and the GLB play it.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence

import msgspec

from proto.motion_data import Motion
from proto.scene import ObjectStateTrack, Scene
from proto.ssg import ActionNode, CharacterNode
from services.orchestrator.document import Sentence
from wana.domain.actions import get_clip
from wana.domain.object_geometry import find_object
from wana.domain.object_state import STATEFUL

CHANGE_S = {"open": 0.6, "on": 0.1}  # seconds a change takes: a door leaf swings, a light comes on at once
OFF_WORDS = re.compile(r"\b(off|out|close[sd]?|closing|shut[s]?|shutting)\b", re.I)
ON_WORDS = re.compile(r"\b(on|up|open[s]?|opened|opening|start[s]?)\b", re.I)
CLOSING = {"close_door"}


def _wanted(action: ActionNode, text: str, states: Mapping[str, float]) -> tuple[str, float] | None:
    """(state, new value) an action asks of an object with these states, or None (it changes nothing)."""
    name = action.action
    words = f"{action.verb} {text}"
    if name in CLOSING or (name.startswith("open_") and OFF_WORDS.search(action.verb)):
        return ("open", 0.0) if "open" in states else None
    if name.startswith("open_") or name == "pull":
        return ("open", 1.0) if "open" in states else None
    if name in ("press_switch", "push_button") and "on" in states:
        if OFF_WORDS.search(words):
            return "on", 0.0
        if ON_WORDS.search(words):
            return "on", 1.0
        return "on", -1.0  # no particle ("flips the switch"): toggles
    return None


def _touch(motion: Motion, k: int, action: str) -> int | None:
    """The frame the hand reaches the object in action k's own segment (its clip's contact window start)."""
    for seg in motion.segments:
        if seg.action_index != k or seg.action != action:
            continue
        try:
            clip = get_clip(action)
        except KeyError:
            return seg.start_frame
        window = clip.interaction.window if clip.interaction is not None else (0.0, 0.0)
        frac = window[0] / clip.duration_s if clip.duration_s > 0 else 0.0
        return seg.start_frame + int(round(frac * (seg.end_frame - seg.start_frame)))
    return None


def state_tracks(
    scene: Scene,
    characters: Mapping[str, tuple[CharacterNode, list[str]]],
    motions: Mapping[str, Motion],
    sentences: Sequence[Sentence],
    fps: int = 30,
) -> list[ObjectStateTrack]:
    """One track per (object, state) some action changes, keys in frame order."""
    texts = {s.id: s for s in sentences}
    changes: list[tuple[int, str, str, str, float]] = []  # (frame, object id, category, state, value)
    for name, (node, sids) in characters.items():
        motion = motions.get(name)
        if motion is None:
            continue
        for k, action in enumerate(node.actions):
            placed = find_object(scene, action.target) if action.target else None
            if placed is None or placed.category not in STATEFUL:
                continue
            s = texts.get(sids[k])
            text = ""
            if s is not None:
                a, b = action.span.start - s.start, action.span.end - s.start
                text = s.text[a:b] if 0 <= a < b <= len(s.text) else s.text
            want = _wanted(action, text, STATEFUL[placed.category])
            frame = _touch(motion, k, action.action)
            if want is not None and frame is not None:
                changes.append((frame, placed.id, placed.category, *want))
    current: dict[tuple[str, str], float] = {}
    keys: dict[tuple[str, str], list[tuple[int, float]]] = {}
    for frame, oid, category, state, value in sorted(changes):
        key = (oid, state)
        was = current.get(key, STATEFUL[category][state])
        new = 1.0 - was if value < 0 else value
        if new == was:
            continue
        end = frame + max(1, int(round(CHANGE_S[state] * fps)))
        track = keys.setdefault(key, [])
        if track and track[-1][0] >= frame:  # a change before the last one finished: from where it is now
            frame = track[-1][0] + 1
            end = max(end, frame + 1)
        track += [(frame, was), (end, new)]
        current[key] = new
    return [
        ObjectStateTrack(object_id=oid, state=state, frames=[f for f, _ in ks], values=[v for _, v in ks])
        for (oid, state), ks in sorted(keys.items())
    ]


def with_states(
    scene: Scene,
    characters: Mapping[str, tuple[CharacterNode, list[str]]],
    motions: Mapping[str, Motion],
    sentences: Sequence[Sentence],
) -> Scene:
    """The scene with the story's object state tracks (unchanged when no action changes a state)."""
    tracks = state_tracks(scene, characters, motions, sentences)
    return msgspec.structs.replace(scene, states=tracks) if tracks or scene.states else scene


__all__ = ["CHANGE_S", "state_tracks", "with_states"]
