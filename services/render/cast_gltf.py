"""A user's own character in the GLB: its mesh and skin as the file had them, the story's motion on its own
joint names (wana.cast retargets it), under a node named after the story character.

The joints keep the rig's rest translations and scales and the file's inverse bind matrices, so the mesh
binds exactly as it did in the user's tool; only rotations (and the Hips' translation) are animated.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from proto.motion_data import Motion
from proto.render import CastMember
from services.render.skinning import character_for, motion_arrays
from wana.arrays import from_wire
from wana.cast import CastPose, CastRig, map_joints, read_rig, retarget
from wana.cast.glb_rig import Primitive
from wana.domain.skeleton import JOINT_INDEX

if TYPE_CHECKING:
    from services.render.gltf_export import _Builder


@dataclass
class CastCharacter:
    """A loaded cast member: the rig and which of its joints is which canonical joint."""

    rig: CastRig
    joints: dict[str, int]


def load_cast(members: list[CastMember]) -> dict[str, CastCharacter]:
    """Story character name -> its rig (wana.cast.CastError for a file that cannot be used)."""
    out = {}
    for m in members:
        rig = read_rig(m.glb, f"the character for {m.name}")
        out[m.name] = CastCharacter(rig, map_joints(rig, m.joint_map or None, f"the character for {m.name}"))
    return out


def cast_pose(cast: CastCharacter, motion: Motion) -> CastPose:
    """The motion on the rig, with the proportions of the built-in character the motion was made for."""
    root, rot, _ = motion_arrays(motion)
    ch = character_for(motion.character)
    rest = ch.rest_joint_positions()
    foot = min(rest[JOINT_INDEX["LeftFoot"], 1], rest[JOINT_INDEX["RightFoot"], 1]) - float(
        ch.vertices[:, 1].min()
    )
    offsets = ch.offsets.astype(np.float64)
    return retarget(cast.rig, cast.joints, rot, root, offsets, float(foot))


def add_cast_character(
    b: _Builder, name: str, cast: CastCharacter, motion: Motion, animation: dict, fps: float
) -> None:
    """The rig's joints under a node "<name>", its mesh as "<name>_body" (more skins: "<name>_body_1"...),
    the animation's channels."""
    from services.render.gltf_export import FLOAT

    rig = cast.rig
    pose = cast_pose(cast, motion)
    base = rig.base
    group = b.node({"name": name, "matrix": [float(x) for x in base.T.reshape(-1)]}, root=True)
    first = len(b.doc["nodes"])
    nodes = []
    for j in range(rig.n_joints):
        node: dict = {
            "name": rig.names[j],
            "translation": [float(x) for x in rig.translation[j]],
            "rotation": [float(x) for x in rig.rotation[j] / np.linalg.norm(rig.rotation[j])],
        }
        if not np.allclose(rig.scale[j], 1.0):
            node["scale"] = [float(x) for x in rig.scale[j]]
        kids = [first + k for k in range(rig.n_joints) if rig.parents[k] == j]
        if kids:
            node["children"] = kids
        nodes.append(b.node(node))
    b.doc["nodes"][group]["children"] = [nodes[j] for j in range(rig.n_joints) if rig.parents[j] < 0]
    for k, skin in enumerate(rig.skins):
        prims = [
            _primitive(b, f"{name}_{i}", prim, len(skin.joints))
            for i, prim in enumerate(rig.primitives)
            if prim.skin == k
        ]
        if not prims:
            continue
        ibm = np.ascontiguousarray(skin.inverse_bind.transpose(0, 2, 1)).reshape(-1, 16).astype(np.float32)
        b.doc.setdefault("skins", []).append(
            {
                "name": name if k == 0 else f"{name}_{k}",
                "joints": [nodes[j] for j in skin.joints],
                "inverseBindMatrices": b.accessor(ibm, FLOAT),
                "skeleton": group,
            }
        )
        b.doc["meshes"].append({"name": name if k == 0 else f"{name}_{k}", "primitives": prims})
        mesh_name = (
            f"{name}_body" if k == 0 else f"{name}_body_{k}"
        )  # a VRM's hair and face have skins of their own
        b.node(
            {"name": mesh_name, "mesh": len(b.doc["meshes"]) - 1, "skin": len(b.doc["skins"]) - 1}, root=True
        )

    t = pose.rotation.shape[0]
    times = b.accessor((np.arange(t, dtype=np.float64) / fps).astype(np.float32), FLOAT, bounds=True)

    def channel(node: int, path: str, values: np.ndarray, interpolation: str = "LINEAR") -> None:
        animation["samplers"].append(
            {
                "input": times,
                "output": b.accessor(values.astype(np.float32), FLOAT),
                "interpolation": interpolation,
            }
        )
        animation["channels"].append(
            {"sampler": len(animation["samplers"]) - 1, "target": {"node": node, "path": path}}
        )

    channel(nodes[pose.hips], "translation", pose.hips_translation)
    if motion.present is not None:
        present = from_wire(motion.present).astype(bool)
        if len(present) == t and not present.all():  # off stage: scale 0, as the built-in characters
            channel(nodes[pose.hips], "scale", rig.scale[pose.hips][None] * present[:, None], "STEP")
    moving = sorted(set(cast.joints.values()))
    for j in moving:
        q = pose.rotation[:, j]
        channel(nodes[j], "rotation", q / np.linalg.norm(q, axis=1, keepdims=True))


