"""GLB (Khronos validator, structure, skinning semantics), BVH (our reader and PyPI's bvh), write_outputs."""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
import trimesh
from scipy.spatial.transform import Rotation

from proto.ssg import Command
from services.render.bvh_export import write_character_bvh
from services.render.demo import demo_scene, walk_motion
from services.render.gltf_export import clean_skin, scene_glb
from services.render.skinning import Rig
from services.render.timeline import COMMAND_HOLD_FRAMES
from services.render.video import probe
from wana.assets.characters import EXPRESSIONS
from wana.assets.gltf import read_glb
from wana.domain.bvh import canonical_motion, read_bvh
from wana.domain.skeleton import JOINT_NAMES, N_JOINTS

REPO = Path(__file__).resolve().parents[3]
VALIDATOR = REPO / "tools" / "node" / "validate_gltf.mjs"


@pytest.fixture(scope="module")
def glb(tmp_path_factory) -> Path:
    motions = [
        walk_motion("Eve", (-2.0, 1.0), (1.0, -1.0), 40),
        walk_motion("Quentin", (1.0, 1.5), (0.0, 0.0), 25),
    ]
    path = tmp_path_factory.mktemp("glb") / "scene.glb"
    path.write_bytes(scene_glb(demo_scene(), motions))
    return path


def test_glb_has_zero_errors_and_warnings_under_the_khronos_validator(glb):
    node = shutil.which("node")
    if node is None:
        pytest.skip("needs node (Node.js) to run the Khronos gltf-validator")
    if not (REPO / "tools" / "node" / "node_modules" / "gltf-validator").is_dir():
        pytest.skip("needs `npm ci` in tools/node (gltf-validator)")
    run = subprocess.run([node, str(VALIDATOR), str(glb)], capture_output=True, text=True, timeout=120)
    report = json.loads(run.stdout)
    issues = report["issues"]
    assert issues["numErrors"] == 0, issues["messages"][:10]
    assert issues["numWarnings"] == 0, issues["messages"][:10]
    assert (
        report["info"]["hasSkins"]
        and report["info"]["hasMorphTargets"]
        and report["info"]["animationCount"] == 1
    )


def _accessor(doc: dict, blob: bytes, i: int) -> np.ndarray:
    acc = doc["accessors"][i]
    view = doc["bufferViews"][acc["bufferView"]]
    dtype = {5126: np.float32, 5121: np.uint8, 5123: np.uint16, 5125: np.uint32}[acc["componentType"]]
    width = {"SCALAR": 1, "VEC3": 3, "VEC4": 4, "MAT4": 16}[acc["type"]]
    start = view["byteOffset"] + acc.get("byteOffset", 0)
    return np.frombuffer(blob, dtype=dtype, count=acc["count"] * width, offset=start).reshape(
        acc["count"], width
    )


def test_glb_skinning_reproduces_the_rendered_pose(glb):
    """Apply glTF's own skinning rule to the file's data and compare with the renderer's vertices."""
    doc, blob = read_glb(glb)
    mesh_node = next(n for n in doc["nodes"] if n.get("name") == "Eve" and "skin" in n)
    skin = doc["skins"][mesh_node["skin"]]
    prim = doc["meshes"][mesh_node["mesh"]]["primitives"][0]
    assert doc["meshes"][mesh_node["mesh"]]["extras"]["targetNames"] == list(EXPRESSIONS)
    anim = doc["animations"][0]
    frame = 30
    local_t = {j: np.array(doc["nodes"][j]["translation"]) for j in skin["joints"]}
    local_r = {j: np.array([0, 0, 0, 1.0]) for j in skin["joints"]}
    weights = np.zeros(len(EXPRESSIONS))
    for ch in anim["channels"]:
        out = _accessor(doc, blob, anim["samplers"][ch["sampler"]]["output"])
        node, path = ch["target"]["node"], ch["target"]["path"]
        if path == "weights" and node == doc["nodes"].index(mesh_node):
            weights = out.reshape(-1, len(EXPRESSIONS))[frame]
        elif node in local_t and path == "translation":
            local_t[node] = out[frame]
        elif node in local_r and path == "rotation":
            local_r[node] = out[frame]
    parent = {c: p for p in skin["joints"] for c in doc["nodes"][p].get("children", [])}
    world: dict[int, np.ndarray] = {}
    for j in skin["joints"]:  # parents come first in our joint order
        m = np.eye(4)
        m[:3, :3] = Rotation.from_quat(local_r[j]).as_matrix()
        m[:3, 3] = local_t[j]
        world[j] = world[parent[j]] @ m if j in parent else m
    ibm = _accessor(doc, blob, skin["inverseBindMatrices"]).reshape(-1, 4, 4).transpose(0, 2, 1)
    joint_mats = np.stack([world[j] @ ibm[k] for k, j in enumerate(skin["joints"])])
    pos = _accessor(doc, blob, prim["attributes"]["POSITION"]).astype(float)
    for k, t in enumerate(prim["targets"]):
        pos = pos + weights[k] * _accessor(doc, blob, t["POSITION"])
    js = _accessor(doc, blob, prim["attributes"]["JOINTS_0"]).astype(int)
    ws = _accessor(doc, blob, prim["attributes"]["WEIGHTS_0"]).astype(float)
    skin_m = np.einsum("vk,vkab->vab", ws, joint_mats[js])
    posed = np.einsum("vab,vb->va", skin_m[:, :3, :3], pos) + skin_m[:, :3, 3]
    expected = Rig.from_motion(walk_motion("Eve", (-2.0, 1.0), (1.0, -1.0), 40)).vertices([frame])[0]
    assert np.abs(posed - expected).max() < 2e-3


