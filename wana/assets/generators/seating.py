"""Seats and beds: chairs, stools, benches, sofas, ottomans, bean bags, beds, bunk beds, cribs."""

from __future__ import annotations

import numpy as np

from wana.assets.generators.registry import register
from wana.assets.params import Builder, Params

# metres from a seat's top to the Hips joint of someone sitting on it: the hip joints ride about a thigh's
# thickness above the seat (the body's thigh spheres are 6 cm, 5 cm under the Hips joint), so the thighs rest
# on the seat instead of sinking 7-11 cm into it.
SIT_HIPS_M = 0.10
# A bench this wide (metres) seats two side by side: besides its middle seat ("sit", where one alone sits) it
# has one BENCH_END_M in from each end ("sit_0", "sit_2"), at least ELBOW_M (slotting) apart: 1.4 m, 0.8 m.
BENCH_FOR_TWO_M = 1.3
BENCH_END_M = 0.3


def _sit(b: Builder, p: Params, seat_h: float, z: float = 0.0, x: float = 0.0, name: str = "sit") -> None:
    b.contact(name, "Hips", (x, seat_h + SIT_HIPS_M, z))


def chair(b: Builder, p: Params, kind: str = "chair") -> None:
    """Four-legged chair family: chair, dining, school and rocking chairs, armchair."""
    w, h, d = p.w, p.h, p.d
    seat_h = h * (0.5 if kind != "armchair" else 0.45)
    t = 0.04 * p.style.top_t * (2.5 if kind == "armchair" else 1.0)
    leg = 0.04
    hx, hz = w / 2 - leg / 2, d / 2 - leg / 2
    base_y = 0.0
    if kind == "rocking":
        base_y = 0.05
        for x in (-hx, hx):
            n = 6
            zs = np.linspace(-d / 2 - 0.05, d / 2 + 0.05, n)
            ys = 0.02 + 0.06 * (zs / (d / 2)) ** 2
            for i in range(n - 1):
                b.rod((x, ys[i], zs[i]), (x, ys[i + 1], zs[i + 1]), 0.015, p.frame)
    if p.style.leg == "pedestal":
        b.cyl((0, 0, 0), w * 0.3, 0.03, p.frame)
        b.cyl((0, 0, 0), 0.03, seat_h - t, p.frame)
    elif kind == "armchair":
        for x in (-hx, hx):
            for z in (-hz, hz):
                p.leg(b, x, z, 0.0, 0.1, leg)
    else:
        for x in (-hx, hx):
            for z in (-hz, hz):
                p.leg(b, x, z, base_y, seat_h - t, leg)
        if p.style.leg == "frame" or kind == "school":
            for x in (-hx, hx):
                b.box((x - 0.01, seat_h * 0.3, -hz), (x + 0.01, seat_h * 0.3 + 0.02, hz), p.frame)
    if kind == "armchair":
        b.box((-w / 2, 0.1, -d / 2), (w / 2, seat_h, d / 2), p.body)
        arm = 0.14 * p.style.leg_t
        for s in (-1, 1):
            b.box(
                (s * w / 2 - (arm if s > 0 else 0), seat_h, -d / 2 + 0.1),
                (s * w / 2 + (arm if s < 0 else 0), seat_h + 0.2, d / 2),
                p.shade(p.body, 0.9),
            )
        b.box((-w / 2, seat_h, -d / 2), (w / 2, h, -d / 2 + 0.18), p.shade(p.body, 0.95))
        _sit(b, p, seat_h, z=0.05)
        b.surface(seat_h, -w / 2 + arm, -d / 2 + 0.2, w / 2 - arm, d / 2)
        b.stand = (0.0, 0.0, d / 2 + 0.3)
        return
    b.box((-w / 2, seat_h - t, -d / 2), (w / 2, seat_h, d / 2), p.body)
    if p.style.trim:
        b.box(
            (-w / 2 + 0.02, seat_h - t - 0.06, -d / 2 + 0.02),
            (w / 2 - 0.02, seat_h - t, d / 2 - 0.02),
            p.shade(p.frame, 0.9),
        )
    back_t = 0.03 * p.style.top_t
    for x in (-hx, hx):
        b.box((x - leg / 2, seat_h, -d / 2), (x + leg / 2, h, -d / 2 + leg), p.frame)
    if kind == "school":
        b.box((-w / 2, seat_h + (h - seat_h) * 0.45, -d / 2), (w / 2, h, -d / 2 + back_t), p.body)
    else:
        b.box(
            (-w / 2 + leg, seat_h + (h - seat_h) * 0.35, -d / 2),
            (w / 2 - leg, h - 0.02, -d / 2 + back_t),
            p.body,
        )
    _sit(b, p, seat_h, z=0.02)
    b.surface(seat_h, -w / 2, -d / 2 + 0.05, w / 2, d / 2)
    b.stand = (0.0, 0.0, d / 2 + 0.3)


