"""Wall things (boards, pictures, mirrors, clocks, windows, doors, curtains) and fireplaces, flip charts.

Wall objects have their back on the object's -Z face; the scene grammar puts that face on a wall.
"""

from __future__ import annotations

import numpy as np

from wana.assets.generators.registry import register
from wana.assets.params import Builder, Params


def panel(b: Builder, p: Params, kind: str = "whiteboard") -> None:
    """A framed flat panel; the face shows the kind (board surface, picture, mirror glass)."""
    w, h, d = p.w, p.h, p.d
    f = 0.04 * p.style.top_t
    if kind in ("poster", "screen"):
        f = 0.0
    # boards and mirrors show the colour knob on their frame; pictures on their canvas
    rim = p.body if kind in ("whiteboard", "mirror") else p.frame
    b.box((-w / 2, 0, -d / 2), (w / 2, h, -d / 2 + d * 0.5), rim if f else p.body)
    face = {
        "whiteboard": p.tone("white"),
        "blackboard": p.tone("chalkgreen"),
        "mirror": p.tone("glass", 1.1),
        "screen": p.tone("white"),
        "poster": p.body,
        "painting": p.body,
    }[kind]
    if kind == "blackboard" and p.body != p.tone("wood"):
        face = p.shade(p.body, 0.35)
    b.box((-w / 2 + f, f, -d / 2 + d * 0.5), (w / 2 - f, h - f, d / 2), face)
    if kind == "painting":
        rng = np.random.default_rng(p.seed + 11)
        palette = ["yellow", "blue", "red", "green", "white", "orange", "teal"]
        for _ in range(5):
            cx, cy = rng.uniform(-w / 3, w / 3), rng.uniform(h / 4, 3 * h / 4)
            sx, sy = rng.uniform(w * 0.1, w * 0.35), rng.uniform(h * 0.1, h * 0.35)
            b.box(
                (cx - sx / 2, cy - sy / 2, d / 2),
                (cx + sx / 2, cy + sy / 2, d / 2 + 0.002),
                p.tone(palette[int(rng.integers(len(palette)))]),
            )
        b.contact("look", "Head", (0.0, h / 2, d / 2))
    if kind == "poster":
        b.box((-w * 0.35, h * 0.55, d / 2), (w * 0.35, h * 0.85, d / 2 + 0.002), p.tone("white"))
        b.contact("look", "Head", (0.0, h / 2, d / 2))
    if kind in ("whiteboard", "blackboard"):
        b.box((-w / 2 + 0.1, -0.03, -d / 2), (w / 2 - 0.1, 0.0, d / 2 + 0.05), p.frame)  # tray
        b.contact("write", "RightHand", (w * 0.1, h * 0.6, d / 2 + 0.03))
        b.stand = (w * 0.2, 0.0, d / 2 + 0.45)
    if kind == "mirror":
        b.contact("look", "Head", (0.0, h * 0.6, d / 2))
    if p.style.trim and f:
        b.box((-w / 2 - 0.02, h, -d / 2), (w / 2 + 0.02, h + 0.03, d / 2 + 0.01), p.shade(p.frame, 0.85))
    if kind == "screen":
        b.cyl((-w / 2 - 0.02, h, 0), 0.04, w + 0.04, p.tone("charcoal"), axis="x")
    b.stand = b.stand or (0.0, 0.0, d / 2 + 0.6)


