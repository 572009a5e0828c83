"""Camera poses of the director's shot types: medium, tracking, close-up, two-shot and over-the-shoulder.

A shot is framed on its subject (and, for two-shots and over-the-shoulder, a partner) from the
characters' smoothed tracks, so a walk is followed without gait bob. The direction a single-subject
shot looks from is fixed when the shot starts (the subject's facing then, turned three-quarters to
``side``), so the camera travels with a walking character instead of swinging round it.

Every framing keeps at least the head-to-knee body in the picture: the ``in_view`` story check
(services.render.camera_checks) counts a character shown only when 70 % of its body points are, so
the director's "close-up" is a medium close-up (head to knees), tighter than the medium shot.

Two-person shots keep the 180° rule: ``side`` says on which side of the line from the first (by name)
to the second character the camera stands, and the director keeps it for the pair for the whole story.

Conventions as services.render.camera: Y up, metres.
"""

from __future__ import annotations

import numpy as np

SHOT_MODES = ("wide", "medium", "tracking", "close_up", "two_shot", "over_shoulder")
TWO_PERSON_MODES = ("two_shot", "over_shoulder")
UP = np.array([0.0, 1.0, 0.0])

# (distance metres, eye above target metres, target above hips metres, vertical field of view degrees,
# turn off the facing in degrees); picked so a standing and a seated character fit head to knee.
FRAMING = {
    "medium": (2.7, 0.35, 0.3, 50.0, 35.0),
    "tracking": (3.0, 0.55, 0.3, 52.0, 60.0),
    "close_up": (2.1, 0.3, 0.25, 46.0, 20.0),
    # the writer's "camera close": head and chest fill the picture's upper part (head to chest a quarter of
    # the frame's height and more, the command_visible check), the trunk and the hands at work below them
    "close": (1.55, 0.25, 0.45, 46.0, 20.0),
}
TWO_SHOT_FOV = 52.0
OTS_BEHIND = 1.3  # metres behind the foreground character's chest, along the line between the two
OTS_ASIDE = 0.75  # metres to the side of that line (the shoulder is at the frame's edge, not in the middle)
OTS_FOV = 50.0


def horizontal(v: np.ndarray) -> np.ndarray:
    """v with y = 0, unit length (+Z when too short)."""
    h = np.array([v[0], 0.0, v[2]], dtype=np.float64)
    n = float(np.linalg.norm(h))
    return h / n if n > 1e-6 else np.array([0.0, 0.0, 1.0])


def turned(v: np.ndarray, degrees: float) -> np.ndarray:
    """A horizontal vector turned about +Y."""
    a = np.radians(degrees)
    c, s = np.cos(a), np.sin(a)
    return np.array([c * v[0] + s * v[2], 0.0, -s * v[0] + c * v[2]])


def single_pose(
    mode: str, hips: np.ndarray, held_facing: np.ndarray, side: int
) -> tuple[np.ndarray, np.ndarray, float]:
    """(eye, target, fov) of a one-subject shot on a character whose smoothed hips are ``hips``.

    Args:
        mode: "medium", "tracking" or "close_up".
        hips: (3,) the subject's smoothed hips.
        held_facing: (3,) the subject's facing when the shot started.
        side: +1 or -1, which three-quarter side.
    """
    dist, rise, lift, fov, turn = FRAMING[mode]
    target = hips + np.array([0.0, lift, 0.0])
    direction = turned(horizontal(held_facing), side * turn)
    return target + direction * dist + np.array([0.0, rise, 0.0]), target, fov


def line_normal(first: np.ndarray, second: np.ndarray, side: int) -> np.ndarray:
    """(3,) horizontal unit normal of the line first -> second, on ``side`` (+1: its left)."""
    d = horizontal(second - first)
    return side * np.array([d[2], 0.0, -d[0]])


def two_shot_pose(
    first_hips: np.ndarray, second_hips: np.ndarray, side: int
) -> tuple[np.ndarray, np.ndarray, float]:
    """(eye, target, fov) of a two-shot: square to the line between the two, both in the frame.

    Args:
        first_hips, second_hips: (3,) smoothed hips of the pair, first by name first.
        side: +1 or -1, the side of the line first -> second the camera keeps (180° rule).
    """
    a, b = first_hips + np.array([0.0, 0.3, 0.0]), second_hips + np.array([0.0, 0.3, 0.0])
    mid = (a + b) / 2.0
    gap = float(np.linalg.norm((b - a)[[0, 2]]))
    dist = 2.2 + 1.15 * gap
    return mid + line_normal(a, b, side) * dist + np.array([0.0, 0.45, 0.0]), mid, TWO_SHOT_FOV


def over_shoulder_pose(
    subject_hips: np.ndarray, partner_hips: np.ndarray, side: int, subject_first: bool
) -> tuple[np.ndarray, np.ndarray, float]:
    """(eye, target, fov) over the partner's shoulder onto the subject (who speaks or acts).

    Args:
        subject_hips, partner_hips: (3,) smoothed hips.
        side: the pair's side of the line first -> second (by name), as for the two-shot.
        subject_first: whether the subject is the first of the pair by name.
    """
    s, p = subject_hips + np.array([0.0, 0.3, 0.0]), partner_hips + np.array([0.0, 0.3, 0.0])
    first, second = (s, p) if subject_first else (p, s)
    normal = line_normal(first, second, side)
    toward = horizontal(s - p)
    eye = p - toward * OTS_BEHIND + normal * OTS_ASIDE + np.array([0.0, 0.35, 0.0])
    return eye, s, OTS_FOV
