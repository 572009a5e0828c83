"""Workshop things: hand and power tools, planks, nails, toolboxes, ladders, sawhorses, bicycles."""

from __future__ import annotations

import numpy as np

from wana.assets.generators.registry import register
from wana.assets.params import Builder, Params


def hand_tool(b: Builder, p: Params, kind: str = "hammer") -> None:
    """Tools lying flat along X: handle on the -X side (p.frame), working end on +X (p.body)."""
    w, h, d = p.w, p.h, p.d
    grip_c = p.frame
    if kind == "hammer":
        b.box((-w / 2, 0, -0.012), (w * 0.3, 0.025, 0.012), grip_c)
        b.box((w * 0.3, 0, -d / 2), (w / 2, h, d / 2), p.body)
        grip = (-w * 0.25, 0.0125, 0.0)
        act = "hammer"
    elif kind == "saw":
        b.box((-w / 2, 0, -d / 2), (-w * 0.25, h, d / 2), p.body)  # the handle carries the colour
        b.box((-w * 0.25, 0, -0.001 - h * 0.02), (w / 2, 0.003, 0.001 + h * 0.02), p.tone("steel"))
        b.boxc((w * 0.1, 0.0015, 0), (w * 0.7, 0.003, d * 0.6), p.tone("steel"))
        grip = (-w * 0.37, h / 2, 0.0)
        act = "saw"
    elif kind == "screwdriver":
        b.cyl((-w / 2, h / 2, 0), h / 2, w * 0.4, grip_c, axis="x", sections=10)
        b.cyl((-w / 2 + w * 0.4, h / 2, 0), h * 0.12, w * 0.6, p.body, axis="x", sections=6)
        grip = (-w * 0.3, h / 2, 0.0)
        act = "screw"
    elif kind == "wrench":
        b.box((-w / 2, 0, -d * 0.15), (w * 0.35, h, d * 0.15), p.body)
        b.cyl((w * 0.35, 0, 0), d / 2, h, p.body, sections=10)
        grip = (-w * 0.2, h / 2, 0.0)
        act = "turn"
    elif kind == "knife":
        b.box((-w / 2, 0, -d / 2), (-w * 0.1, h, d / 2), grip_c)
        b.box((-w * 0.1, 0, -d * 0.4), (w / 2, h * 0.4, d * 0.4), p.tone("chrome"))
        grip = (-w * 0.3, h / 2, 0.0)
        act = "cut"
    elif kind == "pen":
        b.cyl((-w / 2, h / 2, 0), h / 2, w, p.body, axis="x", sections=8)
        b.lathe((w / 2, h / 2, 0), [(h / 2, 0), (0.001, h)], p.tone("black"), axis="x", sections=8)
        grip = (w * 0.2, h / 2, 0.0)
        act = "write"
    elif kind == "broom":  # a broom leans upright: handle along Y
        b.box((-w / 2, 0, -d / 2), (w / 2, 0.1, d / 2), p.body)
        b.cyl((0, 0.1, 0), 0.014, h - 0.1, grip_c, sections=8)
        grip = (0.0, h * 0.7, 0.0)
        act = "sweep"
        b.contact(act, "RightHand", grip, {"LeftHand": (0.0, h * 0.45, 0.0)})
        b.contact("pick_up", "RightHand", grip)  # taken by the handle before it sweeps
        return
    else:  # vise
        b.box((-w / 2, 0, -d / 2), (w / 2, h * 0.3, d / 2), p.body)
        b.box((-w / 2, h * 0.3, -d / 2), (-w * 0.1, h, d / 2), p.body)
        b.box((w * 0.05, h * 0.3, -d / 2), (w * 0.3, h, d / 2), p.body)
        b.cyl((w * 0.3, h * 0.6, 0), 0.012, w * 0.2, p.tone("steel"), axis="x", sections=8)
        grip = (w / 2, h * 0.6, 0.0)
        act = "clamp"
    b.contact(act, "RightHand", grip)
    b.contact("pick_up", "RightHand", grip)


