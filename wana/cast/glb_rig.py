"""Read a rigged humanoid from GLB bytes: its skins' joints (names, hierarchy, rest transforms), the meshes
they bind, and the VRM humanoid bone table when the file is a VRM.

A small reader of our own (json + numpy, no network, no extra package): it reads what a skinned character
needs and nothing else. A file may bind its body, hair and face with skins of their own over one skeleton
(VRoid's VRMs do): the joints are the union of every skin's, each mesh keeps its skin.
"""

from __future__ import annotations

import json
import struct
from dataclasses import dataclass, field

import numpy as np
from scipy.spatial.transform import Rotation

_COMPONENTS = {
    5120: np.int8,
    5121: np.uint8,
    5122: np.int16,
    5123: np.uint16,
    5125: np.uint32,
    5126: np.float32,
}
_WIDTH = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}


class CastError(ValueError):
    """A character file that cannot be used, with a message for the user."""


@dataclass
class Primitive:
    """One skinned triangle list, in bind space (glTF skinning ignores the mesh node's transform)."""

    positions: np.ndarray  # (V, 3) float32
    indices: np.ndarray  # (F*3,) uint32
    joints: np.ndarray  # (V, 4) joint indices into its skin's joint list
    weights: np.ndarray  # (V, 4) float32
    colour: tuple[float, float, float, float] = (0.8, 0.8, 0.8, 1.0)  # the material's base colour
    uv: np.ndarray | None = None  # (V, 2) float32 TEXCOORD_0, with a texture
    texture: tuple[bytes, str] | None = None  # the base colour image (bytes, mime type)
    skin: int = 0  # index into CastRig.skins


@dataclass
class Skin:
    """One skin of the file: its joints (indices into CastRig's joints) and their inverse bind matrices."""

    joints: np.ndarray  # (n,) int
    inverse_bind: np.ndarray  # (n, 4, 4)


@dataclass
class CastRig:
    """A user's character. Joint arrays are in the order of the largest skin's joints, then the others'.

    Attributes:
        names: joint names as in the file.
        parents: index of the nearest ancestor joint, -1 for the skeleton's root(s).
        translation, rotation, scale: rest local transform of each joint (rotation x, y, z, w).
        base: 4x4 world matrix of the root joint's parent node (a Mixamo "Armature" at 0.01 scale, or identity).
        skins: the file's skins (the largest first).
        primitives: the skinned meshes.
        humanoid: VRM humanoid bone name -> joint index (empty for a plain GLB).
    """

    names: list[str]
    parents: np.ndarray
    translation: np.ndarray
    rotation: np.ndarray
    scale: np.ndarray
    base: np.ndarray
    skins: list[Skin]
    primitives: list[Primitive] = field(default_factory=list)
    humanoid: dict[str, int] = field(default_factory=dict)

    @property
    def n_joints(self) -> int:
        return len(self.names)

    def local_matrices(self) -> np.ndarray:
        """(J, 4, 4) rest local matrices."""
        m = np.zeros((self.n_joints, 4, 4))
        m[:, :3, :3] = Rotation.from_quat(self.rotation).as_matrix() * self.scale[:, None, :]
        m[:, :3, 3] = self.translation
        m[:, 3, 3] = 1.0
        return m

    def rest_world(self) -> np.ndarray:
        """(J, 4, 4) rest world matrices (metres, as the file's scene places them)."""
        local = self.local_matrices()
        world = np.zeros_like(local)
        for j in topological(self.parents):
            p = self.parents[j]
            world[j] = (self.base if p < 0 else world[p]) @ local[j]
        return world

    def floor(self) -> float:
        """The lowest vertex at rest, in world metres (the soles)."""
        world = self.rest_world()
        lows = []
        for prim in self.primitives:
            own = self.skins[prim.skin]
            skin = np.einsum(
                "jab,jbc->jac", world[own.joints], own.inverse_bind
            )  # rest skinning: bind -> world
            w = prim.weights.astype(np.float64)
            mats = np.einsum("vk,vkab->vab", w, skin[prim.joints.astype(np.int64)])
            p = np.einsum("vab,vb->va", mats[:, :3, :3], prim.positions.astype(np.float64)) + mats[:, :3, 3]
            lows.append(float(p[:, 1].min()))
        return min(lows) if lows else float(world[:, 1, 3].min())


def topological(parents: np.ndarray) -> list[int]:
    """Joint indices with every parent before its children."""
    order: list[int] = []
    seen: set[int] = set()

    def visit(j: int) -> None:
        if j in seen:
            return
        if parents[j] >= 0:
            visit(int(parents[j]))
        seen.add(j)
        order.append(j)

    for j in range(len(parents)):
        visit(j)
    return order


