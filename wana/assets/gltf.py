"""glTF 2.0 binary (GLB) export and import for skinned characters; GLB export of objects and scenes.

Characters are written by hand (trimesh does not write skins): one mesh with POSITION, NORMAL,
COLOR_0, JOINTS_0, WEIGHTS_0, one morph target per expression (names in mesh.extras.targetNames),
a node per canonical joint (rest translations, T-pose) and a skin with inverse bind matrices.
``load_character_glb`` reads such a file back into an identical ``Character``.
"""

from __future__ import annotations

import json
import struct
from pathlib import Path

import numpy as np
import trimesh

from proto.scene import Scene
from wana.assets.characters import EXPRESSIONS, Character
from wana.domain.skeleton import JOINT_NAMES, N_JOINTS, PARENTS

_GLB_MAGIC = 0x46546C67
_JSON, _BIN = 0x4E4F534A, 0x004E4942
_COMPONENT: dict[np.dtype, int] = {
    np.dtype(np.float32): 5126,
    np.dtype(np.uint32): 5125,
    np.dtype(np.uint16): 5123,
    np.dtype(np.uint8): 5121,
}
_NP = {v: k for k, v in _COMPONENT.items()}
_TYPE = {1: "SCALAR", 2: "VEC2", 3: "VEC3", 4: "VEC4", 16: "MAT4"}
_WIDTH = {v: k for k, v in _TYPE.items()}


class _Writer:
    def __init__(self) -> None:
        self.blob = bytearray()
        self.views: list[dict] = []
        self.accessors: list[dict] = []

    def add(
        self, array: np.ndarray, target: int | None = None, normalized: bool = False, minmax: bool = False
    ) -> int:
        a = np.ascontiguousarray(array)
        while len(self.blob) % 4:
            self.blob.append(0)
        view = {"buffer": 0, "byteOffset": len(self.blob), "byteLength": a.nbytes}
        if target:
            view["target"] = target
        self.blob.extend(a.tobytes())
        self.views.append(view)
        width = 1 if a.ndim == 1 else a.shape[1]
        acc = {
            "bufferView": len(self.views) - 1,
            "componentType": _COMPONENT[a.dtype],
            "count": int(a.shape[0]),
            "type": _TYPE[width],
        }
        if normalized:
            acc["normalized"] = True
        if minmax:
            acc["min"] = [float(x) for x in a.min(axis=0)]
            acc["max"] = [float(x) for x in a.max(axis=0)]
        self.accessors.append(acc)
        return len(self.accessors) - 1


def export_character_glb(character: Character, path: str | Path) -> Path:
    """Write a skinned, morphable character to a .glb file; returns the path."""
    w = _Writer()
    mesh = trimesh.Trimesh(character.vertices, character.faces, process=False)
    normals = np.asarray(mesh.vertex_normals, np.float32)
    attrs = {
        "POSITION": w.add(character.vertices, 34962, minmax=True),
        "NORMAL": w.add(normals, 34962),
        "COLOR_0": w.add(character.colours, 34962, normalized=True),
        "JOINTS_0": w.add(character.joints, 34962),
        "WEIGHTS_0": w.add(character.weights, 34962),
    }
    indices = w.add(character.faces.reshape(-1), 34963)
    names = [n for n in EXPRESSIONS if n in character.blendshapes]
    targets = [{"POSITION": w.add(character.blendshapes[n], 34962, minmax=True)} for n in names]
    rest = character.rest_joint_positions()
    ibm = np.zeros((N_JOINTS, 16), np.float32)
    for j in range(N_JOINTS):
        m = np.eye(4)
        m[:3, 3] = -rest[j]
        ibm[j] = m.T.reshape(-1)  # glTF matrices are column-major
    ibm_acc = w.add(ibm)
    nodes: list[dict] = []
    for j, name in enumerate(JOINT_NAMES):
        node: dict = {"name": name, "translation": [float(x) for x in character.offsets[j]]}
        kids = [int(k) for k in np.nonzero(PARENTS == j)[0]]
        if kids:
            node["children"] = kids
        nodes.append(node)
    nodes.append({"name": character.name, "mesh": 0, "skin": 0})
    gltf = {
        "asset": {"version": "2.0", "generator": "wana.assets.gltf"},
        "scene": 0,
        "scenes": [{"nodes": [0, N_JOINTS]}],
        "nodes": nodes,
        "meshes": [
            {
                "name": character.name,
                "primitives": [{"attributes": attrs, "indices": indices, "mode": 4, "targets": targets}],
                "weights": [0.0] * len(names),
                "extras": {"targetNames": names},
            }
        ],
        "skins": [{"joints": list(range(N_JOINTS)), "inverseBindMatrices": ibm_acc, "skeleton": 0}],
        "accessors": w.accessors,
        "bufferViews": w.views,
        "buffers": [{"byteLength": len(w.blob)}],
        "extras": {"wana": {"character": character.name, "height": character.height}},
    }
    return _write_glb(gltf, bytes(w.blob), path)