def test_an_independent_loader_reads_the_glb(glb):
    loaded = trimesh.load(glb, force="scene")
    names = set(loaded.geometry)
    assert {"floor", "desk", "chair"} <= names and len(names) >= 9


def test_clean_skin_merges_duplicates_and_normalises():
    j, w = clean_skin(np.array([[3, 3, 1, 0]]), np.array([[0.3, 0.3, 0.4, 0.0]]))
    assert w.sum() == pytest.approx(1.0, abs=1e-7)
    nz = j[0][w[0] > 0]
    assert len(set(nz.tolist())) == len(nz) and set(nz.tolist()) == {1, 3}


def test_bvh_reads_back_with_our_reader_and_with_the_pypi_bvh_parser(tmp_path):
    motion = walk_motion("Tom", (0.0, 0.0), (1.5, 0.5), 33)
    path = write_character_bvh(tmp_path, motion)
    assert path.name == "Tom.bvh"
    rig = Rig.from_motion(motion)
    root, rot = canonical_motion(read_bvh(path))
    np.testing.assert_allclose(root, rig.root, atol=1e-5)
    dots = np.abs(np.sum(rot * rig.rotations, axis=-1))
    assert dots.min() > 1 - 1e-6  # the same rotations (q and -q alike)
    bvh = pytest.importorskip("bvh", reason="the independent parser is the PyPI package bvh")
    with open(path) as fh:
        mocap = bvh.Bvh(fh.read())
    assert mocap.nframes == 33 and mocap.frame_time == pytest.approx(1 / 30, abs=1e-6)
    assert mocap.get_joints_names() == list(JOINT_NAMES)
    xyz = np.array(mocap.frames_joint_channels("Hips", ["Xposition", "Yposition", "Zposition"]), dtype=float)
    np.testing.assert_allclose(xyz, rig.root, atol=1e-5)
    assert len(mocap.joint_channels("LeftArm")) == 3 and len(JOINT_NAMES) == N_JOINTS


@pytest.mark.slow
def test_write_outputs_writes_video_glb_one_bvh_per_character_and_report(tmp_path):
    from services.render.export import write_outputs

    eve = walk_motion("Eve", (-1.5, 1.0), (0.5, 0.0), 20, sentence_id="s1")
    tom = walk_motion("Tom", (1.0, 1.5), (0.0, 1.5), 20, sentence_id="s1")
    paths = write_outputs(
        tmp_path,
        demo_scene(),
        {"Eve": eve, "Tom": tom},
        [("s2", Command(kind="camera", value="close"))],
        [("s1", "Eve and Tom walk."), ("s2", "camera close")],
        {"diagnostics": {"s1": []}},
        width=160,
        height=120,
        progress=False,
    )
    assert sorted(paths) == ["Eve.bvh", "Tom.bvh", "animation.mp4", "report.json", "scene.glb"]
    info = probe(paths["animation.mp4"])
    # "camera close" ends the story: the video holds the final pose until it has shown for 1.5 s
    assert info["frames"] == 20 + COMMAND_HOLD_FRAMES and info["width"] == 160 and info["codec"] == "h264"
    report = json.loads(paths["report.json"].read_text())
    assert report["diagnostics"] == {"s1": []}
    assert report["render"]["frames"] == 20 + COMMAND_HOLD_FRAMES
    assert report["render"]["commands"][0]["value"] == "close"
    assert report["render"]["captions"][0]["text"] == "Eve and Tom walk."
    assert read_bvh(paths["Eve.bvh"]).n_frames == 20
