"""Gym equipment: boxing bag, ring and gloves, treadmill, bikes, rowers, weights, mats."""

from __future__ import annotations

from wana.assets.generators.registry import register
from wana.assets.params import Builder, Params


def boxing_bag(b: Builder, p: Params) -> None:
    """A heavy bag hanging from a free-standing frame (bag centre about 1.2 m up)."""
    w, h, d = p.w, p.h, p.d
    r = min(w, d) * 0.25
    b.box((-w / 2, 0, -d / 2), (w / 2, 0.05, -d / 2 + 0.1), p.frame)
    b.box((-0.05, 0, -d / 2), (0.05, 0.05, d / 2), p.frame)
    b.box((-0.04, 0.05, -d / 2), (0.04, h, -d / 2 + 0.08), p.frame)
    b.box((-0.04, h - 0.08, -d / 2), (0.04, h, 0.1), p.frame)
    bag_top = h - 0.35
    bag_bottom = max(0.3, bag_top - 1.0 * p.h / 2.2)
    b.rod((0, h - 0.08, 0.05), (0, bag_top, 0.05), 0.006, p.tone("steel"))
    b.lathe(
        (0, bag_bottom, 0.05),
        [(r * 0.9, 0), (r, 0.05), (r, bag_top - bag_bottom - 0.05), (r * 0.8, bag_top - bag_bottom)],
        p.body,
        sections=16,
    )
    mid = (bag_top + bag_bottom) / 2
    b.contact("punch", "RightHand", (0.0, mid + 0.15, 0.05 + r), {"LeftHand": (0.0, mid + 0.2, 0.05 + r)})
    b.contact("kick", "RightToeBase", (0.0, bag_bottom + 0.2, 0.05 + r))
    b.stand = (0.0, 0.0, 0.05 + r + 0.45)


