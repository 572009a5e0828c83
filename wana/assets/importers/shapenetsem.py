"""ShapeNetSem-style import: ``metadata.csv`` + ``models-OBJ/models/<id>.obj``.

Columns used (as in ShapeNetSem's metadata.csv): ``fullId`` ("wss.<id>"), ``category`` (comma
separated, CamelCase, e.g. "Chair,OfficeChair"), ``wnlemmas``, ``up`` and ``front`` ("0\\,0\\,1"),
``unit`` (metres per model unit), ``name``. Rows whose category the vocabulary does not know are
reported and skipped; imported objects are registered under "shapenet:<id>" for ``catalog.asset_for``.
"""

from __future__ import annotations

import csv
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from wana.assets.catalog import AssetObject
from wana.assets.importers.meshes import asset_from_mesh, load_mesh_file, resolve_category
from wana.assets.importers.registry import register_imported


@dataclass(frozen=True)
class ShapeNetEntry:
    model_id: str
    category: str | None  # vocabulary category, None when unknown
    raw_category: str
    up: tuple[float, float, float]
    front: tuple[float, float, float]
    unit: float
    name: str


def _vec(text: str, default: tuple[float, float, float]) -> tuple[float, float, float]:
    parts = [p for p in text.replace("\\", "").replace(" ", "").split(",") if p]
    if len(parts) != 3:
        return default
    return tuple(float(p) for p in parts)  # type: ignore[return-value]


def read_metadata(csv_path: str | Path) -> list[ShapeNetEntry]:
    """Parse a ShapeNetSem metadata CSV into entries (category resolved through the vocabulary)."""
    entries = []
    with open(csv_path, newline="", encoding="utf-8") as f:
        for row in csv.DictReader(f, escapechar="\\"):  # ShapeNetSem writes "0\\,0\\,1"
            full = row.get("fullId", "").strip()
            if not full:
                continue
            model_id = full.split(".", 1)[1] if "." in full else full
            raw = row.get("category", "")
            unit_text = (row.get("unit") or "").strip()
            entries.append(
                ShapeNetEntry(
                    model_id=model_id,
                    category=resolve_category(raw, row.get("wnlemmas", ""), row.get("name", "")),
                    raw_category=raw,
                    up=_vec(row.get("up", ""), (0.0, 0.0, 1.0)),
                    front=_vec(row.get("front", ""), (0.0, -1.0, 0.0)),
                    unit=float(unit_text) if unit_text else 0.0254,
                    name=row.get("name", ""),
                )
            )
    return entries


def import_shapenetsem(
    csv_path: str | Path, models_dir: str | Path, limit: int | None = None, register: bool = True
) -> tuple[list[AssetObject], list[str]]:
    """Import the models a metadata CSV lists.

    Returns:
        (objects, skipped) where skipped holds one reason per row that was not imported.
    """
    objects: list[AssetObject] = []
    skipped: list[str] = []
    for e in read_metadata(csv_path)[:limit]:
        path = Path(models_dir) / f"{e.model_id}.obj"
        if e.category is None:
            skipped.append(f"{e.model_id}: unknown category {e.raw_category!r}")
            continue
        if not path.is_file():
            skipped.append(f"{e.model_id}: missing {path.name}")
            continue
        try:
            obj = asset_from_mesh(load_mesh_file(path), e.category, np.array(e.up), np.array(e.front), e.unit)
        except ValueError as exc:
            skipped.append(f"{e.model_id}: {exc}")
            continue
        objects.append(obj)
        if register:
            register_imported(f"shapenet:{e.model_id}", obj)
    return objects, skipped