def _chunks(data: bytes) -> tuple[dict, bytes]:
    if len(data) < 20 or data[:4] != b"glTF":
        raise CastError("not a GLB file (a binary glTF or VRM; an FBX needs Blender: see --cast)")
    _, _, total = struct.unpack_from("<III", data, 0)
    off, doc, blob = 12, None, b""
    while off + 8 <= min(total, len(data)):
        length, kind = struct.unpack_from("<I4s", data, off)
        body = data[off + 8 : off + 8 + length]
        if kind == b"JSON":
            doc = json.loads(body.decode("utf-8"))
        elif kind == b"BIN\x00":
            blob = body
        off += 8 + length
    if doc is None:
        raise CastError("the GLB has no JSON chunk")
    return doc, blob


def _accessor(doc: dict, blob: bytes, index: int) -> np.ndarray:
    acc = doc["accessors"][index]
    width = _WIDTH[acc["type"]]
    dtype = np.dtype(_COMPONENTS[acc["componentType"]])
    count = int(acc["count"])
    if "bufferView" not in acc:
        return np.zeros((count, width), dtype=dtype)
    view = doc["bufferViews"][acc["bufferView"]]
    if view.get("buffer", 0) != 0:
        raise CastError("the GLB refers to an external buffer; embed it (export as .glb)")
    start = int(view.get("byteOffset", 0)) + int(acc.get("byteOffset", 0))
    stride = int(view.get("byteStride", 0)) or width * dtype.itemsize
    raw = np.frombuffer(
        blob, dtype=np.uint8, count=stride * (count - 1) + width * dtype.itemsize, offset=start
    )
    rows = np.lib.stride_tricks.as_strided(raw, shape=(count, width * dtype.itemsize), strides=(stride, 1))
    out = np.ascontiguousarray(rows).view(dtype).reshape(count, width)
    if acc.get("normalized") and dtype.kind in "ui":
        out = out.astype(np.float32) / float(np.iinfo(str(dtype)).max)
    return out


def _image(doc: dict, blob: bytes, texture: int | None) -> tuple[bytes, str] | None:
    """The embedded image of a texture (bytes, mime type), or None (no texture, or an external file)."""
    if texture is None or texture >= len(doc.get("textures", [])):
        return None
    source = doc["textures"][texture].get("source")
    if source is None or source >= len(doc.get("images", [])):
        return None
    image = doc["images"][source]
    if "bufferView" not in image:
        return None
    view = doc["bufferViews"][image["bufferView"]]
    start = int(view.get("byteOffset", 0))
    return bytes(blob[start : start + int(view["byteLength"])]), str(image.get("mimeType", "image/png"))


def _node_matrix(node: dict) -> np.ndarray:
    if "matrix" in node:
        return np.array(node["matrix"], dtype=np.float64).reshape(4, 4).T  # column-major
    m = np.eye(4)
    r = Rotation.from_quat(node.get("rotation", [0, 0, 0, 1])).as_matrix()
    m[:3, :3] = r * np.array(node.get("scale", [1, 1, 1]), dtype=np.float64)[None, :]
    m[:3, 3] = node.get("translation", [0, 0, 0])
    return m


def _trs(node: dict) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    if "matrix" not in node:
        return (
            np.array(node.get("translation", [0, 0, 0]), dtype=np.float64),
            np.array(node.get("rotation", [0, 0, 0, 1]), dtype=np.float64),
            np.array(node.get("scale", [1, 1, 1]), dtype=np.float64),
        )
    m = _node_matrix(node)
    s = np.linalg.norm(m[:3, :3], axis=0)
    return m[:3, 3].copy(), Rotation.from_matrix(m[:3, :3] / s[None, :]).as_quat(), s


def _humanoid(doc: dict, node_to_joint: dict[int, int]) -> dict[str, int]:
    ext = doc.get("extensions", {})
    out: dict[str, int] = {}
    if "VRMC_vrm" in ext:  # VRM 1.0
        for bone, entry in ext["VRMC_vrm"].get("humanoid", {}).get("humanBones", {}).items():
            if entry.get("node") in node_to_joint:
                out[bone] = node_to_joint[entry["node"]]
    elif "VRM" in ext:  # VRM 0.x
        for entry in ext["VRM"].get("humanoid", {}).get("humanBones", []):
            if entry.get("node") in node_to_joint and entry.get("bone"):
                out[entry["bone"]] = node_to_joint[entry["node"]]
    return out


