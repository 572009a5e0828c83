"""Electronics and lamps: computers, screens, keyboards, phones, audio gear, appliances, lamps."""

from __future__ import annotations

import numpy as np

from wana.assets.generators.registry import register
from wana.assets.params import Builder, Params


def laptop(b: Builder, p: Params, kind: str = "laptop") -> None:
    w, h, d = p.w, p.h, p.d
    base_t = 0.02 * p.style.top_t
    if kind == "tablet":
        b.box((-w / 2, 0, -d / 2), (w / 2, h, d / 2), p.body)
        b.box((-w / 2 + 0.01, h, -d / 2 + 0.01), (w / 2 - 0.01, h + 0.001, d / 2 - 0.01), p.tone("screen"))
        b.contact("use", "RightHandMiddle1", (0.0, h, 0.0))
        return
    b.box((-w / 2, 0, -d / 2), (w / 2, base_t, d / 2), p.body)
    b.box((-w / 2 + 0.02, base_t, -d / 2 + 0.02), (w / 2 - 0.02, base_t + 0.002, 0.0), p.tone("charcoal"))
    b.box((-0.05, base_t, 0.02), (0.05, base_t + 0.001, d / 2 - 0.02), p.shade(p.body, 0.85))
    lid_h = h - base_t
    tilt = 0.3
    b.boxc(
        (0, base_t + lid_h / 2 * np.cos(tilt), -d / 2 - lid_h / 2 * np.sin(tilt) + 0.01),
        (w, lid_h, 0.008),
        p.body,
        pitch=-tilt,
    )
    b.boxc(
        (0, base_t + lid_h / 2 * np.cos(tilt), -d / 2 - lid_h / 2 * np.sin(tilt) + 0.016),
        (w * 0.9, lid_h * 0.85, 0.002),
        p.tone("screen"),
        pitch=-tilt,
    )
    b.two_hands("type", base_t + 0.01, -d * 0.1, w * 0.35)
    b.stand = (0.0, 0.0, d / 2 + 0.5)


def keyboard(b: Builder, p: Params, kind: str = "keyboard") -> None:
    w, h, d = p.w, p.h, p.d
    if kind == "mouse":
        b.ellipsoid((0, h / 2, 0), (w / 2, h / 2, d / 2), p.body)
        b.box((-0.001, h * 0.7, -d / 2 + 0.005), (0.001, h * 0.98, 0.0), p.tone("charcoal"))
        b.contact("click", "RightHandMiddle1", (0.0, h, -d * 0.2))
        return
    b.box((-w / 2, 0, -d / 2), (w / 2, h * 0.6, d / 2), p.body)
    rows, cols = 4, 14
    for r in range(rows):
        for c in range(0, cols, 2 if p.style.name == "minimalist" else 1):
            x0 = -w / 2 + 0.01 + c * (w - 0.02) / cols
            z0 = -d / 2 + 0.01 + r * (d - 0.02) / rows
            b.box(
                (x0 + 0.002, h * 0.6, z0 + 0.002),
                (x0 + (w - 0.02) / cols - 0.002, h, z0 + (d - 0.02) / rows - 0.002),
                p.shade(p.body, 1.3),
            )
    b.two_hands("type", h + 0.005, 0.0, w * 0.4)


def screen(b: Builder, p: Params, kind: str = "monitor") -> None:
    w, h, d = p.w, p.h, p.d
    panel_t = 0.03 * p.style.top_t
    if kind == "television" or p.style.leg == "pedestal":
        b.box((-w * 0.2, 0, -d * 0.4), (w * 0.2, 0.02, d * 0.4), p.frame)
    else:
        b.cyl((0, 0, 0), min(w * 0.12, d / 2), 0.015, p.frame)
    b.box((-0.02, 0.0, -0.02), (0.02, h * 0.3, 0.02), p.frame)
    b.box((-w / 2, h * 0.22, -panel_t / 2), (w / 2, h, panel_t / 2), p.body)
    b.box(
        (-w / 2 + 0.01, h * 0.22 + 0.01, panel_t / 2),
        (w / 2 - 0.01, h - 0.01, panel_t / 2 + 0.002),
        p.tone("screen"),
    )
    b.contact("watch", "Head", (0.0, (h * 0.22 + h) / 2, panel_t))
    b.stand = (0.0, 0.0, 0.8 if kind == "monitor" else 2.2)


