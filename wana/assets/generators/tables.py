"""Tables and desks: tables, desks, counters, workbenches, nightstands, dressing tables, lecterns."""

from __future__ import annotations

import numpy as np

from wana.assets.generators.registry import register
from wana.assets.params import Builder, Params, desk_clutter


def _legs(
    b: Builder, p: Params, w: float, d: float, y1: float, inset: float = 0.04, leg: float = 0.05
) -> None:
    hx, hz = w / 2 - inset, d / 2 - inset
    if p.style.leg == "pedestal":
        b.cyl((0, 0, 0), min(w, d) * 0.3, 0.03, p.frame)
        b.cyl((0, 0, 0), 0.05, y1, p.frame)
        return
    for x in (-hx, hx):
        for z in (-hz, hz):
            p.leg(b, x, z, 0.0, y1, leg)
    if p.style.leg == "frame":
        for z in (-hz, hz):
            b.box((-hx, 0.08, z - 0.012), (hx, 0.1, z + 0.012), p.frame)
        for x in (-hx, hx):
            b.box((x - 0.012, 0.08, -hz), (x + 0.012, 0.1, hz), p.frame)


def table(b: Builder, p: Params, kind: str = "table", round_top: bool = False, work: str = "write") -> None:
    """A top on legs; desks add a drawer block, workbenches a lower shelf, counters a cabinet base."""
    w, h, d = p.w, p.h, p.d
    t = 0.04 * p.style.top_t
    if kind == "cafe" or round_top:
        b.cyl((0, 0, 0), min(w, d) * 0.3, 0.03, p.frame)
        b.cyl((0, 0, 0), 0.04 * p.style.leg_t, h - t, p.frame)
        b.cyl((0, h - t, 0), min(w, d) / 2, t, p.body, sections=24)
        r = min(w, d) / 2 * 0.7
        b.surface(h, -r, -r, r, r)
        b.two_hands(work, h + 0.02, r * 0.8, 0.35)
        b.stand = (0.0, 0.0, min(w, d) / 2 + 0.4)
        return
    if kind in ("counter", "island"):
        b.box((-w / 2 + 0.02, 0.0, -d / 2 + 0.02), (w / 2 - 0.02, 0.1, d / 2 - 0.06), p.tone("charcoal"))
        b.box((-w / 2 + 0.02, 0.1, -d / 2 + 0.02), (w / 2 - 0.02, h - t, d / 2 - 0.04), p.frame)
        n = max(1, int(round(w / 0.6)))
        for i in range(n):
            x0 = -w / 2 + 0.02 + i * (w - 0.04) / n
            b.box(
                (x0 + 0.01, 0.12, d / 2 - 0.04),
                (x0 + (w - 0.04) / n - 0.01, h - t - 0.02, d / 2 - 0.02),
                p.shade(p.frame, 1.1),
            )
            b.box((x0 + 0.05, h - t - 0.12, d / 2 - 0.02), (x0 + 0.15, h - t - 0.1, d / 2), p.tone("chrome"))
    elif kind == "nightstand":
        _legs(b, p, w, d, 0.1, 0.03, 0.04)
        b.box((-w / 2, 0.1, -d / 2), (w / 2, h - t, d / 2 - 0.02), p.frame)
        for y0, y1 in ((0.12, (h - t) / 2), ((h - t) / 2 + 0.02, h - t - 0.02)):
            b.box((-w / 2 + 0.02, y0, d / 2 - 0.02), (w / 2 - 0.02, y1, d / 2), p.shade(p.body, 1.05))
            b.box(
                (-0.04, (y0 + y1) / 2 - 0.01, d / 2),
                (0.04, (y0 + y1) / 2 + 0.01, d / 2 + 0.02),
                p.tone("gold"),
            )
    elif kind == "lectern":
        b.box((-w * 0.3, 0.0, -d * 0.3), (w * 0.3, h * 0.85, d * 0.3), p.body)
        b.box((-w / 2, 0.0, -d / 2), (w / 2, 0.05, d / 2), p.frame)
        b.boxc((0, h * 0.92, 0), (w, 0.04, d * 0.95), p.body, pitch=0.25)
        b.contact("talk", "RightHand", (w * 0.25, h, d * 0.35), {"LeftHand": (-w * 0.25, h, d * 0.35)})
        b.stand = (0.0, 0.0, d / 2 + 0.35)
        return
    else:
        _legs(b, p, w, d, h - t, leg=0.05 if kind != "workbench" else 0.08)
    b.box((-w / 2, h - t, -d / 2), (w / 2, h, d / 2), p.body)
    if p.style.trim and kind not in ("counter", "island"):
        b.box(
            (-w / 2 + 0.05, h - t - 0.08, -d / 2 + 0.05),
            (w / 2 - 0.05, h - t, d / 2 - 0.05),
            p.shade(p.frame, 0.9),
        )
    if kind in ("desk", "teacher"):
        # drawer block under the right side (the user's right when seated at +Z facing -Z is -X... keep +X)
        x0 = w / 2 - min(0.42, w * 0.3)
        b.box((x0, 0.05, -d / 2 + 0.03), (w / 2 - 0.02, h - t, d / 2 - 0.03), p.shade(p.body, 0.92))
        for i in range(3):
            y = 0.08 + i * (h - t - 0.1) / 3
            b.box(
                (x0 + 0.02, y, d / 2 - 0.03),
                (w / 2 - 0.04, y + (h - t - 0.1) / 3 - 0.02, d / 2 - 0.01),
                p.body,
            )
        if kind == "teacher":
            b.box((-w / 2 + 0.05, 0.2, -d / 2 + 0.02), (x0, h - t, -d / 2 + 0.04), p.shade(p.body, 0.9))
    if kind == "student":
        b.box(
            (-w / 2 + 0.05, h - t - 0.15, -d / 2 + 0.05), (w / 2 - 0.05, h - t - 0.13, d / 2 - 0.1), p.frame
        )
    if kind == "standing":
        for x in (-w / 2 + 0.08, w / 2 - 0.08):
            b.box((x - 0.03, 0, -d / 2 + 0.05), (x + 0.03, 0.04, d / 2 - 0.05), p.frame)
    if kind == "workbench":
        b.box((-w / 2 + 0.05, 0.15, -d / 2 + 0.05), (w / 2 - 0.05, 0.18, d / 2 - 0.05), p.body)
        b.box((-w / 2, h, -d / 2), (w / 2, h + 0.5, -d / 2 + 0.03), p.tone("lightwood"))  # pegboard
        for i, x in enumerate(np.linspace(-w / 2 + 0.2, w / 2 - 0.2, 4)):
            b.box(
                (x - 0.015, h + 0.2, -d / 2 + 0.03),
                (x + 0.015, h + 0.42, -d / 2 + 0.06),
                p.tone(("red", "steel", "charcoal", "yellow")[i]),
            )
    if kind == "dressing":
        b.box((-w * 0.3, h, -d / 2), (w * 0.3, h + 0.6, -d / 2 + 0.03), p.frame)
        b.box((-w * 0.27, h + 0.03, -d / 2 + 0.03), (w * 0.27, h + 0.57, -d / 2 + 0.035), p.tone("glass"))
    back = -d / 2 + (0.55 if kind == "workbench" else 0.0)
    clutter_z = -d / 2 + (0.06 if kind == "workbench" else 0.0)
    free_z0 = back
    if p.state in ("organized", "messy"):
        strip = min(0.3, d * 0.35)
        desk_clutter(b, p, h, -w / 2 + 0.05, w / 2 - 0.05, clutter_z, clutter_z + strip)
        free_z0 = max(back, clutter_z + strip + 0.02)
    b.surface(
        h,
        -w / 2 + 0.03,
        free_z0 if kind != "workbench" else max(free_z0, -d / 2 + 0.1),
        w / 2 - 0.03,
        d / 2 - 0.03,
    )
    b.two_hands(work, h + 0.02, d / 2 - 0.15, 0.35)
    b.stand = (0.0, 0.0, d / 2 + 0.4)


