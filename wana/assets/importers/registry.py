"""Objects imported at run time (from user data) that placements can refer to by category name."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from wana.assets.catalog import AssetObject

_IMPORTED: dict[str, AssetObject] = {}


def register_imported(name: str, obj: AssetObject) -> None:
    """Make ``name`` resolve to ``obj`` in catalog.asset_for (e.g. "shapenet:1a2b3c")."""
    _IMPORTED[name] = obj


def imported_object(name: str) -> AssetObject | None:
    return _IMPORTED.get(name)


def clear_imported() -> None:
    _IMPORTED.clear()
