"""The static part of a frame: room (floor and four one-sided walls) and the placed catalog objects;
and the props held in a hand (Motion.props), drawn on their own and posed per frame.

Meshes are flattened to per-face colours (each triangle gets its own three vertices), so flat
shading and exact material colours survive the per-vertex-colour renderer and the glTF export.
Shadows are planar: the mesh projected onto the floor along the light direction.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import trimesh

from proto.motion_data import Motion
from proto.scene import PlacedObject, Room, Scene

FLOOR_RGBA = (196, 178, 150, 255)
WALL_RGBA = (232, 228, 218, 255)
SHADOW_LIFT = 0.004  # metres above the floor, to stay in front of it in the depth buffer


@dataclass(frozen=True)
class ColouredMesh:
    """A named triangle mesh in world coordinates.

    Attributes:
        name: scene object id, "floor" or "wall_*".
        vertices: (V, 3) float64 metres.
        faces: (F, 3) int64.
        colours: (V, 4) uint8 RGBA.
    """

    name: str
    vertices: np.ndarray
    faces: np.ndarray
    colours: np.ndarray


def _face_coloured(name: str, mesh: trimesh.Trimesh, transform: np.ndarray | None = None) -> ColouredMesh:
    verts = np.asarray(mesh.vertices, dtype=np.float64)
    if transform is not None:
        verts = verts @ transform[:3, :3].T + transform[:3, 3]
    faces = np.asarray(mesh.faces, dtype=np.int64)
    visual: Any = mesh.visual  # ColorVisuals, TextureVisuals or None; only the first has face colours
    try:
        fc = np.asarray(visual.face_colors, dtype=np.uint8)
    except Exception:  # meshes without a colour visual
        fc = np.full((len(faces), 4), 180, dtype=np.uint8)
    if fc.shape != (len(faces), 4):
        fc = np.full((len(faces), 4), 180, dtype=np.uint8)
    if transform is not None and np.linalg.det(transform[:3, :3]) < 0:
        faces = faces[:, ::-1]
    flat = verts[faces].reshape(-1, 3)
    return ColouredMesh(
        name=name,
        vertices=flat,
        faces=np.arange(len(flat), dtype=np.int64).reshape(-1, 3),
        colours=np.repeat(fc, 3, axis=0),
    )


def _quad(name: str, corners: np.ndarray, rgba: tuple[int, int, int, int], tiles: int = 1) -> ColouredMesh:
    """A one-sided quad (corners counter-clockwise seen from the visible side), split into tiles."""
    a, b, c, d = corners
    verts: list[np.ndarray] = []
    faces: list[list[int]] = []
    for i in range(tiles):
        for j in range(tiles):
            u0, u1, v0, v1 = i / tiles, (i + 1) / tiles, j / tiles, (j + 1) / tiles

            def p(u, v):  # noqa: ANN001, ANN202
                return a + (b - a) * u + (d - a) * v

            k = len(verts)
            verts += [p(u0, v0), p(u1, v0), p(u1, v1), p(u0, v1)]
            faces += [[k, k + 1, k + 2], [k, k + 2, k + 3]]
    verts_a = np.asarray(verts, dtype=np.float64)
    faces_a = np.asarray(faces, dtype=np.int64)
    colours = np.tile(np.asarray(rgba, dtype=np.uint8), (len(verts_a), 1))
    if tiles > 1:  # a faint checker so motion over the floor reads on screen
        shade = (
            np.arange(len(faces_a) // 2)[:, None] // tiles + np.arange(len(faces_a) // 2)[:, None] % tiles
        ) % 2
        dim = np.repeat(np.where(shade[:, 0] == 1, 0.93, 1.0), 4)
        colours = colours.copy()
        colours[:, :3] = (colours[:, :3] * dim[:, None]).astype(np.uint8)
    del c
    return ColouredMesh(name=name, vertices=verts_a, faces=faces_a, colours=colours)


def room_meshes(room: Room) -> list[ColouredMesh]:
    """Floor (facing up) and four walls facing inwards; from outside, a wall is culled and the room shows."""
    w, d, h = room.width / 2.0, room.depth / 2.0, room.height
    tiles = int(max(1, min(12, round(max(room.width, room.depth) / 0.5))))
    floor = _quad("floor", np.array([[-w, 0, d], [w, 0, d], [w, 0, -d], [-w, 0, -d]]), FLOOR_RGBA, tiles)
    walls = [
        _quad("wall_back", np.array([[-w, 0, -d], [w, 0, -d], [w, h, -d], [-w, h, -d]]), WALL_RGBA),
        _quad("wall_front", np.array([[w, 0, d], [-w, 0, d], [-w, h, d], [w, h, d]]), WALL_RGBA),
        _quad("wall_left", np.array([[-w, 0, d], [-w, 0, -d], [-w, h, -d], [-w, h, d]]), WALL_RGBA),
        _quad("wall_right", np.array([[w, 0, -d], [w, 0, d], [w, h, d], [w, h, -d]]), WALL_RGBA),
    ]
    return [floor, *walls]


def object_meshes(scene: Scene, leave_out: set[str] | frozenset[str] = frozenset()) -> list[ColouredMesh]:
    """Every placed object in world coordinates (catalog mesh through ``object_to_world``), but those
    left out (props held in a hand, drawn on their own)."""
    from wana.assets.catalog import asset_for, object_to_world

    out = []
    for placed in scene.objects:
        if placed.id in leave_out:
            continue
        try:
            asset = asset_for(placed)
        except KeyError as exc:
            raise ValueError(f"scene object {placed.id!r}: {exc}") from exc
        out.append(_face_coloured(placed.id, asset.mesh, object_to_world(placed)))
    return out


def held_ids(motions: list[Motion]) -> set[str]:
    """Objects some character holds at some frame (drawn on their own, posed per frame)."""
    return {track.object_id for m in motions for track in m.props}


def prop_mesh(placed: PlacedObject) -> ColouredMesh:
    """A held object's mesh in its own frame, scaled (``prop_pose`` places it per frame)."""
    from wana.assets.catalog import asset_for

    scale = np.eye(4)
    scale[:3, :3] = np.diag(placed.scale)
    return _face_coloured(placed.id, asset_for(placed).mesh, scale)