def _primitive(b: _Builder, material_name: str, prim: Primitive, n_joints: int) -> dict:
    """One skinned primitive of the user's mesh and its material, into the builder."""
    from services.render.gltf_export import (
        ARRAY_BUFFER,
        ELEMENT_ARRAY_BUFFER,
        FLOAT,
        UNSIGNED_BYTE,
        UNSIGNED_INT,
        UNSIGNED_SHORT,
        clean_skin,
        unit_normals,
    )

    pbr: dict = {"baseColorFactor": list(prim.colour), "metallicFactor": 0.0}
    if prim.texture is not None and prim.uv is not None:  # the character's own look, embedded
        image, mime = prim.texture
        b.doc.setdefault("images", []).append({"bufferView": b.view(image), "mimeType": mime})
        b.doc.setdefault("textures", []).append({"source": len(b.doc["images"]) - 1})
        pbr["baseColorTexture"] = {"index": len(b.doc["textures"]) - 1}
    material = len(b.doc["materials"])
    b.doc["materials"].append({"name": material_name, "pbrMetallicRoughness": pbr})
    _, weights = clean_skin(prim.joints, prim.weights)
    joints = np.where(weights > 0, prim.joints, 0)  # clean_skin's indices are 8-bit; a rig may have more
    faces = prim.indices.reshape(-1, 3)
    wide = UNSIGNED_SHORT if n_joints > 255 else UNSIGNED_BYTE
    idx_type = UNSIGNED_SHORT if len(prim.positions) < 65535 else UNSIGNED_INT
    return {
        "attributes": {
            "POSITION": b.accessor(prim.positions, FLOAT, target=ARRAY_BUFFER, bounds=True),
            "NORMAL": b.accessor(unit_normals(prim.positions, faces), FLOAT, target=ARRAY_BUFFER),
            "JOINTS_0": b.accessor(
                joints.astype(np.uint16 if wide == UNSIGNED_SHORT else np.uint8),
                wide,
                target=ARRAY_BUFFER,
            ),
            "WEIGHTS_0": b.accessor(weights, FLOAT, target=ARRAY_BUFFER),
            **(
                {"TEXCOORD_0": b.accessor(prim.uv, FLOAT, target=ARRAY_BUFFER)}
                if prim.texture is not None and prim.uv is not None
                else {}
            ),
        },
        "indices": b.accessor(
            prim.indices.astype(np.uint16 if idx_type == UNSIGNED_SHORT else np.uint32),
            idx_type,
            target=ELEMENT_ARRAY_BUFFER,
        ),
        "material": material,
    }
