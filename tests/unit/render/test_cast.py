"""`--cast`: the user's rigged humanoid in the GLB, on its own joint names, feet on the floor.

Three rigs the test builds (tests/unit/cast_rigs.py): Mixamo names under a centimetre armature; Unreal
mannequin names, long legs, a short torso, an A-pose, extra twist and finger joints; names no table knows
(jnt_00...) with short legs, mapped by a user map; plus a VRM humanoid table."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from proto.render import CastMember
from services.render.cast_gltf import cast_pose, load_cast
from services.render.demo import demo_scene, walk_motion
from services.render.gltf_export import scene_glb
from services.render.skinning import Rig
from tests.unit.cast_rigs import CUSTOM, MIXAMO, UNREAL, rig_glb, rig_joints
from wana.assets.gltf import read_glb
from wana.cast import CastError, map_joints, read_rig
from wana.domain.skeleton import JOINT_INDEX, JOINT_NAMES

RIGS = {
    "mixamo": (rig_glb(rig_joints(MIXAMO), centimetres=True), {}),
    "unreal": (rig_glb(rig_joints(UNREAL, legs=1.15, torso=0.85, extras=True), a_pose=True), {}),
    "custom": (rig_glb(rig_joints(CUSTOM, legs=0.8, arms=1.1)), {c: u for c, u in CUSTOM.items()}),
}


def _world_at(doc: dict, blob: bytes, frame: int, names: list[str]) -> dict[str, np.ndarray]:
    """World positions of the named nodes at a keyframe, by glTF's own rules (TRS, animation channels)."""
    nodes = doc["nodes"]
    trs = {
        i: [
            np.array(n.get("translation", [0, 0, 0])),
            np.array(n.get("rotation", [0, 0, 0, 1])),
            np.array(n.get("scale", [1, 1, 1])),
        ]
        for i, n in enumerate(nodes)
    }
    for ch in doc["animations"][0]["channels"]:
        s = doc["animations"][0]["samplers"][ch["sampler"]]
        out = _read(doc, blob, s["output"])
        k = {"translation": 0, "rotation": 1, "scale": 2}.get(ch["target"]["path"])
        if k is not None:
            trs[ch["target"]["node"]][k] = out[min(frame, len(out) - 1)].astype(np.float64)
    parent = {c: i for i, n in enumerate(nodes) for c in n.get("children", [])}

    def world(i: int) -> np.ndarray:
        n = nodes[i]
        if "matrix" in n:
            m = np.array(n["matrix"]).reshape(4, 4).T
        else:
            t, r, s = trs[i]
            m = np.eye(4)
            m[:3, :3] = Rotation.from_quat(r).as_matrix() * s
            m[:3, 3] = t
        return m if i not in parent else world(parent[i]) @ m

    index = {n.get("name"): i for i, n in enumerate(nodes)}
    return {name: world(index[name])[:3, 3] for name in names}


def _read(doc: dict, blob: bytes, i: int) -> np.ndarray:
    a = doc["accessors"][i]
    v = doc["bufferViews"][a["bufferView"]]
    w = {"SCALAR": 1, "VEC3": 3, "VEC4": 4}[a["type"]]
    return np.frombuffer(
        blob, np.float32, a["count"] * w, v.get("byteOffset", 0) + a.get("byteOffset", 0)
    ).reshape(-1, w)


@pytest.fixture(scope="module")
def walk():
    return walk_motion("Eve", (-2.0, 1.0), (1.0, -1.0), 60)


def _planted(walk) -> list[tuple[int, int]]:
    """(frame, 0 left / 1 right) where a canonical foot stands (the built-in Eve's foot nearly still)."""
    rig = Rig.from_motion(walk)
    feet = rig.joint_positions[:, [JOINT_INDEX["LeftFoot"], JOINT_INDEX["RightFoot"]]]
    speed = np.linalg.norm(np.diff(feet[..., [0, 2]], axis=0), axis=-1) * 30
    return [(int(f) + 1, int(k)) for f, k in zip(*np.nonzero(speed < 0.6), strict=True)]


