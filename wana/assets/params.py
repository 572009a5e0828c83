"""Knob values -> generator parameters: sizes, style profiles, palettes, clutter, and the Builder.

A generator receives a ``Builder`` (parts + contact points + support surfaces) and ``Params``
(target dimensions after the size and style knobs, colours after the colour and material knobs,
the style profile, the state and a seeded RNG).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from wana.assets.geometry import RGBA, PartList

COLOURS: dict[str, tuple[int, int, int]] = {
    "red": (190, 40, 40),
    "orange": (230, 120, 30),
    "yellow": (235, 200, 50),
    "green": (60, 150, 70),
    "blue": (45, 90, 190),
    "purple": (120, 60, 160),
    "pink": (230, 130, 170),
    "brown": (120, 75, 40),
    "black": (30, 30, 32),
    "white": (240, 240, 236),
    "grey": (128, 128, 130),
    "beige": (215, 195, 160),
    "teal": (30, 140, 140),
    "navy": (25, 35, 90),
}
MATERIALS: dict[str, tuple[int, int, int]] = {
    "wooden": (150, 100, 55),
    "metal": (175, 178, 185),
    "plastic": (225, 225, 218),
    "leather": (95, 55, 32),
    "fabric": (150, 138, 120),
    "glass": (175, 210, 222),
    "stone": (165, 162, 152),
}
# Named default tones for generator specs.
TONES: dict[str, tuple[int, int, int]] = {
    **COLOURS,
    **MATERIALS,
    "wood": (150, 100, 55),
    "darkwood": (95, 60, 35),
    "lightwood": (205, 170, 120),
    "steel": (175, 178, 185),
    "chrome": (205, 208, 212),
    "screen": (20, 24, 30),
    "cream": (235, 225, 200),
    "gold": (200, 160, 60),
    "skin": (225, 190, 160),
    "leaf": (50, 130, 55),
    "terracotta": (180, 95, 60),
    "paper": (245, 243, 235),
    "rubber": (40, 40, 40),
    "ivory": (245, 240, 225),
    "charcoal": (55, 55, 60),
    "chalkgreen": (40, 70, 55),
}

SIZE_FACTORS = {"small": 0.8, "medium": 1.0, "large": 1.25}


@dataclass(frozen=True)
class StyleProfile:
    """How a style changes geometry.

    Attributes:
        name: the style value ("" for the category default).
        leg: "box", "cyl", "turned", "frame", "pedestal" or "taper".
        leg_t: leg thickness factor.
        top_t: top/panel thickness factor.
        trim: adds a trim/apron or ornament part.
        dims: (3,) width/height/depth factors.
        tint: multiplies the body colour (ageing, sheen).
    """

    name: str
    leg: str
    leg_t: float
    top_t: float
    trim: bool
    dims: tuple[float, float, float]
    tint: float


STYLES: dict[str, StyleProfile] = {
    "": StyleProfile("", "box", 1.0, 1.0, False, (1.0, 1.0, 1.0), 1.0),
    "modern": StyleProfile("modern", "cyl", 0.7, 0.8, False, (1.0, 0.96, 1.0), 1.05),
    "classic": StyleProfile("classic", "turned", 1.1, 1.1, True, (1.0, 1.03, 1.0), 0.95),
    "old": StyleProfile("old", "box", 1.15, 1.25, True, (0.97, 1.0, 0.97), 0.75),
    "rustic": StyleProfile("rustic", "box", 1.6, 1.7, False, (1.05, 1.0, 1.05), 0.9),
    "minimalist": StyleProfile("minimalist", "box", 0.6, 0.6, False, (0.95, 0.95, 0.95), 1.1),
    "industrial": StyleProfile("industrial", "frame", 0.9, 1.3, False, (1.05, 1.0, 1.05), 0.85),
    "luxurious": StyleProfile("luxurious", "turned", 1.3, 1.2, True, (1.1, 1.05, 1.1), 1.0),
    "futuristic": StyleProfile("futuristic", "pedestal", 1.0, 0.9, False, (1.0, 1.0, 0.95), 1.15),
}


def _rgba(rgb: tuple[int, int, int] | np.ndarray, k: float = 1.0) -> RGBA:
    c = np.clip(np.asarray(rgb, float) * k, 0, 255).astype(int)
    return (int(c[0]), int(c[1]), int(c[2]), 255)


def mix(a: tuple[int, int, int], b: tuple[int, int, int], t: float) -> tuple[int, int, int]:
    return tuple(int(round(x * (1 - t) + y * t)) for x, y in zip(a, b, strict=True))  # type: ignore[return-value]


@dataclass
class Params:
    """Generator inputs after applying the knobs (see module docstring)."""

    category: str
    w: float
    h: float
    d: float
    style: StyleProfile
    body: RGBA
    frame: RGBA
    accent: RGBA
    state: str
    material: str
    seed: int
    rng: np.random.Generator

    def tone(self, name: str, k: float = 1.0) -> RGBA:
        return _rgba(TONES[name], k)

    def shade(self, c: RGBA, k: float) -> RGBA:
        return _rgba(np.asarray(c[:3]), k)

    def leg(
        self, b: PartList, x: float, z: float, y0: float, y1: float, t: float, colour: RGBA | None = None
    ) -> None:
        """One furniture leg in the style's shape, footprint about t x t metres."""
        c = self.frame if colour is None else colour
        t = t * self.style.leg_t
        kind = self.style.leg
        if kind == "cyl":
            b.cyl((x, y0, z), t / 2, y1 - y0, c, sections=10)
        elif kind == "turned":
            hgt = y1 - y0
            b.lathe(
                (x, y0, z),
                [
                    (t * 0.35, 0),
                    (t * 0.45, hgt * 0.15),
                    (t * 0.3, hgt * 0.35),
                    (t * 0.55, hgt * 0.6),
                    (t * 0.35, hgt * 0.85),
                    (t * 0.5, hgt),
                ],
                c,
                sections=10,
            )
        elif kind == "taper":
            b.lathe((x, y0, z), [(t * 0.25, 0), (t * 0.5, y1 - y0)], c, sections=8)
        else:  # box, frame, pedestal (callers draw pedestals themselves) fall back to square legs
            b.box((x - t / 2, y0, z - t / 2), (x + t / 2, y1, z + t / 2), c)


