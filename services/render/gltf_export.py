"""Animated GLB: the room and its objects, skinned characters, skeletal animation and face morph weights.

Layout (glTF 2.0, metres, Y up): one node per static mesh (floor, walls, objects; flat per-face
colours in COLOR_0); per character a joint hierarchy rooted at "<name>:Hips" and a skinned mesh
node "<name>" (both scene roots, as the validator recommends) with morph targets named in
``mesh.extras.targetNames`` (three.js reads them into ``morphTargetDictionary``); one animation
"wana" with a rotation channel per joint, the Hips translation and the morph weights, sampled at
30 fps with LINEAR interpolation.

Everything the Khronos validator checks is made to hold by construction: unit normals, weights
that sum to one with no duplicate or zero-weight joint indices, unit quaternions, accessor bounds,
4-byte aligned buffer views with targets only on vertex and index data.
"""

from __future__ import annotations

import json
import struct
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from proto.motion_data import Motion
from proto.scene import Scene
from services.render.cast_gltf import CastCharacter, add_cast_character
from services.render.gltf_camera import add_camera
from services.render.gltf_states import add_states
from services.render.object_states import stateful_objects
from services.render.scene_geometry import (
    ColouredMesh,
    held_ids,
    object_meshes,
    prop_mesh,
    prop_track,
    room_meshes,
)
from services.render.skinning import Rig
from services.render.staging import CameraTrack
from wana.arrays import from_wire
from wana.assets.characters import EXPRESSIONS
from wana.domain.skeleton import JOINT_NAMES, N_JOINTS, PARENTS

ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
FLOAT, UNSIGNED_BYTE, UNSIGNED_SHORT, UNSIGNED_INT = 5126, 5121, 5123, 5125
_TYPES = {1: "SCALAR", 2: "VEC2", 3: "VEC3", 4: "VEC4", 16: "MAT4"}


