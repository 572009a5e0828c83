"""Objects whose state the story changes, drawn per frame: a door leaf swinging on its hinge, a laptop lid
closing, a lamp's shade and a screen lit, and the room brighter around a lamp that is on.

The scene's state tracks (Scene.states, services/orchestrator/stages/states.py) say each state's value
per frame; the moving and glowing parts come from wana.domain.object_state. Objects with a track are left
out of the renderer's static mesh and drawn here; the static mesh's colours are relit when a lamp's value
changes (a warm pool of light falling off with distance), so a frame after "turns on the lamp" is brighter
near the lamp than one before.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from proto.scene import PlacedObject, Scene
from services.render.scene_geometry import ColouredMesh, _face_coloured
from wana.domain.object_state import (
    LIGHTS,
    STATEFUL,
    glowing_faces,
    lit_colour,
    moving_faces,
    open_transform,
    state_at,
)

LIGHT_GAIN = 0.7  # how much brighter a surface right at a lamp is when it is on (x its colour)
LIGHT_RADIUS = 1.1  # metres: the lamp's pool of light (gaussian sigma)
LIGHT_WARM = np.array([1.0, 0.93, 0.78])  # the colour of a lamp's light


@dataclass(frozen=True)
class StatefulObject:
    """One object with a state track: its mesh in its own frame and the parts its states move and light."""

    placed: PlacedObject
    mesh: ColouredMesh  # object frame, scaled, face-flattened
    leaf: np.ndarray  # (V,) int8: the leaf an "open" state turns each vertex with (0: still)
    glowing: np.ndarray  # (V,) bool: vertices an "on" state lights
    bounds: np.ndarray  # (2, 3) object-frame bounds
    parts: dict[int, np.ndarray]  # leaf -> its (2, 3) object-frame bounds

    @property
    def moving(self) -> np.ndarray:
        """(V,) bool: the vertices an "open" state moves."""
        return self.leaf > 0

    light: np.ndarray  # (3,) world position of its light (lamps), else the object's origin


def stateful_objects(scene: Scene) -> dict[str, StatefulObject]:
    """The scene's objects that have a state track, by id."""
    from wana.assets.catalog import asset_for, object_to_world

    tracked = {t.object_id for t in scene.states}
    out = {}
    for placed in scene.objects:
        if placed.id not in tracked or placed.category not in STATEFUL:
            continue
        scale = np.eye(4)
        scale[:3, :3] = np.diag(placed.scale)
        mesh = _face_coloured(placed.id, asset_for(placed).mesh, scale)
        tri = mesh.vertices.reshape(-1, 3, 3)
        centroids = tri.mean(axis=1)
        face_rgb = mesh.colours[::3, :3]
        leaf = np.repeat(moving_faces(placed.category, tri), 3)
        glowing = np.repeat(glowing_faces(placed.category, centroids, face_rgb), 3)
        bounds = np.stack([mesh.vertices.min(axis=0), mesh.vertices.max(axis=0)])
        parts = {
            int(k): np.stack([mesh.vertices[leaf == k].min(axis=0), mesh.vertices[leaf == k].max(axis=0)])
            for k in np.unique(leaf)
            if k > 0
        }
        top = np.array([0.0, bounds[1, 1] * 0.8, 0.0, 1.0])
        light = (object_to_world(placed) @ top)[:3]
        out[placed.id] = StatefulObject(placed, mesh, leaf, glowing, bounds, parts, light)
    return out


def posed(obj: StatefulObject, scene: Scene, frame: float) -> tuple[np.ndarray, np.ndarray]:
    """(V, 3) world vertices and (V, 3) RGB 0..1 colours of a stateful object at a frame."""
    from wana.assets.catalog import yaw_matrix

    rest = STATEFUL[obj.placed.category]
    verts = obj.mesh.vertices.copy()
    if "open" in rest:
        value = state_at(scene.states, obj.placed.id, "open", rest["open"], frame)
        for k, part in obj.parts.items():
            m = open_transform(obj.placed.category, part, value, k)
            verts[obj.leaf == k] = verts[obj.leaf == k] @ m[:3, :3].T + m[:3, 3]
    verts = verts @ yaw_matrix(obj.placed.yaw).T + np.asarray(obj.placed.position, float)
    colours = obj.mesh.colours[:, :3].astype(np.float64) / 255.0
    if "on" in rest:
        on = state_at(scene.states, obj.placed.id, "on", rest["on"], frame)
        lit = np.asarray(lit_colour(obj.placed.category), float) / 255.0
        colours[obj.glowing] = colours[obj.glowing] * (1.0 - on) + lit * on
    return verts, colours


def lights_at(objects: dict[str, StatefulObject], scene: Scene, frame: float) -> tuple[float, ...]:
    """How much each lamp is on at a frame (a key: the room is relit only when it changes)."""
    return tuple(
        round(state_at(scene.states, oid, "on", STATEFUL[o.placed.category]["on"], frame), 3)
        for oid, o in sorted(objects.items())
        if o.placed.category in LIGHTS
    )


def relit(
    colours: np.ndarray, vertices: np.ndarray, objects: dict[str, StatefulObject], values: tuple[float, ...]
) -> np.ndarray:
    """(V, 3) RGB 0..1: static colours under the lamps that are on (a warm pool around each)."""
    lamps = [o for _, o in sorted(objects.items()) if o.placed.category in LIGHTS]
    gain = np.ones((len(vertices), 3))
    for lamp, on in zip(lamps, values, strict=True):
        if on <= 0.0:
            continue
        d2 = np.sum((vertices - lamp.light) ** 2, axis=1)
        gain += on * LIGHT_GAIN * np.exp(-d2 / (2 * LIGHT_RADIUS**2))[:, None] * LIGHT_WARM
    return np.clip(colours * gain, 0.0, 1.0)


__all__ = ["StatefulObject", "lights_at", "posed", "relit", "stateful_objects"]
