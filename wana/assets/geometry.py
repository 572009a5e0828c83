"""Solid parts that generators compose into meshes, and the voxelisation that turns them into boxes.

Every part is a closed primitive (box, solid of revolution, ellipsoid) in its own local frame plus a
rigid transform. A part knows both its triangle mesh and a conservative occupancy test, so that an
object's collision boxes come from voxelising the union of its parts on a regular grid (the paper's
"many small boxes"), without ray casting the mesh.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:  # imported by build_mesh: trimesh with scipy costs 0.65 s, parsing never needs it
    import trimesh

RGBA = tuple[int, int, int, int]


@dataclass
class Part:
    """One solid primitive.

    Attributes:
        kind: "box" (params: half extents (3,)), "lathe" (params: profile (P, 2) of (radius, y) rows,
            bottom to top, axis along local +Y) or "ellipsoid" (params: radii (3,)).
        params: shape parameters as above.
        rotation: (3, 3) local -> object frame.
        translation: (3,) object-frame position of the local origin.
        colour: RGBA uint8.
        solid: False for parts that are drawn but do not block (light cones, glass panes stay solid).
    """

    kind: str
    params: np.ndarray
    rotation: np.ndarray
    translation: np.ndarray
    colour: RGBA
    solid: bool = True
    sections: int = 16

    def local_mesh(self) -> tuple[np.ndarray, np.ndarray]:
        """Vertices (V, 3) and faces (F, 3) in the local frame, outward winding."""
        if self.kind == "box":
            v, f = _box_mesh(self.params)
        elif self.kind == "lathe":
            v, f = _lathe_mesh(self.params, self.sections)
        elif self.kind == "ellipsoid":
            v, f = _ellipsoid_mesh(self.params)
        else:
            raise ValueError(f"unknown part kind {self.kind!r}")
        return _orient_outward(v, f)

    def mesh(self) -> tuple[np.ndarray, np.ndarray]:
        v, f = self.local_mesh()
        return v @ self.rotation.T + self.translation, f

    def occupies(self, centres: np.ndarray, half: np.ndarray) -> np.ndarray:
        """Which grid cells this part overlaps (conservative for rotated parts).

        Args:
            centres: (N, 3) cell centres, object frame.
            half: (3,) cell half sizes, object frame.

        Returns:
            (N,) bool.
        """
        q = (centres - self.translation) @ self.rotation  # local coordinates
        hl = np.abs(self.rotation.T) @ half  # AABB of the cell in the local frame
        eps = 1e-6
        if self.kind == "box":
            e = self.params
            return np.all(np.abs(q) < e + hl - eps, axis=1)
        if self.kind == "ellipsoid":
            d = np.maximum(np.abs(q) - hl, 0.0) / self.params
            return np.sum(d * d, axis=1) < 1.0
        prof = self.params
        ys, rs = prof[:, 1], prof[:, 0]
        lo = q[:, 1] - hl[1]
        hi = q[:, 1] + hl[1]
        inside_y = (hi > ys[0] + eps) & (lo < ys[-1] - eps)
        lo_c = np.clip(lo, ys[0], ys[-1])
        hi_c = np.clip(hi, ys[0], ys[-1])
        rmax = np.maximum(np.interp(lo_c, ys, rs), np.interp(hi_c, ys, rs))
        within = (ys[None, :] >= lo_c[:, None]) & (ys[None, :] <= hi_c[:, None])
        rmax = np.maximum(rmax, np.max(np.where(within, rs[None, :], 0.0), axis=1))
        dx = np.maximum(np.abs(q[:, 0]) - hl[0], 0.0)
        dz = np.maximum(np.abs(q[:, 2]) - hl[2], 0.0)
        return inside_y & (dx * dx + dz * dz < rmax * rmax - eps)


def _box_mesh(half: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    signs = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)
    v = signs * half
    f = np.array(
        [
            [0, 1, 3],
            [0, 3, 2],
            [4, 6, 7],
            [4, 7, 5],
            [0, 4, 5],
            [0, 5, 1],
            [2, 3, 7],
            [2, 7, 6],
            [0, 2, 6],
            [0, 6, 4],
            [1, 5, 7],
            [1, 7, 3],
        ],
        dtype=np.int64,
    )
    return v, f


def _lathe_mesh(profile: np.ndarray, sections: int) -> tuple[np.ndarray, np.ndarray]:
    """Closed surface of revolution about +Y; the profile's first and last radius should be 0."""
    theta = np.linspace(0.0, 2.0 * np.pi, sections, endpoint=False)
    ring = np.stack([np.cos(theta), np.zeros_like(theta), np.sin(theta)], axis=1)
    verts: list[np.ndarray] = []
    rings: list[list[int]] = []
    n = 0
    for r, y in profile:
        if r <= 1e-9:
            verts.append(np.array([[0.0, y, 0.0]]))
            rings.append([n] * sections)
            n += 1
        else:
            verts.append(ring * r + np.array([0.0, y, 0.0]))
            rings.append(list(range(n, n + sections)))
            n += sections
    faces: list[list[int]] = []
    for a, b in zip(rings[:-1], rings[1:], strict=True):
        for j in range(sections):
            k = (j + 1) % sections
            if a[j] != a[k]:
                faces.append([a[j], b[j], a[k]])
            if b[j] != b[k]:
                faces.append([a[k], b[j], b[k]])
    return np.concatenate(verts), np.array(faces, dtype=np.int64)