def phone(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    if p.style.name in ("old", "classic", "rustic"):
        b.box((-w / 2, 0, -d / 2), (w / 2, h * 0.6, d / 2), p.body)
        b.boxc((0, h * 0.8, 0), (w * 0.95, h * 0.3, d * 0.25), p.shade(p.body, 0.8))
        b.contact("call", "RightHand", (0.0, h * 0.8, 0.0))
        return
    b.box((-w / 2, 0, -d / 2), (w / 2, h, d / 2), p.body)
    b.box((-w / 2 + 0.004, h, -d / 2 + 0.006), (w / 2 - 0.004, h + 0.001, d / 2 - 0.006), p.tone("screen"))
    b.contact("call", "RightHand", (0.0, h, 0.0))


def box_device(b: Builder, p: Params, kind: str = "computer") -> None:
    """Box-shaped devices with front details: computers, printers, projectors, recorders, radios, amps."""
    w, h, d = p.w, p.h, p.d
    b.box((-w / 2, 0, -d / 2), (w / 2, h, d / 2), p.body)
    fz = d / 2
    if kind == "computer":
        b.box((-w / 2 + 0.02, h * 0.75, fz), (w / 2 - 0.02, h * 0.9, fz + 0.003), p.tone("charcoal"))
        b.cyl((0, h * 0.4, fz), 0.012, 0.004, p.tone("blue"), axis="z")
        b.contact("use", "RightHandMiddle1", (0.0, h * 0.4, fz))
        # "uses the computer" types: both hands on the desk top in front of it, where its keyboard would lie
        # (its one "use" point is the power button: the left hand of the typing clip had nowhere to go)
        b.two_hands("type", 0.02, fz + 0.2, 0.3)
    elif kind == "printer":
        b.box((-w / 2 + 0.05, h, -d / 2 + 0.05), (w / 2 - 0.05, h + 0.02, d / 2 - 0.1), p.shade(p.body, 0.85))
        b.box((-w * 0.35, h * 0.3, fz), (w * 0.35, h * 0.35, fz + 0.08), p.tone("paper"))
        b.contact("use", "RightHandMiddle1", (w * 0.3, h, fz - 0.05))
    elif kind == "projector":
        b.cyl((-w * 0.25, h * 0.5, fz), h * 0.3, 0.02, p.tone("screen"), axis="z")
    elif kind in ("recorder", "radio"):
        b.cyl((-w * 0.25, h * 0.5, fz), min(h, w) * 0.3, 0.005, p.tone("charcoal"), axis="z")
        for i in range(4):
            b.box(
                (w * 0.05 + i * w * 0.1, h, -0.01),
                (w * 0.05 + i * w * 0.1 + w * 0.07, h + 0.008, 0.01),
                p.tone("steel"),
            )
        if kind == "radio":
            b.rod((w * 0.4, h, -d * 0.3), (w * 0.4, h + 0.25, -d * 0.3), 0.004, p.tone("chrome"))
        b.contact("record" if kind == "recorder" else "use", "RightHandMiddle1", (w * 0.1, h + 0.01, 0.0))
    elif kind in ("amplifier", "speaker"):
        n = 1 if kind == "amplifier" else 2
        for i in range(n):
            y = h * (0.45 if n == 1 else (0.3 + 0.42 * i))
            r = min(w, h / n) * 0.35
            b.lathe((0, y, fz), [(r, 0), (r * 0.6, 0.01), (r * 0.2, 0.012)], p.tone("charcoal"), axis="z")
        if kind == "amplifier":
            b.box((-w / 2 + 0.02, h * 0.85, fz), (w / 2 - 0.02, h - 0.02, fz + 0.005), p.tone("gold"))
    elif kind == "console":
        b.box((-w * 0.3, h, -d * 0.3), (-w * 0.1, h + 0.005, -d * 0.1), p.tone("blue"))
        b.box((w * 0.25, 0, fz), (w * 0.4, h * 0.4, fz + 0.05), p.tone("black"))
        b.contact("play", "RightHand", (w * 0.3, h * 0.3, fz + 0.05))
    elif kind == "camera":
        b.cyl((0, h * 0.45, fz), h * 0.35, d * 0.8, p.tone("black"), axis="z")
        b.contact("shoot", "RightHand", (w * 0.4, h * 0.5, 0.0), {"LeftHand": (0.0, h * 0.45, fz + d * 0.5)})
        # held up to the eye to take a photo: the planner and the check find it by these points
        b.contact("take_photo", "RightHand", (w * 0.4, h * 0.5, 0.0))
        b.contact("pick_up", "RightHand", (w * 0.4, h * 0.5, 0.0))
    elif kind == "microwave":
        b.box((-w / 2 + 0.03, 0.03, fz), (w * 0.2, h - 0.03, fz + 0.005), p.tone("screen", 1.5))
        b.box((w * 0.25, h * 0.5, fz), (w * 0.4, h * 0.8, fz + 0.005), p.tone("charcoal"))
        b.contact("open", "RightHand", (w * 0.2, h * 0.5, fz + 0.02))
    elif kind == "toaster":
        for x in (-w * 0.2, w * 0.2):
            b.box((x - 0.02, h, -d * 0.35), (x + 0.02, h + 0.002, d * 0.35), p.tone("charcoal"))
        b.box((w / 2, h * 0.6, -0.01), (w / 2 + 0.02, h * 0.7, 0.01), p.tone("black"))
    elif kind == "mixer":
        for i in range(8):
            x = -w / 2 + (i + 0.5) * w / 8
            b.box((x - 0.005, h, -d * 0.3), (x + 0.005, h + 0.01, d * 0.3), p.tone("steel"))
            b.cyl((x, h, -d * 0.4), 0.008, 0.015, p.tone(("red", "yellow", "white")[i % 3]), sections=8)
        b.two_hands("mix", h + 0.01, 0.0, w * 0.5)
    if p.style.trim:
        b.box((-w / 2 - 0.005, 0, -d / 2 - 0.005), (w / 2 + 0.005, 0.015, d / 2 + 0.005), p.frame)
    b.surface(h, -w / 2 + 0.01, -d / 2 + 0.01, w / 2 - 0.01, d / 2 - 0.01)


def microphone(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    for k in range(3):
        a = 2 * np.pi * k / 3
        b.rod((0, 0.1, 0), (w / 2 * np.cos(a), 0.0, d / 2 * np.sin(a)), 0.01, p.frame)
    b.cyl((0, 0.08, 0), 0.012, h - 0.25, p.frame, sections=8)
    b.rod((0, h - 0.17, 0), (0, h - 0.08, 0.06), 0.01, p.frame)
    b.lathe((0, h - 0.1, 0.06), [(0.012, 0), (0.02, 0.06), (0.028, 0.075), (0.02, 0.1)], p.body, sections=12)
    b.contact("sing", "RightHand", (0.0, h - 0.07, 0.08))
    b.stand = (0.0, 0.0, 0.35)


def headphones(b: Builder, p: Params) -> None:
    w, h, _d = p.w, p.h, p.d
    for s in (-1, 1):
        b.cyl((s * (w / 2 - 0.02), h * 0.3, 0), h * 0.3, 0.035, p.body, axis="x" if s < 0 else "-x")
    n = 6
    for i in range(n):
        a0, a1 = np.pi * i / n, np.pi * (i + 1) / n
        b.rod(
            ((w / 2 - 0.02) * np.cos(a0), h * 0.3 + (h * 0.7) * np.sin(a0), 0),
            ((w / 2 - 0.02) * np.cos(a1), h * 0.3 + (h * 0.7) * np.sin(a1), 0),
            0.008,
            p.frame,
        )
    b.contact("wear", "RightHand", (w / 2, h * 0.3, 0.0))


def lamp(b: Builder, p: Params, kind: str = "table") -> None:
    w, h, d = p.w, p.h, p.d
    r = min(w, d) / 2
    shade_h = h * (0.3 if kind == "table" else 0.2)
    b.cyl((0, 0, 0), r * 0.6, 0.025, p.frame)
    if kind == "desk":
        b.rod((0, 0.02, 0), (0, h * 0.55, -d * 0.2), 0.01, p.frame)
        b.rod((0, h * 0.55, -d * 0.2), (0, h * 0.9, d * 0.2), 0.01, p.frame)
        b.lathe((0, h * 0.72, d * 0.25), [(0.02, shade_h * 0.9), (r * 0.6, 0)], p.body, sections=14)
        b.contact("switch", "RightHandMiddle1", (0.0, 0.03, r * 0.5))
        return
    if p.style.leg == "turned":
        p.leg(b, 0, 0, 0.02, h - shade_h, 0.06)
    else:
        b.cyl((0, 0.02, 0), 0.012 * p.style.leg_t, h - shade_h, p.frame, sections=8)
    top_r = r * (0.6 if p.style.name != "modern" else 0.95)
    b.lathe((0, h - shade_h, 0), [(r, 0), (top_r, shade_h)], p.body, sections=18)
    b.contact("switch", "RightHandMiddle1", (0.0, h - shade_h - 0.02, 0.02))


def fan(b: Builder, p: Params) -> None:
    w, h, _d = p.w, p.h, p.d
    b.cyl((0, 0, 0), w * 0.3, 0.04, p.frame)
    b.cyl((0, 0.04, 0), 0.015, h - w / 2 - 0.04, p.frame)
    b.cyl((0, h - w / 2, -0.05), w / 2, 0.08, p.body, axis="z", sections=20)
    b.cyl((0, h - w / 2, 0.03), 0.06, 0.03, p.frame, axis="z")
    b.contact("switch", "RightHandMiddle1", (0.0, 0.04, w * 0.25))


def water_cooler(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    b.box((-w / 2, 0, -d / 2), (w / 2, h * 0.7, d / 2), p.body)
    b.lathe((0, h * 0.7, 0), [(w * 0.4, 0), (w * 0.4, h * 0.25), (0.03, h * 0.3)], p.tone("glass"))
    b.box((-0.03, h * 0.5, d / 2), (0.03, h * 0.55, d / 2 + 0.04), p.tone("blue"))
    b.contact("drink", "RightHand", (0.0, h * 0.52, d / 2 + 0.06))
    b.surface(h * 0.7, -w / 2, -d / 2, w / 2, d / 2)  # the cabinet top around the bottle


def radiator(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    n = max(4, int(w / 0.06))
    for i in range(n):
        x = -w / 2 + (i + 0.5) * w / n
        b.box((x - w / n * 0.35, 0.1, -d / 2), (x + w / n * 0.35, h, d / 2), p.body)
    for x in (-w / 2 + 0.02, w / 2 - 0.02):
        b.box((x - 0.015, 0, -0.015), (x + 0.015, 0.1, 0.015), p.frame)
    b.box((-w / 2, h - 0.05, -0.01), (w / 2, h - 0.03, 0.01), p.body)


register("computer", box_device, (0.2, 0.45, 0.45), body="charcoal", kind="computer")
register("laptop", laptop, (0.34, 0.24, 0.24), body="grey")
register("tablet", laptop, (0.18, 0.008, 0.25), body="charcoal", kind="tablet")
register("monitor", screen, (0.56, 0.45, 0.18), body="black", frame="charcoal", kind="monitor")
register("television", screen, (1.25, 0.85, 0.28), body="black", frame="charcoal", kind="television")
register("keyboard", keyboard, (0.44, 0.03, 0.14), body="charcoal")
register("mouse", keyboard, (0.065, 0.035, 0.11), body="grey", kind="mouse")
register("printer", box_device, (0.45, 0.3, 0.4), body="white", kind="printer")
register("projector", box_device, (0.3, 0.1, 0.25), body="white", kind="projector")
register("phone", phone, (0.075, 0.01, 0.15), body="black")
register("speaker", box_device, (0.3, 0.5, 0.28), body="black", kind="speaker")
register("microphone", microphone, (0.5, 1.6, 0.5), body="charcoal", frame="black")
register("recorder", box_device, (0.2, 0.06, 0.12), body="grey", kind="recorder")
register("headphones", headphones, (0.19, 0.2, 0.08), body="black", frame="steel")
register("amplifier", box_device, (0.55, 0.45, 0.28), body="black", frame="charcoal", kind="amplifier")
register("mixing_console", box_device, (0.6, 0.08, 0.4), body="charcoal", kind="mixer")
register("radio", box_device, (0.3, 0.18, 0.12), body="brown", kind="radio")
register("camera", box_device, (0.14, 0.1, 0.08), body="black", kind="camera")
register("game_console", box_device, (0.3, 0.08, 0.25), body="white", kind="console")
register("microwave", box_device, (0.5, 0.3, 0.38), body="white", kind="microwave")
register("toaster", box_device, (0.28, 0.2, 0.17), body="steel", kind="toaster")
register("fan", fan, (0.45, 1.2, 0.35), body="white", frame="grey")
register("water_cooler", water_cooler, (0.32, 1.3, 0.35), body="white")
register("radiator", radiator, (0.9, 0.6, 0.1), body="white", frame="steel")
register("floor_lamp", lamp, (0.42, 1.65, 0.42), body="cream", frame="steel", kind="floor")
register("desk_lamp", lamp, (0.18, 0.45, 0.3), body="black", frame="charcoal", kind="desk")
register("lamp", lamp, (0.3, 0.5, 0.3), body="cream", frame="gold", kind="table")