register("table", table, (1.2, 0.75, 0.8), body="wood", frame="wood")
register("desk", table, (1.3, 0.75, 0.7), body="lightwood", frame="wood", kind="desk")
register("standing_desk", table, (1.4, 1.05, 0.7), body="white", frame="charcoal", kind="standing")
register("teacher_desk", table, (1.5, 0.76, 0.75), body="wood", frame="darkwood", kind="teacher")
register("student_desk", table, (0.7, 0.72, 0.5), body="lightwood", frame="steel", kind="student")
register("dining_table", table, (1.8, 0.76, 0.95), body="wood", frame="darkwood", work="eat")
register("coffee_table", table, (1.1, 0.42, 0.6), body="darkwood", frame="darkwood")
register("side_table", table, (0.5, 0.58, 0.5), body="wood", frame="wood")
register("nightstand", table, (0.48, 0.55, 0.42), body="lightwood", frame="wood", kind="nightstand")
register("conference_table", table, (3.0, 0.76, 1.2), body="darkwood", frame="charcoal")
register("workbench", table, (1.8, 0.9, 0.8), body="lightwood", frame="wood", kind="workbench", work="work")
register("kitchen_island", table, (1.8, 0.92, 0.9), body="stone", frame="white", kind="island", work="cook")
register("cafe_table", table, (0.75, 0.75, 0.75), body="white", frame="charcoal", kind="cafe", work="eat")
register(
    "kitchen_counter", table, (2.4, 0.92, 0.62), body="stone", frame="white", kind="counter", work="cook"
)
register("dressing_table", table, (1.1, 0.76, 0.48), body="white", frame="white", kind="dressing")
register("lectern", table, (0.6, 1.15, 0.5), body="wood", frame="darkwood", kind="lectern")
