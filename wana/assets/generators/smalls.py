"""Small things: books, paper, stationery, bags, cases, boxes, photo frames, sculptures, toys, cushions."""

from __future__ import annotations

import numpy as np

from wana.assets.generators.registry import register
from wana.assets.params import Builder, Params


def book(b: Builder, p: Params, kind: str = "book") -> None:
    """A book or notebook lying flat (messy: open / askew), or a stack of paper."""
    w, h, d = p.w, p.h, p.d
    rng = np.random.default_rng(p.seed + 41)
    if kind == "paper":
        n = {"messy": 6, "empty": 1}.get(p.state, 4)
        for i in range(n):
            yaw = float(rng.uniform(-0.6, 0.6)) if p.state == "messy" else 0.0
            b.boxc(
                (0.0, (i + 0.5) * h / n, 0.0),
                (w, h / n * 0.9, d),
                p.tone("paper", 1 - 0.02 * (i % 2)),
                yaw=yaw,
            )
        b.contact("read", "RightHand", (w / 2, h, 0.0), {"LeftHand": (-w / 2, h, 0.0)})
        b.contact("write", "RightHand", (0.05, h, 0.02))
        return
    if p.state == "messy":
        for s in (-1, 1):
            b.boxc((s * w / 2, h / 4, 0), (w, h / 2, d), p.body, roll=-s * 0.08)
            b.boxc(
                (s * w / 2, h / 2 + 0.002, 0), (w * 0.95, 0.004, d * 0.95), p.tone("paper"), roll=-s * 0.08
            )
    else:
        b.box((-w / 2, 0, -d / 2), (w / 2, h, d / 2), p.body)
        b.box((-w / 2 + 0.005, 0.003, -d / 2 + 0.003), (w / 2, h - 0.003, d / 2 - 0.003), p.tone("paper"))
        if p.style.trim:
            b.box((-w / 2, h, -d / 2), (-w / 2 + 0.02, h + 0.001, d / 2), p.tone("gold"))
        if p.state == "organized":  # a bookmark ribbon marks the page
            b.box((w * 0.2, h * 0.5, d / 2), (w * 0.25, h * 0.6, d / 2 + 0.04), p.tone("red"))
    b.contact("read", "RightHand", (w / 2, h, 0.0), {"LeftHand": (-w / 2, h, 0.0)})
    if kind == "notebook":
        b.contact("write", "RightHand", (0.05, h, 0.02))
    if kind == "stapler":
        b.box((-w / 2, h, -d * 0.4), (w / 2, h * 1.8, d * 0.4), p.tone("charcoal"))


def bag(b: Builder, p: Params, kind: str = "backpack") -> None:
    w, h, d = p.w, p.h, p.d
    if kind == "backpack":
        b.box((-w / 2, 0, -d / 2), (w / 2, h * 0.85, d / 2), p.body)
        b.ellipsoid((0, h * 0.85, 0), (w / 2, h * 0.15, d / 2), p.body)
        b.box((-w * 0.35, h * 0.1, d / 2), (w * 0.35, h * 0.45, d / 2 + 0.05), p.shade(p.body, 0.85))
        grip = (0.0, h, 0.0)
    elif kind == "handbag":
        b.lathe((0, 0, 0), [(w / 2, 0), (w * 0.4, h * 0.7)], p.body, axis="y", sections=4)
        b.rod((-w * 0.25, h * 0.65, 0), (0, h, 0), 0.008, p.frame)
        b.rod((0, h, 0), (w * 0.25, h * 0.65, 0), 0.008, p.frame)
        grip = (0.0, h, 0.0)
    else:  # briefcase, suitcase: upright case with a top handle
        b.box((-w / 2, 0.03 if kind == "suitcase" else 0.0, -d / 2), (w / 2, h * 0.88, d / 2), p.body)
        b.box((-w * 0.15, h * 0.88, -0.012), (-w * 0.12, h, 0.012), p.frame)
        b.box((w * 0.12, h * 0.88, -0.012), (w * 0.15, h, 0.012), p.frame)
        b.box((-w * 0.15, h - 0.02, -0.012), (w * 0.15, h, 0.012), p.frame)
        if kind == "suitcase":
            for x in (-w / 2 + 0.04, w / 2 - 0.04):
                b.ellipsoid((x, 0.03, -d / 2 + 0.04), (0.025, 0.03, 0.025), p.tone("rubber"))
        grip = (0.0, h, 0.0)
    b.contact("carry", "RightHand", grip)
    b.contact("pick_up", "RightHand", grip)
    b.contact("open", "RightHand", (0.0, h * 0.8, d / 2))


