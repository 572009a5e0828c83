"""Storage: shelves and bookcases, cabinets with doors or drawers, wardrobes, chests, racks, cases."""

from __future__ import annotations

import numpy as np

from wana.assets.generators.registry import register
from wana.assets.params import Builder, Params, books_row


def shelves(b: Builder, p: Params, kind: str = "bookshelf", levels: int = 5) -> None:
    """Open shelving; books (or boxes) fill the left part of each level, the right part stays free."""
    w, h, d = p.w, p.h, p.d
    t = 0.025 * p.style.top_t
    if kind == "rack":
        for x in (-w / 2 + 0.02, w / 2 - 0.02):
            for z in (-d / 2 + 0.02, d / 2 - 0.02):
                b.box((x - 0.015, 0, z - 0.015), (x + 0.015, h, z + 0.015), p.frame)
    else:
        b.box((-w / 2, 0, -d / 2), (-w / 2 + t, h, d / 2), p.body)
        b.box((w / 2 - t, 0, -d / 2), (w / 2, h, d / 2), p.body)
        b.box((-w / 2 + t, 0, -d / 2), (w / 2 - t, h, -d / 2 + 0.01), p.shade(p.body, 0.85))
    gap = (h - t) / levels
    for i in range(levels + 1):
        y = min(i * gap, h - t)
        b.box(
            (-w / 2 + (t if kind != "rack" else 0), y, -d / 2 + 0.01),
            (w / 2 - (t if kind != "rack" else 0), y + t, d / 2),
            p.body,
        )
    if p.style.trim:
        b.box((-w / 2 - 0.02, h, -d / 2), (w / 2 + 0.02, h + 0.04, d / 2 + 0.02), p.shade(p.body, 0.9))
    split = -w / 2 + t + (w - 2 * t) * 0.6
    for i in range(levels):
        y = i * gap + t
        if kind == "bookshelf":
            books_row(b, p, -w / 2 + t, split, y, -d / 2 + 0.02, d / 2 - 0.02, gap - 0.03)
        elif p.state != "empty":
            rng = np.random.default_rng(p.seed * 31 + i)
            x = -w / 2 + 0.04
            while x < split - 0.2:
                bw = float(rng.uniform(0.15, 0.3))
                yaw = 0.0 if p.state != "messy" else float(rng.uniform(-0.3, 0.3))
                bh = min(gap - 0.05, float(rng.uniform(0.1, 0.25)))
                b.boxc(
                    (x + bw / 2, y + bh / 2, 0.0),
                    (bw * 0.9, bh, min(d - 0.08, 0.3)),
                    p.tone(("beige", "terracotta", "grey")[int(rng.integers(3))]),
                    yaw=yaw,
                )
                x += bw + 0.02
        if i > 0:
            b.surface(y, split + 0.02, -d / 2 + 0.03, w / 2 - t - 0.01, d / 2 - 0.01)
    b.surface(h + (0.04 if p.style.trim else 0.0), -w / 2 + 0.01, -d / 2 + 0.01, w / 2 - 0.01, d / 2 - 0.01)
    b.contact("take", "RightHand", (split - 0.1, min(1.3, h * 0.6), d / 2))
    b.stand = (0.0, 0.0, d / 2 + 0.4)


def cabinet(
    b: Builder,
    p: Params,
    kind: str = "doors",
    cols: int = 2,
    rows: int = 1,
    plinth: float = 0.08,
    wheels: bool = False,
    handle_tone: str = "chrome",
) -> None:
    """A carcass with a grid of fronts: kind "doors" (tall fronts) or "drawers" (short fronts)."""
    w, h, d = p.w, p.h, p.d
    fz = d / 2
    y0 = plinth
    if wheels:
        for x in (-w / 2 + 0.05, w / 2 - 0.05):
            for z in (-d / 2 + 0.05, d / 2 - 0.05):
                b.ellipsoid((x, 0.04, z), (0.03, 0.04, 0.03), p.tone("rubber"))
    elif p.style.leg in ("cyl", "turned", "taper") and plinth > 0:
        for x in (-w / 2 + 0.04, w / 2 - 0.04):
            for z in (-d / 2 + 0.04, d / 2 - 0.06):
                p.leg(b, x, z, 0, plinth, 0.04)
    elif plinth > 0:
        b.box((-w / 2 + 0.02, 0, -d / 2 + 0.02), (w / 2 - 0.02, plinth, d / 2 - 0.05), p.shade(p.frame, 0.7))
    b.box((-w / 2, y0, -d / 2), (w / 2, h, d / 2 - 0.02), p.body)
    fw, fh = w / cols, (h - y0) / rows
    for c in range(cols):
        for r in range(rows):
            x0, yy = -w / 2 + c * fw, y0 + r * fh
            b.box(
                (x0 + 0.005, yy + 0.005, fz - 0.02),
                (x0 + fw - 0.005, yy + fh - 0.005, fz),
                p.shade(p.body, 1.06),
            )
            if kind == "drawers":
                hx0, hx1, hy0, hy1 = x0 + fw * 0.35, x0 + fw * 0.65, yy + fh * 0.6, yy + fh * 0.6 + 0.02
            else:
                hx = x0 + (fw - 0.06 if c % 2 == 0 else 0.04)
                hx0, hx1, hy0, hy1 = hx, hx + 0.02, yy + fh * 0.4, yy + fh * 0.6
            b.box((hx0, hy0, fz), (hx1, hy1, fz + 0.025), p.tone(handle_tone))
    if p.style.trim:
        b.box((-w / 2 - 0.015, h, -d / 2), (w / 2 + 0.015, h + 0.03, d / 2 + 0.01), p.shade(p.frame, 0.9))
    top = h + (0.03 if p.style.trim else 0.0)
    b.surface(top, -w / 2 + 0.01, -d / 2 + 0.01, w / 2 - 0.01, d / 2 - 0.03)
    b.contact("open", "RightHand", (-w / 2 + fw - 0.05, min(h * 0.6, 1.1), fz + 0.04))
    b.stand = (0.0, 0.0, d / 2 + 0.45)


