"""Where a hiding action puts its character relative to the object it names: "hides behind the door",
"crouches under the table".

The parse keeps the object ("door") but not the preposition, so the place word is read back from the
sentence next to the object's word. "Behind" is judged on the object's own front (catalog objects face +Z):
behind the door is on its back side or against the wall beside it, never out in front of it, where a viewer
sees the character standing before the door rather than hidden by it.
"""

from __future__ import annotations

import re

import numpy as np

from proto.fidelity import Check
from wana.assets.catalog import asset_for, object_to_world
from wana.fidelity.acts import Act
from wana.fidelity.bodies import Body
from wana.fidelity.words import frame_list, third_person
from wana.fidelity.world import World, display

PLACE_WORDS = ("behind", "in front of", "under", "underneath", "beneath", "beside", "next to")
# Only hiding is judged: "behind" a desk or a counter is its working side ("sits behind her desk"), the
# catalog's front, while behind a door or a sofa one hides from is its back; hiding is about not being seen.
HIDING = ("hide", "crouch", "duck", "take cover", "lurk")
IN_FRONT_M = (
    0.35  # metres past an object's front face a body (its own depth) may stand and still be beside it
)
BESIDE_M = 1.0  # metres from the object's footprint: beside / next to / behind it at all
PLACE_SHARE = 0.5  # of the action's frames at the stated place


def stated_place(act: Act) -> tuple[str, str] | None:
    """(place word, object id) when the sentence says where the action happens relative to its target."""
    target = act.node.target or act.node.destination
    if not target or target not in act.words or not act.text:
        return None
    verb = act.node.verb.lower()
    if act.node.action not in HIDING and not any(verb == h or verb.startswith(h + " ") for h in HIDING):
        return None
    word = re.escape(act.words[target].lower())
    places = "|".join(re.escape(p) for p in PLACE_WORDS)
    m = re.search(rf"\b({places})\s+(?:the|a|an|his|her|their|its)\s+(?:\w+\s+)?{word}\b", act.text.lower())
    if m is None:
        return None
    place = {"underneath": "under", "beneath": "under", "next to": "beside"}.get(m.group(1), m.group(1))
    return place, target


def placement(act: Act, body: Body, world: World) -> Check | None:
    """The `contact` check of an action with a stated place: the hips there on at least half its frames."""
    said = stated_place(act)
    seg = act.clip
    if said is None or seg is None:
        return None
    place, target = said
    found = world.find(target)
    who, verb = act.character, act.node.verb or act.node.action
    where = f"{place} the {display(target)}"
    if not found:
        return Check(
            name="contact", character=who, ok=False, reason=f"there is no {display(target)} to be {where}"
        )
    frames = np.arange(seg.start_frame, min(seg.end_frame, body.frames))
    if not len(frames):
        return None
    hips = body.joint("Hips")[frames]
    best, best_share, best_local = None, -1.0, None
    for placed in found:
        m = object_to_world(placed)
        local = (hips - m[:3, 3]) @ np.linalg.inv(m[:3, :3]).T  # object frame: front is +Z
        half = asset_for(placed).dims / 2.0
        ok = _at(place, local, half, float(asset_for(placed).dims[1]))
        if ok.mean() > best_share:
            best, best_share, best_local = placed, float(ok.mean()), local
    assert best is not None and best_local is not None
    if best_share >= PLACE_SHARE:
        return Check(name="contact", character=who, ok=True, reason=f"{who} {third_person(verb)} {where}")
    half = asset_for(best).dims / 2.0
    front = float(np.median(best_local[:, 2])) - half[2]
    if place in ("behind", "beside") and front > IN_FRONT_M:
        why = f"{who} stands {front:.1f} m in front of the {display(best.id)}, in full view, not {place} it"
    else:
        gap = float(np.median(np.hypot(*np.maximum(np.abs(best_local[:, [0, 2]]) - half[[0, 2]], 0.0).T)))
        why = f"{who} is {gap:.1f} m from the {display(best.id)}, not {place} it"
    return Check(name="contact", character=who, ok=False, reason=why, frames=frame_list(frames))


def _at(place: str, local: np.ndarray, half: np.ndarray, height: float) -> np.ndarray:
    """(F,) whether object-frame hips (F, 3) are at the place relative to a box of half extents `half`."""
    out_x = np.maximum(np.abs(local[:, 0]) - half[0], 0.0)
    out_z = np.maximum(np.abs(local[:, 2]) - half[2], 0.0)
    near = np.hypot(out_x, out_z) <= BESIDE_M
    if place == "under":
        return (out_x == 0.0) & (out_z == 0.0) & (local[:, 1] < height)
    if place == "in front of":
        return near & (local[:, 2] > half[2])
    if place == "behind":
        return near & (local[:, 2] <= half[2] + IN_FRONT_M) & ((local[:, 2] < -half[2]) | (out_x > 0.0))
    return near & (local[:, 2] <= half[2] + IN_FRONT_M)  # beside: next to it, not out in front


__all__ = ["placement", "stated_place"]
