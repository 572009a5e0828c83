"""Stateful objects in the outputs: the door leaf turns on its hinge from the touch frame (MP4 geometry and
the GLB's hinge node), and a real render after "turns on the lamp" is brighter near the lamp."""

from __future__ import annotations

import json
import shutil
import struct
import subprocess
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from proto.scene import ObjectStateTrack, PlacedObject, Room, Scene
from services.render.camera import CameraPose, project
from services.render.demo import walk_motion
from services.render.gltf_export import scene_glb
from services.render.object_states import posed, stateful_objects
from services.render.renderer import FrameRenderer

REPO = Path(__file__).resolve().parents[3]
TOUCH = 20
OUT = REPO / "out" / "tests" / "states"  # the frames, to look at
ROOM = Room(room_type="living_room", width=5.0, depth=4.0, height=2.8)


def _scene(door: bool = True) -> Scene:
    objects = [PlacedObject(id="lamp", category="floor_lamp", position=(1.2, 0.0, -1.4))]
    states = [ObjectStateTrack(object_id="lamp", state="on", frames=[TOUCH, TOUCH + 3], values=[0.0, 1.0])]
    if door:
        objects.append(PlacedObject(id="door", category="door", position=(-1.0, 0.0, -1.95)))
        states.append(
            ObjectStateTrack(object_id="door", state="open", frames=[TOUCH, TOUCH + 18], values=[0.0, 1.0])
        )
    return Scene(room=ROOM, objects=objects, states=states)


def test_the_door_leaf_turns_on_its_hinge_only_after_the_touch_frame():
    scene = _scene()
    door = stateful_objects(scene)["door"]
    before, _ = posed(door, scene, TOUCH - 1)
    after, _ = posed(door, scene, TOUCH + 18)
    rest = door.mesh.vertices + np.asarray(door.placed.position)
    assert np.allclose(before, rest)  # shut until the hand touches it
    leaf = door.moving
    assert leaf.sum() > 0 and (~leaf).sum() > 0  # the frame posts stay, the leaf moves
    assert np.allclose(after[~leaf], rest[~leaf])
    # the leaf, shut along the wall (x), now stands out into the room (+z) from its hinge
    assert np.ptp(before[leaf][:, 2]) < 0.2 and np.ptp(after[leaf][:, 2]) > 0.6
    assert after[leaf][:, 2].max() > before[leaf][:, 2].max() + 0.6


def _glb_doc(data: bytes) -> tuple[dict, bytes]:
    n = struct.unpack("<I", data[12:16])[0]
    return json.loads(data[20 : 20 + n]), data[20 + n + 8 :]


def test_the_glb_turns_the_door_leaf_node_and_drives_the_lamps_light(tmp_path):
    scene = _scene()
    data = scene_glb(scene, [walk_motion("Eve", (0.0, 1.0), (0.5, 0.5), 60)])
    doc, blob = _glb_doc(data)
    names = [n["name"] for n in doc["nodes"]]
    hinge = names.index("door:hinge")
    channel = next(c for c in doc["animations"][0]["channels"] if c["target"].get("node") == hinge)
    acc = doc["accessors"][doc["animations"][0]["samplers"][channel["sampler"]]["output"]]
    view = doc["bufferViews"][acc["bufferView"]]
    rot = np.frombuffer(blob, np.float32, acc["count"] * 4, view["byteOffset"]).reshape(-1, 4)
    angle = 2 * np.degrees(np.arccos(np.clip(np.abs(rot[:, 3]), 0, 1)))
    assert angle[TOUCH - 1] < 0.5 and angle[TOUCH + 18] > 80
    assert doc["extensions"]["KHR_lights_punctual"]["lights"][0]["name"] == "lamp:light"
    path = tmp_path / "s.glb"
    path.write_bytes(data)
    node = shutil.which("node")
    validator = REPO / "tools" / "node" / "validate_gltf.mjs"
    if node is None or not (REPO / "tools" / "node" / "node_modules" / "gltf-validator").is_dir():
        pytest.skip("needs node and `npm ci` in tools/node (gltf-validator)")
    run = subprocess.run([node, str(validator), str(path)], capture_output=True, text=True, timeout=120)
    issues = json.loads(run.stdout)["issues"]
    assert issues["numErrors"] == 0 and issues["numWarnings"] == 0, issues["messages"][:5]


@pytest.mark.slow
def test_a_frame_after_the_lamp_turns_on_is_brighter_near_the_lamp():
    scene = _scene(door=False)
    w, h = 320, 240
    pose = CameraPose(
        eye=np.array([0.0, 2.2, 2.4]), target=np.array([0.0, 0.6, -1.2]), up=np.array([0.0, 1.0, 0.0])
    )
    OUT.mkdir(parents=True, exist_ok=True)
    with FrameRenderer(scene, [], n_frames=60, width=w, height=h) as r:
        before, after = r.render(TOUCH - 1, pose), r.render(TOUCH + 5, pose)
    uv, _ = project(
        np.array([[1.2, 0.02, -0.9], [-1.8, 0.02, -0.9]]), pose, w, h
    )  # the floor by the lamp, far from it
    Image.fromarray(np.concatenate([before, after], axis=1)).save(OUT / "lamp_before_after.png")

    def patch(img: np.ndarray, p: np.ndarray) -> float:
        x, y = int(p[0]), int(p[1])
        return float(img[max(0, y - 30) : y + 30, max(0, x - 30) : x + 30].astype(float).mean())

    near_gain = patch(after, uv[0]) - patch(before, uv[0])
    far_gain = patch(after, uv[1]) - patch(before, uv[1])
    assert near_gain > 8.0, near_gain
    assert near_gain > 2 * max(far_gain, 0.5), (near_gain, far_gain)


def test_a_wardrobe_opens_its_two_fronts_outwards_on_their_outer_hinges():
    scene = Scene(
        room=ROOM,
        objects=[PlacedObject(id="wardrobe", category="wardrobe", position=(0.0, 0.0, -1.6))],
        states=[ObjectStateTrack(object_id="wardrobe", state="open", frames=[0, 18], values=[0.0, 1.0])],
    )
    obj = stateful_objects(scene)["wardrobe"]
    assert sorted(obj.parts) == [1, 2]  # left and right fronts, the carcass still
    shut, _ = posed(obj, scene, 0)
    wide, _ = posed(obj, scene, 18)
    for leaf, side in ((1, -1), (2, 1)):
        mask = obj.leaf == leaf
        assert wide[mask][:, 2].max() > shut[mask][:, 2].max() + 0.4  # swung out to the front
        outer = shut[mask][:, 0].min() if side < 0 else shut[mask][:, 0].max()
        assert (
            abs((wide[mask][:, 0].min() if side < 0 else wide[mask][:, 0].max()) - outer) < 0.05
        )  # hinge side
    assert np.allclose(wide[obj.leaf == 0], shut[obj.leaf == 0])