def _ellipsoid_mesh(radii: np.ndarray, rows: int = 7, cols: int = 12) -> tuple[np.ndarray, np.ndarray]:
    phi = np.linspace(0.0, np.pi, rows + 1)
    prof = np.stack([np.sin(phi), -np.cos(phi)], axis=1)
    v, f = _lathe_mesh(prof, cols)
    return v * radii, f


def _orient_outward(v: np.ndarray, f: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    tri = v[f]
    signed = np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])).sum()
    return (v, f) if signed >= 0 else (v, f[:, ::-1].copy())


@dataclass
class PartList:
    """A growing list of parts with helpers in object-frame coordinates (metres, Y up, front +Z)."""

    parts: list[Part] = field(default_factory=list)

    def box(
        self,
        lo: tuple[float, float, float],
        hi: tuple[float, float, float],
        colour: RGBA,
        yaw: float = 0.0,
        solid: bool = True,
    ) -> None:
        """Box from min to max corner (before an optional yaw about its own centre)."""
        lo_a, hi_a = np.asarray(lo, float), np.asarray(hi, float)
        half = np.maximum((hi_a - lo_a) / 2.0, 1e-4)
        self.parts.append(Part("box", half, _yaw(yaw), (lo_a + hi_a) / 2.0, colour, solid))

    def boxc(
        self,
        centre: tuple[float, float, float],
        size: tuple[float, float, float],
        colour: RGBA,
        yaw: float = 0.0,
        pitch: float = 0.0,
        roll: float = 0.0,
    ) -> None:
        """Box by centre and full size, rotated by yaw (Y), then pitch (X), then roll (Z)."""
        rot = _yaw(yaw) @ _rot_x(pitch) @ _rot_z(roll)
        self.parts.append(
            Part("box", np.maximum(np.asarray(size, float) / 2, 1e-4), rot, np.asarray(centre, float), colour)
        )

    def lathe(
        self,
        base: tuple[float, float, float],
        profile: list[tuple[float, float]],
        colour: RGBA,
        axis: str = "y",
        sections: int = 16,
    ) -> None:
        """Solid of revolution; profile rows are (radius, height along the axis from base)."""
        prof = np.asarray(profile, float)
        if prof[0, 0] > 0:
            prof = np.vstack([[0.0, prof[0, 1]], prof])
        if prof[-1, 0] > 0:
            prof = np.vstack([prof, [0.0, prof[-1, 1]]])
        rot = {
            "y": np.eye(3),
            "x": _rot_z(-np.pi / 2),
            "z": _rot_x(np.pi / 2),
            "-x": _rot_z(np.pi / 2),
            "-z": _rot_x(-np.pi / 2),
            "-y": _rot_x(np.pi),
        }[axis]
        self.parts.append(Part("lathe", prof, rot, np.asarray(base, float), colour, sections=sections))

    def cyl(
        self,
        base: tuple[float, float, float],
        radius: float,
        height: float,
        colour: RGBA,
        axis: str = "y",
        sections: int = 16,
    ) -> None:
        self.lathe(base, [(radius, 0.0), (radius, height)], colour, axis, sections)

    def rod(
        self,
        p0: tuple[float, float, float],
        p1: tuple[float, float, float],
        radius: float,
        colour: RGBA,
        sections: int = 8,
    ) -> None:
        """Cylinder between two points (any direction)."""
        a, b = np.asarray(p0, float), np.asarray(p1, float)
        length = float(np.linalg.norm(b - a))
        if length < 1e-6:
            return
        rot = _rotation_from_y((b - a) / length)
        prof = np.array([[0.0, 0.0], [radius, 0.0], [radius, length], [0.0, length]])
        self.parts.append(Part("lathe", prof, rot, a, colour, sections=sections))

    def ellipsoid(
        self, centre: tuple[float, float, float], radii: tuple[float, float, float], colour: RGBA
    ) -> None:
        self.parts.append(
            Part("ellipsoid", np.asarray(radii, float), np.eye(3), np.asarray(centre, float), colour)
        )