def clock(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    r = min(w, h) / 2
    if p.style.leg in ("turned", "box") and p.style.trim:
        b.box((-w / 2, 0, -d / 2), (w / 2, h, 0), p.frame)
    b.cyl((0, h / 2, -d / 2), r, d * 0.8, p.body, axis="z", sections=24)
    b.cyl((0, h / 2, -d / 2 + d * 0.8), r * 0.88, d * 0.1, p.tone("white"), axis="z", sections=24)
    b.boxc((0, h / 2 + r * 0.25, d / 2 - 0.005), (0.01, r * 0.5, 0.005), p.tone("black"))
    b.boxc((r * 0.2, h / 2, d / 2 - 0.005), (r * 0.4, 0.01, 0.005), p.tone("black"))
    b.contact("look", "Head", (0.0, h / 2, d / 2))


def window(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    f = 0.06 * p.style.top_t
    b.box((-w / 2, 0, -d / 2), (w / 2, f, d / 2 + 0.08), p.body)  # sill
    b.box((-w / 2, h - f, -d / 2), (w / 2, h, d / 2), p.body)
    for x in (-w / 2, w / 2 - f):
        b.box((x, f, -d / 2), (x + f, h - f, d / 2), p.body)
    panes = 2 if p.style.name in ("", "modern", "minimalist", "futuristic") else 4
    b.box((-w / 2 + f, f, -d / 2 + d * 0.4), (w / 2 - f, h - f, -d / 2 + d * 0.5), p.tone("glass"))
    b.box((-f / 4, f, -d / 2), (f / 4, h - f, d / 2 - 0.01), p.body)
    if panes == 4:
        b.box((-w / 2 + f, h / 2 - f / 4, -d / 2), (w / 2 - f, h / 2 + f / 4, d / 2 - 0.01), p.body)
    b.contact("open", "RightHand", (0.05, h / 2, d / 2 + 0.02))
    b.contact("look", "Head", (0.0, h / 2, 0.0))
    b.stand = (0.0, 0.0, d / 2 + 0.5)


def door(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    f = 0.07
    b.box((-w / 2, 0, -d / 2), (-w / 2 + f, h, d / 2), p.frame)
    b.box((w / 2 - f, 0, -d / 2), (w / 2, h, d / 2), p.frame)
    b.box((-w / 2, h - f, -d / 2), (w / 2, h, d / 2), p.frame)
    b.box((-w / 2 + f, 0, -d * 0.2), (w / 2 - f, h - f, d * 0.2), p.body)
    if p.style.trim or p.style.name == "classic":
        for y0, y1 in ((0.2, h * 0.45), (h * 0.52, h - 0.25)):
            b.box((-w / 2 + 0.15, y0, d * 0.2), (w / 2 - 0.15, y1, d * 0.2 + 0.01), p.shade(p.body, 0.9))
    b.lathe(
        (w / 2 - 0.15, 1.0, d * 0.2),
        [(0.03, 0), (0.03, 0.05), (0.018, 0.05), (0.018, 0.09)],
        p.tone("chrome"),
        axis="z",
        sections=10,
    )
    b.contact("open", "RightHand", (w / 2 - 0.15, 1.0, d * 0.2 + 0.08))
    b.stand = (0.0, 0.0, d / 2 + 0.5)


def curtain(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    b.cyl((-w / 2, h - 0.03, 0), 0.015, w, p.tone("steel"), axis="x", sections=8)
    n = 10
    for side in (-1, 1):
        for i in range(n):
            x = side * (w / 2 - (i + 0.5) * w * 0.35 / n)
            b.box(
                (x - w * 0.35 / n / 2, 0.02, -d / 2 + (0.02 if i % 2 else 0.0)),
                (x + w * 0.35 / n / 2, h - 0.05, d / 2 - (0.0 if i % 2 else 0.02)),
                p.body,
            )
    b.contact("open", "RightHand", (w / 2 - 0.2, 1.3, d / 2 + 0.02))


def fireplace(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    b.box((-w / 2, 0, -d / 2), (-w / 2 + 0.25, h * 0.85, d / 2), p.body)
    b.box((w / 2 - 0.25, 0, -d / 2), (w / 2, h * 0.85, d / 2), p.body)
    b.box((-w / 2, h * 0.6, -d / 2), (w / 2, h * 0.85, d / 2), p.body)
    b.box((-w / 2 + 0.25, 0, -d / 2), (w / 2 - 0.25, h * 0.6, -d / 2 + 0.1), p.tone("charcoal"))
    b.box((-w / 2 - 0.05, h * 0.85, -d / 2), (w / 2 + 0.05, h, d / 2 + 0.05), p.frame)  # mantel
    b.ellipsoid((0, 0.12, 0), (w * 0.2, 0.12, d * 0.2), p.tone("orange"))
    b.surface(h, -w / 2, -d / 2 + 0.02, w / 2, d / 2)
    b.contact("warm", "RightHand", (0.0, h * 0.4, d / 2 + 0.1))
    b.stand = (0.0, 0.0, d / 2 + 0.6)


def flip_chart(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    b.rod((-w * 0.4, 0, d / 2), (-w * 0.3, h * 0.9, 0), 0.015, p.body)
    b.rod((w * 0.4, 0, d / 2), (w * 0.3, h * 0.9, 0), 0.015, p.body)
    b.rod((0, 0, -d / 2), (0, h * 0.9, 0), 0.015, p.body)
    b.boxc((0, h * 0.72, 0.04), (w * 0.85, h * 0.52, 0.01), p.tone("paper"), pitch=-0.1)
    b.box((-w * 0.45, h * 0.95, -0.01), (w * 0.45, h, 0.06), p.body)
    b.contact("write", "RightHand", (w * 0.1, h * 0.7, 0.1))
    b.stand = (w * 0.2, 0.0, d / 2 + 0.45)


register("blackboard", panel, (2.4, 1.2, 0.05), body="wood", frame="wood", kind="blackboard")
register("whiteboard", panel, (1.8, 1.1, 0.04), body="steel", frame="steel", kind="whiteboard")
register("projector_screen", panel, (2.0, 1.4, 0.03), body="white", kind="screen")
register("painting", panel, (0.9, 0.7, 0.04), body="beige", frame="gold", kind="painting")
register("poster", panel, (0.6, 0.85, 0.005), body="blue", kind="poster")
register("mirror", panel, (0.6, 1.0, 0.03), body="darkwood", frame="darkwood", kind="mirror")
register("clock", clock, (0.35, 0.35, 0.05), body="white", frame="darkwood")
register("window", window, (1.2, 1.3, 0.12), body="white")
register("door", door, (0.95, 2.1, 0.1), body="wood", frame="white")
register("curtain", curtain, (1.6, 2.2, 0.1), body="red")
register("fireplace", fireplace, (1.5, 1.15, 0.45), body="stone", frame="darkwood")
register("flip_chart", flip_chart, (0.75, 1.85, 0.6), body="steel", frame="steel")
