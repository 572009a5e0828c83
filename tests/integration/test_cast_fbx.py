"""An FBX character (the format most rigs come in) goes through Blender to GLB and maps to our skeleton.

Blender writes the FBX itself from a Mixamo-named rig the tests build, so the file is what a DCC exports.
"""

from __future__ import annotations

import importlib.util
import subprocess
import sys

import pytest

from tests.unit.cast_rigs import MIXAMO, rig_glb, rig_joints
from wana.cast import map_joints, read_rig
from wana.cast.fbx import fbx_to_glb
from wana.domain.skeleton import JOINT_NAMES

pytestmark = [
    pytest.mark.slow,
    pytest.mark.skipif(importlib.util.find_spec("bpy") is None, reason="needs Blender's bpy (make setup)"),
]

TO_FBX = """
import sys, bpy
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=sys.argv[1])
bpy.ops.export_scene.fbx(filepath=sys.argv[2], add_leaf_bones=False)
"""


def test_an_fbx_rig_converts_and_every_canonical_joint_maps(tmp_path):
    src, fbx = tmp_path / "mixamo.glb", tmp_path / "mixamo.fbx"
    src.write_bytes(rig_glb(rig_joints(MIXAMO), centimetres=True))
    run = subprocess.run(
        [sys.executable, "-c", TO_FBX, str(src), str(fbx)], capture_output=True, text=True, timeout=300
    )
    assert run.returncode == 0 and fbx.is_file(), run.stderr[-600:]
    rig = read_rig(fbx_to_glb(fbx), "mixamo.fbx")
    mapped = map_joints(rig, label="mixamo.fbx")
    assert sorted(mapped) == sorted(JOINT_NAMES)
    assert {n: rig.names[i] for n, i in mapped.items()} == {n: f"mixamorig:{n}" for n in JOINT_NAMES}
