"""Preview = export: the editor's reader of the director's camera (editor/src/directorcam.js, run by
node) gives, frame by frame, the camera the MP4 is rendered with."""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from proto.common import Header
from proto.render import ExportRequest
from proto.scene import Room, Scene
from services.render.demo import walk_motion
from services.render.handlers import handle_export
from services.render.staging import Staging

REPO = Path(__file__).resolve().parents[3]
SCENE = Scene(room=Room(room_type="office", width=6.0, depth=5.0, height=2.8), objects=[], seed=0)
SCRIPT = """
import { readFileSync } from "node:fs";
import { directorCamera, cameraAt } from "%s";
const buf = readFileSync(process.argv[2]);
const cam = directorCamera(buf.buffer.slice(buf.byteOffset, buf.byteOffset + buf.byteLength));
console.log(JSON.stringify([0, 30, 61, 89, 500].map((f) => cameraAt(cam, f))));
"""


def test_the_editor_reads_the_camera_the_video_is_rendered_with(tmp_path: Path) -> None:
    node = shutil.which("node")
    if node is None:
        pytest.skip("needs node (Node.js) to run the editor's camera reader")
    eve = walk_motion("Eve", (-2.0, 1.0), (1.5, -1.0), 90, sentence_id="s1")
    tom = walk_motion("Tom", (2.0, 1.5), (0.5, 0.5), 90, sentence_id="s2")
    glb = tmp_path / "scene.glb"
    glb.write_bytes(
        handle_export(ExportRequest(header=Header(), format="glb", scene=SCENE, motions=[eve, tom])).data
    )
    script = tmp_path / "read.mjs"
    script.write_text(SCRIPT % (REPO / "editor" / "src" / "directorcam.js").as_uri())
    run = subprocess.run(
        [node, str(script), str(glb)], capture_output=True, text=True, timeout=60, check=True
    )
    got = json.loads(run.stdout)
    track = Staging.build(SCENE, [eve, tom]).camera_track()
    for item, f in zip(got, [0, 30, 61, 89, 500], strict=True):
        pose = track.pose(min(f, len(track) - 1))
        np.testing.assert_allclose(item["position"], pose.eye, atol=1e-5)
        forward = Rotation.from_quat(item["quaternion"]).apply(
            [0.0, 0.0, -1.0]
        )  # three.js cameras look down -Z
        want = (pose.target - pose.eye) / np.linalg.norm(pose.target - pose.eye)
        np.testing.assert_allclose(forward, want, atol=1e-5)
        assert abs(item["fovDeg"] - pose.fov_deg) < 1e-4