def drill(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    b.box((-w / 2, 0, -d / 2), (w * 0.1, h * 0.15, d / 2), p.tone("black"))
    b.box((-w * 0.3, h * 0.15, -d * 0.35), (-w * 0.05, h * 0.7, d * 0.35), p.body)
    b.box((-w / 2, h * 0.65, -d / 2), (w * 0.25, h, d / 2), p.body)
    b.cyl((w * 0.25, h * 0.82, 0), h * 0.08, w * 0.25, p.tone("steel"), axis="x", sections=8)
    b.contact("drill", "RightHand", (-w * 0.17, h * 0.45, 0.0))
    b.contact("pick_up", "RightHand", (-w * 0.17, h * 0.45, 0.0))


def plank(b: Builder, p: Params, kind: str = "plank") -> None:
    w, h, d = p.w, p.h, p.d
    if kind == "nail":
        n = 1 if p.state == "empty" else 5
        rng = np.random.default_rng(p.seed + 31)
        for i in range(n):
            z = -d / 2 + (i + 0.5) * d / n
            yaw = float(rng.uniform(-0.5, 0.5)) if i else 0.0
            b.boxc((0.0, 0.0025, z), (w * 0.8, 0.005, 0.004), p.body, yaw=yaw)
            b.boxc((-w * 0.42, 0.003, z), (0.01, 0.006, 0.01), p.body, yaw=yaw)
        b.contact("pick_up", "RightHandMiddle1", (0.0, 0.005, 0.0))
        return
    n = {"organized": 3, "messy": 3}.get(p.state, 1)
    rng = np.random.default_rng(p.seed + 37)
    for i in range(n):
        yaw = float(rng.uniform(-0.25, 0.25)) if p.state == "messy" and i else 0.0
        dx = float(rng.uniform(-0.05, 0.05)) if p.state == "messy" and i else 0.0
        b.boxc((dx, h * (i + 0.5), 0.0), (w, h * 0.98, d), p.shade(p.body, 1.0 - 0.07 * i), yaw=yaw)
    top = h * n
    b.two_hands("lift", top / 2, 0.0, w * 0.7, finger=False)
    b.contact("saw", "RightHand", (w * 0.3, top, 0.0), {"LeftHand": (-w * 0.1, top, 0.0)})
    b.contact("hammer", "RightHand", (0.0, top, 0.0))
    b.surface(top, -w / 2 + 0.02, -d / 2 + 0.01, w / 2 - 0.02, d / 2 - 0.01)


def toolbox(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    b.box((-w / 2, 0, -d / 2), (w / 2, h * 0.75, d / 2), p.body)
    b.box(
        (-w / 2 - 0.005, h * 0.72, -d / 2 - 0.005),
        (w / 2 + 0.005, h * 0.8, d / 2 + 0.005),
        p.shade(p.body, 0.8),
    )
    for x in (-w * 0.25, w * 0.25):
        b.box((x - 0.01, h * 0.8, -0.01), (x + 0.01, h, 0.01), p.tone("black"))
    b.box((-w * 0.25, h - 0.02, -0.012), (w * 0.25, h, 0.012), p.tone("black"))
    b.contact("carry", "RightHand", (0.0, h, 0.0))
    b.contact("open", "RightHand", (0.0, h * 0.76, d / 2 + 0.01))


def ladder(b: Builder, p: Params, kind: str = "ladder") -> None:
    w, h, d = p.w, p.h, p.d
    if kind == "sawhorse":
        for z in (-d / 2 + 0.03, d / 2 - 0.03):
            for x in (-w / 2 + 0.08, w / 2 - 0.08):
                b.rod((x, 0, z), (x * 0.9, h - 0.08, z * 0.2), 0.02, p.frame)
        b.box((-w / 2, h - 0.08, -0.045), (w / 2, h, 0.045), p.body)
        b.surface(h, -w / 2 + 0.02, -0.04, w / 2 - 0.02, 0.04)
        b.two_hands("work", h + 0.02, 0.0, 0.5)
        return
    for x in (-w / 2 + 0.03, w / 2 - 0.03):
        b.rod((x, 0, d / 2 - 0.03), (x, h, 0.0), 0.022, p.body)
        b.rod((x, 0, -d / 2 + 0.03), (x, h - 0.05, 0.0), 0.018, p.frame)
    n = max(3, int(h / 0.28))
    for i in range(1, n):
        y = h * i / n
        z = (d / 2 - 0.03) * (1 - y / h)
        b.box((-w / 2 + 0.03, y - 0.015, z - 0.05), (w / 2 - 0.03, y + 0.015, z + 0.02), p.body)
    b.contact(
        "climb",
        "RightHand",
        (w / 2 - 0.03, h * 0.6, (d / 2 - 0.03) * 0.4),
        {"LeftHand": (-w / 2 + 0.03, h * 0.6, (d / 2 - 0.03) * 0.4)},
    )
    b.stand = (0.0, 0.0, d / 2 + 0.3)


def bicycle(b: Builder, p: Params) -> None:
    """A bicycle on its kickstand, frame along Z."""
    w, h, d = p.w, p.h, p.d
    r = h * 0.33
    for z in (-d / 2 + r, d / 2 - r):
        b.lathe((-0.02, r, z), [(r, 0), (r, 0.04)], p.tone("rubber"), axis="x", sections=20)
    rear, front = (0.0, r, -d / 2 + r), (0.0, r, d / 2 - r)
    seat, bars = (0.0, h * 0.8, -d * 0.12), (0.0, h * 0.9, d / 2 - r - 0.05)
    crank = (0.0, r * 0.9, -d * 0.02)
    for a, c in ((rear, seat), (seat, crank), (crank, rear), (seat, bars), (crank, bars), (bars, front)):
        b.rod(a, c, 0.018, p.body)
    b.box((-0.1, h * 0.8, -d * 0.18), (0.1, h * 0.84, -d * 0.06), p.tone("black"))
    b.cyl((-w / 2, h * 0.95, d / 2 - r - 0.05), 0.012, w, p.tone("black"), axis="x", sections=8)
    b.contact("sit", "Hips", (0.0, h * 0.86, -d * 0.12))
    b.two_hands("ride", h * 0.95, d / 2 - r - 0.05, w * 0.8, finger=False)
    b.stand = (w / 2 + 0.35, 0.0, 0.0)


register("hammer", hand_tool, (0.32, 0.035, 0.1), body="steel", frame="wood", kind="hammer")
register("saw", hand_tool, (0.6, 0.12, 0.14), body="red", frame="steel", kind="saw")
register("screwdriver", hand_tool, (0.22, 0.03, 0.03), body="steel", frame="yellow", kind="screwdriver")
register("wrench", hand_tool, (0.25, 0.015, 0.06), body="steel", frame="steel", kind="wrench")
register("knife", hand_tool, (0.3, 0.02, 0.04), body="chrome", frame="black", kind="knife")
register("pen", hand_tool, (0.14, 0.01, 0.01), body="blue", kind="pen")
register("vise", hand_tool, (0.25, 0.15, 0.12), body="blue", frame="steel", kind="vise")
register("broom", hand_tool, (0.32, 1.3, 0.06), body="yellow", frame="wood", kind="broom")
register("drill", drill, (0.25, 0.24, 0.08), body="yellow")
register("wood_plank", plank, (1.2, 0.03, 0.2), body="lightwood")
register("nail", plank, (0.07, 0.006, 0.05), body="steel", kind="nail")
register("cutting_board", plank, (0.4, 0.02, 0.28), body="lightwood", kind="board")
register("toolbox", toolbox, (0.45, 0.24, 0.22), body="red")
register("ladder", ladder, (0.5, 1.8, 0.7), body="steel", frame="steel")
register("sawhorse", ladder, (0.9, 0.7, 0.55), body="lightwood", frame="wood", kind="sawhorse")
register("bicycle", bicycle, (0.55, 1.0, 1.75), body="red")