@dataclass
class ContactSpec:
    joint: str
    position: tuple[float, float, float]
    extra: dict[str, tuple[float, float, float]] = field(default_factory=dict)


@dataclass
class Builder(PartList):
    """Parts plus interaction data, all in the object frame before recentring."""

    contacts: dict[str, ContactSpec] = field(default_factory=dict)
    surfaces: list[tuple[float, float, float, float, float]] = field(default_factory=list)
    stand: tuple[float, float, float] | None = None

    def contact(
        self,
        name: str,
        joint: str,
        pos: tuple[float, float, float],
        extra: dict[str, tuple[float, float, float]] | None = None,
    ) -> None:
        """Interaction ``name``: ``joint`` goes to ``pos``; ``extra`` holds other joints of the same act."""
        self.contacts[name] = ContactSpec(
            joint, (float(pos[0]), float(pos[1]), float(pos[2])), dict(extra or {})
        )

    def two_hands(
        self, name: str, y: float, z: float, spread: float, x: float = 0.0, finger: bool = True
    ) -> None:
        """A two-handed contact: right hand at x - spread/2 (the character's right is -X when facing -Z)."""
        j = "HandMiddle1" if finger else "Hand"
        # A character using the object faces it (faces -Z in object frame), so its right hand is at +X.
        self.contact(name, "Right" + j, (x + spread / 2, y, z), {"Left" + j: (x - spread / 2, y, z)})

    def surface(self, y: float, x0: float, z0: float, x1: float, z1: float) -> None:
        """A horizontal support rectangle at height y spanning [x0, x1] x [z0, z1]."""
        if x1 - x0 > 0.02 and z1 - z0 > 0.02:
            self.surfaces.append((float(y), float(x0), float(z0), float(x1), float(z1)))


def books_row(
    b: Builder, p: Params, x0: float, x1: float, y: float, z0: float, z1: float, max_h: float
) -> None:
    """Books standing on a shelf between x0 and x1 (state decides order: organized, messy, empty)."""
    if p.state == "empty":
        return
    rng = np.random.default_rng(abs(p.seed * 7919 + int(y * 1000) + int(x0 * 100)))
    palette = ["red", "blue", "green", "navy", "brown", "beige", "black", "teal", "orange"]
    x = x0 + 0.01
    depth = min(z1 - z0, 0.25)
    while x < x1 - 0.05:
        t = float(rng.uniform(0.025, 0.05))
        hh = float(min(max_h, rng.uniform(0.17, 0.28))) if p.state != "organized" else min(max_h, 0.24)
        col = p.tone(palette[int(rng.integers(len(palette)))])
        if p.state == "messy" and rng.random() < 0.3 and x + hh < x1:
            b.box((x, y, z0), (x + hh, y + t, z0 + depth * 0.8), col)  # a book lying flat
            x += hh + 0.01
            continue
        b.box((x, y, z0), (x + t, y + hh, z0 + depth), col)
        x += t + (0.002 if p.state == "organized" else float(rng.uniform(0.0, 0.03)))


def desk_clutter(b: Builder, p: Params, y: float, x0: float, x1: float, z0: float, z1: float) -> None:
    """Papers and small things on a top in the strip [z0, z1]: neat stacks or a scattered mess."""
    if p.state in ("", "empty"):
        return
    rng = np.random.default_rng(p.seed * 104729 + 17)
    paper = p.tone("paper")
    if p.state == "organized":
        w = min(0.3, (x1 - x0) * 0.3)
        b.box((x0 + 0.03, y, z0 + 0.02), (x0 + 0.03 + w * 0.7, y + 0.04, z0 + 0.02 + (z1 - z0) * 0.8), paper)
        b.box(
            (x1 - 0.03 - w * 0.5, y, z0 + 0.02),
            (x1 - 0.03, y + 0.08, z0 + 0.02 + (z1 - z0) * 0.6),
            p.tone("navy"),
        )
        return
    for _ in range(6):
        sx, sz = float(rng.uniform(0.15, 0.3)), float(rng.uniform(0.1, 0.2))
        cx = float(rng.uniform(x0 + 0.15, max(x0 + 0.16, x1 - 0.15)))
        cz = float(rng.uniform(z0 + 0.08, max(z0 + 0.09, z1 - 0.08)))
        sz = min(sz, (z1 - z0) * 0.6)
        b.boxc(
            (cx, y + 0.004 + float(rng.uniform(0, 0.02)), cz),
            (sx, 0.006, sz),
            paper,
            yaw=float(rng.uniform(-0.8, 0.8)),
        )
    cx = float(rng.uniform(x0 + 0.1, max(x0 + 0.11, x1 - 0.1)))
    b.cyl((cx, y, (z0 + z1) / 2), 0.035, 0.09, p.tone("red"))
