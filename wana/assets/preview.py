"""Small software previews of meshes (painter's algorithm with PIL) and catalog contact sheets.

No OpenGL: faces are projected with a three-quarter orthographic camera, shaded by a fixed light and
drawn back to front. Good enough to eyeball shapes and colours of hundreds of objects in seconds.
"""

from __future__ import annotations

from pathlib import Path
from typing import cast

import numpy as np
import trimesh
from PIL import Image, ImageDraw
from trimesh.visual import ColorVisuals

_LIGHT = np.array([0.4, 0.8, 0.6]) / np.linalg.norm([0.4, 0.8, 0.6])


def view_matrix(azimuth: float = 0.6, elevation: float = 0.45) -> np.ndarray:
    """(3, 3) world -> camera rotation for a camera looking at the object's front from the right-top."""
    ca, sa = np.cos(azimuth), np.sin(azimuth)
    ce, se = np.cos(elevation), np.sin(elevation)
    yaw = np.array([[ca, 0.0, -sa], [0.0, 1.0, 0.0], [sa, 0.0, ca]])
    pitch = np.array([[1.0, 0.0, 0.0], [0.0, ce, -se], [0.0, se, ce]])
    return pitch @ yaw


def render_mesh(
    mesh: trimesh.Trimesh,
    size: int = 160,
    background: tuple[int, int, int] = (245, 245, 245),
    azimuth: float = 0.6,
    elevation: float = 0.45,
) -> Image.Image:
    """Render a coloured mesh to a square RGB image.

    Args:
        mesh: mesh with face colours (F, 4) uint8.
        size: image edge in pixels.
    """
    img = Image.new("RGB", (size, size), background)
    if len(mesh.faces) == 0:
        return img
    rot = view_matrix(azimuth, elevation)
    v = np.asarray(mesh.vertices) @ rot.T
    lo, hi = v.min(axis=0), v.max(axis=0)
    scale = 0.86 * size / max(hi[0] - lo[0], hi[1] - lo[1], 1e-6)
    centre = (lo + hi) / 2.0
    xy = np.empty((len(v), 2))
    xy[:, 0] = (v[:, 0] - centre[0]) * scale + size / 2
    xy[:, 1] = size / 2 - (v[:, 1] - centre[1]) * scale
    faces = np.asarray(mesh.faces)
    tri = v[faces]
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    norm = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = normals / np.maximum(norm, 1e-12)
    visible = normals[:, 2] > 0  # camera looks down -Z in camera space; keep faces turned to it
    light = rot @ _LIGHT
    shade = 0.45 + 0.55 * np.clip(normals @ light, 0.0, 1.0)
    visual = cast(ColorVisuals, mesh.visual)  # the caller passes a face-coloured mesh (see Args)
    colours = np.asarray(visual.face_colors)[:, :3].astype(float)
    lit = np.clip(colours * shade[:, None], 0, 255).astype(np.uint8)
    depth = tri[:, :, 2].mean(axis=1)
    draw = ImageDraw.Draw(img)
    for i in np.argsort(depth):
        if not visible[i]:
            continue
        pts = [tuple(p) for p in xy[faces[i]]]
        draw.polygon(pts, fill=tuple(int(c) for c in lit[i]))
    return img


def contact_sheet(
    items: list[tuple[str, trimesh.Trimesh]], path: str | Path, cols: int = 12, cell: int = 140
) -> Path:
    """Grid of labelled previews written to a PNG; returns the path."""
    rows = max(1, int(np.ceil(len(items) / cols)))
    label_h = 14
    sheet = Image.new("RGB", (cols * cell, rows * (cell + label_h)), (255, 255, 255))
    draw = ImageDraw.Draw(sheet)
    for k, (label, mesh) in enumerate(items):
        r, c = divmod(k, cols)
        x, y = c * cell, r * (cell + label_h)
        sheet.paste(render_mesh(mesh, cell), (x, y))
        draw.text((x + 3, y + cell), label[:22], fill=(20, 20, 20))
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(out)
    return out
