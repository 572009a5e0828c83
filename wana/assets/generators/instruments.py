"""Musical instruments: pianos, synthesizers, guitars, strings, drums, winds, music stands."""

from __future__ import annotations

import numpy as np

from wana.assets.generators.registry import register
from wana.assets.params import Builder, Params


def _keys(b: Builder, p: Params, x0: float, x1: float, y: float, z0: float, z1: float) -> None:
    b.box((x0, y, z0), (x1, y + 0.02, z1), p.tone("ivory"))
    n = 36
    for i in range(n):
        if i % 7 in (2, 6):
            continue
        x = x0 + (i + 0.75) * (x1 - x0) / n
        b.box((x - 0.006, y + 0.02, z0), (x + 0.006, y + 0.035, z0 + (z1 - z0) * 0.6), p.tone("black"))


def piano(b: Builder, p: Params, kind: str = "upright") -> None:
    w, h, d = p.w, p.h, p.d
    key_h = 0.72
    if kind == "grand":
        for x, z in ((-w * 0.4, d * 0.35), (w * 0.4, d * 0.35), (0.0, -d * 0.4)):
            p.leg(b, x, z, 0.0, key_h - 0.1, 0.09)
        b.cyl((0.0, key_h - 0.1, -d * 0.05), w / 2, 0.32, p.body, sections=24)
        b.box((-w / 2, key_h - 0.1, d * 0.25), (w / 2, key_h + 0.22, d * 0.42), p.body)
        b.boxc((0.0, key_h + 0.45, -d * 0.05), (w * 0.9, 0.02, d * 0.6), p.body, pitch=-0.7)
        _keys(b, p, -w / 2 + 0.05, w / 2 - 0.05, key_h - 0.02, d * 0.42, d / 2)
        z = d * 0.46
    else:
        b.box((-w / 2, 0.0, -d / 2), (w / 2, h, -d / 2 + d * 0.55), p.body)
        for x in (-w / 2 + 0.03, w / 2 - 0.03):
            b.box((x - 0.03, 0.0, -d / 2), (x + 0.03, key_h, d / 2), p.body)
        b.box((-w / 2 + 0.06, key_h - 0.04, -d / 2), (w / 2 - 0.06, key_h - 0.02, d / 2), p.body)
        _keys(b, p, -w / 2 + 0.06, w / 2 - 0.06, key_h - 0.02, d * 0.05, d / 2 - 0.01)
        if p.style.trim:
            b.box((-w / 2 - 0.01, h - 0.04, -d / 2), (w / 2 + 0.01, h, -d / 2 + d * 0.6), p.frame)
        b.surface(h, -w / 2 + 0.05, -d / 2 + 0.03, w / 2 - 0.05, -d / 2 + d * 0.5)
        z = d / 2 - 0.05
    b.two_hands("play", key_h + 0.03, z, 0.4, finger=True)
    b.stand = (0.0, 0.0, d / 2 + 0.45)


