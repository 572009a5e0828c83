"""Things stories put on tables and floors that no furniture family covers: a rug, a cake, a box of
chocolates, vegetables and a loaf of bread to cut, a strip of photo negatives, a pill bottle, and the low cradle
an instrument rests on."""

from __future__ import annotations

import numpy as np

from wana.assets.generators.registry import register
from wana.assets.params import Builder, Params


def rug(b: Builder, p: Params) -> None:
    """A flat rug with a border: low enough to walk over (see wana.domain.routes), so no stand spot."""
    w, h, d = p.w, p.h, p.d
    e = 0.08  # the border's width
    b.box((-w / 2 + e, 0, -d / 2 + e), (w / 2 - e, h, d / 2 - e), p.body)
    b.box((-w / 2, 0, -d / 2), (w / 2, h, -d / 2 + e), p.frame)
    b.box((-w / 2, 0, d / 2 - e), (w / 2, h, d / 2), p.frame)
    b.box((-w / 2, 0, -d / 2 + e), (-w / 2 + e, h, d / 2 - e), p.frame)
    b.box((w / 2 - e, 0, -d / 2 + e), (w / 2, h, d / 2 - e), p.frame)
    if p.style.trim:  # a fringe at both short ends
        for s in (-1, 1):
            b.box((s * w / 2, 0, -d / 2), (s * (w / 2 + 0.04), h * 0.3, d / 2), p.tone("cream"))
    b.contact("vacuum", "RightHand", (0.0, h, 0.0))
    b.contact("sweep", "RightHand", (0.0, h, 0.0))
    b.stand = (0.0, 0.0, d / 2 + 0.3)


def instrument_stand(b: Builder, p: Params) -> None:
    """A low A-frame cradle: two padded arms an instrument's body rests on."""
    w, h, d = p.w, p.h, p.d
    for s in (-1, 1):
        b.rod((s * w / 2, 0.0, -d / 2), (s * w * 0.3, h, 0.0), 0.012, p.frame)
        b.rod((s * w / 2, 0.0, d / 2), (s * w * 0.3, h, 0.0), 0.012, p.frame)
    b.box((-w * 0.35, h - 0.02, -0.03), (w * 0.35, h, 0.03), p.body)
    b.surface(h, -w * 0.35, -0.03, w * 0.35, 0.03)
    b.contact("pick_up", "RightHand", (0.0, h, 0.0))


def cake(b: Builder, p: Params) -> None:
    """A round cake on a plate: two tiers of sponge, icing on top, candles unless eaten (state empty)."""
    w, h, d = p.w, p.h, p.d
    r = min(w, d) / 2
    b.cyl((0, 0, 0), r * 1.1, 0.012, p.tone("white"), sections=24)
    b.cyl((0, 0.012, 0), r, h * 0.45, p.body, sections=24)
    b.cyl((0, 0.012 + h * 0.45, 0), r * 0.98, h * 0.08, p.tone("cream"), sections=24)
    b.cyl((0, 0.012 + h * 0.53, 0), r * 0.7, h * 0.3, p.body, sections=24)
    top = 0.012 + h * 0.83
    b.cyl((0, top, 0), r * 0.7, h * 0.05, p.tone("pink"), sections=24)
    if p.state != "empty":
        for k in range(5):
            a = 2 * np.pi * k / 5
            x, z = r * 0.45 * np.cos(a), r * 0.45 * np.sin(a)
            b.cyl((x, top, z), 0.005, h * 0.12, p.tone("ivory"), sections=6)
    b.contact("eat", "RightHand", (r * 0.9, h * 0.5, 0.0))
    b.contact("cut", "RightHand", (0.0, top, r * 0.3))
    b.contact("blow", "Head", (0.0, top + 0.25, r + 0.1))
    b.surface(top, -r * 0.4, -r * 0.4, r * 0.4, r * 0.4)


def chocolate_box(b: Builder, p: Params) -> None:
    """A flat box of chocolates with the lid off to one side; rows of pralines inside."""
    w, h, d = p.w, p.h, p.d
    b.box((-w / 2, 0, -d / 2), (w / 2, h * 0.7, d / 2), p.body)
    if p.state != "empty":
        for i in range(4):
            for j in range(3):
                x = -w / 2 + w * (i + 0.5) / 4
                z = -d / 2 + d * (j + 0.5) / 3
                b.ellipsoid((x, h * 0.75, z), (w / 10, h * 0.3, d / 8), p.tone("brown", 0.7 + 0.1 * (i % 2)))
    b.contact("pick_up", "RightHand", (w / 2, h * 0.5, 0.0))
    b.contact("eat", "RightHand", (0.0, h, 0.0))
    b.contact("present", "RightHand", (w / 2, h * 0.5, 0.0), {"LeftHand": (-w / 2, h * 0.5, 0.0)})