def read_rig(data: bytes, label: str = "the character") -> CastRig:
    """The skinned humanoid in GLB (or VRM) bytes.

    Raises:
        CastError: not a GLB, or no skinned mesh in it.
    """
    doc, blob = _chunks(data)
    skins = doc.get("skins", [])
    if not skins:
        raise CastError(f"{label} has no skin (a rigged, skinned mesh is needed)")
    order = sorted(range(len(skins)), key=lambda i: -len(skins[i]["joints"]))
    nodes = doc.get("nodes", [])
    joint_nodes: list[int] = []
    for i in order:
        joint_nodes += [int(n) for n in skins[i]["joints"] if int(n) not in joint_nodes]
    node_to_joint = {n: j for j, n in enumerate(joint_nodes)}
    parent_of: dict[int, int] = {}
    for i, node in enumerate(nodes):
        for c in node.get("children", []):
            parent_of[int(c)] = i
    parents = np.full(len(joint_nodes), -1, dtype=np.int64)
    for j, n in enumerate(joint_nodes):
        p = parent_of.get(n)
        while p is not None and p not in node_to_joint:
            p = parent_of.get(p)
        if p is not None:
            parents[j] = node_to_joint[p]
    root = joint_nodes[int(np.flatnonzero(parents < 0)[0])]  # roots share one parent in any rig we know
    base = np.eye(4)
    p = parent_of.get(root)
    while p is not None:  # the fixed transform above the skeleton (an armature node)
        base = _node_matrix(nodes[p]) @ base
        p = parent_of.get(p)
    trs = [_trs(nodes[n]) for n in joint_nodes]
    skin_of = {}
    own_skins = []
    for k, i in enumerate(order):
        joints = [int(n) for n in skins[i]["joints"]]
        if "inverseBindMatrices" in skins[i]:
            ibm = _accessor(doc, blob, skins[i]["inverseBindMatrices"]).astype(np.float64).reshape(-1, 4, 4)
            ibm = ibm.transpose(0, 2, 1)  # column-major
        else:
            ibm = np.repeat(np.eye(4)[None], len(joints), axis=0)
        own_skins.append(Skin(np.array([node_to_joint[n] for n in joints], dtype=np.int64), ibm))
        skin_of[i] = k
    rig = CastRig(
        names=[nodes[n].get("name", f"joint{j}") for j, n in enumerate(joint_nodes)],
        parents=parents,
        translation=np.array([t for t, _, _ in trs]),
        rotation=np.array([r for _, r, _ in trs]),
        scale=np.array([s for _, _, s in trs]),
        base=base,
        skins=own_skins,
        humanoid=_humanoid(doc, node_to_joint),
    )
    if len(set(rig.names)) != len(rig.names):
        raise CastError(f"{label} has joints of the same name; every joint needs its own name")
    materials = doc.get("materials", [])
    for node in nodes:
        if node.get("skin") not in skin_of or "mesh" not in node:
            continue
        for prim in doc["meshes"][node["mesh"]]["primitives"]:
            attrs = prim.get("attributes", {})
            if prim.get("mode", 4) != 4 or not {"POSITION", "JOINTS_0", "WEIGHTS_0"} <= set(attrs):
                continue
            pos = _accessor(doc, blob, attrs["POSITION"]).astype(np.float32)
            idx = (
                _accessor(doc, blob, prim["indices"]).reshape(-1).astype(np.uint32)
                if "indices" in prim
                else np.arange(len(pos), dtype=np.uint32)
            )
            colour = (0.8, 0.8, 0.8, 1.0)
            texture = None
            if "material" in prim and prim["material"] < len(materials):
                pbr = materials[prim["material"]].get("pbrMetallicRoughness", {})
                f = pbr.get("baseColorFactor")
                if f:
                    colour = (float(f[0]), float(f[1]), float(f[2]), float(f[3]))
                texture = _image(doc, blob, pbr.get("baseColorTexture", {}).get("index"))
            uv = None
            if texture is not None and "TEXCOORD_0" in attrs:
                uv = _accessor(doc, blob, attrs["TEXCOORD_0"]).astype(np.float32)
            else:
                texture = None
            rig.primitives.append(
                Primitive(
                    positions=pos,
                    indices=idx,
                    joints=_accessor(doc, blob, attrs["JOINTS_0"]).astype(np.uint16),
                    weights=_accessor(doc, blob, attrs["WEIGHTS_0"]).astype(np.float32),
                    colour=colour,
                    uv=uv,
                    texture=texture,
                    skin=skin_of[node["skin"]],
                )
            )
    if not rig.primitives:
        raise CastError(f"{label} has a skeleton but no mesh skinned to it")
    return rig
