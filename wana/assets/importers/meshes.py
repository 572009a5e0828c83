"""Any OBJ/GLB mesh (+ a small JSON annotation) -> AssetObject with collision boxes and contact points.

Annotation (``<mesh stem>.json`` beside the mesh, or passed explicitly), every key optional:

    {"category": "office chair",        # any word the vocabulary knows; default: from the file name
     "up": [0, 0, 1], "front": [0, -1, 0],   # the file's up and front axes (default Y up, +Z front)
     "unit": 0.01,                        # metres per file unit (default 1)
     "contact_points": {"sit": {"joint": "Hips", "position": [0, 0.45, 0]}}}  # object frame, metres

Imported objects get collision boxes by voxelising the mesh (trimesh) and default contact points,
stand point and support surfaces from the catalog template of their category, scaled to their size.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import trimesh

from wana.assets import vocabulary
from wana.assets.catalog import FRONT, AssetObject, ContactPoint, SupportSurface, _frozen, make_object


def frame_rotation(up: np.ndarray, front: np.ndarray) -> np.ndarray:
    """(3, 3) rotation taking the file's up axis to +Y and its front axis to +Z."""
    u = np.asarray(up, float) / np.linalg.norm(up)
    f = np.asarray(front, float)
    f = f - u * (f @ u)
    if np.linalg.norm(f) < 1e-9:
        raise ValueError("front must not be parallel to up")
    f /= np.linalg.norm(f)
    x = np.cross(u, f)
    src = np.stack([x, u, f])  # rows: file-frame axes that become X, Y, Z
    return src


def voxel_collision_boxes(mesh: trimesh.Trimesh, max_cells: int = 12) -> np.ndarray:
    """(N, 2, 3) boxes of the filled voxelisation of a mesh (object frame)."""
    ext = float(np.max(mesh.extents))
    pitch = max(ext / max_cells, 0.01)
    try:
        grid = mesh.voxelized(pitch)
        grid = grid.fill() if mesh.is_watertight else grid
        centres = np.asarray(grid.points)
    except Exception:  # noqa: BLE001 - degenerate meshes fall back to their bounds
        centres = np.empty((0, 3))
    if len(centres) == 0:
        return mesh.bounds[None].copy()
    half = pitch / 2.0
    boxes = np.stack([centres - half, centres + half], axis=1)
    lo, hi = mesh.bounds
    return np.clip(boxes, lo, hi)


def resolve_category(*words: str) -> str | None:
    """First vocabulary category among words ("OfficeChair" and "office_chair" both work)."""
    import re

    for w in words:
        if not w:
            continue
        for token in [w, *re.split(r"[,;|]", w)]:
            spaced = re.sub(r"(?<=[a-z])(?=[A-Z])", " ", token.strip())
            cat = vocabulary.lookup(spaced)
            if cat is not None:
                return cat
    return None


def asset_from_mesh(
    mesh: trimesh.Trimesh,
    category: str | None,
    up=(0.0, 1.0, 0.0),
    front=(0.0, 0.0, 1.0),  # noqa: ANN001
    unit: float = 1.0,
    contact_points: dict | None = None,
) -> AssetObject:
    """Bring a mesh into the object frame and attach collision boxes and default interactions.

    Args:
        mesh: the mesh in file units and axes.
        category: a vocabulary category or None (then only a default "touch" contact).
        up, front: the file's up and front directions.
        unit: metres per file unit.
        contact_points: optional overrides {name: {"joint": str, "position": [x, y, z]}} (object frame).
    """
    m = mesh.copy()
    if len(m.faces) == 0:
        raise ValueError("mesh has no faces")
    rot = np.eye(4)
    rot[:3, :3] = frame_rotation(np.asarray(up, float), np.asarray(front, float))
    m.apply_transform(rot)
    m.apply_scale(float(unit))
    lo, hi = m.bounds
    m.apply_translation([-(lo[0] + hi[0]) / 2, -lo[1], -(lo[2] + hi[2]) / 2])
    if not isinstance(m.visual, trimesh.visual.ColorVisuals) or not m.visual.defined:
        m.visual = trimesh.visual.ColorVisuals(
            m, face_colors=np.tile([170, 170, 175, 255], (len(m.faces), 1))
        )
    dims = m.extents.copy()
    boxes = voxel_collision_boxes(m)
    contacts: dict[str, ContactPoint] = {}
    surfaces: list[SupportSurface] = []
    stand = np.array([0.0, 0.0, dims[2] / 2 + 0.35])
    if category is not None:
        template = make_object(category)
        k = dims / np.maximum(template.dims, 1e-6)
        contacts = {
            n: ContactPoint(c.joint, _frozen(c.position * k), {j: _frozen(p * k) for j, p in c.extra.items()})
            for n, c in template.contact_points.items()
        }
        surfaces = [
            SupportSurface(s.height * k[1], _frozen(s.min_xz * k[[0, 2]]), _frozen(s.max_xz * k[[0, 2]]))
            for s in template.support_surfaces
        ]
        stand = template.stand_point * np.array([k[0], 0.0, 1.0])
        stand[2] = dims[2] / 2 + (template.stand_point[2] - template.dims[2] / 2)
    for name, spec in (contact_points or {}).items():
        contacts[name] = ContactPoint(str(spec["joint"]), _frozen(spec["position"]))
    if not contacts:
        contacts["touch"] = ContactPoint(
            "RightHandMiddle1", _frozen([0.0, min(dims[1] * 0.8, 1.2), dims[2] / 2])
        )
    return AssetObject(
        category=category or "unknown",
        attributes={},
        seed=0,
        mesh=m,
        dims=_frozen(dims),
        collision_boxes=_frozen(boxes),
        contact_points=contacts,
        stand_point=_frozen(stand),
        support_surfaces=surfaces,
        front=_frozen(FRONT),
    )


def load_mesh_file(path: str | Path) -> trimesh.Trimesh:
    """One mesh from an OBJ/GLB/PLY/STL file (scenes are flattened in their own frame)."""
    loaded = trimesh.load(str(path), force="mesh", process=False)
    if not isinstance(loaded, trimesh.Trimesh) or len(loaded.faces) == 0:
        raise ValueError(f"{path}: no triangles found")
    return loaded


def import_mesh(path: str | Path, annotation: str | Path | dict | None = None) -> AssetObject:
    """Import any OBJ/GLB mesh with an optional annotation (see module docstring).

    Raises:
        FileNotFoundError: missing mesh file. ValueError: unreadable mesh or bad annotation.
    """
    p = Path(path)
    if not p.is_file():
        raise FileNotFoundError(f"no mesh file {p}")
    if annotation is None and p.with_suffix(".json").is_file():
        annotation = p.with_suffix(".json")
    ann: dict = {}
    if isinstance(annotation, dict):
        ann = annotation
    elif annotation is not None:
        ann = json.loads(Path(annotation).read_text())
    category = resolve_category(str(ann.get("category", "")), p.stem.replace("-", " ").replace("_", " "))
    return asset_from_mesh(
        load_mesh_file(p),
        category,
        ann.get("up", (0, 1, 0)),
        ann.get("front", (0, 0, 1)),
        float(ann.get("unit", 1.0)),
        ann.get("contact_points"),
    )