def _yaw(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def _rot_x(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def _rot_z(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _rotation_from_y(d: np.ndarray) -> np.ndarray:
    """Rotation taking +Y to unit vector d."""
    y = np.array([0.0, 1.0, 0.0])
    v = np.cross(y, d)
    c = float(np.dot(y, d))
    if np.linalg.norm(v) < 1e-9:
        return np.eye(3) if c > 0 else _rot_x(np.pi)
    k = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return np.eye(3) + k + k @ k * (1.0 / (1.0 + c))


def build_mesh(parts: list[Part]) -> trimesh.Trimesh:
    """Concatenate parts into one mesh with per-face colours."""
    import trimesh

    verts, faces, colours = [], [], []
    n = 0
    for p in parts:
        v, f = p.mesh()
        verts.append(v)
        faces.append(f + n)
        colours.append(np.tile(np.asarray(p.colour, np.uint8), (len(f), 1)))
        n += len(v)
    return trimesh.Trimesh(
        np.concatenate(verts), np.concatenate(faces), face_colors=np.concatenate(colours), process=False
    )


def voxel_boxes(
    parts: list[Part], bounds: np.ndarray, max_cells: int = 12, min_pitch: float = 0.03
) -> np.ndarray:
    """Collision boxes: the grid cells over ``bounds`` that any solid part overlaps.

    Args:
        parts: the object's parts (object frame).
        bounds: (2, 3) min/max corners of the object.
        max_cells: most cells along one axis.
        min_pitch: smallest cell edge in metres (small objects get few cells).

    Returns:
        (N, 2, 3) min/max corners of occupied cells, object frame; N >= 1.
    """
    ext = np.maximum(bounds[1] - bounds[0], 1e-4)
    pitch = max(float(ext.max()) / max_cells, min_pitch)
    n = np.clip(np.ceil(ext / pitch - 1e-9), 1, max_cells).astype(int)
    size = ext / n
    idx = np.stack(np.meshgrid(*[np.arange(k) for k in n], indexing="ij"), axis=-1).reshape(-1, 3)
    centres = bounds[0] + (idx + 0.5) * size
    occ = np.zeros(len(centres), bool)
    for p in parts:
        if p.solid:
            occ |= p.occupies(centres, size / 2.0)
    if not occ.any():
        return bounds[None].copy()
    c = centres[occ]
    return np.stack([c - size / 2.0, c + size / 2.0], axis=1)
