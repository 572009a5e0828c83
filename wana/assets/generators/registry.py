"""Generator registry: category -> (function, base dimensions, default tones, options)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from wana.assets.params import Builder, Params

GeneratorFn = Callable[..., None]


@dataclass(frozen=True)
class GenSpec:
    """How to build one category.

    Attributes:
        fn: ``fn(builder, params, **opts)`` adds parts, contacts and surfaces.
        dims: base (width x, height y, depth z) in metres at size "medium".
        body, frame, accent: default tone names (see params.TONES).
        opts: keyword options passed to fn (the family's variant, e.g. kind="office").
    """

    fn: GeneratorFn
    dims: tuple[float, float, float]
    body: str
    frame: str
    accent: str
    opts: dict[str, Any] = field(default_factory=dict)


REGISTRY: dict[str, GenSpec] = {}


def register(
    category: str,
    fn: GeneratorFn,
    dims: tuple[float, float, float],
    body: str = "wood",
    frame: str | None = None,
    accent: str = "charcoal",
    **opts: Any,
) -> None:
    if category in REGISTRY:
        raise ValueError(f"generator for {category!r} registered twice")
    REGISTRY[category] = GenSpec(fn, dims, body, frame or body, accent, dict(opts))


def run(spec: GenSpec, builder: Builder, params: Params) -> None:
    spec.fn(builder, params, **spec.opts)
