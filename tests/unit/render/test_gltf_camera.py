"""The directed camera travels in scene.glb: read back from the file's JSON and binary chunk alone, its
node and perspective reproduce the video's projection of the characters."""

from __future__ import annotations

import json
import shutil
import struct
import subprocess
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from proto.common import Header
from proto.render import ExportRequest, TimedCommand
from proto.scene import Room, Scene
from proto.ssg import Command
from services.render.camera import project
from services.render.demo import walk_motion
from services.render.handlers import handle_export
from services.render.staging import Staging

SCENE = Scene(room=Room(room_type="office", width=6.0, depth=5.0, height=2.8), objects=[], seed=0)
W, H = 320, 240
REPO = Path(__file__).resolve().parents[3]


def read_glb(data: bytes) -> tuple[dict, bytes]:
    magic, version, _ = struct.unpack_from("<III", data, 0)
    assert magic == 0x46546C67 and version == 2
    n_json, _ = struct.unpack_from("<I4s", data, 12)
    doc = json.loads(data[20 : 20 + n_json])
    n_bin, _ = struct.unpack_from("<I4s", data, 20 + n_json)
    start = 28 + n_json
    return doc, data[start : start + n_bin]


def accessor(doc: dict, blob: bytes, index: int) -> np.ndarray:
    acc = doc["accessors"][index]
    view = doc["bufferViews"][acc["bufferView"]]
    width = {"SCALAR": 1, "VEC3": 3, "VEC4": 4}[acc["type"]]
    offset = view["byteOffset"] + acc.get("byteOffset", 0)
    raw = np.frombuffer(blob, np.float32, acc["count"] * width, offset)
    return raw.reshape(acc["count"], width) if width > 1 else raw


def project_gltf(points: np.ndarray, t: np.ndarray, q: np.ndarray, yfov: float) -> np.ndarray:
    """Pixels of world points through a glTF camera node (local -Z forward, +Y up), as a viewer draws."""
    local = (points - t) @ Rotation.from_quat(q).as_matrix()  # world -> camera-local
    f = (H / 2.0) / np.tan(yfov / 2.0)
    x, y, z = local[:, 0], local[:, 1], -local[:, 2]
    return np.stack([f * x / z + W / 2.0 - 0.5, -f * y / z + H / 2.0 - 0.5], axis=1)


def test_the_glb_camera_reproduces_the_videos_framing() -> None:
    eve = walk_motion("Eve", (-2.0, 1.0), (1.5, -1.0), 120, sentence_id="s1")
    tom = walk_motion("Tom", (2.0, 1.5), (0.5, 0.5), 120, sentence_id="s2")
    req = ExportRequest(header=Header(), format="glb", scene=SCENE, motions=[eve, tom], width=W, height=H)
    reply = handle_export(req)
    doc, blob = read_glb(reply.data)
    (node,) = [n for n in doc["nodes"] if n.get("camera") is not None]
    cam = doc["cameras"][node["camera"]]
    assert cam["type"] == "perspective" and abs(cam["perspective"]["aspectRatio"] - W / H) < 1e-6
    index = doc["nodes"].index(node)
    anim = doc["animations"][0]
    channels = {c["target"]["path"]: c for c in anim["channels"] if c["target"].get("node") == index}
    samplers = anim["samplers"]
    times = accessor(doc, blob, samplers[channels["translation"]["sampler"]]["input"])
    trans = accessor(doc, blob, samplers[channels["translation"]["sampler"]]["output"])
    rots = accessor(doc, blob, samplers[channels["rotation"]["sampler"]]["output"])
    stage = Staging.build(SCENE, [eve, tom])
    track = stage.camera_track(W, H)
    assert len(times) == len(track) == reply.n_frames
    fovs = node["extras"]["yfov_per_frame"]
    points = np.concatenate([stage.rigs[n].joint_positions[60] for n in ("Eve", "Tom")])
    for f in (0, 45, 60, 119):
        want, _ = project(points, track.pose(f), W, H)
        got = project_gltf(points, trans[f], rots[f], fovs[f])
        np.testing.assert_allclose(got, want, atol=0.05)  # pixels
    assert abs(cam["perspective"]["yfov"] - np.radians(track.fov_deg[0])) < 1e-6
    assert [s.type for s in reply.shots][0] == "wide"


def test_the_glb_with_its_camera_passes_the_khronos_validator(tmp_path) -> None:  # noqa: ANN001
    node = shutil.which("node")
    if node is None:
        pytest.skip("needs node (Node.js) to run the Khronos gltf-validator")
    if not (REPO / "tools" / "node" / "node_modules" / "gltf-validator").is_dir():
        pytest.skip("needs `npm ci` in tools/node (gltf-validator)")
    eve = walk_motion("Eve", (-2.0, 1.0), (1.5, -1.0), 120, sentence_id="s1")
    close = TimedCommand(
        frame=60, command=Command(kind="camera", value="close", target="Eve"), sentence_id="s2"
    )
    req = ExportRequest(header=Header(), format="glb", scene=SCENE, motions=[eve], commands=[close])
    path = tmp_path / "scene.glb"
    path.write_bytes(handle_export(req).data)
    doc, _ = read_glb(path.read_bytes())
    assert "KHR_animation_pointer" in doc["extensionsUsed"]  # the close-up's yfov differs: it is keyed
    validator = REPO / "tools" / "node" / "validate_gltf.mjs"
    run = subprocess.run([node, str(validator), str(path)], capture_output=True, text=True, timeout=120)
    issues = json.loads(run.stdout)["issues"]
    assert issues["numErrors"] == 0 and issues["numWarnings"] == 0, issues["messages"][:10]