class _Builder:
    """Accumulates the JSON document and the binary chunk."""

    def __init__(self) -> None:
        self.blob = bytearray()
        self.doc: dict = {
            "asset": {"version": "2.0", "generator": "wana render service"},
            "buffers": [],
            "bufferViews": [],
            "accessors": [],
            "meshes": [],
            "materials": [],
            "nodes": [],
            "scenes": [{"name": "wana", "nodes": []}],
            "scene": 0,
        }

    def view(self, data: bytes, target: int | None = None) -> int:
        while len(self.blob) % 4:
            self.blob.append(0)
        v: dict = {"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(data)}
        if target is not None:
            v["target"] = target
        self.blob.extend(data)
        self.doc["bufferViews"].append(v)
        return len(self.doc["bufferViews"]) - 1

    def accessor(
        self,
        array: np.ndarray,
        component: int,
        *,
        target: int | None = None,
        normalized: bool = False,
        bounds: bool = False,
    ) -> int:
        a = np.ascontiguousarray(array)
        width = 1 if a.ndim == 1 else int(np.prod(a.shape[1:]))
        acc: dict = {
            "bufferView": self.view(a.tobytes(), target),
            "componentType": component,
            "count": int(a.shape[0]),
            "type": _TYPES[width],
        }
        if normalized:
            acc["normalized"] = True
        if bounds:
            flat = a.reshape(a.shape[0], width)
            acc["min"] = [float(x) for x in flat.min(axis=0)]
            acc["max"] = [float(x) for x in flat.max(axis=0)]
            if component != FLOAT:
                acc["min"] = [int(x) for x in acc["min"]]
                acc["max"] = [int(x) for x in acc["max"]]
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def node(self, node: dict, root: bool = False) -> int:
        self.doc["nodes"].append(node)
        i = len(self.doc["nodes"]) - 1
        if root:
            self.doc["scenes"][0]["nodes"].append(i)
        return i

    def material(self, name: str) -> int:
        self.doc["materials"].append(
            {
                "name": name,
                "pbrMetallicRoughness": {
                    "baseColorFactor": [1.0, 1.0, 1.0, 1.0],
                    "metallicFactor": 0.0,
                    "roughnessFactor": 0.85,
                },
            }
        )
        return len(self.doc["materials"]) - 1

    def glb(self) -> bytes:
        while len(self.blob) % 4:
            self.blob.append(0)
        self.doc["buffers"] = [{"byteLength": len(self.blob)}]
        doc = {k: v for k, v in self.doc.items() if v != []}
        js = json.dumps(doc, separators=(",", ":")).encode("utf-8")
        js += b" " * (-len(js) % 4)
        total = 12 + 8 + len(js) + 8 + len(self.blob)
        return (
            struct.pack("<III", 0x46546C67, 2, total)
            + struct.pack("<I4s", len(js), b"JSON")
            + js
            + struct.pack("<I4s", len(self.blob), b"BIN\x00")
            + bytes(self.blob)
        )


def unit_normals(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """(V, 3) float32 unit vertex normals (area-weighted); vertices on no or degenerate faces get +Y."""
    v = np.asarray(vertices, dtype=np.float64)
    f = np.asarray(faces, dtype=np.int64)
    fn = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    n = np.zeros_like(v)
    for k in range(3):
        np.add.at(n, f[:, k], fn)
    length = np.linalg.norm(n, axis=1, keepdims=True)
    n = np.where(length > 1e-12, n / np.maximum(length, 1e-12), np.array([0.0, 1.0, 0.0]))
    n = n.astype(np.float32)
    return n / np.linalg.norm(n, axis=1, keepdims=True)


def clean_skin(joints: np.ndarray, weights: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Merge duplicate joint indices, zero the index of zero weights, renormalise in float32.

    Returns:
        joints (V, 4) uint8 and weights (V, 4) float32 summing to 1.
    """
    j = np.asarray(joints, dtype=np.int64).copy()
    w = np.clip(np.asarray(weights, dtype=np.float64), 0.0, None).copy()
    for a in range(4):
        for b in range(a + 1, 4):
            dup = (j[:, a] == j[:, b]) & (w[:, b] > 0)
            w[dup, a] += w[dup, b]
            w[dup, b] = 0.0
    w[w < 1e-4] = 0.0
    total = w.sum(axis=1, keepdims=True)
    w = np.where(total > 0, w / np.maximum(total, 1e-12), np.array([1.0, 0.0, 0.0, 0.0]))
    j[w == 0] = 0
    dead = (w == 0).all(axis=1)
    j[dead, 0] = 0
    w32 = w.astype(np.float32)
    top = np.argmax(w32, axis=1)
    rows = np.arange(len(w32))
    w32[rows, top] = np.float32(1.0) - (w32.sum(axis=1) - w32[rows, top])
    # after that a duplicate index can only be among zero weights, which all point at joint 0
    return j.astype(np.uint8 if N_JOINTS < 256 else np.uint16), w32


def _add_static(b: _Builder, mesh: ColouredMesh, material: int) -> None:
    if len(mesh.faces) == 0:
        return
    pos = mesh.vertices.astype(np.float32)
    attrs = {
        "POSITION": b.accessor(pos, FLOAT, target=ARRAY_BUFFER, bounds=True),
        "NORMAL": b.accessor(unit_normals(pos, mesh.faces), FLOAT, target=ARRAY_BUFFER),
        "COLOR_0": b.accessor(
            mesh.colours.astype(np.uint8), UNSIGNED_BYTE, target=ARRAY_BUFFER, normalized=True
        ),
    }
    idx_type = UNSIGNED_SHORT if len(pos) < 65535 else UNSIGNED_INT
    idx = mesh.faces.reshape(-1).astype(np.uint16 if idx_type == UNSIGNED_SHORT else np.uint32)
    prim = {
        "attributes": attrs,
        "indices": b.accessor(idx, idx_type, target=ELEMENT_ARRAY_BUFFER),
        "material": material,
    }
    b.doc["meshes"].append({"name": mesh.name, "primitives": [prim]})
    b.node({"name": mesh.name, "mesh": len(b.doc["meshes"]) - 1}, root=True)


def _unit_quats(q: np.ndarray) -> np.ndarray:
    q = np.asarray(q, dtype=np.float64)
    n = np.linalg.norm(q, axis=-1, keepdims=True)
    q = np.where(n > 1e-9, q / np.maximum(n, 1e-9), np.array([0.0, 0.0, 0.0, 1.0]))
    return q.astype(np.float32)


def _add_character(
    b: _Builder, rig: Rig, material: int, animation: dict, fps: float, armature_node: bool = False
) -> None:
    ch = rig.character
    name = rig.name or ch.name
    offsets = ch.offsets.astype(np.float64)
    rest = ch.rest_joint_positions()
    rig_node = b.node({"name": name}, root=True) if armature_node else -1
    first = len(b.doc["nodes"])
    joint_nodes = []
    for j in range(N_JOINTS):
        node = {"name": f"{name}:{JOINT_NAMES[j]}", "translation": [float(x) for x in offsets[j]]}
        kids = [first + k for k in range(N_JOINTS) if PARENTS[k] == j]
        if kids:
            node["children"] = kids
        joint_nodes.append(b.node(node, root=PARENTS[j] < 0 and not armature_node))
    if armature_node:
        b.doc["nodes"][rig_node]["children"] = [joint_nodes[0]]
    ibm = np.zeros((N_JOINTS, 4, 4), dtype=np.float32)
    ibm[:] = np.eye(4, dtype=np.float32)
    ibm[:, :3, 3] = -rest  # rest pose has identity rotations: the inverse bind is a translation
    ibm_acc = b.accessor(
        np.ascontiguousarray(ibm.transpose(0, 2, 1)).reshape(N_JOINTS, 16), FLOAT
    )  # column-major
    b.doc.setdefault("skins", []).append(
        {"name": name, "joints": joint_nodes, "inverseBindMatrices": ibm_acc, "skeleton": joint_nodes[0]}
    )
    pos = ch.vertices.astype(np.float32)
    joints, weights = clean_skin(ch.joints, ch.weights)
    attrs = {
        "POSITION": b.accessor(pos, FLOAT, target=ARRAY_BUFFER, bounds=True),
        "NORMAL": b.accessor(unit_normals(pos, ch.faces), FLOAT, target=ARRAY_BUFFER),
        "COLOR_0": b.accessor(
            ch.colours.astype(np.uint8), UNSIGNED_BYTE, target=ARRAY_BUFFER, normalized=True
        ),
        "JOINTS_0": b.accessor(
            joints, UNSIGNED_BYTE if joints.dtype == np.uint8 else UNSIGNED_SHORT, target=ARRAY_BUFFER
        ),
        "WEIGHTS_0": b.accessor(weights, FLOAT, target=ARRAY_BUFFER),
    }
    targets = [
        {
            "POSITION": b.accessor(
                ch.blendshapes.get(k, np.zeros_like(pos)).astype(np.float32),
                FLOAT,
                target=ARRAY_BUFFER,
                bounds=True,
            )
        }
        for k in EXPRESSIONS
    ]
    idx_type = UNSIGNED_SHORT if len(pos) < 65535 else UNSIGNED_INT
    idx = ch.faces.reshape(-1).astype(np.uint16 if idx_type == UNSIGNED_SHORT else np.uint32)
    prim = {
        "attributes": attrs,
        "indices": b.accessor(idx, idx_type, target=ELEMENT_ARRAY_BUFFER),
        "material": material,
        "targets": targets,
    }
    b.doc["meshes"].append(
        {
            "name": name,
            "primitives": [prim],
            "weights": [0.0] * len(EXPRESSIONS),
            "extras": {"targetNames": list(EXPRESSIONS)},
        }
    )
    mesh_node = b.node(
        {
            "name": f"{name}_body" if armature_node else name,
            "mesh": len(b.doc["meshes"]) - 1,
            "skin": len(b.doc["skins"]) - 1,
        },
        root=True,
    )

    t = rig.n_frames
    times = b.accessor((np.arange(t, dtype=np.float64) / fps).astype(np.float32), FLOAT, bounds=True)
    samplers, channels = animation["samplers"], animation["channels"]

    def channel(node: int, path: str, values: np.ndarray, interpolation: str = "LINEAR") -> None:
        samplers.append({"input": times, "output": b.accessor(values, FLOAT), "interpolation": interpolation})
        channels.append({"sampler": len(samplers) - 1, "target": {"node": node, "path": path}})

    channel(joint_nodes[0], "translation", rig.root.astype(np.float32))
    if rig.present is not None and len(rig.present) == t and not rig.present.all():
        # Off stage: the Hips (and so the whole skinned body) at scale 0, switched on and off, not faded.
        scale = np.repeat(rig.present.astype(np.float32)[:, None], 3, axis=1)
        channel(joint_nodes[0], "scale", scale, "STEP")
    quats = _unit_quats(rig.rotations)
    for j in range(N_JOINTS):
        channel(joint_nodes[j], "rotation", quats[:, j])
    expr = np.zeros((t, len(EXPRESSIONS)), dtype=np.float32)
    if rig.expression is not None:
        e = rig.expression[:, : len(EXPRESSIONS)]
        expr[:, : e.shape[1]] = e
    channel(mesh_node, "weights", np.clip(expr, 0.0, 1.0).reshape(-1))


def _add_props(
    b: _Builder,
    scene: Scene,
    motions: list[Motion],
    held: set[str],
    material: int,
    animation: dict,
    fps: float,
) -> None:
    """Each held prop as a node of its own, its translation and rotation animated (in the hand while held)."""
    n = max((int(from_wire(m.root_position).shape[0]) for m in motions), default=0)
    if not held or n == 0:
        return
    times = b.accessor((np.arange(n, dtype=np.float64) / fps).astype(np.float32), FLOAT, bounds=True)
    for placed in scene.objects:
        if placed.id not in held:
            continue
        _add_static(b, prop_mesh(placed), material)  # the mesh in its own frame, at the node
        node = len(b.doc["nodes"]) - 1
        pos, rot = prop_track(placed, motions, n)
        for path, values in (("translation", pos.astype(np.float32)), ("rotation", _unit_quats(rot))):
            animation["samplers"].append(
                {"input": times, "output": b.accessor(values, FLOAT), "interpolation": "LINEAR"}
            )
            animation["channels"].append(
                {"sampler": len(animation["samplers"]) - 1, "target": {"node": node, "path": path}}
            )


def scene_glb(
    scene: Scene,
    motions: list[Motion],
    fps: float = 30.0,
    camera: CameraTrack | None = None,
    armature_nodes: bool = False,
    cast: Mapping[str, CastCharacter] | None = None,
) -> bytes:
    """The GLB bytes of the scene with its animated characters and held props (and the video's camera when
    given: services.render.gltf_camera).

    ``armature_nodes`` puts each character's Hips under a plain node named after the character (its mesh
    node then is "<name>_body"): Blender's glTF importer makes an armature of the parent of a skeleton's
    root, so with the Hips at the scene root every character would land in one shared armature. The FBX
    export asks for it; the GLB we ship keeps the validator's layout.

    ``cast`` (story name -> the user's character, services.render.cast_gltf) swaps those characters' built-in
    bodies for the user's mesh on its own joints, always under a node of the character's name."""
    b = _Builder()
    static_mat = b.material("scene")
    held = held_ids(motions)
    stateful = {k: v for k, v in stateful_objects(scene).items() if k not in held}
    for mesh in room_meshes(scene.room) + object_meshes(scene, held | set(stateful)):
        _add_static(b, mesh, static_mat)
    animation: dict = {"name": "wana", "samplers": [], "channels": []}
    _add_props(b, scene, motions, held, static_mat, animation, fps)
    if stateful:  # doors and lids on their hinges, lamps and screens lit (services.render.gltf_states)
        n = max((int(from_wire(m.root_position).shape[0]) for m in motions), default=0)
        n = max([n, *(max(t.frames) + 1 for t in scene.states if t.frames)])
        add_states(b, scene, stateful, static_mat, animation, n, fps, _add_static)
    if motions:
        skin_mat = b.material("characters")
        for m in motions:
            if cast and m.character in cast:
                add_cast_character(b, m.character, cast[m.character], m, animation, fps)
                continue
            rig = Rig.from_motion(m)
            _add_character(b, rig, skin_mat, animation, fps, armature_nodes)
    if camera is not None:
        add_camera(b, camera, animation, fps)
    if animation["channels"]:
        b.doc["animations"] = [animation]
    return b.glb()


def write_glb(
    path: str | Path,
    scene: Scene,
    motions: list[Motion],
    fps: float = 30.0,
    camera: CameraTrack | None = None,
    cast: Mapping[str, CastCharacter] | None = None,
) -> Path:
    """Write ``scene_glb`` to a file."""
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_bytes(scene_glb(scene, motions, fps, camera, cast=cast))
    return out
