"""A character off stage (Motion.present == 0) is drawn nowhere: a point in the MP4's skinning, scale 0 in
the GLB."""

from __future__ import annotations

import msgspec
import numpy as np

from services.render.demo import demo_scene, walk_motion
from services.render.gltf_export import scene_glb
from services.render.skinning import Rig
from wana.arrays import to_wire
from wana.assets.gltf import read_glb

FRAMES = 40


def entering():
    """Eve's walk, on stage from frame 10 to frame 30."""
    on = np.zeros(FRAMES, np.uint8)
    on[10:30] = 1
    return msgspec.structs.replace(walk_motion("Eve", (-1.0, 0.5), (1.0, -0.5), FRAMES), present=to_wire(on))


def test_off_stage_frames_skin_to_a_single_point_and_on_stage_frames_to_the_body():
    rig = Rig.from_motion(entering())
    verts = rig.vertices(np.arange(FRAMES))
    size = np.ptp(verts, axis=1).max(axis=1)  # (T,) the mesh's largest extent per frame
    assert np.all(size[:10] == 0) and np.all(size[30:] == 0)
    assert np.all(size[10:30] > 1.0)  # a standing body is over a metre tall


def test_a_motion_without_presence_is_drawn_on_every_frame():
    rig = Rig.from_motion(walk_motion("Eve", (-1.0, 0.5), (1.0, -0.5), FRAMES))
    assert np.all(np.ptp(rig.vertices(np.arange(FRAMES)), axis=1).max(axis=1) > 1.0)


def test_the_glb_scales_the_hips_to_zero_off_stage(tmp_path):
    path = tmp_path / "scene.glb"
    path.write_bytes(scene_glb(demo_scene(), [entering()]))
    doc, blob = read_glb(path)
    hips = next(i for i, n in enumerate(doc["nodes"]) if n.get("name") == "Eve:Hips")
    anim = doc["animations"][0]
    (channel,) = [c for c in anim["channels"] if c["target"] == {"node": hips, "path": "scale"}]
    sampler = anim["samplers"][channel["sampler"]]
    assert sampler["interpolation"] == "STEP"
    acc = doc["accessors"][sampler["output"]]
    view = doc["bufferViews"][acc["bufferView"]]
    start = view["byteOffset"] + acc.get("byteOffset", 0)
    scale = np.frombuffer(blob, np.float32, count=acc["count"] * 3, offset=start).reshape(-1, 3)
    assert np.all(scale[:10] == 0) and np.all(scale[10:30] == 1) and np.all(scale[30:] == 0)


def test_the_glb_of_a_character_always_on_stage_has_no_scale_channel(tmp_path):
    path = tmp_path / "scene.glb"
    path.write_bytes(scene_glb(demo_scene(), [walk_motion("Eve", (-1.0, 0.5), (1.0, -0.5), FRAMES)]))
    doc, _ = read_glb(path)
    assert not [c for c in doc["animations"][0]["channels"] if c["target"]["path"] == "scale"]
