"""Rigged humanoids the cast tests build themselves: the canonical skeleton renamed, re-proportioned,
optionally under a centimetre armature, in an A-pose, with extra twist and finger joints; one box per bone,
rigidly skinned."""

from __future__ import annotations

import json
import struct

import numpy as np
from scipy.spatial.transform import Rotation

from wana.domain.skeleton import JOINT_NAMES, PARENTS, REST_OFFSETS

MIXAMO = {n: f"mixamorig:{n}" for n in JOINT_NAMES}
UNREAL = {
    "Hips": "pelvis",
    "Spine": "spine_01",
    "Spine1": "spine_02",
    "Spine2": "spine_03",
    "Neck": "neck_01",
    "Head": "head",
    **{
        f"{side}{ours}": f"{ue}_{s}"
        for s, side in (("l", "Left"), ("r", "Right"))
        for ue, ours in (
            ("clavicle", "Shoulder"),
            ("upperarm", "Arm"),
            ("lowerarm", "ForeArm"),
            ("hand", "Hand"),
            ("middle_01", "HandMiddle1"),
            ("thigh", "UpLeg"),
            ("calf", "Leg"),
            ("foot", "Foot"),
            ("ball", "ToeBase"),
        )
    },
}
CUSTOM = {n: f"jnt_{i:02d}" for i, n in enumerate(JOINT_NAMES)}  # only a --cast-map can name these


def rig_joints(
    names: dict[str, str], legs: float = 1.0, torso: float = 1.0, arms: float = 1.0, extras: bool = False
) -> list[tuple[str, int, np.ndarray]]:
    """(name, parent index, rest offset) of a canonical-shaped rig with scaled limbs (and extra joints)."""
    out: list[tuple[str, int, np.ndarray]] = []
    for j, n in enumerate(JOINT_NAMES):
        o = REST_OFFSETS[j].copy()
        if "Leg" in n or "Foot" in n or "Toe" in n:
            o *= legs
        elif "Arm" in n or "Hand" in n:
            o *= arms
        elif j:
            o *= torso
        if n == "Hips":
            o[1] = (0.42 + 0.42 + 0.06) * legs + 0.05 * torso
        out.append((names[n], int(PARENTS[j]), o))
    if extras:
        for side, sgn in (("Left", 1.0), ("Right", -1.0)):
            arm = JOINT_NAMES.index(f"{side}Arm")
            out.append((f"{side}UpperArmTwist", arm, np.array([sgn * 0.14 * arms, 0.0, 0.0])))
            hand = JOINT_NAMES.index(f"{side}Hand")
            for f, z in (("Index", 0.03), ("Ring", -0.03)):
                out.append((f"{side}Hand{f}1", hand, np.array([sgn * 0.09 * arms, 0.0, z])))
                out.append((f"{side}Hand{f}2", len(out) - 1, np.array([sgn * 0.04 * arms, 0.0, 0.0])))
    return out


def _box(a: np.ndarray, b: np.ndarray, r: float) -> tuple[np.ndarray, np.ndarray]:
    lo, hi = np.minimum(a, b) - r, np.maximum(a, b) + r
    v = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])])
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
        ]
    )
    return v, f


