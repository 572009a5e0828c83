"""Round things made by revolving a profile: drinkware, tableware, cookware, vases, bins, plants, balls."""

from __future__ import annotations

import numpy as np

from wana.assets.generators.registry import register
from wana.assets.params import Builder, Params

# Profiles as (radius fraction of w/2, height fraction of h), bottom to top.
PROFILES: dict[str, list[tuple[float, float]]] = {
    "cup": [(0.7, 0.0), (0.85, 0.4), (1.0, 1.0)],
    "mug": [(1.0, 0.0), (1.0, 1.0)],
    "glass": [(0.75, 0.0), (0.9, 0.6), (1.0, 1.0)],
    "wineglass": [(0.8, 0.0), (0.8, 0.02), (0.1, 0.05), (0.1, 0.5), (0.8, 0.6), (1.0, 0.8), (0.9, 1.0)],
    "bottle": [(1.0, 0.0), (1.0, 0.6), (0.4, 0.78), (0.35, 1.0)],
    "can": [(0.9, 0.0), (1.0, 0.06), (1.0, 0.92), (0.85, 1.0)],
    "vase": [(0.6, 0.0), (1.0, 0.35), (0.45, 0.8), (0.6, 1.0)],
    "teapot": [(0.7, 0.0), (1.0, 0.4), (0.8, 0.8), (0.3, 0.9), (0.1, 1.0)],
    "kettle": [(1.0, 0.0), (0.85, 0.75), (0.3, 0.85)],
    "jug": [(0.85, 0.0), (1.0, 0.45), (0.8, 0.85), (0.9, 1.0)],
    "bowl": [(0.55, 0.0), (0.9, 0.5), (1.0, 1.0)],
    "plate": [(0.7, 0.0), (1.0, 0.6), (1.0, 1.0)],
    "pot": [(1.0, 0.0), (1.0, 0.95), (0.3, 1.0)],
    "pan": [(0.85, 0.0), (1.0, 1.0)],
    "bin": [(0.8, 0.0), (1.0, 1.0)],
    "bucket": [(0.85, 0.0), (1.0, 1.0)],
    "basket": [(0.8, 0.0), (1.0, 0.9), (0.95, 1.0)],
    "candle": [(1.0, 0.0), (1.0, 1.0)],
    "plantpot": [(0.7, 0.0), (1.0, 1.0)],
    "umbrella": [(0.9, 0.0), (1.0, 1.0)],
    "extinguisher": [(1.0, 0.0), (1.0, 0.8), (0.5, 0.9), (0.3, 1.0)],
    "soap": [(0.8, 0.0), (1.0, 0.5), (0.6, 0.8), (0.25, 1.0)],
}

_STYLE_WARP = {
    "": 1.0,
    "modern": 0.9,
    "classic": 1.1,
    "old": 1.05,
    "rustic": 1.15,
    "minimalist": 0.85,
    "industrial": 1.0,
    "luxurious": 1.2,
    "futuristic": 0.8,
}


def vessel(
    b: Builder,
    p: Params,
    shape: str = "cup",
    handle: bool = False,
    act: str = "drink",
    also: tuple[str, ...] = (),
    spout: bool = False,
    lid: bool = False,
    rim: bool = False,
) -> None:
    w, h, d = p.w, p.h, p.d
    r = min(w, d) / 2
    warp = _STYLE_WARP[p.style.name]
    prof = [(r * (f**warp if f > 0 else f), h * y) for f, y in PROFILES[shape]]
    b.lathe((0, 0, 0), prof, p.body, sections=20)
    if rim or p.style.trim:
        b.lathe(
            (0, h * 0.97, 0), [(prof[-1][0] * 1.02, 0), (prof[-1][0] * 1.02, h * 0.03)], p.frame, sections=20
        )
    if lid:
        b.lathe((0, h, 0), [(r * 0.35, 0), (r * 0.1, h * 0.08), (0.0, h * 0.1)], p.frame, sections=12)
    hx = r
    if handle:
        for y0, y1 in ((0.25, 0.45), (0.45, 0.65), (0.65, 0.8)):
            x0 = hx + (0.02 if y0 > 0.3 and y1 < 0.7 else 0.005)
            b.rod(
                (hx * 0.95 if y0 == 0.25 else x0, h * y0, 0),
                (x0 if y1 < 0.8 else hx * 0.95, h * y1, 0),
                max(0.004, r * 0.1),
                p.body,
                sections=6,
            )
    if spout:
        b.rod((-r * 0.8, h * 0.35, 0), (-r * 1.5, h * 0.75, 0), r * 0.12, p.body, sections=8)
    grip = (hx + 0.02, h * 0.5, 0.0) if handle else (r, h * 0.5, 0.0)
    b.contact(act, "RightHand", grip)
    for more in also:  # a bottle is drunk from and poured from, held the same way
        b.contact(more, "RightHand", grip)
    b.contact("pick_up", "RightHand", grip)
    if shape in ("plate", "bowl", "pan", "pot"):
        b.surface(h * 0.3, -r * 0.5, -r * 0.5, r * 0.5, r * 0.5)


