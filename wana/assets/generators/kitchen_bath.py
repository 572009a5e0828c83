"""Kitchen appliances and bathroom fixtures: fridge, stove, dishwasher, sinks, toilet, tub, shower."""

from __future__ import annotations

from wana.assets.generators.registry import register
from wana.assets.params import Builder, Params


def appliance(b: Builder, p: Params, kind: str = "fridge") -> None:
    w, h, d = p.w, p.h, p.d
    fz = d / 2
    b.box((-w / 2, 0, -d / 2), (w / 2, h, d / 2 - 0.02), p.body)
    handle = p.tone("chrome") if p.style.name != "old" else p.tone("black")
    if kind == "fridge":
        split = h * (0.62 if p.style.name != "modern" else 0.7)
        for y0, y1 in ((0.02, split - 0.01), (split + 0.01, h - 0.02)):
            b.box((-w / 2 + 0.01, y0, fz - 0.02), (w / 2 - 0.01, y1, fz), p.shade(p.body, 1.03))
            b.box(
                (w / 2 - 0.08, (y0 + y1) / 2 - 0.15, fz),
                (w / 2 - 0.06, (y0 + y1) / 2 + 0.15, fz + 0.04),
                handle,
            )
        b.contact("open", "RightHand", (w / 2 - 0.07, split - 0.2, fz + 0.05))
    elif kind in ("stove", "dishwasher", "washer"):
        if kind == "stove":
            for x in (-w / 4, w / 4):
                for z in (-d / 4, d / 6):
                    b.cyl((x, h, z), 0.08, 0.01, p.tone("charcoal"), sections=14)
            b.box((-w / 2 + 0.03, 0.1, fz - 0.02), (w / 2 - 0.03, h - 0.15, fz), p.tone("screen", 2.0))
            b.box((-w / 2, h - 0.12, fz - 0.02), (w / 2, h - 0.02, fz), p.shade(p.body, 0.9))
            b.two_hands("cook", h + 0.05, 0.0, 0.4)
        elif kind == "washer":
            b.cyl((0, h * 0.45, fz - 0.02), min(w, h) * 0.3, 0.03, p.tone("glass"), axis="z", sections=20)
        else:
            b.box((-w / 2 + 0.01, 0.1, fz - 0.02), (w / 2 - 0.01, h - 0.02, fz), p.shade(p.body, 1.05))
        b.box((-w / 2 + 0.1, h - 0.1, fz), (w / 2 - 0.1, h - 0.08, fz + 0.03), handle)
        b.contact("open", "RightHand", (0.0, h - 0.09, fz + 0.05))
        b.surface(h, -w / 2 + 0.02, -d / 2 + 0.02, w / 2 - 0.02, d / 2 - 0.04)
    elif kind == "boiler":  # a tall tank: a dial panel at chest height and pipes from its top to the wall
        b.box((-w / 2 + 0.08, h * 0.55, fz - 0.02), (w / 2 - 0.08, h * 0.7, fz), p.tone("charcoal"))
        b.cyl((0.0, h * 0.62, fz), 0.04, 0.02, p.tone("white"), axis="z", sections=12)
        for x in (-w / 4, 0.0, w / 4):
            b.cyl((x, h, 0.0), 0.025, 0.25, p.tone("gold", 0.8), sections=8)
        b.contact("use", "RightHand", (0.0, h * 0.62, fz + 0.04))
    b.stand = (0.0, 0.0, d / 2 + 0.45)


