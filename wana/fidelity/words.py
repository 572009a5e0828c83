"""Plain words for the checks' reasons: body parts, verbs, frame ranges."""

from __future__ import annotations

import numpy as np


def joint_words(joints: list[str] | tuple[str, ...]) -> str:
    limbs = {j.replace("Middle1", "") for j in joints}
    if limbs == {"LeftHand", "RightHand"}:
        return "hands"
    if limbs == {"Hips"}:
        return "hips"
    return " and ".join(
        sorted({"left hand" if "Left" in j else "right hand" if "Right" in j else j.lower() for j in limbs})
    )


def stays(parts: str) -> str:
    return "stay" if parts.endswith("s") or " and " in parts else "stays"


def third_person(verb: str) -> str:
    """ "hammer" -> "hammers", "watch" -> "watches", "carry" -> "carries" (the first word of a phrase)."""
    head, _, rest = verb.partition(" ")
    if head.endswith(("s", "sh", "ch", "x", "z", "o")):
        head += "es"
    elif head.endswith("y") and head[-2:-1] not in "aeiou":
        head = head[:-1] + "ies"
    else:
        head += "s"
    return f"{head} {rest}".strip()


def frame_list(frames: np.ndarray | range | list[int], limit: int = 120) -> list[int]:
    """Story frames for a check, at most `limit` of them (evenly spread, first and last kept)."""
    arr = np.asarray(list(frames) if isinstance(frames, range) else frames, dtype=np.int64)
    if len(arr) > limit:
        arr = arr[np.linspace(0, len(arr) - 1, limit).round().astype(np.int64)]
    return [int(f) for f in arr]


def span_words(frames: np.ndarray | list[int]) -> str:
    frames = list(frames)
    if not frames:
        return ""
    return f"frame {frames[0]}" if len(frames) == 1 else f"frames {frames[0]}-{frames[-1]}"