def plant(b: Builder, p: Params, tall: bool = True) -> None:
    w, h, d = p.w, p.h, p.d
    r = min(w, d) / 2
    pot_h = h * (0.25 if tall else 0.4)
    b.lathe((0, 0, 0), [(r * 0.45, 0), (r * 0.6, pot_h)], p.body, sections=16)
    leaf = p.tone("leaf") if p.state != "messy" else p.tone("brown")  # a neglected plant wilts
    rng = np.random.default_rng(p.seed + 23)
    b.cyl((0, pot_h, 0), 0.015, (h - pot_h) * 0.5, p.tone("darkwood"), sections=6)
    n = 5 if p.state != "empty" else 2
    for i in range(n):
        a = 2 * np.pi * i / n + rng.uniform(-0.3, 0.3)
        rr = r * (0.45 if i else 0.0)
        cy = pot_h + (h - pot_h) * (0.55 + 0.1 * (i % 2))
        b.ellipsoid(
            (rr * np.cos(a), cy, rr * np.sin(a)),
            (r * 0.5, (h - pot_h) * 0.3, r * 0.5),
            p.shade(leaf, 0.85 + 0.1 * (i % 3)),
        )
    b.contact("water", "RightHand", (0.0, pot_h + 0.05, r * 0.6))


def globe(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    r = min(w, d) / 2
    b.cyl((0, 0, 0), r * 0.6, 0.02, p.frame)
    b.cyl((0, 0.02, 0), 0.01, h - 2 * r, p.frame, sections=6)
    b.ellipsoid((0, h - r, 0), (r, r, r), p.body)
    b.ellipsoid((r * 0.3, h - r * 0.8, r * 0.3), (r * 0.5, r * 0.55, r * 0.75), p.tone("leaf"))
    b.contact("spin", "RightHand", (r, h - r, 0.0))


def ball(b: Builder, p: Params, kind: str = "ball") -> None:
    _w, h, _d = p.w, p.h, p.d
    r = h / 2
    b.ellipsoid((0, r, 0), (r, r, r), p.body)
    b.ellipsoid((0, r, 0), (r * 1.001, r * 0.12, r * 1.001), p.tone("white" if kind == "ball" else "grey"))
    if kind == "ball":
        b.contact("kick", "RightToeBase", (0.0, r * 0.4, r))
        b.contact("pick_up", "RightHand", (r, r, 0.0), {"LeftHand": (-r, r, 0.0)})
    else:
        b.contact("sit", "Hips", (0.0, h + 0.02, 0.0))


def kettlebell(b: Builder, p: Params) -> None:
    w, _h, d = p.w, p.h, p.d
    r = min(w, d) / 2
    b.ellipsoid((0, r, 0), (r, r, r), p.body)
    b.rod((-r * 0.6, r * 1.6, 0), (r * 0.6, r * 1.6, 0), 0.012, p.body)
    for s in (-1, 1):
        b.rod((s * r * 0.6, r * 1.6, 0), (s * r * 0.5, r * 1.2, 0), 0.012, p.body)
    b.contact("lift", "RightHand", (0.0, r * 1.6, 0.0))


register("cup", vessel, (0.08, 0.09, 0.08), body="white", shape="cup", handle=True)
register("mug", vessel, (0.085, 0.1, 0.085), body="blue", shape="mug", handle=True)
register("glass", vessel, (0.07, 0.12, 0.07), body="glass", shape="glass")
register(
    "bottle",
    vessel,
    (0.075, 0.28, 0.075),
    body="green",
    frame="steel",
    shape="bottle",
    rim=True,
    also=("pour",),
)
register("soda_can", vessel, (0.066, 0.122, 0.066), body="red", frame="steel", shape="can")
register("vase", vessel, (0.18, 0.35, 0.18), body="teal", frame="gold", shape="vase", act="touch")
register(
    "teapot",
    vessel,
    (0.18, 0.16, 0.18),
    body="white",
    shape="teapot",
    handle=True,
    spout=True,
    lid=True,
    act="pour",
)
register("jug", vessel, (0.13, 0.22, 0.13), body="glass", shape="jug", handle=True, spout=True, act="pour")
register(
    "kettle",
    vessel,
    (0.18, 0.24, 0.18),
    body="steel",
    frame="black",
    shape="kettle",
    handle=True,
    spout=True,
    lid=True,
    act="pour",
)
register("bowl", vessel, (0.2, 0.08, 0.2), body="white", shape="bowl", act="eat")
register("plate", vessel, (0.26, 0.025, 0.26), body="white", shape="plate", act="eat")
register("pot", vessel, (0.26, 0.18, 0.26), body="steel", frame="black", shape="pot", lid=True, act="cook")
register("pan", vessel, (0.28, 0.05, 0.28), body="charcoal", shape="pan", handle=True, act="cook")
register(
    "trash_can", vessel, (0.32, 0.45, 0.32), body="grey", frame="charcoal", shape="bin", rim=True, act="throw"
)
register(
    "paint_bucket",
    vessel,
    (0.28, 0.32, 0.28),
    body="white",
    frame="steel",
    shape="bucket",
    handle=True,
    act="paint",
)
register("basket", vessel, (0.45, 0.4, 0.45), body="lightwood", shape="basket", act="carry", rim=True)
register("candle", vessel, (0.06, 0.2, 0.06), body="ivory", frame="gold", shape="candle", act="light")
register("umbrella_stand", vessel, (0.25, 0.55, 0.25), body="charcoal", shape="umbrella", act="touch")
register(
    "fire_extinguisher",
    vessel,
    (0.16, 0.55, 0.16),
    body="red",
    frame="black",
    shape="extinguisher",
    handle=True,
    act="spray",
)
register("soap", vessel, (0.08, 0.18, 0.08), body="white", frame="chrome", shape="soap", act="wash")
register("plant", plant, (0.5, 1.1, 0.5), body="terracotta")
register("globe", globe, (0.3, 0.45, 0.3), body="blue", frame="gold")
register("ball", ball, (0.22, 0.22, 0.22), body="white", kind="ball")
register("exercise_ball", ball, (0.65, 0.65, 0.65), body="blue", kind="exercise")
register("kettlebell", kettlebell, (0.2, 0.28, 0.2), body="charcoal")