def _write_glb(gltf: dict, blob: bytes, path: str | Path) -> Path:
    js = json.dumps(gltf, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    blob += b"\0" * (-len(blob) % 4)
    total = 12 + 8 + len(js) + 8 + len(blob)
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    with out.open("wb") as f:
        f.write(struct.pack("<III", _GLB_MAGIC, 2, total))
        f.write(struct.pack("<II", len(js), _JSON) + js)
        f.write(struct.pack("<II", len(blob), _BIN) + blob)
    return out


def read_glb(path: str | Path) -> tuple[dict, bytes]:
    """(json, binary chunk) of a .glb file. Raises ValueError for a file that is not GLB 2.0."""
    data = Path(path).read_bytes()
    if len(data) < 20:
        raise ValueError(f"{path}: too short for a GLB file")
    magic, version, _ = struct.unpack_from("<III", data, 0)
    if magic != _GLB_MAGIC or version != 2:
        raise ValueError(f"{path}: not a glTF 2.0 binary file")
    off, gltf, blob = 12, None, b""
    while off < len(data):
        length, kind = struct.unpack_from("<II", data, off)
        chunk = data[off + 8 : off + 8 + length]
        if kind == _JSON:
            gltf = json.loads(chunk)
        elif kind == _BIN:
            blob = chunk
        off += 8 + length
    if gltf is None:
        raise ValueError(f"{path}: GLB without a JSON chunk")
    return gltf, blob


def _accessor(gltf: dict, blob: bytes, index: int) -> np.ndarray:
    acc = gltf["accessors"][index]
    view = gltf["bufferViews"][acc["bufferView"]]
    dtype = _NP[acc["componentType"]]
    width = _WIDTH[acc["type"]]
    start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    arr = np.frombuffer(blob, dtype=dtype, count=acc["count"] * width, offset=start)
    return arr.reshape(acc["count"], width).copy() if width > 1 else arr.copy()


def load_character_glb(path: str | Path) -> Character:
    """Read a character written by ``export_character_glb`` (joint nodes matched by name)."""
    gltf, blob = read_glb(path)
    prim = gltf["meshes"][0]["primitives"][0]
    a = prim["attributes"]
    names = gltf["meshes"][0].get("extras", {}).get("targetNames", [])
    shapes = {
        n: _accessor(gltf, blob, t["POSITION"]).astype(np.float32)
        for n, t in zip(names, prim.get("targets", []), strict=True)
    }
    skin = gltf["skins"][0]
    by_name = {gltf["nodes"][k]["name"]: k for k in skin["joints"]}
    missing = [n for n in JOINT_NAMES if n not in by_name]
    if missing:
        raise ValueError(f"{path}: skin lacks canonical joints {missing}")
    file_order = [gltf["nodes"][k]["name"] for k in skin["joints"]]
    remap = np.array([JOINT_NAMES.index(n) for n in file_order], np.uint16)
    offsets = np.array(
        [gltf["nodes"][by_name[n]].get("translation", [0, 0, 0]) for n in JOINT_NAMES], np.float32
    )
    meta = gltf.get("extras", {}).get("wana", {})
    return Character(
        name=meta.get("character", gltf["meshes"][0].get("name", Path(path).stem)),
        height=float(meta.get("height", 0.0)),
        offsets=offsets,
        vertices=_accessor(gltf, blob, a["POSITION"]).astype(np.float32),
        faces=_accessor(gltf, blob, prim["indices"]).reshape(-1, 3).astype(np.uint32),
        colours=_accessor(gltf, blob, a["COLOR_0"]).astype(np.uint8),
        joints=remap[_accessor(gltf, blob, a["JOINTS_0"]).astype(np.int64)],
        weights=_accessor(gltf, blob, a["WEIGHTS_0"]).astype(np.float32),
        blendshapes=shapes,
    )


def export_object_glb(obj, path: str | Path) -> Path:  # noqa: ANN001 - AssetObject (avoid import cycle)
    """Write one catalog object (object frame) to .glb."""
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_bytes(trimesh.Scene({obj.category: obj.mesh.copy()}).export(file_type="glb"))
    return out


def scene_trimesh(scene: Scene, with_room: bool = True) -> trimesh.Scene:
    """A trimesh.Scene of placed catalog objects (world frame), optionally with floor and walls."""
    from wana.assets.catalog import asset_for, object_to_world

    ts = trimesh.Scene()
    if with_room:
        r = scene.room
        floor = trimesh.creation.box((r.width, 0.02, r.depth))
        floor.apply_translation((0, -0.01, 0))
        floor.visual.face_colors = (200, 190, 175, 255)
        ts.add_geometry(floor, node_name="floor", geom_name="floor")
        for name, size, centre in (
            ("wall_N", (r.width, r.height, 0.02), (0, r.height / 2, -r.depth / 2 - 0.01)),
            ("wall_W", (0.02, r.height, r.depth), (-r.width / 2 - 0.01, r.height / 2, 0)),
        ):
            wall = trimesh.creation.box(size)
            wall.apply_translation(centre)
            wall.visual.face_colors = (235, 232, 225, 255)
            ts.add_geometry(wall, node_name=name, geom_name=name)
    for placed in scene.objects:
        ts.add_geometry(
            asset_for(placed).mesh.copy(),
            node_name=placed.id,
            geom_name=placed.id,
            transform=object_to_world(placed),
        )
    return ts


def export_scene_glb(scene: Scene, path: str | Path, with_room: bool = True) -> Path:
    """Write a composed scene (room + placed objects, world frame) to .glb."""
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_bytes(scene_trimesh(scene, with_room).export(file_type="glb"))
    return out
