"""Objects whose state a story changes: which categories have a state, its value at a frame, and the
moving or glowing part of each (a door leaf on its hinge, a laptop lid, a lamp's shade, a screen).

The catalog meshes are one piece each; the part a state moves is found here from the generator's layout
(wana/assets/generators: the door's leaf between its frame posts, the laptop's lid behind its base, the
panel coloured with the "screen" tone), so every output (MP4, GLB) poses the same part the same way.
"""

from __future__ import annotations

import numpy as np

from proto.scene import ObjectStateTrack

# category -> {state: value at rest (before any sentence changes it)}
STATEFUL: dict[str, dict[str, float]] = {
    "door": {"open": 0.0},
    "refrigerator": {"open": 0.0},
    "wardrobe": {"open": 0.0},
    "cabinet": {"open": 0.0},
    "microwave": {"open": 0.0},
    "laptop": {"open": 1.0, "on": 0.0},
    "lamp": {"on": 0.0},
    "floor_lamp": {"on": 0.0},
    "desk_lamp": {"on": 0.0},
    "television": {"on": 0.0},
    "monitor": {"on": 0.0},
    "computer": {"on": 0.0},
}
LIGHTS = ("lamp", "floor_lamp", "desk_lamp")  # categories that light the room when on
DOOR_SWING = np.radians(85.0)  # how far an open door leaf turns on its hinge
LID_TILT = 0.3  # radians the generator leans an open laptop lid back from upright (electronics.laptop)
SCREEN_RGB = (20, 24, 30)  # wana.assets.params TONES["screen"]: the colour of a switched-off screen
LIT_SCREEN_RGB = (150, 200, 245)
LIT_SHADE_RGB = (255, 238, 190)
FRAME_T = 0.07  # metres: the door generator's frame post width
FRONT_T = (
    0.02  # metres: a cabinet's or fridge's front panel before its carcass (generators storage, kitchen_bath)
)


def value_at(track: ObjectStateTrack, frame: float) -> float:
    """The track's state at a frame (linear between keys, held outside them)."""
    if not track.frames:
        return 0.0
    return float(np.interp(frame, track.frames, track.values))


def state_at(tracks: list[ObjectStateTrack], object_id: str, state: str, rest: float, frame: float) -> float:
    """An object's state at a frame: its track's value, else its value at rest."""
    for t in tracks:
        if t.object_id == object_id and t.state == state:
            return value_at(t, frame)
    return rest


FRONTS = ("refrigerator", "wardrobe", "cabinet", "microwave")  # appliances and furniture with hinged fronts
PAIRED = ("wardrobe", "cabinet")  # two columns of fronts: the left ones hinge left, the right ones right


def moving_faces(category: str, triangles: np.ndarray) -> np.ndarray:
    """(F,) int8 leaf of each face an "open" state turns (0: still), from the faces' (F, 3, 3) corners,
    object frame: a door's leaf (between its frame posts, under its head), a laptop's lid
    (above its base, which the touchpad on its front half tops), a fridge's or wardrobe's fronts (in front
    of the carcass; a two-column wardrobe's right fronts are leaf 2, hinged on the right)."""
    centroids = triangles.mean(axis=1)
    lo, hi = centroids.min(axis=0), centroids.max(axis=0)
    out = np.zeros(len(centroids), np.int8)
    if category == "door":
        w_half = max(abs(lo[0]), abs(hi[0]))
        inside = np.abs(centroids[:, 0]) < w_half - FRAME_T + 1e-4
        out[inside & (centroids[:, 1] < hi[1] - FRAME_T + 1e-4)] = 1
    elif category == "laptop":
        front = centroids[:, 2] > 0.02
        base_top = float(centroids[front, 1].max()) if front.any() else 0.02
        y, z = centroids[:, 1], centroids[:, 2]
        out[(y > base_top + 0.003) | ((z < -hi[2] + 0.018) & (y > base_top - 0.004))] = 1
    elif category in FRONTS:
        fronts = centroids[:, 2] > _front_face(triangles) - FRONT_T + 1e-3
        out[fronts] = 1
        if category in PAIRED:
            out[fronts & (centroids[:, 0] > 0)] = 2
    return out


def _front_face(triangles: np.ndarray) -> float:
    """z of the fronts' outer face: the frontmost large face looking forward (+Z), handles left aside."""
    n = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    area = np.linalg.norm(n, axis=1) / 2
    forward = (n[:, 2] > 0.99 * 2 * area) & (area > 0.02)
    z = triangles.mean(axis=1)[:, 2]
    return float(z[forward].max()) if forward.any() else float(z.max())


def open_hinge(
    category: str, part: np.ndarray, value: float, leaf: int = 1
) -> tuple[np.ndarray, np.ndarray, float]:
    """(hinge point, unit axis, angle in radians) a moving leaf of an "open" state turns by at a value,
    object frame, from the leaf's (2, 3) bounds; angle 0 where nothing moves.

    Door, fridge, wardrobe: the leaf turns about its back edge on the left (leaf 1) or the right (leaf 2)
    out to the front (+Z), 0 shut, 1 open. Laptop: the lid turns about its front bottom edge (the hinge on
    the base) down onto the base, 1 open (as modelled), 0 shut.
    """
    up = np.array([0.0, 1.0, 0.0])
    if category == "door" or category in FRONTS:
        x = part[0, 0] if leaf == 1 else part[1, 0]
        swing = DOOR_SWING * value
        return np.array([x, 0.0, part[0, 2]]), up, -swing if leaf == 1 else swing
    if category == "laptop":
        hinge = np.array([0.0, part[0, 1], part[1, 2]])
        return hinge, np.array([1.0, 0.0, 0.0]), (1.0 - value) * (np.pi / 2 + LID_TILT - 0.03)
    return np.zeros(3), up, 0.0


def open_transform(category: str, part: np.ndarray, value: float, leaf: int = 1) -> np.ndarray:
    """(4, 4) object-frame transform of a moving leaf (its (2, 3) bounds) at an "open" value."""
    hinge, axis, a = open_hinge(category, part, value, leaf)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    r = np.eye(3) + np.sin(a) * k + (1 - np.cos(a)) * (k @ k)  # Rodrigues
    m = np.eye(4)
    m[:3, :3] = r
    m[:3, 3] = hinge - r @ hinge
    return m


def glowing_faces(category: str, centroids: np.ndarray, colours: np.ndarray) -> np.ndarray:
    """(F,) bool: the faces an "on" state lights: a screen's panel, a lamp's shade (its top third)."""
    if category in LIGHTS:
        lo, hi = centroids[:, 1].min(), centroids[:, 1].max()
        return centroids[:, 1] > hi - (hi - lo) * 0.35
    return np.all(np.abs(colours.astype(int) - np.array(SCREEN_RGB)) <= 6, axis=1)


def lit_colour(category: str) -> tuple[int, int, int]:
    """The RGB a lit part shows."""
    return LIT_SHADE_RGB if category in LIGHTS else LIT_SCREEN_RGB


__all__ = [
    "FRONTS",
    "LIGHTS",
    "STATEFUL",
    "glowing_faces",
    "lit_colour",
    "moving_faces",
    "open_hinge",
    "open_transform",
    "state_at",
    "value_at",
]
