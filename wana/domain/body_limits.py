"""How fast a body can move: the speeds the motion service keeps its clips under and the story checks
(wana.fidelity.body_checks) hold every animation to.

A person's hips travel at most about 6 m/s (a sprint) and a hand at about 10 m/s in everyday actions; a
throw, a punch or a kick is a hand or foot at 10-20 m/s by nature (a thrown ball leaves the hand at 15 m/s
and more), so inside those clips a hand may reach STRIKE_MAX_MS.
"""

from __future__ import annotations

HIPS_MAX_MS = 6.0  # metres per second between two frames
HANDS_MAX_MS = 10.0
STRIKES = ("throw", "punch", "kick", "punch_bag", "box", "slap")
STRIKE_MAX_MS = 20.0


def hand_limit(action: str) -> float:
    """The fastest a hand may move in an action (m/s)."""
    return STRIKE_MAX_MS if action in STRIKES else HANDS_MAX_MS
