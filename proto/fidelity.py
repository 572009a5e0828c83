"""Story fidelity: does the animation show what each sentence says? (DESIGN §2, "What the animation must show")

Every sentence gets checks derived from its parse (what it asks) and from the computed animation (what the
pipeline made), each true or false with a plain-words reason and the frames involved. The checks are computed
by `wana.fidelity` (body, scene, continuity, entrances) and by the render service (camera and commands, which
only it knows); a sentence's verdict joins them.
"""

from __future__ import annotations

from typing import Literal

import msgspec

Verdict = Literal["ok", "partial", "failed"]

# Stable check names: eval/story.py's JSON `checks` map and the report use them as keys.
CHECK_NAMES = (
    "object_exists",  # every object a scene sentence names is in the room, with the stated count
    "relation_holds",  # every relation a scene sentence states holds geometrically
    "performed",  # the action is done, by the right character, in story order
    "contact",  # the clip's contact joint within 5 cm of the object's contact point for >= half the frames
    "supported",  # no sitting, lying or leaning on air
    "penetration",  # no body part inside furniture beyond 3 cm except at the stated contact
    "overlap",  # no two characters' bodies overlapping
    "continuity",  # no joint faster than physically possible, no pose popping between actions
    "entrance",  # "walks in"/"enters" starts outside or at a door; nobody visible before their sentence
    "in_view",  # the acting character in frame and >= 70 % unoccluded for >= 90 % of its frames
    "command_visible",  # a camera or light command is in force for >= 1.5 s of the video
)


class Check(msgspec.Struct, frozen=True, kw_only=True):
    """One checkable claim about one sentence."""

    name: str  # one of CHECK_NAMES
    ok: bool
    reason: str  # plain words: what was verified, or what is wrong ("the hammer is not in Eve's hand")
    frames: list[int] = []  # frames involved (the failing ones when ok is False), 30 fps story frames
    character: str = ""  # the character the check is about, "" for scene checks
    essential: bool = False  # True when failing it means the sentence is not shown at all


class SentenceVerdict(msgspec.Struct, frozen=True, kw_only=True):
    sentence_id: str
    verdict: Verdict
    checks: list[Check] = []


def verdict_of(checks: list[Check]) -> Verdict:
    """ok when every check passes; failed when an essential check fails or none passes; else partial.

    A sentence with no checks at all is ok only if it asks for nothing (callers add a failing check when
    something was asked and dropped, so that nothing the system could not honour passes silently).
    """
    if all(c.ok for c in checks):
        return "ok"
    if any(c.essential and not c.ok for c in checks) or not any(c.ok for c in checks):
        return "failed"
    return "partial"