def office_chair(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    seat_h = h * 0.45
    r = max(w, d) / 2
    for k in range(5):
        a = 2 * np.pi * k / 5 + np.pi / 2
        end = (r * np.cos(a) * 0.9, 0.06, r * np.sin(a) * 0.9)
        b.rod((0, 0.08, 0), end, 0.018, p.frame)
        b.ellipsoid((end[0], 0.03, end[2]), (0.03, 0.03, 0.03), p.tone("rubber"))
    b.cyl((0, 0.06, 0), 0.025 * p.style.leg_t, seat_h - 0.14, p.tone("chrome"))
    b.box((-w * 0.45, seat_h - 0.09, -d * 0.42), (w * 0.45, seat_h, d * 0.45), p.body)
    b.box((-w * 0.42, seat_h + 0.08, -d / 2), (w * 0.42, h, -d / 2 + 0.07 * p.style.top_t), p.body)
    b.box((-0.03, seat_h - 0.05, -d / 2), (0.03, seat_h + 0.1, -d / 2 + 0.04), p.frame)
    if p.style.trim or p.style.name in ("", "modern", "luxurious"):
        for s in (-1, 1):
            x = s * (w * 0.45 + 0.02)
            b.box((x - 0.02, seat_h, -0.05), (x + 0.02, seat_h + 0.2, -0.01), p.frame)
            b.box((x - 0.03, seat_h + 0.2, -d * 0.3), (x + 0.03, seat_h + 0.23, d * 0.25), p.frame)
    _sit(b, p, seat_h, z=0.02)
    b.stand = (0.0, 0.0, d / 2 + 0.3)


def stool(b: Builder, p: Params, kind: str = "stool") -> None:
    w, h, d = p.w, p.h, p.d
    r = min(w, d) / 2
    t = 0.04 * p.style.top_t
    if p.style.leg == "pedestal":
        b.cyl((0, 0, 0), r * 0.8, 0.03, p.frame)
        b.cyl((0, 0, 0), 0.03, h - t, p.frame)
    else:
        for k in range(4 if kind == "bar" else 3):
            a = 2 * np.pi * k / (4 if kind == "bar" else 3) + np.pi / 4
            b.rod(
                (r * 0.95 * np.cos(a), 0, r * 0.95 * np.sin(a)),
                (r * 0.55 * np.cos(a), h - t, r * 0.55 * np.sin(a)),
                0.018 * p.style.leg_t,
                p.frame,
            )
    if kind == "bar":
        b.lathe((0, h * 0.33, 0), [(r * 0.75, 0), (r * 0.8, 0.02)], p.frame, sections=12)
        b.box((-r * 0.5, h, -r * 0.9), (r * 0.5, h + 0.25, -r * 0.8), p.body)
    b.cyl((0, h - t, 0), r, t, p.body)
    _sit(b, p, h)
    b.surface(h, -r * 0.7, -r * 0.7, r * 0.7, r * 0.7)
    b.stand = (0.0, 0.0, r + 0.3)


def bench(b: Builder, p: Params, kind: str = "bench") -> None:
    w, h, d = p.w, p.h, p.d
    t = 0.05 * p.style.top_t
    for x in (-w / 2 + 0.06, w / 2 - 0.06):
        if kind == "piano" or p.style.leg in ("cyl", "turned"):
            for z in (-d / 2 + 0.04, d / 2 - 0.04):
                p.leg(b, x, z, 0, h - t, 0.045)
        else:
            b.box(
                (x - 0.03 * p.style.leg_t, 0, -d / 2 + 0.02),
                (x + 0.03 * p.style.leg_t, h - t, d / 2 - 0.02),
                p.frame,
            )
    b.box((-w / 2, h - t, -d / 2), (w / 2, h, d / 2), p.body)
    if kind == "weight":
        b.box((-w / 2 + 0.02, h, -d / 2 + 0.02), (w / 2 - 0.02, h + 0.08, d / 2 - 0.02), p.tone("black"))
        b.contact("lie", "Hips", (0.0, h + 0.1, 0.0))
        h += 0.08
    if p.style.trim and kind == "bench":
        b.box((-w / 2, h, -d / 2), (w / 2, h + 0.35, -d / 2 + 0.04), p.body)
    _sit(b, p, h)
    if kind == "bench" and w >= BENCH_FOR_TWO_M:
        # two side by side: a seat towards each end ("Ivy sits beside him" on grandpa's park bench)
        for i, x in ((0, -(w / 2 - BENCH_END_M)), (2, w / 2 - BENCH_END_M)):
            _sit(b, p, h, x=x, name=f"sit_{i}")
    b.surface(h, -w / 2 + 0.02, -d / 2 + 0.05, w / 2 - 0.02, d / 2 - 0.02)
    b.stand = (0.0, 0.0, d / 2 + 0.3)


def sofa(b: Builder, p: Params, seats: int = 3) -> None:
    w, h, d = p.w, p.h, p.d
    seat_h = h * 0.52
    arm = 0.18 * p.style.leg_t
    for x in (-w / 2 + 0.06, w / 2 - 0.06):
        for z in (-d / 2 + 0.06, d / 2 - 0.06):
            p.leg(b, x, z, 0, 0.1, 0.05)
    b.box((-w / 2, 0.1, -d / 2), (w / 2, seat_h - 0.12, d / 2), p.shade(p.body, 0.85))
    inner = w - 2 * arm
    cw = inner / seats
    for i in range(seats):
        x0 = -w / 2 + arm + i * cw
        b.box((x0 + 0.01, seat_h - 0.12, -d / 2 + 0.22), (x0 + cw - 0.01, seat_h, d / 2 - 0.02), p.body)
        b.box((x0 + 0.01, seat_h, -d / 2 + 0.02), (x0 + cw - 0.01, h - 0.04, -d / 2 + 0.22), p.body)
    b.box((-w / 2, seat_h - 0.12, -d / 2), (w / 2, h, -d / 2 + 0.02 + 0.0), p.shade(p.body, 0.8))
    for s in (-1, 1):
        x0, x1 = (w / 2 - arm, w / 2) if s > 0 else (-w / 2, -w / 2 + arm)
        b.box((x0, 0.1, -d / 2), (x1, seat_h + 0.2, d / 2), p.shade(p.body, 0.9))
    if p.state in ("organized", "messy"):
        rng = np.random.default_rng(p.seed + 5)
        for i in range(seats):
            x = -w / 2 + arm + (i + 0.5) * cw
            yaw = 0.0 if p.state == "organized" else float(rng.uniform(-0.7, 0.7))
            b.boxc(
                (x, seat_h + 0.2, -d / 2 + 0.3),
                (0.4, 0.35, 0.12),
                p.tone("beige" if i % 2 else "teal"),
                yaw=yaw,
                pitch=-0.3,
            )
    for i in range(seats):
        x = -w / 2 + arm + (i + 0.5) * cw
        _sit(b, p, seat_h, z=0.05, x=x, name="sit" if i == seats // 2 else f"sit_{i}")
    b.contact("lie", "Hips", (0.0, seat_h + 0.1, 0.05))
    b.surface(seat_h, -w / 2 + arm, -d / 2 + 0.3, w / 2 - arm, d / 2)
    b.stand = (0.0, 0.0, d / 2 + 0.3)


def ottoman(b: Builder, p: Params, kind: str = "ottoman") -> None:
    w, h, d = p.w, p.h, p.d
    if kind == "bean_bag":
        b.ellipsoid((0, h / 2, 0), (w / 2, h / 2, d / 2), p.body)
        b.ellipsoid((0, h * 0.75, -d * 0.2), (w * 0.35, h * 0.3, d * 0.25), p.shade(p.body, 0.9))
        _sit(b, p, h * 0.55, z=0.05)
        b.stand = (0.0, 0.0, d / 2 + 0.3)
        return
    if p.style.leg in ("cyl", "turned"):
        b.cyl((0, 0.05, 0), w / 2, h - 0.05, p.body)
        for k in range(4):
            a = np.pi / 4 + k * np.pi / 2
            p.leg(b, w * 0.35 * np.cos(a), w * 0.35 * np.sin(a), 0, 0.05, 0.04)
    else:
        b.box((-w / 2, 0.05, -d / 2), (w / 2, h, d / 2), p.body)
        for x in (-w / 2 + 0.04, w / 2 - 0.04):
            for z in (-d / 2 + 0.04, d / 2 - 0.04):
                p.leg(b, x, z, 0, 0.05, 0.04)
    _sit(b, p, h)
    b.surface(h, -w * 0.35, -d * 0.35, w * 0.35, d * 0.35)
    b.stand = (0.0, 0.0, d / 2 + 0.3)


def bed(b: Builder, p: Params, kind: str = "bed") -> None:
    w, h, d = p.w, p.h, p.d
    frame_h = 0.3 if kind != "crib" else 0.45
    mat_h = 0.2 if kind != "crib" else 0.1
    for x in (-w / 2 + 0.04, w / 2 - 0.04):
        for z in (-d / 2 + 0.04, d / 2 - 0.04):
            p.leg(b, x, z, 0, frame_h, 0.07)
    b.box((-w / 2, frame_h - 0.08, -d / 2), (w / 2, frame_h, d / 2), p.frame)
    b.box(
        (-w / 2 + 0.03, frame_h, -d / 2 + 0.03),
        (w / 2 - 0.03, frame_h + mat_h, d / 2 - 0.03),
        p.body if kind == "crib" or p.state == "empty" else p.tone("white"),
    )
    top = frame_h + mat_h
    if kind == "crib":
        for x in np.linspace(-w / 2 + 0.02, w / 2 - 0.02, 9):
            for z in (-d / 2 + 0.02, d / 2 - 0.02):
                b.rod((x, frame_h, z), (x, h, z), 0.012, p.frame)
        for z in (-d / 2 + 0.02, d / 2 - 0.02):
            b.box((-w / 2, h - 0.04, z - 0.02), (w / 2, h, z + 0.02), p.frame)
    else:
        # headboard at the back (-Z), footboard at the front
        b.box(
            (-w / 2, 0, -d / 2),
            (w / 2, h if kind == "bed" else top + 0.3, -d / 2 + 0.05 * p.style.top_t),
            p.frame,
        )
        if p.style.trim:
            b.box((-w / 2, 0, d / 2 - 0.05), (w / 2, top + 0.1, d / 2), p.frame)
        if p.state != "empty":  # an empty (stripped) bed has neither pillow nor cover
            b.box(
                (-w / 2 + 0.1, top, -d / 2 + 0.08),
                (w / 2 - 0.1, top + 0.12, -d / 2 + 0.45),
                p.tone("white", 0.95),
            )
        cover_z = -d / 2 + 0.5
        if p.state == "messy":
            rng = np.random.default_rng(p.seed + 3)
            b.boxc(
                (float(rng.uniform(-0.1, 0.1)), top + 0.06, cover_z + 0.5),
                (w * 0.9, 0.1, 0.9),
                p.body,
                yaw=float(rng.uniform(-0.4, 0.4)),
            )
        elif p.state != "empty":
            b.box((-w / 2 + 0.02, top, cover_z), (w / 2 - 0.02, top + 0.05, d / 2 - 0.02), p.body)
    if kind == "bunk":
        y2 = h - 0.35
        for x in (-w / 2 + 0.04, w / 2 - 0.04):
            for z in (-d / 2 + 0.04, d / 2 - 0.04):
                b.box((x - 0.035, frame_h, z - 0.035), (x + 0.035, h, z + 0.035), p.frame)
        b.box((-w / 2, y2 - 0.08, -d / 2), (w / 2, y2, d / 2), p.frame)
        b.box((-w / 2 + 0.03, y2, -d / 2 + 0.03), (w / 2 - 0.03, y2 + 0.18, d / 2 - 0.03), p.body)
        for i in range(4):
            y = frame_h + (y2 - frame_h) * (i + 1) / 5
            b.box((w / 2 - 0.02, y, d / 2 - 0.35), (w / 2 + 0.02, y + 0.03, d / 2 - 0.05), p.frame)
    b.contact("sit", "Hips", (0.0, top + SIT_HIPS_M, d / 2 - 0.35))
    b.contact("lie", "Hips", (0.0, top + 0.1, 0.0))
    b.surface(
        top + (0.0 if p.state == "empty" or kind == "crib" else 0.05),
        -w / 2 + 0.1,
        0.0,
        w / 2 - 0.1,
        d / 2 - 0.1,
    )
    b.stand = (0.0, 0.0, d / 2 + 0.35)


register("chair", chair, (0.46, 0.9, 0.48), body="wood", frame="wood")
register("office_chair", office_chair, (0.62, 1.1, 0.62), body="charcoal", frame="steel")
register("armchair", chair, (0.85, 0.95, 0.85), body="beige", frame="darkwood", kind="armchair")
register("dining_chair", chair, (0.46, 0.98, 0.5), body="lightwood", frame="wood", kind="dining")
register("folding_chair", chair, (0.44, 0.82, 0.46), body="grey", frame="steel", kind="folding")
register("rocking_chair", chair, (0.55, 1.05, 0.7), body="wood", frame="darkwood", kind="rocking")
register("school_chair", chair, (0.42, 0.8, 0.44), body="blue", frame="steel", kind="school")
register("stool", stool, (0.36, 0.48, 0.36), body="wood", frame="wood")
register("bar_stool", stool, (0.4, 0.76, 0.4), body="black", frame="chrome", kind="bar")
register("piano_bench", bench, (0.75, 0.5, 0.36), body="black", frame="black", kind="piano")
register("bench", bench, (1.4, 0.45, 0.4), body="lightwood", frame="steel")
register("weight_bench", bench, (0.35, 0.42, 1.2), body="black", frame="steel", kind="weight")
register("sofa", sofa, (2.0, 0.85, 0.9), body="grey", frame="darkwood", seats=3)
register("loveseat", sofa, (1.45, 0.85, 0.85), body="beige", frame="darkwood", seats=2)
register("ottoman", ottoman, (0.6, 0.42, 0.6), body="brown", frame="darkwood")
register("bean_bag", ottoman, (0.8, 0.6, 0.8), body="orange", kind="bean_bag")
register("bed", bed, (1.6, 1.0, 2.1), body="blue", frame="wood")
register("bunk_bed", bed, (1.0, 1.7, 2.05), body="red", frame="lightwood", kind="bunk")
register("crib", bed, (0.7, 0.95, 1.25), body="pink", frame="white", kind="crib")