def box(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    b.box((-w / 2, 0, -d / 2), (w / 2, h, d / 2), p.body)
    b.box((-w / 2, h * 0.48, d / 2), (w / 2, h * 0.52, d / 2 + 0.001), p.shade(p.body, 0.8))
    if p.state == "messy":
        for s in (-1, 1):
            b.boxc((s * w * 0.4, h + 0.05, 0), (w * 0.3, 0.005, d * 0.9), p.body, roll=s * 0.9)
    elif p.state == "organized":
        b.box(
            (-w / 2 - 0.002, h * 0.5 - 0.02, -d / 2 - 0.002),
            (w / 2 + 0.002, h * 0.5 + 0.02, d / 2 + 0.002),
            p.tone("beige"),
        )
    b.two_hands("lift", h * 0.5, 0.0, w, finger=False)
    b.surface(h, -w / 2 + 0.02, -d / 2 + 0.02, w / 2 - 0.02, d / 2 - 0.02)


def photo_frame(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    b.boxc((0, h / 2, 0), (w, h, 0.015), p.frame, pitch=-0.15)
    b.boxc((0, h / 2, 0.008), (w * 0.8, h * 0.8, 0.002), p.body, pitch=-0.15)
    b.rod((0, h * 0.6, -0.01), (0, 0.0, -d / 2 + 0.005), 0.005, p.frame)
    b.contact("look", "Head", (0.0, h / 2, 0.02))
    b.contact("pick_up", "RightHand", (w / 2, h / 2, 0.0))


def sculpture(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    b.box((-w / 2, 0, -d / 2), (w / 2, h * 0.1, d / 2), p.frame)
    shape = p.style.name
    if shape in ("modern", "minimalist", "futuristic"):
        for i in range(3):
            b.boxc(
                (0, h * (0.25 + 0.27 * i), 0),
                (w * (0.6 - 0.12 * i), h * 0.25, d * (0.6 - 0.12 * i)),
                p.body,
                yaw=0.5 * i,
            )
    else:
        b.lathe(
            (0, h * 0.1, 0),
            [(w * 0.25, 0), (w * 0.35, h * 0.3), (w * 0.2, h * 0.55), (w * 0.15, h * 0.62)],
            p.body,
        )
        b.ellipsoid((0, h * 0.8, 0), (w * 0.2, h * 0.18, d * 0.22), p.body)
    b.contact("look", "Head", (0.0, h * 0.6, d / 2))
    b.contact("touch", "RightHand", (0.0, h * 0.6, d * 0.3))


def teddy(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    b.ellipsoid((0, h * 0.3, 0), (w * 0.35, h * 0.3, d * 0.35), p.body)
    b.ellipsoid((0, h * 0.75, 0), (w * 0.28, h * 0.22, d * 0.28), p.body)
    for s in (-1, 1):
        b.ellipsoid((s * w * 0.22, h * 0.95, 0), (w * 0.1, h * 0.06, d * 0.05), p.body)
        b.ellipsoid((s * w * 0.38, h * 0.35, d * 0.1), (w * 0.12, h * 0.1, d * 0.12), p.body)
        b.ellipsoid((s * w * 0.1, h * 0.78, d * 0.26), (0.008, 0.008, 0.008), p.tone("black"))
    b.contact("hug", "RightHand", (w * 0.3, h * 0.5, 0.0), {"LeftHand": (-w * 0.3, h * 0.5, 0.0)})
    b.contact("pick_up", "RightHand", (w * 0.3, h * 0.5, 0.0))


def cushion(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    if p.state == "messy":
        b.boxc((0, h / 2, 0), (w, h * 0.8, d), p.body, yaw=0.4, roll=0.15)
    else:
        h = h * (0.6 if p.state == "empty" else 1.0)  # an empty cushion is flat
        b.box((-w / 2, 0, -d / 2), (w / 2, h, d / 2), p.body)
        b.box(
            (-w / 2 - 0.005, h * 0.45, -d / 2 - 0.005),
            (w / 2 + 0.005, h * 0.55, d / 2 + 0.005),
            p.shade(p.body, 0.8),
        )
    b.contact("pick_up", "RightHand", (w / 2, h / 2, 0.0))


register("book", book, (0.16, 0.035, 0.24), body="red", kind="book")
register("notebook", book, (0.15, 0.012, 0.21), body="blue", kind="notebook")
register("paper", book, (0.21, 0.02, 0.297), body="white", kind="paper")
register("stapler", book, (0.05, 0.03, 0.16), body="black", kind="stapler")
register("backpack", bag, (0.32, 0.45, 0.2), body="navy", kind="backpack")
register("handbag", bag, (0.32, 0.3, 0.14), body="brown", frame="darkwood", kind="handbag")
register("briefcase", bag, (0.44, 0.36, 0.11), body="brown", frame="charcoal", kind="briefcase")
register("suitcase", bag, (0.45, 0.68, 0.26), body="charcoal", frame="steel", kind="suitcase")
register("box", box, (0.5, 0.4, 0.4), body="beige")
register("photo_frame", photo_frame, (0.2, 0.25, 0.12), body="teal", frame="darkwood")
register("sculpture", sculpture, (0.5, 1.4, 0.5), body="white", frame="stone")
register("teddy_bear", teddy, (0.3, 0.35, 0.22), body="brown")
register("cushion", cushion, (0.42, 0.14, 0.42), body="teal")