def rig_glb(
    joints: list[tuple[str, int, np.ndarray]],
    *,
    centimetres: bool = False,
    a_pose: bool = False,
    vrm: dict[str, str] | None = None,
    facing_back: bool = False,
    texture: bytes | None = None,
    hair: bool = False,
) -> bytes:
    """GLB bytes of the rig: joints (under an "Armature" node at 0.01 scale with centimetre offsets when asked),
            the arms rotated 40 degrees down at rest for an A-pose, a VRM 0.x humanoid table when given
            (VRM bone -> joint name), facing -Z (as VRM 0.x models do) when asked, with a PNG base colour texture
        when given (UVs from the vertices' x and y), and with ``hair`` a second mesh over the head bound by a skin of
    its own (joints: the head only), as VRoid's VRMs bind hair and face."""
    if facing_back:
        joints = [(name, p, o * np.array([-1.0, 1.0, -1.0])) for name, p, o in joints]
    n = len(joints)
    unit = 100.0 if centimetres else 1.0
    local_r = [Rotation.identity() for _ in range(n)]
    if a_pose:
        for j in range(len(joints)):
            if j < len(JOINT_NAMES) and JOINT_NAMES[j] in ("LeftArm", "RightArm"):
                local_r[j] = Rotation.from_euler(
                    "z", -40 if JOINT_NAMES[j] == "LeftArm" else 40, degrees=True
                )
    world_m = np.zeros((n, 4, 4))
    for j, (_, p, o) in enumerate(joints):
        m = np.eye(4)
        m[:3, :3] = local_r[j].as_matrix()
        m[:3, 3] = o * unit
        world_m[j] = m if p < 0 else world_m[p] @ m
    pos = world_m[:, :3, 3]
    verts, faces, vj = [], [], []
    for j, (_, p, _) in enumerate(joints):
        if p < 0:
            continue
        v, f = _box(pos[p], pos[j], 0.03 * unit)
        faces.append(f + sum(len(x) for x in verts))
        verts.append(v)
        vj.append(np.full(len(v), p))
    vertices = np.concatenate(verts).astype(np.float32)
    indices = np.concatenate(faces).reshape(-1).astype(np.uint32)
    jidx = np.zeros((len(vertices), 4), dtype=np.uint16)
    jidx[:, 0] = np.concatenate(vj)
    weights = np.zeros((len(vertices), 4), dtype=np.float32)
    weights[:, 0] = 1.0
    ibm = np.linalg.inv(world_m).transpose(0, 2, 1).astype(np.float32)  # column-major
    blob = bytearray()
    views, accessors = [], []

    def add(a: np.ndarray, comp: int, kind: str, bounds: bool = False) -> int:
        while len(blob) % 4:
            blob.append(0)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": a.nbytes})
        blob.extend(np.ascontiguousarray(a).tobytes())
        acc = {"bufferView": len(views) - 1, "componentType": comp, "count": len(a), "type": kind}
        if bounds:
            acc["min"], acc["max"] = a.min(axis=0).tolist(), a.max(axis=0).tolist()
        accessors.append(acc)
        return len(accessors) - 1

    nodes: list[dict] = []
    first = 1 if centimetres else 0
    if centimetres:
        nodes.append({"name": "Armature", "scale": [0.01, 0.01, 0.01], "children": [first]})
    for j, (name, _, o) in enumerate(joints):
        node = {"name": name, "translation": (o * unit).tolist(), "rotation": local_r[j].as_quat().tolist()}
        kids = [first + k for k, (_, p, _) in enumerate(joints) if p == j]
        if kids:
            node["children"] = kids
        nodes.append(node)
    prim = {
        "attributes": {
            "POSITION": add(vertices, 5126, "VEC3", bounds=True),
            "JOINTS_0": add(jidx, 5123, "VEC4"),
            "WEIGHTS_0": add(weights, 5126, "VEC4"),
        },
        "indices": add(indices, 5125, "SCALAR"),
        "material": 0,
    }
    images: dict = {}
    if texture is not None:
        prim["attributes"]["TEXCOORD_0"] = add((vertices[:, :2] % 1.0).astype(np.float32), 5126, "VEC2")
        while len(blob) % 4:
            blob.append(0)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(texture)})
        blob.extend(texture)
        images = {
            "images": [{"bufferView": len(views) - 1, "mimeType": "image/png"}],
            "textures": [{"source": 0}],
        }
    nodes.append({"name": "body", "mesh": 0, "skin": 0})
    extra: dict = {"meshes": [], "skins": [], "nodes": []}
    if hair:
        head = JOINT_NAMES.index("Head")  # rig_joints keeps the canonical order first
        v, f = _box(
            pos[head] + np.array([0, 0.1, 0]) * unit, pos[head] + np.array([0, 0.25, 0]) * unit, 0.1 * unit
        )
        hair_prim = {
            "attributes": {
                "POSITION": add(v.astype(np.float32), 5126, "VEC3", bounds=True),
                "JOINTS_0": add(np.zeros((len(v), 4), dtype=np.uint16), 5123, "VEC4"),
                "WEIGHTS_0": add(np.tile(np.float32([1, 0, 0, 0]), (len(v), 1)), 5126, "VEC4"),
            },
            "indices": add(f.reshape(-1).astype(np.uint32), 5125, "SCALAR"),
            "material": 0,
        }
        extra["meshes"].append({"primitives": [hair_prim]})
        extra["skins"].append(
            {
                "joints": [first + head],
                "inverseBindMatrices": add(ibm[head : head + 1].reshape(1, 16), 5126, "MAT4"),
            }
        )
        extra["nodes"].append({"name": "hair", "mesh": 1, "skin": 1})
    doc: dict = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0, len(nodes) - 1] + ([len(nodes)] if hair else [])}],
        "nodes": nodes + extra["nodes"],
        "meshes": [{"primitives": [prim]}] + extra["meshes"],
        "materials": [
            {
                "pbrMetallicRoughness": {
                    "baseColorFactor": [0.2, 0.5, 0.8, 1.0],
                    **({"baseColorTexture": {"index": 0}} if texture is not None else {}),
                }
            }
        ],
        **images,
        "skins": [
            {
                "joints": [first + j for j in range(n)],
                "inverseBindMatrices": add(ibm.reshape(n, 16), 5126, "MAT4"),
            }
        ]
        + extra["skins"],
        "accessors": accessors,
        "bufferViews": views,
    }
    if vrm is not None:
        index = {name: first + j for j, (name, _, _) in enumerate(joints)}
        doc["extensionsUsed"] = ["VRM"]
        doc["extensions"] = {
            "VRM": {"humanoid": {"humanBones": [{"bone": b, "node": index[j]} for b, j in vrm.items()]}}
        }
    while len(blob) % 4:
        blob.append(0)
    doc["buffers"] = [{"byteLength": len(blob)}]
    js = json.dumps(doc).encode()
    js += b" " * (-len(js) % 4)
    return (
        struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(js) + 8 + len(blob))
        + struct.pack("<I4s", len(js), b"JSON")
        + js
        + struct.pack("<I4s", len(blob), b"BIN\x00")
        + bytes(blob)
    )