@pytest.mark.parametrize("kind", sorted(RIGS))
def test_the_glb_has_the_users_joints_and_its_feet_plant_on_the_floor(kind, walk):
    data, joint_map = RIGS[kind]
    rig = read_rig(data)
    member = CastMember(name="Eve", glb=data, joint_map=joint_map)
    glb = scene_glb(demo_scene(), [walk], cast=load_cast([member]))
    doc, blob = _glb(glb)
    body = next(n for n in doc["nodes"] if n.get("name") == "Eve_body")
    skin_names = [doc["nodes"][j]["name"] for j in doc["skins"][body["skin"]]["joints"]]
    assert skin_names == rig.names  # the user's own names, twists and fingers included
    assert not any(n.get("name", "").startswith("Eve:") for n in doc["nodes"])  # no built-in Eve
    joints = map_joints(rig, joint_map or None)
    feet = [rig.names[joints[f]] for f in ("LeftFoot", "RightFoot")]
    floor = rig.floor()
    ankle = rig.rest_world()[joints["LeftFoot"], 1, 3] - floor  # the rig's ankle over its soles at rest
    planted = _planted(walk)
    assert len(planted) > 10
    eve = Rig.from_motion(walk)
    canon = eve.joint_positions
    canon_ankle = (
        eve.character.rest_joint_positions()[JOINT_INDEX["LeftFoot"], 1] - eve.character.vertices[:, 1].min()
    )
    errors = []
    for f, k in planted:
        side = ("LeftFoot", "RightFoot")[k]
        assert abs(canon[f, JOINT_INDEX[side], 1] - canon_ankle) < 0.03  # the built-in foot is down
        user = _world_at(doc, blob, f, [feet[k]])[feet[k]][1]
        errors.append(abs((user - ankle) - (canon[f, JOINT_INDEX[side], 1] - canon_ankle)))
    assert max(errors) < 0.02, max(errors)
    # the character walks the same path: its hips over the canonical hips
    hips = _world_at(doc, blob, 30, [rig.names[joints["Hips"]]])[rig.names[joints["Hips"]]]
    assert np.linalg.norm(hips[[0, 2]] - canon[30, 0, [0, 2]]) < 1e-3


def _glb(data: bytes):
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as tmp:
        p = Path(tmp) / "s.glb"
        p.write_bytes(data)
        return read_glb(p)


@pytest.mark.parametrize("kind", ["unreal", "vrm0"])
def test_limbs_follow_the_canonical_bones_whatever_the_rest_pose(kind, walk):
    """A-pose, other proportions, a rig facing -Z: each mapped bone of the upper body points where the
    canonical bone points; the legs (bent by IK on their own lengths) put the ankles over the canonical ankles."""
    data = RIGS["unreal"][0] if kind == "unreal" else rig_glb(rig_joints(MIXAMO, legs=1.1), facing_back=True)
    cast = load_cast([CastMember(name="Eve", glb=data)])["Eve"]
    pose = cast_pose(cast, walk)
    canon = Rig.from_motion(walk).joint_positions
    for a, b in (("LeftArm", "LeftForeArm"), ("RightForeArm", "RightHand"), ("Spine", "Spine1")):
        d_user = pose.world[:, cast.joints[b]] - pose.world[:, cast.joints[a]]
        d_canon = canon[:, JOINT_INDEX[b]] - canon[:, JOINT_INDEX[a]]
        cos = (
            np.sum(d_user * d_canon, axis=1)
            / np.linalg.norm(d_user, axis=1)
            / np.linalg.norm(d_canon, axis=1)
        )
        assert cos.min() > 0.999, (a, b, cos.min())
    for foot in ("LeftFoot", "RightFoot"):  # no sliding: the ankle over the canonical ankle at every frame
        gap = pose.world[:, cast.joints[foot]][:, [0, 2]] - canon[:, JOINT_INDEX[foot]][:, [0, 2]]
        assert np.linalg.norm(gap, axis=1).max() < 0.01