def prop_track(placed: PlacedObject, motions: list[Motion], n_frames: int) -> tuple[np.ndarray, np.ndarray]:
    """(T, 3) world positions and (T, 4) rotations (x, y, z, w) of an object over the animation: the
    tracks holding it where they do, where the scene placed it elsewhere (an animated GLB node)."""
    from wana.arrays import from_wire
    from wana.domain import quat

    pos = np.tile(np.asarray(placed.position, dtype=np.float64), (n_frames, 1))
    rot = np.tile(quat.yaw(np.array(float(placed.yaw))), (n_frames, 1))
    for motion in motions:
        for track in motion.props:
            if track.object_id != placed.id:
                continue
            a, b = max(0, track.start_frame), min(n_frames, track.end_frame)
            if b > a:
                pos[a:b] = from_wire(track.position)[a - track.start_frame : b - track.start_frame]
                rot[a:b] = from_wire(track.rotation)[a - track.start_frame : b - track.start_frame]
    return pos, rot


def prop_pose(placed: PlacedObject, motions: list[Motion], frame: int) -> np.ndarray:
    """(4, 4) object -> world (no scale) of an object at a frame: in the hand of the track holding it
    then, else where the scene placed it."""
    from wana.arrays import from_wire
    from wana.assets.catalog import yaw_matrix

    m = np.eye(4)
    for motion in motions:
        for track in motion.props:
            if track.object_id == placed.id and track.start_frame <= frame < track.end_frame:
                i = frame - track.start_frame
                x, y, z, w = (float(v) for v in from_wire(track.rotation)[i])
                m[:3, :3] = [
                    [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                    [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                    [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
                ]
                m[:3, 3] = from_wire(track.position)[i]
                return m
    m[:3, :3] = yaw_matrix(placed.yaw)
    m[:3, 3] = placed.position
    return m


def merge(meshes: list[ColouredMesh], name: str = "static") -> ColouredMesh:
    """One mesh out of many (fewer draw calls)."""
    if not meshes:
        return ColouredMesh(
            name=name,
            vertices=np.zeros((0, 3)),
            faces=np.zeros((0, 3), np.int64),
            colours=np.zeros((0, 4), np.uint8),
        )
    offsets = np.cumsum([0] + [len(m.vertices) for m in meshes[:-1]])
    return ColouredMesh(
        name=name,
        vertices=np.concatenate([m.vertices for m in meshes]),
        faces=np.concatenate([m.faces + o for m, o in zip(meshes, offsets, strict=True)]),
        colours=np.concatenate([m.colours for m in meshes]),
    )


def project_to_floor(vertices: np.ndarray, sun: np.ndarray, room: Room) -> np.ndarray:
    """Planar shadow: (..., 3) points moved along ``sun`` onto y = SHADOW_LIFT, clamped to the floor."""
    sun = np.asarray(sun, dtype=np.float64)
    dy = min(sun[1], -0.2)
    t = (SHADOW_LIFT - vertices[..., 1]) / dy
    out = vertices + t[..., None] * sun
    out[..., 1] = SHADOW_LIFT
    out[..., 0] = np.clip(out[..., 0], -room.width / 2, room.width / 2)
    out[..., 2] = np.clip(out[..., 2], -room.depth / 2, room.depth / 2)
    return out


def shadow_faces(faces: np.ndarray) -> np.ndarray:
    """Faces of a shadow mesh: both windings, since projection flips half of the triangles."""
    return np.concatenate([faces, faces[:, ::-1]])