def sink(b: Builder, p: Params, kind: str = "kitchen") -> None:
    w, h, d = p.w, p.h, p.d
    if kind == "kitchen":
        b.box((-w / 2, 0.1, -d / 2), (w / 2, h - 0.04, d / 2 - 0.02), p.frame)
        b.box((-w / 2 + 0.02, 0, -d / 2 + 0.02), (w / 2 - 0.02, 0.1, d / 2 - 0.06), p.tone("charcoal"))
        b.box((-w / 2, h - 0.04, -d / 2), (-w * 0.3, h, d / 2), p.body)
        b.box((w * 0.3, h - 0.04, -d / 2), (w / 2, h, d / 2), p.body)
        b.box((-w * 0.3, h - 0.04, -d / 2), (w * 0.3, h, -d / 2 + 0.08), p.body)
        b.box((-w * 0.3, h - 0.04, d / 2 - 0.08), (w * 0.3, h, d / 2), p.body)
        b.box((-w * 0.3, h - 0.2, -d / 2 + 0.08), (w * 0.3, h - 0.04, d / 2 - 0.08), p.tone("chrome"))
        top = h
        b.surface(h, w * 0.3, -d / 2 + 0.02, w / 2 - 0.02, d / 2 - 0.02)
    else:
        if p.style.leg == "pedestal" or p.style.name in ("", "classic", "old", "luxurious"):
            b.lathe((0, 0, -d * 0.1), [(0.1, 0), (0.07, h * 0.5), (0.12, h * 0.8)], p.body)
        else:
            b.box((-w / 2, 0, -d / 2), (w / 2, h * 0.8, d / 2 - 0.02), p.frame)
        b.lathe((0, h * 0.8, 0), [(min(w, d) * 0.3, 0), (min(w, d) * 0.5, h * 0.2)], p.body, sections=20)
        top = h
        r = min(w, d) * 0.5
        b.surface(h, -r, -r, r, r)  # the basin's rim
    b.lathe((0, top, -d / 2 + 0.05), [(0.02, 0), (0.015, 0.25)], p.tone("chrome"), sections=8)
    b.rod((0, top + 0.23, -d / 2 + 0.05), (0, top + 0.2, -d / 2 + 0.2), 0.012, p.tone("chrome"))
    b.two_hands("wash", top - 0.05, 0.0, 0.3)
    b.stand = (0.0, 0.0, d / 2 + 0.35)