def test_a_vrm_humanoid_table_names_the_bones():
    names = {n: f"b{i}" for i, n in enumerate(JOINT_NAMES)}
    vrm = {"hips": "b0", "spine": "b1", "chest": "b2", "head": "b5"}
    vrm |= {
        f"{s}{b}": names[f"{S}{c}"]
        for s, S in (("left", "Left"), ("right", "Right"))
        for b, c in (
            ("UpperArm", "Arm"),
            ("LowerArm", "ForeArm"),
            ("Hand", "Hand"),
            ("UpperLeg", "UpLeg"),
            ("LowerLeg", "Leg"),
            ("Foot", "Foot"),
        )
    }
    rig = read_rig(rig_glb(rig_joints(names), vrm=vrm))
    joints = map_joints(rig)
    assert rig.names[joints["LeftForeArm"]] == names["LeftForeArm"] and rig.names[joints["Spine1"]] == "b2"


def test_a_rig_the_tables_cannot_cover_names_every_missing_joint():
    rig = read_rig(RIGS["custom"][0])
    with pytest.raises(CastError, match="Hips, Spine, Head, LeftArm.*RightFoot.*--cast-map"):
        map_joints(rig)
    with pytest.raises(CastError, match=r"does not have \(did you mean 'jnt_\d\d'"):
        map_joints(rig, {"Hips": "jnt_0"})
    with pytest.raises(CastError, match="did you mean LeftArm"):
        map_joints(rig, {"LeftArn": "jnt_00"})
    with pytest.raises(CastError, match="not a GLB"):
        read_rig(b"Kaydara FBX Binary  \x00")


def test_the_characters_texture_comes_along(walk):
    import io

    from PIL import Image

    png = io.BytesIO()
    Image.new("RGB", (4, 4), (200, 30, 40)).save(png, format="PNG")
    data = rig_glb(rig_joints(MIXAMO), texture=png.getvalue())
    glb = scene_glb(demo_scene(), [walk], cast=load_cast([CastMember(name="Eve", glb=data)]))
    doc, blob = _glb(glb)
    body = next(n for n in doc["nodes"] if n.get("name") == "Eve_body")
    prim = doc["meshes"][body["mesh"]]["primitives"][0]
    assert "TEXCOORD_0" in prim["attributes"]
    texture = doc["materials"][prim["material"]]["pbrMetallicRoughness"]["baseColorTexture"]["index"]
    view = doc["bufferViews"][doc["images"][doc["textures"][texture]["source"]]["bufferView"]]
    image = Image.open(io.BytesIO(blob[view["byteOffset"] : view["byteOffset"] + view["byteLength"]]))
    assert image.getpixel((1, 1)) == (200, 30, 40)


def test_a_mesh_with_a_skin_of_its_own_comes_along_and_follows_the_head(walk):
    """VRoid's VRMs bind hair and face with skins of their own over the body's skeleton."""
    data = rig_glb(rig_joints(MIXAMO), hair=True)
    rig = read_rig(data)
    assert len(rig.skins) == 2 and [p.skin for p in rig.primitives] == [0, 1]
    glb = scene_glb(demo_scene(), [walk], cast=load_cast([CastMember(name="Eve", glb=data)]))
    doc, blob = _glb(glb)
    hair = next(n for n in doc["nodes"] if n.get("name") == "Eve_body_1")
    skin = doc["skins"][hair["skin"]]
    assert [doc["nodes"][j]["name"] for j in skin["joints"]] == ["mixamorig:Head"]
    head = _world_at(doc, blob, 20, ["mixamorig:Head"])["mixamorig:Head"]
    canon = Rig.from_motion(walk).joint_positions[20, JOINT_INDEX["Head"]]
    assert np.linalg.norm(head[[0, 2]] - canon[[0, 2]]) < 0.1  # the head (and its hair) walks along