def synthesizer(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    for s in (-1, 1):
        b.rod((s * w * 0.3, 0.0, -d / 2), (-s * w * 0.3, h - 0.1, d / 2), 0.015, p.frame)
        b.rod((s * w * 0.3, 0.0, d / 2), (-s * w * 0.3, h - 0.1, -d / 2), 0.015, p.frame)
    b.box((-w / 2, h - 0.1, -d / 2), (w / 2, h - 0.04, d / 2), p.body)
    _keys(b, p, -w / 2 + 0.05, w / 2 - 0.05, h - 0.04, -d * 0.1, d / 2 - 0.01)
    b.two_hands("play", h, d * 0.3, 0.4)
    b.stand = (0.0, 0.0, d / 2 + 0.45)


def guitar(b: Builder, p: Params, kind: str = "acoustic") -> None:
    """A guitar standing on a small floor stand, strings facing +Z."""
    w, h, d = p.w, p.h, p.d
    b.box((-w * 0.45, 0.0, -d / 2), (w * 0.45, 0.03, d / 2), p.tone("black"))
    body_h = h * 0.42
    y0 = 0.05
    if kind == "acoustic":
        b.ellipsoid((0, y0 + body_h * 0.3, 0), (w * 0.5, body_h * 0.32, d * 0.3), p.body)
        b.ellipsoid((0, y0 + body_h * 0.72, 0), (w * 0.38, body_h * 0.28, d * 0.3), p.body)
        b.cyl((0, y0 + body_h * 0.6, d * 0.28), 0.04, 0.005, p.tone("black"), axis="z")
    else:
        b.boxc(
            (0, y0 + body_h / 2, 0), (w * 0.8, body_h, d * 0.35), p.body, roll=0.12 if kind == "bass" else 0.0
        )
        for i in range(3 if kind == "electric" else 2):
            b.box(
                (-w * 0.2, y0 + body_h * (0.2 + 0.15 * i), d * 0.17),
                (w * 0.2, y0 + body_h * (0.2 + 0.15 * i) + 0.02, d * 0.19),
                p.tone("white"),
            )
    neck_top = h - 0.16
    b.box((-0.025, y0 + body_h * 0.9, -0.012), (0.025, neck_top, 0.012), p.tone("darkwood"))
    b.box((-0.04, neck_top, -0.012), (0.04, h, 0.012), p.tone("darkwood"))
    b.contact(
        "play",
        "RightHand",
        (0.0, y0 + body_h * 0.45, d * 0.3),
        {"LeftHand": (0.0, y0 + body_h + (neck_top - body_h) * 0.5, 0.02)},
    )
    b.contact("pick_up", "RightHand", (0.0, neck_top - 0.05, 0.02))
    b.stand = (0.0, 0.0, d / 2 + 0.35)


def bowed(b: Builder, p: Params, kind: str = "violin") -> None:
    w, h, d = p.w, p.h, p.d
    if kind == "violin":  # lying in its open case
        b.box((-w / 2, 0, -d / 2), (w / 2, h * 0.5, d / 2), p.tone("black"))
        b.ellipsoid((0, h * 0.5, -d * 0.1), (w * 0.4, h * 0.35, d * 0.22), p.body)
        b.box((-0.015, h * 0.5, d * 0.1), (0.015, h * 0.75, d / 2 - 0.02), p.tone("black"))
        b.contact("play", "LeftHand", (0.0, h * 0.7, d * 0.4), {"RightHand": (0.0, h * 0.8, -d * 0.1)})
        return
    b.rod((0, 0, 0.05), (0, 0.12, 0.0), 0.008, p.tone("steel"))
    b.ellipsoid((0, 0.12 + h * 0.18, 0), (w * 0.5, h * 0.18, d * 0.45), p.body)
    b.ellipsoid((0, 0.12 + h * 0.42, 0), (w * 0.4, h * 0.14, d * 0.45), p.body)
    b.box((-0.025, 0.12 + h * 0.5, -0.015), (0.025, h, 0.015), p.tone("black"))
    b.contact("play", "RightHand", (0.0, 0.12 + h * 0.3, d / 2 + 0.05), {"LeftHand": (0.0, h * 0.8, 0.02)})
    b.stand = (0.0, 0.0, d / 2 + 0.5)


def harp(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    b.box((-w / 2, 0, -d / 2), (w / 2, 0.1, d / 2), p.body)
    b.rod((-w * 0.4, 0.1, 0), (-w * 0.4, h, 0), 0.035, p.body)
    b.rod((w * 0.4, 0.1, 0), (0.0, h * 0.95, 0), 0.05, p.body)
    b.rod((-w * 0.4, h, 0), (w * 0.45, h * 0.8, 0), 0.03, p.body)
    for i in range(8):
        x = -w * 0.35 + i * w * 0.09
        top = h - 0.05 - (x + w * 0.4) * 0.2
        b.rod((x, 0.15 + (x + w * 0.4) * 0.8, 0), (x, top, 0), 0.002, p.tone("gold"))
    b.two_hands("play", h * 0.55, d / 2, 0.3)


def drum_kit(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    b.cyl((0, 0.28, -d * 0.2), 0.28, 0.4, p.body, axis="z", sections=20)  # bass drum on its side
    b.cyl((0, 0.0, -d * 0.2 + 0.15), 0.28, 0.02, p.body, axis="z")
    for x, z, r, y in (
        (-w * 0.3, d * 0.15, 0.18, 0.55),
        (w * 0.28, d * 0.1, 0.2, 0.5),
        (-0.12, -d * 0.05, 0.13, 0.75),
        (0.14, -d * 0.05, 0.13, 0.75),
    ):
        b.cyl((x, 0, z), 0.012, y, p.frame, sections=6)
        b.cyl((x, y, z), r, 0.16, p.body, sections=16)
        b.cyl((x, y + 0.16, z), r, 0.004, p.tone("white"), sections=16)
    for x in (-w / 2 + 0.1, w / 2 - 0.1):
        b.cyl((x, 0, -d * 0.35), 0.012, h - 0.02, p.frame, sections=6)
        b.lathe((x, h - 0.02, -d * 0.35), [(0.03, 0), (0.22, 0.01), (0.2, 0.02)], p.tone("gold"), sections=16)
    b.contact("play", "RightHand", (w * 0.28, 0.7, d * 0.1), {"LeftHand": (-w * 0.3, 0.75, d * 0.15)})
    b.contact("sit", "Hips", (0.0, 0.5, d / 2 + 0.25))
    b.stand = (0.0, 0.0, d / 2 + 0.35)


def wind(b: Builder, p: Params, kind: str = "trumpet") -> None:
    w, h, _d = p.w, p.h, p.d
    if kind == "trumpet":
        b.cyl((-w / 2 + 0.02, h / 2, 0), h * 0.25, w * 0.7, p.body, axis="x", sections=12)
        b.lathe((w * 0.2, h / 2, 0), [(h * 0.25, 0), (h * 0.5, w * 0.28)], p.body, axis="x")
        for i in range(3):
            b.cyl((-0.03 + i * 0.03, h / 2, 0), 0.008, h * 0.5, p.tone("steel"), sections=6)
    elif kind == "sax":
        b.lathe((0, 0, 0), [(0.06, 0), (0.07, 0.1), (0.03, h * 0.7), (0.015, h)], p.body)
        b.lathe((0.05, 0.05, 0), [(0.04, 0), (0.07, 0.12)], p.body, axis="x")
    else:
        b.cyl((-w / 2, h / 2, 0), h / 2, w, p.body, axis="x", sections=10)
        for i in range(6):
            b.cyl((-w * 0.2 + i * w * 0.07, h - 0.001, 0), h * 0.3, 0.002, p.tone("chrome"), sections=6)
    b.contact("play", "RightHand", (0.0, h / 2, 0.0), {"LeftHand": (-w * 0.3, h / 2, 0.0)})


def music_stand(b: Builder, p: Params, kind: str = "music") -> None:
    w, h, d = p.w, p.h, p.d
    for k in range(3):
        a = 2 * np.pi * k / 3 + np.pi / 2
        b.rod((0, 0.3, 0), (w * 0.35 * np.cos(a), 0.0, d * 0.4 * np.sin(a)), 0.01, p.frame)
    if kind == "easel":
        b.rod((0, 0, -d / 2), (0, h, 0), 0.02, p.body)
        b.box((-w / 2, h * 0.35, 0.02), (w / 2, h * 0.38, 0.1), p.body)
        b.boxc((0, h * 0.62, 0.06), (w * 0.9, h * 0.45, 0.02), p.tone("paper"), pitch=-0.12)
        b.contact("paint", "RightHand", (w * 0.2, h * 0.6, 0.15))
        b.stand = (0.0, 0.0, d / 2 + 0.5)
        return
    b.cyl((0, 0.3, 0), 0.01, h - 0.55, p.frame, sections=8)
    b.boxc((0, h - 0.18, 0.02), (w, 0.34, 0.01), p.body, pitch=-0.25)
    b.box((-w / 2, h - 0.36, 0.05), (w / 2, h - 0.34, 0.11), p.body)
    b.contact("read", "Head", (0.0, h - 0.18, 0.05))


register("piano", piano, (1.5, 1.25, 0.62), body="black", frame="gold")
register("grand_piano", piano, (1.5, 1.3, 1.9), body="black", frame="gold", kind="grand")
register("synthesizer", synthesizer, (1.1, 0.9, 0.4), body="charcoal", frame="steel")
register("guitar", guitar, (0.4, 1.05, 0.15), body="lightwood")
register("electric_guitar", guitar, (0.36, 1.05, 0.12), body="red", kind="electric")
register("bass_guitar", guitar, (0.36, 1.2, 0.12), body="black", kind="bass")
register("violin", bowed, (0.25, 0.12, 0.8), body="wood", kind="violin")
register("cello", bowed, (0.45, 1.25, 0.3), body="wood", kind="cello")
register("harp", harp, (0.9, 1.75, 0.45), body="lightwood")
register("drum_kit", drum_kit, (1.6, 1.25, 1.3), body="red", frame="chrome")
register("trumpet", wind, (0.5, 0.14, 0.14), body="gold", kind="trumpet")
register("saxophone", wind, (0.25, 0.7, 0.15), body="gold", kind="sax")
register("flute", wind, (0.65, 0.025, 0.03), body="chrome", kind="flute")
register("music_stand", music_stand, (0.5, 1.3, 0.45), body="black", frame="black")
register("easel", music_stand, (0.7, 1.7, 0.6), body="wood", frame="wood", kind="easel")
