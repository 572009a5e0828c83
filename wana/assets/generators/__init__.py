"""Parametric generators, one per catalog category, grouped by family.

Importing this package registers every family; ``REGISTRY`` maps category -> GenSpec.
"""

from __future__ import annotations

from wana.assets.generators import (  # noqa: F401  (registration side effects)
    electronics,
    gym,
    household,
    instruments,
    kitchen_bath,
    seating,
    smalls,
    storage,
    tables,
    vessels,
    walls,
    workshop,
)
from wana.assets.generators.registry import REGISTRY, GenSpec, register

__all__ = ["REGISTRY", "GenSpec", "register"]


def _fill_missing() -> None:
    from wana.assets.generators.generic import block
    from wana.assets.vocabulary import CATEGORIES

    sizes = {"floor": (0.6, 0.8, 0.5), "surface": (0.2, 0.15, 0.15), "wall": (1.0, 0.8, 0.04)}
    for name, info in CATEGORIES.items():
        if name not in REGISTRY:
            register(name, block, sizes[info.mount], body="grey")


_fill_missing()