def vegetable(b: Builder, p: Params) -> None:
    """A few vegetables lying together (an onion, a carrot, a tomato): what one chops on a board."""
    w, h, d = p.w, p.h, p.d
    r = h / 2
    b.ellipsoid((-w * 0.25, r, -d * 0.1), (r * 1.05, r, r * 1.05), p.body)  # the onion
    b.cyl((-w * 0.25, h * 0.95, -d * 0.1), r * 0.12, h * 0.12, p.tone("leaf"), sections=6)
    b.ellipsoid((w * 0.22, r * 0.85, d * 0.2), (r * 0.85, r * 0.85, r * 0.85), p.tone("red"))  # the tomato
    b.rod((-w * 0.45, h * 0.2, d * 0.38), (w * 0.45, h * 0.2, d * 0.3), h * 0.2, p.tone("orange"))  # a carrot
    top = (0.0, h, 0.0)
    b.contact("pick_up", "RightHand", top)
    b.contact("cut", "RightHandMiddle1", top)
    b.contact("eat", "RightHand", top)


def bread(b: Builder, p: Params) -> None:
    """A loaf of bread: a rounded crust, scored across the top."""
    w, h, d = p.w, p.h, p.d
    b.box((-w / 2, 0, -d / 2), (w / 2, h * 0.55, d / 2), p.body)
    b.ellipsoid((0, h * 0.55, 0), (w / 2, h * 0.45, d / 2), p.body)
    for k in (-1, 0, 1):
        b.boxc((k * w * 0.25, h * 0.97, 0), (0.01, 0.006, d * 0.6), p.tone("cream"), yaw=0.4)
    b.contact("pick_up", "RightHand", (0.0, h, 0.0))
    b.contact("cut", "RightHandMiddle1", (0.0, h, 0.0))
    b.contact("eat", "RightHand", (w * 0.4, h * 0.6, 0.0))


def film_negative(b: Builder, p: Params) -> None:
    """A strip of negatives in a paper sleeve lying flat: frames in dark amber."""
    w, h, d = p.w, p.h, p.d
    b.box((-w / 2, 0, -d / 2), (w / 2, h * 0.5, d / 2), p.tone("paper"))
    for i in range(5):
        x0 = -w / 2 + w * i / 5 + 0.004
        b.box((x0, h * 0.5, -d * 0.35), (x0 + w / 5 - 0.008, h, d * 0.35), p.body)
    b.contact("pick_up", "RightHand", (w / 2, h, 0.0))
    b.contact("look", "Head", (0.0, h, 0.0))


def pill_bottle(b: Builder, p: Params) -> None:
    """A small pill bottle with a white cap."""
    w, h, d = p.w, p.h, p.d
    r = min(w, d) / 2
    b.cyl((0, 0, 0), r, h * 0.78, p.body, sections=14)
    b.cyl((0, h * 0.78, 0), r * 1.05, h * 0.22, p.tone("white"), sections=14)
    b.cyl((0, h * 0.3, 0), r * 1.04, h * 0.3, p.tone("white"), sections=14)  # the label
    b.contact("pick_up", "RightHand", (r, h * 0.5, 0.0))
    b.contact("eat", "RightHand", (r, h * 0.5, 0.0))


register("rug", rug, (2.0, 0.012, 1.4), body="red", frame="navy")
register("instrument_stand", instrument_stand, (0.34, 0.14, 0.3), body="rubber", frame="black")
register("cake", cake, (0.26, 0.16, 0.26), body="beige")
register("chocolate_box", chocolate_box, (0.24, 0.04, 0.18), body="red")
register("vegetable", vegetable, (0.2, 0.07, 0.14), body="beige")
register("bread", bread, (0.28, 0.11, 0.13), body="brown")
register("film_negative", film_negative, (0.2, 0.004, 0.05), body="orange")
register("pill_bottle", pill_bottle, (0.045, 0.09, 0.045), body="orange")
