"""A plain block for categories without a dedicated generator (and for imported placeholders)."""

from __future__ import annotations

from wana.assets.params import Builder, Params


def block(b: Builder, p: Params) -> None:
    w, h, d = p.w, p.h, p.d
    b.box((-w / 2, 0, -d / 2), (w / 2, h, d / 2), p.body)
    b.box((-w / 2 + 0.01, h, -d / 2 + 0.01), (w / 2 - 0.01, h + min(0.02, h * 0.05), d / 2 - 0.01), p.frame)
    b.surface(h, -w / 2 + 0.01, -d / 2 + 0.01, w / 2 - 0.01, d / 2 - 0.01)