def boxing_ring(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    floor_h = 0.5
    b.box((-w / 2, 0, -d / 2), (w / 2, floor_h, d / 2), p.frame)
    b.box((-w / 2 + 0.02, floor_h, -d / 2 + 0.02), (w / 2 - 0.02, floor_h + 0.02, d / 2 - 0.02), p.body)
    for x in (-w / 2 + 0.06, w / 2 - 0.06):
        for z in (-d / 2 + 0.06, d / 2 - 0.06):
            b.cyl((x, floor_h, z), 0.05, h - floor_h, p.tone("white"), sections=10)
    for k in range(3):
        y = floor_h + 0.4 + 0.35 * k
        rc = p.tone(("red", "white", "blue")[k])
        b.box((-w / 2 + 0.06, y, -d / 2 + 0.05), (w / 2 - 0.06, y + 0.025, -d / 2 + 0.07), rc)
        b.box((-w / 2 + 0.06, y, d / 2 - 0.07), (w / 2 - 0.06, y + 0.025, d / 2 - 0.05), rc)
        b.box((-w / 2 + 0.05, y, -d / 2 + 0.06), (-w / 2 + 0.07, y + 0.025, d / 2 - 0.06), rc)
        b.box((w / 2 - 0.07, y, -d / 2 + 0.06), (w / 2 - 0.05, y + 0.025, d / 2 - 0.06), rc)
    b.surface(floor_h + 0.02, -w / 2 + 0.2, -d / 2 + 0.2, w / 2 - 0.2, d / 2 - 0.2)
    b.contact("climb", "RightHand", (0.0, floor_h + 0.4, d / 2 - 0.05))
    b.stand = (0.0, 0.0, d / 2 + 0.4)


def gloves(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    for s in (-1, 1):
        b.ellipsoid((s * w / 4, h / 2, 0), (w / 4, h / 2, d / 2), p.body)
        b.cyl((s * w / 4, h * 0.3, -d / 2), h * 0.3, d * 0.3, p.tone("white"), axis="z", sections=10)
    b.contact("wear", "RightHand", (w / 4, h / 2, 0.0), {"LeftHand": (-w / 4, h / 2, 0.0)})


def treadmill(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    b.box((-w / 2, 0, -d / 2), (w / 2, 0.18, d / 2 - 0.2), p.frame)
    b.box((-w / 2 + 0.08, 0.18, -d / 2 + 0.05), (w / 2 - 0.08, 0.2, d / 2 - 0.25), p.tone("rubber"))
    for x in (-w / 2 + 0.04, w / 2 - 0.04):
        b.rod((x, 0.1, -d / 2 + 0.15), (x, h - 0.1, -d / 2 + 0.05), 0.025, p.frame)
        b.box((x - 0.025, 1.0, -d / 2 + 0.05), (x + 0.025, 1.04, -d / 2 + 0.45), p.frame)
    b.boxc((0, h - 0.08, -d / 2 + 0.08), (w * 0.9, 0.2, 0.08), p.body, pitch=0.5)
    b.contact("run", "Hips", (0.0, 1.0, 0.1))
    b.two_hands("hold", 1.06, -d / 2 + 0.3, w - 0.08, finger=False)
    b.stand = (0.0, 0.0, d / 2 + 0.3)


def exercise_bike(b: Builder, p: Params, kind: str = "bike") -> None:
    w, h, d = p.w, p.h, p.d
    if kind == "rower":
        b.box((-0.06, 0.1, -d / 2), (0.06, 0.16, d / 2), p.frame)
        for z in (-d / 2 + 0.05, d / 2 - 0.05):
            b.box((-w / 2, 0, z - 0.04), (w / 2, 0.1, z + 0.04), p.frame)
        b.cyl((0, 0.35, -d / 2 + 0.05), 0.25, 0.12, p.body, axis="x", sections=18)
        b.box((-0.15, 0.2, -0.1), (0.15, 0.26, 0.2), p.tone("black"))
        b.contact("sit", "Hips", (0.0, 0.29, 0.05))
        b.two_hands("row", 0.5, -d / 2 + 0.35, 0.4, finger=False)
        b.stand = (w / 2 + 0.4, 0.0, 0.0)
        return
    for z in (-d / 2 + 0.05, d / 2 - 0.05):
        b.box((-w / 2, 0, z - 0.04), (w / 2, 0.06, z + 0.04), p.frame)
    b.rod((0, 0.06, d / 2 - 0.05), (0, 0.85, d / 2 - 0.25), 0.03, p.frame)
    b.rod((0, 0.06, -d / 2 + 0.05), (0, h - 0.1, -d / 2 + 0.12), 0.03, p.frame)
    b.cyl((-0.02, 0.35, -d / 2 + 0.25), 0.2, 0.04, p.body, axis="x", sections=18)
    b.box((-0.12, 0.85, d / 2 - 0.38), (0.12, 0.91, d / 2 - 0.12), p.tone("black"))
    b.box((-w / 2 + 0.02, h - 0.1, -d / 2 + 0.08), (w / 2 - 0.02, h - 0.06, -d / 2 + 0.16), p.frame)
    b.contact("sit", "Hips", (0.0, 0.93, d / 2 - 0.25))
    b.two_hands("ride", h - 0.08, -d / 2 + 0.12, w - 0.1, finger=False)
    b.stand = (w / 2 + 0.35, 0.0, d / 2 - 0.25)


def weights(b: Builder, p: Params, kind: str = "dumbbell") -> None:
    w, h, _d = p.w, p.h, p.d
    r = h / 2
    bar = p.tone("chrome")
    b.cyl((-w / 2, r, 0), 0.015, w, bar, axis="x", sections=8)
    n = 2 if kind == "dumbbell" else 3
    for s in (-1, 1):
        for i in range(n):
            x = s * (w / 2 - (0.03 if kind == "dumbbell" else 0.12) - i * 0.035)
            b.cyl((x - 0.015, r, 0), r * (1 - 0.12 * i), 0.03, p.body, axis="x", sections=16)
    if kind == "dumbbell":
        b.contact("lift", "RightHand", (0.0, r, 0.0))
        b.contact("pick_up", "RightHand", (0.0, r, 0.0))  # taken by the bar before it is lifted
    else:
        b.two_hands("lift", r, 0.0, 0.6, finger=False)


def mat(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    b.box((-w / 2, 0, -d / 2), (w / 2, h, d / 2), p.body)
    b.cyl((-w / 2, h, -d / 2 + 0.05), 0.05, w, p.body, axis="x", sections=12)
    b.contact("lie", "Hips", (0.0, h + 0.1, 0.1))
    b.contact("sit", "Hips", (0.0, h + 0.05, 0.1))
    b.stand = (w / 2 + 0.3, 0.0, 0.0)


register("boxing_bag", boxing_bag, (0.9, 2.2, 0.9), body="red", frame="charcoal")
register("boxing_ring", boxing_ring, (4.0, 1.65, 4.0), body="blue", frame="charcoal")
register("boxing_gloves", gloves, (0.3, 0.14, 0.22), body="red")
register("treadmill", treadmill, (0.8, 1.4, 1.8), body="charcoal", frame="grey")
register("exercise_bike", exercise_bike, (0.55, 1.25, 1.05), body="charcoal", frame="grey")
register("rowing_machine", exercise_bike, (0.55, 0.6, 2.2), body="charcoal", frame="grey", kind="rower")
register("dumbbell", weights, (0.32, 0.12, 0.12), body="black", kind="dumbbell")
register("barbell", weights, (1.8, 0.42, 0.42), body="black", kind="barbell")
register("yoga_mat", mat, (0.62, 0.008, 1.75), body="purple")