def toilet(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    seat_h = 0.42
    b.lathe((0, 0, 0.05), [(0.12, 0), (0.14, seat_h * 0.6)], p.body)
    b.ellipsoid((0, seat_h - 0.06, 0.08), (w / 2 * 0.95, 0.07, d * 0.3), p.body)
    b.box((-w / 2, seat_h - 0.1, -d / 2), (w / 2, h, -d / 2 + 0.2), p.body)  # tank
    b.box((-0.04, h - 0.01, -d / 2 + 0.08), (0.04, h + 0.01, -d / 2 + 0.12), p.tone("chrome"))
    b.contact("sit", "Hips", (0.0, seat_h + 0.10, 0.05))  # the thighs on the seat, not in it
    b.contact("flush", "RightHand", (0.0, h + 0.02, -d / 2 + 0.1))
    b.stand = (0.0, 0.0, d / 2 + 0.3)


def bathtub(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    wall = 0.08 * p.style.top_t
    if p.style.leg in ("turned", "cyl"):
        for x in (-w / 2 + 0.15, w / 2 - 0.15):
            for z in (-d / 2 + 0.1, d / 2 - 0.1):
                p.leg(b, x, z, 0, 0.12, 0.06, p.tone("gold"))
        y0 = 0.12
    else:
        y0 = 0.0
    b.box((-w / 2, y0, -d / 2), (w / 2, y0 + 0.08, d / 2), p.body)
    b.box((-w / 2, y0, -d / 2), (w / 2, h, -d / 2 + wall), p.body)
    b.box((-w / 2, y0, d / 2 - wall), (w / 2, h, d / 2), p.body)
    b.box((-w / 2, y0, -d / 2), (-w / 2 + wall, h, d / 2), p.body)
    b.box((w / 2 - wall, y0, -d / 2), (w / 2, h, d / 2), p.body)
    b.box((-w / 2 + wall, y0 + 0.08, -d / 2 + wall), (w / 2 - wall, h - 0.15, d / 2 - wall), p.tone("glass"))
    b.contact("lie", "Hips", (0.0, y0 + 0.15, 0.0))
    b.contact("sit", "Hips", (w * 0.25, y0 + 0.15, 0.0))
    b.surface(y0 + 0.08, -w / 2 + wall, -d / 2 + wall, w / 2 - wall, d / 2 - wall)  # the tub's floor: lain on
    b.stand = (0.0, 0.0, d / 2 + 0.35)


def shower(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    b.box((-w / 2, 0, -d / 2), (w / 2, 0.1, d / 2), p.body)
    b.box((-w / 2, 0.1, -d / 2), (w / 2, h, -d / 2 + 0.02), p.body)
    b.box((-w / 2, 0.1, -d / 2), (-w / 2 + 0.02, h, d / 2), p.tone("glass"))
    b.box((w / 2 - 0.02, 0.1, -d / 2), (w / 2, h, d / 2), p.tone("glass"))
    b.rod((0, h - 0.2, -d / 2 + 0.02), (0, h - 0.25, -d / 2 + 0.25), 0.012, p.tone("chrome"))
    b.cyl((0, h - 0.27, -d / 2 + 0.25), 0.07, 0.02, p.tone("chrome"))
    b.contact("wash", "RightHand", (0.0, 1.3, -d / 2 + 0.05))
    b.stand = (0.0, 0.0, 0.0)


def towel_rack(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    for x in (-w / 2 + 0.02, w / 2 - 0.02):
        b.box((x - 0.015, 0, -d / 2), (x + 0.015, 0.02, d / 2), p.frame)
        b.cyl((x, 0.0, 0), 0.012, h, p.frame, sections=8)
    for y in (h * 0.6, h * 0.95):
        b.cyl((-w / 2 + 0.02, y, 0), 0.01, w - 0.04, p.frame, axis="x", sections=8)
    b.box((-w * 0.35, h * 0.5, -0.02), (w * 0.35, h * 0.96, 0.02), p.body)
    b.contact("take", "RightHand", (0.0, h * 0.9, 0.03))
    b.surface(h * 0.96, -w / 2 + 0.02, -d / 2, w / 2 - 0.02, d / 2)  # things hang over the top bar


def towel(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    if p.state == "messy":
        b.ellipsoid((0, h / 2, 0), (w / 2, h / 2, d / 2), p.body)
    else:
        n = 1 if p.state == "empty" else 3
        for i in range(n):
            b.box(
                (-w / 2, i * h / 3, -d / 2),
                (w / 2, (i + 1) * h / 3 - 0.003, d / 2),
                p.shade(p.body, 1 - 0.08 * i),
            )
    b.contact("pick_up", "RightHand", (0.0, h, 0.0))


def coffee_maker(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    b.box((-w / 2, 0, -d / 2), (w / 2, 0.04, d / 2), p.body)
    b.box((-w / 2, 0, -d / 2), (w / 2, h, -d / 2 + d * 0.45), p.body)
    b.box((-w / 2, h * 0.7, -d / 2), (w / 2, h, d / 2), p.body)
    b.lathe((0, 0.04, d * 0.1), [(w * 0.3, 0), (w * 0.35, h * 0.45)], p.tone("glass"), sections=14)
    b.cyl((w * 0.25, h * 0.8, d / 2), 0.015, 0.01, p.tone("red"), axis="z", sections=8)
    b.contact("use", "RightHandMiddle1", (w * 0.25, h * 0.8, d / 2 + 0.01))
    b.contact("pick_up", "RightHand", (w * 0.35, h * 0.25, d * 0.1))


def toothbrush(b: Builder, p: Params) -> None:
    w, h, _d = p.w, p.h, p.d
    b.lathe((0, 0, 0), [(w * 0.4, 0), (w * 0.45, h * 0.5)], p.tone("white"), sections=14)
    for i, s in enumerate((-1, 1)):
        b.rod(
            (s * w * 0.12, h * 0.05, 0),
            (s * w * 0.35, h, 0.0),
            0.005,
            p.body if i else p.shade(p.body, 0.7),
            sections=6,
        )
    b.contact("brush", "RightHand", (w * 0.3, h * 0.8, 0.0))


register("coffee_maker", coffee_maker, (0.22, 0.36, 0.3), body="black")
register("toothbrush", toothbrush, (0.08, 0.2, 0.08), body="teal")
register("refrigerator", appliance, (0.7, 1.8, 0.7), body="white", kind="fridge")
register("stove", appliance, (0.6, 0.9, 0.6), body="white", kind="stove")
register("dishwasher", appliance, (0.6, 0.85, 0.6), body="steel", kind="dishwasher")
register("washing_machine", appliance, (0.6, 0.85, 0.6), body="white", kind="washer")
register("boiler", appliance, (0.5, 1.6, 0.45), body="white", kind="boiler")
register("kitchen_sink", sink, (1.0, 0.92, 0.6), body="stone", frame="white", kind="kitchen")
register("bathroom_sink", sink, (0.55, 0.85, 0.45), body="white", frame="lightwood", kind="bathroom")
register("toilet", toilet, (0.4, 0.8, 0.68), body="white")
register("bathtub", bathtub, (1.7, 0.58, 0.78), body="white")
register("shower", shower, (0.9, 2.1, 0.9), body="white")
register("towel_rack", towel_rack, (0.6, 0.9, 0.3), body="white", frame="chrome")
register("towel", towel, (0.3, 0.08, 0.22), body="teal")
