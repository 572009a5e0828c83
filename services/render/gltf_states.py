"""Stateful objects in the GLB: a door leaf or laptop lid as a node turning on its hinge, a lit part whose
material glows, and a lamp's light (KHR_lights_punctual) whose intensity follows the lamp's "on" state.

Each object with a state track (Scene.states) is exported in up to three pieces: the still body (a plain
node in world coordinates, like every other object), the moving part under a node at the hinge whose
rotation is sampled per frame, and the glowing part with a material of its own whose emissiveFactor is
animated through KHR_animation_pointer (as the camera's field of view is: services.render.gltf_camera).
A lamp also gets a point light node with its intensity animated the same way.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from proto.scene import Scene
from services.render.gltf_camera import POINTER
from services.render.object_states import StatefulObject
from services.render.scene_geometry import ColouredMesh
from wana.domain import quat
from wana.domain.object_state import LIGHTS, STATEFUL, lit_colour, open_hinge, state_at

LIGHTS_EXT = "KHR_lights_punctual"
LAMP_CANDELA = 60.0  # a lamp's point light intensity when on (candela, glTF's unit for point lights)


def _part(mesh: ColouredMesh, keep: np.ndarray, offset: np.ndarray | None = None) -> ColouredMesh:
    """The faces of a face-flattened mesh whose vertices are kept (by triples), moved by -offset."""
    faces = keep.reshape(-1, 3).all(axis=1)
    verts = mesh.vertices.reshape(-1, 3, 3)[faces].reshape(-1, 3)
    if offset is not None:
        verts = verts - offset
    return ColouredMesh(
        name=mesh.name,
        vertices=verts,
        faces=np.arange(len(verts), dtype=np.int64).reshape(-1, 3),
        colours=mesh.colours.reshape(-1, 3, 4)[faces].reshape(-1, 4),
    )


def _used(b: Any, name: str) -> None:
    used = b.doc.setdefault("extensionsUsed", [])
    if name not in used:
        used.append(name)


def add_states(
    b: Any,
    scene: Scene,
    objects: dict[str, StatefulObject],
    material: int,
    animation: dict,
    n_frames: int,
    fps: float,
    add_mesh: Any,
) -> None:
    """Every stateful object of ``objects`` into the builder ``b`` (gltf_export._Builder), its state tracks
    sampled per frame into ``animation``. ``add_mesh(b, mesh, material)`` adds a mesh as a root node."""
    from services.render.gltf_export import FLOAT
    from wana.assets.catalog import object_to_world

    n = max(1, n_frames)
    frames = np.arange(n, dtype=np.float64)
    times = b.accessor((frames / fps).astype(np.float32), FLOAT, bounds=True)

    def channel(target: dict, values: np.ndarray) -> None:
        sampler = {
            "input": times,
            "output": b.accessor(values.astype(np.float32), FLOAT),
            "interpolation": "LINEAR",
        }
        animation["samplers"].append(sampler)
        animation["channels"].append({"sampler": len(animation["samplers"]) - 1, "target": target})

    for oid, obj in sorted(objects.items()):
        placed, category = obj.placed, obj.placed.category
        rest = STATEFUL[category]
        world = object_to_world(placed)
        world[:3, :3] = world[:3, :3] @ np.diag(1.0 / np.asarray(placed.scale, float))  # mesh is scaled
        still = ~obj.moving & ~obj.glowing if "on" in rest else ~obj.moving
        body = _part(obj.mesh, still)
        add_mesh(
            b,
            ColouredMesh(oid, body.vertices @ world[:3, :3].T + world[:3, 3], body.faces, body.colours),
            material,
        )
        yaw_q = quat.yaw(np.array(float(placed.yaw)))
        values = [state_at(scene.states, oid, "open", rest.get("open", 0.0), f) for f in frames]
        for k, bounds in sorted(obj.parts.items()) if "open" in rest else []:
            hinge, axis, _ = open_hinge(category, bounds, 0.0, k)
            part = _part(obj.mesh, obj.leaf == k, hinge)
            label = f"{oid}:part" if len(obj.parts) == 1 else f"{oid}:part{k}"
            add_mesh(b, ColouredMesh(label, part.vertices, part.faces, part.colours), material)
            node = len(b.doc["nodes"]) - 1
            b.doc["scenes"][0]["nodes"].remove(node)
            pivot = b.node({"name": label.replace(":part", ":hinge"), "children": [node]}, root=True)
            angles = np.array([open_hinge(category, bounds, v, k)[2] for v in values])
            rot = quat.mul(
                np.broadcast_to(yaw_q, (n, 4)), quat.from_axis_angle(np.broadcast_to(axis, (n, 3)), angles)
            )
            b.doc["nodes"][pivot]["translation"] = [float(x) for x in world[:3, :3] @ hinge + world[:3, 3]]
            channel({"node": pivot, "path": "rotation"}, quat.normalize(rot))
        if "on" not in rest:
            continue
        on = np.array([state_at(scene.states, oid, "on", rest["on"], f) for f in frames])
        if obj.glowing.any():
            glow = _part(obj.mesh, obj.glowing & ~obj.moving)
            b.doc["materials"].append(
                {
                    "name": f"glow:{oid}",
                    "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0},
                    "emissiveFactor": [0.0, 0.0, 0.0],
                }
            )
            mat = len(b.doc["materials"]) - 1
            add_mesh(
                b,
                ColouredMesh(
                    f"{oid}:glow", glow.vertices @ world[:3, :3].T + world[:3, 3], glow.faces, glow.colours
                ),
                mat,
            )
            lit = np.asarray(lit_colour(category), float) / 255.0
            target = {
                "path": "pointer",
                "extensions": {POINTER: {"pointer": f"/materials/{mat}/emissiveFactor"}},
            }
            channel(target, on[:, None] * lit[None, :])
            _used(b, POINTER)
        if category in LIGHTS:
            ext = b.doc.setdefault("extensions", {}).setdefault(LIGHTS_EXT, {"lights": []})
            ext["lights"].append(
                {"name": f"{oid}:light", "type": "point", "color": [1.0, 0.93, 0.78], "intensity": 0.0}
            )
            light = len(ext["lights"]) - 1
            b.node(
                {
                    "name": f"{oid}:light",
                    "translation": [float(x) for x in obj.light],
                    "extensions": {LIGHTS_EXT: {"light": light}},
                },
                root=True,
            )
            pointer = {POINTER: {"pointer": f"/extensions/{LIGHTS_EXT}/lights/{light}/intensity"}}
            channel({"path": "pointer", "extensions": pointer}, on * LAMP_CANDELA)
            _used(b, LIGHTS_EXT)
            _used(b, POINTER)


__all__ = ["LAMP_CANDELA", "add_states"]
