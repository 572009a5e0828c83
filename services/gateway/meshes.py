"""Catalog object variants as GLB, generated once per (category, attributes, seed) and kept in an LRU cache."""

from __future__ import annotations

import json
import threading
from collections import OrderedDict
from typing import Any


class MeshUnavailable(RuntimeError):
    """The asset catalog is not in this build."""


class UnknownObject(ValueError):
    """A category or attribute the catalog refuses."""


def parse_attributes(raw: str) -> dict[str, str]:
    """The `attributes` query parameter: a JSON object of string to string ('' means none).

    Raises:
        UnknownObject: not a JSON object of strings.
    """
    if not raw:
        return {}
    try:
        value = json.loads(raw)
    except json.JSONDecodeError as exc:
        raise UnknownObject(f"attributes must be a JSON object: {exc}") from exc
    if not isinstance(value, dict) or not all(
        isinstance(k, str) and isinstance(v, str) for k, v in value.items()
    ):
        raise UnknownObject("attributes must be a JSON object mapping strings to strings")
    return value


class MeshCache:
    """GLB bytes per object variant, least recently used first out."""

    def __init__(self, capacity: int = 256) -> None:
        self.capacity = capacity
        self._items: OrderedDict[tuple[Any, ...], bytes] = OrderedDict()
        self._lock = threading.Lock()

    def glb(self, category: str, attributes: dict[str, str], seed: int) -> bytes:
        """The variant's mesh as GLB bytes.

        Raises:
            MeshUnavailable: wana.assets.catalog is missing.
            UnknownObject: the catalog does not know the category or refuses the attributes.
        """
        key = (category, tuple(sorted(attributes.items())), seed)
        with self._lock:
            if key in self._items:
                self._items.move_to_end(key)
                return self._items[key]
        data = _generate(category, attributes, seed)
        with self._lock:
            self._items[key] = data
            while len(self._items) > self.capacity:
                self._items.popitem(last=False)
        return data


def _generate(category: str, attributes: dict[str, str], seed: int) -> bytes:
    try:
        from wana.assets import catalog
    except ImportError as exc:
        raise MeshUnavailable(f"the asset catalog is not available yet ({exc})") from exc
    try:
        asset_for = getattr(catalog, "asset_for", None)
        if asset_for is not None:  # also knows objects brought in by the importers
            from proto.scene import PlacedObject

            obj = asset_for(PlacedObject(id="mesh", category=category, attributes=attributes, seed=seed))
        else:
            obj = catalog.make_object(category, attributes=attributes, seed=seed)
    except (KeyError, ValueError) as exc:
        raise UnknownObject(f"cannot make a {category!r} with {attributes}: {exc}") from exc
    data = obj.mesh.export(file_type="glb")
    if not isinstance(data, bytes):
        raise UnknownObject(f"the {category!r} mesh did not export as GLB")
    return data
