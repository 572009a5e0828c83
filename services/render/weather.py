"""Weather and light: sunny, night, rainy, foggy, snowy as colour grading, background, fog, particles.

Like the camera, each frame's look and particles are a pure function of the frame index and the
keys (particles move on closed-form paths from a fixed seed), so render chunks join seamlessly.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from proto.scene import Room
from wana.domain.units import FPS

WEATHERS = ("sunny", "night", "rainy", "foggy", "snowy")
TRANSITION_FRAMES = 30
PARTICLE_SEED = 20210801  # recorded seed: particles are the same in every run and every chunk


@dataclass(frozen=True)
class WeatherKey:
    frame: int
    weather: str


@dataclass(frozen=True)
class Look:
    """How a frame looks.

    Attributes:
        background: (3,) RGB in [0, 1] behind the room.
        gain: (3,) per-channel multiplier applied to the lit picture (light colour and strength).
        fog: fog density per metre (0 = none); pixels fade to ``fog_colour`` with 1 - exp(-fog * depth).
        fog_colour: (3,) RGB.
        shadow: darkness of projected shadows in [0, 1] (0 = none).
        sun: (3,) unit direction the light travels (downwards), for projected shadows.
        rain: share of rain particles shown in [0, 1].
        snow: share of snow particles shown in [0, 1].
    """

    background: np.ndarray
    gain: np.ndarray
    fog: float
    fog_colour: np.ndarray
    shadow: float
    sun: np.ndarray
    rain: float = 0.0
    snow: float = 0.0


def _sun(x: float, y: float, z: float) -> np.ndarray:
    v = np.array([x, y, z], dtype=float)
    return v / np.linalg.norm(v)


LOOKS: dict[str, Look] = {
    "sunny": Look(
        background=np.array([0.62, 0.78, 0.95]),
        gain=np.array([1.05, 1.02, 0.95]),
        fog=0.0,
        fog_colour=np.array([0.8, 0.85, 0.9]),
        shadow=0.55,
        sun=_sun(0.45, -1.0, -0.35),
    ),
    "night": Look(
        background=np.array([0.03, 0.04, 0.10]),
        gain=np.array([0.38, 0.42, 0.62]),
        fog=0.0,
        fog_colour=np.array([0.05, 0.05, 0.1]),
        shadow=0.35,
        sun=_sun(-0.2, -1.0, 0.25),
    ),
    "rainy": Look(
        background=np.array([0.42, 0.45, 0.50]),
        gain=np.array([0.72, 0.75, 0.82]),
        fog=0.04,
        fog_colour=np.array([0.55, 0.58, 0.62]),
        shadow=0.2,
        sun=_sun(0.1, -1.0, -0.1),
        rain=1.0,
    ),
    "foggy": Look(
        background=np.array([0.78, 0.80, 0.82]),
        gain=np.array([0.92, 0.93, 0.95]),
        fog=0.28,
        fog_colour=np.array([0.80, 0.82, 0.84]),
        shadow=0.15,
        sun=_sun(0.1, -1.0, -0.1),
    ),
    "snowy": Look(
        background=np.array([0.86, 0.89, 0.94]),
        gain=np.array([0.92, 0.96, 1.05]),
        fog=0.03,
        fog_colour=np.array([0.9, 0.92, 0.96]),
        shadow=0.3,
        sun=_sun(0.2, -1.0, -0.2),
        snow=1.0,
    ),
}


def _mix(a: Look, b: Look, s: float) -> Look:
    def lerp(x, y):  # noqa: ANN001, ANN202
        return x + (y - x) * s

    sun = lerp(a.sun, b.sun)
    return Look(
        background=lerp(a.background, b.background),
        gain=lerp(a.gain, b.gain),
        fog=lerp(a.fog, b.fog),
        fog_colour=lerp(a.fog_colour, b.fog_colour),
        shadow=lerp(a.shadow, b.shadow),
        sun=sun / np.linalg.norm(sun),
        rain=lerp(a.rain, b.rain),
        snow=lerp(a.snow, b.snow),
    )


def look_at(frame: int, keys: list[WeatherKey]) -> Look:
    """The look of a frame: sunny until the first key, then eased from one weather to the next (a key at
    frame 0 is how the film opens: no fade from daylight)."""
    active = [k for k in keys if k.frame <= frame]
    if not active:
        return LOOKS["sunny"]
    cur = LOOKS[active[-1].weather]
    since = frame - active[-1].frame
    opening = len(active) == 1 and active[0].frame <= 0  # how the film opens: no fade in
    if since >= TRANSITION_FRAMES or opening:
        return cur
    prev = LOOKS[active[-2].weather] if len(active) > 1 else LOOKS["sunny"]
    x = since / TRANSITION_FRAMES
    return _mix(prev, cur, x * x * (3 - 2 * x))


def rain_segments(frame: int, room: Room, share: float, count: int = 500) -> np.ndarray:
    """Rain streaks inside the room volume: (2N, 3) segment end points (N = share * count)."""
    n = int(round(count * share))
    if n <= 0:
        return np.zeros((0, 3))
    rng = np.random.default_rng(PARTICLE_SEED)
    base = rng.uniform(0, 1, (count, 3))[:n]
    speed = rng.uniform(5.0, 7.0, count)[:n]  # metres per second
    t = frame / FPS
    x = (base[:, 0] - 0.5) * room.width
    z = (base[:, 2] - 0.5) * room.depth
    y = np.mod(base[:, 1] * room.height - speed * t, room.height)
    top = np.stack([x, y, z], axis=1)
    bottom = top + np.array([0.02, -0.18, 0.0])
    return np.stack([top, bottom], axis=1).reshape(-1, 3)


def snow_points(frame: int, room: Room, share: float, count: int = 600) -> np.ndarray:
    """Snowflakes drifting down inside the room volume: (N, 3)."""
    n = int(round(count * share))
    if n <= 0:
        return np.zeros((0, 3))
    rng = np.random.default_rng(PARTICLE_SEED + 1)
    base = rng.uniform(0, 1, (count, 3))[:n]
    speed = rng.uniform(0.4, 0.8, count)[:n]
    phase = rng.uniform(0, 2 * np.pi, count)[:n]
    t = frame / FPS
    x = (base[:, 0] - 0.5) * room.width + 0.15 * np.sin(1.3 * t + phase)
    z = (base[:, 2] - 0.5) * room.depth + 0.15 * np.cos(1.1 * t + phase)
    y = np.mod(base[:, 1] * room.height - speed * t, room.height)
    return np.stack([x, y, z], axis=1)


def grade(rgb: np.ndarray, depth: np.ndarray | None, look: Look) -> np.ndarray:
    """Apply light gain and fog to a rendered frame.

    Args:
        rgb: (H, W, 3) uint8 as rendered (background drawn in ``background_for_render(look)``).
        depth: (H, W) metres, 0 where nothing was drawn; needed only when ``look.fog > 0``.

    Returns:
        (H, W, 3) uint8.
    """
    if look.fog <= 1e-4 or depth is None:  # per-channel lookup tables: much cheaper than float maths
        levels = np.arange(256, dtype=np.float64)[:, None] * look.gain[None, :]
        lut = np.clip(levels + 0.5, 0, 255).astype(np.uint8)  # (256, 3)
        return np.stack([lut[rgb[..., c], c] for c in range(3)], axis=-1)
    img = rgb.astype(np.float32) * (look.gain.astype(np.float32) / 255.0)
    if look.fog > 1e-4 and depth is not None:
        f = 1.0 - np.exp(-look.fog * depth.astype(np.float32))
        f[depth <= 0] = 1.0
        img = img * (1.0 - f[..., None]) + look.fog_colour.astype(np.float32) * f[..., None]
    return np.clip(img * 255.0 + 0.5, 0, 255).astype(np.uint8)


def background_for_render(look: Look) -> np.ndarray:
    """The clear colour to render with so that after ``grade`` the background is ``look.background``."""
    return np.clip(look.background / np.maximum(look.gain, 1e-3), 0.0, 1.0)