def chest(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    b.box((-w / 2, 0, -d / 2), (w / 2, h * 0.8, d / 2), p.body)
    if p.style.name in ("classic", "old", "rustic", "luxurious"):
        b.cyl((-w / 2, h * 0.8, 0), d / 2, w, p.body, axis="x", sections=16)
    else:
        b.box((-w / 2, h * 0.8, -d / 2), (w / 2, h, d / 2), p.shade(p.body, 0.9))
    for x in (-w * 0.35, w * 0.35):
        b.box((x - 0.02, 0, d / 2), (x + 0.02, h * 0.8, d / 2 + 0.01), p.frame)
    b.box((-0.04, h * 0.6, d / 2), (0.04, h * 0.75, d / 2 + 0.02), p.tone("gold"))
    b.contact("open", "RightHand", (0.0, h * 0.8, d / 2 + 0.03))
    b.surface(h, -w / 2 + 0.02, -d * 0.2, w / 2 - 0.02, d * 0.2)


def coat_rack(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    for k in range(4):
        a = np.pi / 4 + k * np.pi / 2
        b.rod((0, 0.15, 0), (w / 2 * np.cos(a), 0.0, d / 2 * np.sin(a)), 0.015, p.frame)
    b.cyl((0, 0.0, 0), 0.02 * p.style.leg_t, h, p.body, sections=10)
    for k in range(6):
        a = k * np.pi / 3
        b.rod((0, h - 0.15, 0), (0.18 * np.cos(a), h - 0.05, 0.18 * np.sin(a)), 0.01, p.body)
    b.box((0.05, h - 0.75, 0.05), (0.25, h - 0.15, 0.15), p.tone("navy"))
    b.contact("hang", "RightHand", (0.0, h - 0.05, 0.18))


def display_case(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    b.box((-w / 2, 0, -d / 2), (w / 2, h * 0.4, d / 2), p.body)
    b.box((-w / 2, h * 0.4, -d / 2), (w / 2, h, d / 2), p.tone("glass"))
    b.box((-w / 2 - 0.01, h - 0.03, -d / 2 - 0.01), (w / 2 + 0.01, h, d / 2 + 0.01), p.frame)
    for i, x in enumerate(np.linspace(-w * 0.3, w * 0.3, 3)):
        b.ellipsoid((x, h * 0.5, 0), (0.05, 0.08, 0.05), p.tone(("gold", "teal", "white")[i]))
    b.contact("look", "Head", (0.0, h * 0.5, d / 2))
    b.surface(h, -w / 2 + 0.01, -d / 2 + 0.01, w / 2 - 0.01, d / 2 - 0.01)


def pedestal(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    if p.style.leg in ("turned", "cyl"):
        b.lathe(
            (0, 0, 0),
            [(w / 2, 0), (w / 2, 0.06), (w * 0.35, 0.1), (w * 0.35, h - 0.1), (w / 2, h - 0.05), (w / 2, h)],
            p.body,
        )
        r = w * 0.35
    else:
        b.box((-w / 2, 0, -d / 2), (w / 2, h, d / 2), p.body)
        r = w / 2 - 0.02
    b.surface(h, -r, -r, r, r)


register("bookshelf", shelves, (0.9, 1.9, 0.32), body="wood", kind="bookshelf")
register("shelf", shelves, (1.0, 1.8, 0.45), body="lightwood", frame="steel", kind="rack", levels=4)
register("shoe_rack", shelves, (0.8, 0.6, 0.32), body="lightwood", kind="shoes", levels=2)
register("wardrobe", cabinet, (1.2, 2.0, 0.6), body="wood", frame="darkwood", cols=2, rows=1)
register("cabinet", cabinet, (1.2, 0.85, 0.45), body="wood", frame="darkwood", cols=3, rows=1)
register(
    "filing_cabinet",
    cabinet,
    (0.47, 1.32, 0.62),
    body="grey",
    frame="charcoal",
    kind="drawers",
    cols=1,
    rows=4,
    plinth=0.03,
)
register("dresser", cabinet, (1.0, 0.95, 0.5), body="wood", frame="darkwood", kind="drawers", cols=2, rows=3)
register(
    "kitchen_cabinet", cabinet, (0.8, 0.9, 0.6), body="white", frame="charcoal", cols=2, rows=1, plinth=0.1
)
register(
    "tv_stand", cabinet, (1.6, 0.5, 0.42), body="darkwood", frame="charcoal", kind="drawers", cols=3, rows=1
)
register(
    "locker",
    cabinet,
    (0.9, 1.8, 0.45),
    body="blue",
    frame="charcoal",
    cols=3,
    rows=1,
    plinth=0.05,
    handle_tone="steel",
)
register(
    "tool_cabinet",
    cabinet,
    (0.7, 1.0, 0.46),
    body="red",
    frame="charcoal",
    kind="drawers",
    cols=1,
    rows=6,
    plinth=0.09,
    wheels=True,
    handle_tone="steel",
)
register("chest", chest, (0.9, 0.5, 0.5), body="wood", frame="darkwood")
register("coat_rack", coat_rack, (0.5, 1.8, 0.5), body="darkwood", frame="darkwood")
register("display_case", display_case, (1.0, 1.5, 0.5), body="white", frame="steel")
register("pedestal", pedestal, (0.45, 1.0, 0.45), body="white", frame="white")
