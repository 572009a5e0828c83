"""FBX export through Blender: re-imported with Blender's own FBX importer, every joint within 1 cm of the BVH,
the skins' joint names, the held prop and the camera; the GLB read by Blender's glTF importer the same way.

Blender runs in subprocesses (services.render.fbx_export); the tests skip when no Python with bpy is found.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from proto.common import Header
from proto.motion_data import Motion, PropTrack
from proto.render import ExportRequest
from proto.scene import PlacedObject, Scene
from services.render import fbx_export
from services.render.bvh_export import motion_bvh
from services.render.demo import demo_scene, walk_motion
from services.render.handlers import handle_export
from services.render.skinning import Rig, character_for
from services.render.staging import Staging
from wana.arrays import from_wire, to_wire
from wana.domain.bvh import parse_bvh
from wana.domain.skeleton import JOINT_INDEX, JOINT_NAMES

try:
    fbx_export.blender_python()
except ModuleNotFoundError as exc:
    pytest.skip(str(exc), allow_module_level=True)

pytestmark = pytest.mark.slow
FRAMES = [0, 9, 15, 24, 39]


def _scene_and_motions() -> tuple[Scene, list[Motion]]:
    base = demo_scene()
    cup = PlacedObject(id="cup", category="cup", position=(-1.0, 0.75, -1.5), yaw=0.0)
    scene = Scene(room=base.room, objects=[*base.objects, cup], seed=base.seed)
    eve = walk_motion("Eve", (-2.0, 1.0), (1.0, -1.0), 40)
    hand = Rig.from_motion(eve).joint_positions[10:30, JOINT_INDEX["RightHand"]]
    track = PropTrack(
        object_id="cup",
        joint="RightHand",
        start_frame=10,
        end_frame=30,
        position=to_wire(hand.astype(np.float32)),
        rotation=to_wire(
            Rotation.from_euler("y", np.linspace(0, 1.5, 20)[:, None]).as_quat().astype(np.float32)
        ),
    )
    eve = Motion(**{**{f: getattr(eve, f) for f in eve.__struct_fields__}, "props": [track]})
    return scene, [eve, walk_motion("Quentin", (1.0, 1.5), (0.0, 0.0), 25)]


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    scene, motions = _scene_and_motions()
    folder = tmp_path_factory.mktemp("fbx")
    reply = handle_export(ExportRequest(header=Header(), format="fbx", scene=scene, motions=motions))
    (folder / reply.filename).write_bytes(reply.data)
    glb = handle_export(ExportRequest(header=Header(), format="glb", scene=scene, motions=motions))
    (folder / glb.filename).write_bytes(glb.data)
    return reply, folder, scene, motions


@pytest.fixture(scope="module")
def read_back(exported):
    """What Blender's importers read from the FBX and from the GLB."""
    _, folder, _, _ = exported
    return {
        "fbx": fbx_export.probe(folder / "animation.fbx", FRAMES),
        "glb": fbx_export.probe(folder / "scene.glb", FRAMES),
    }


def test_the_reply_is_a_binary_fbx(exported):
    reply = exported[0]
    assert reply.format == "fbx" and reply.filename == "animation.fbx"
    assert reply.data.startswith(b"Kaydara FBX Binary")
    assert reply.n_frames == 40 and reply.shots


@pytest.mark.parametrize("source", ["fbx", "glb"])
def test_every_joint_of_every_character_reads_back_within_1_cm_of_the_bvh(exported, read_back, source):
    motions = exported[3]
    arms = read_back[source]["armatures"]
    if source == "fbx":  # one armature per character (the GLB's Hips sit at its scene root: Blender's glTF
        # importer puts every character of scene.glb in one armature, bones named "<character>:<joint>")
        assert sorted(arms) == ["Eve", "Quentin"]
    bones = {b: a for a in arms.values() for b in a["bones"]}
    for m in motions:
        bvh = parse_bvh(motion_bvh(m)).global_positions()
        names = [f"{m.character}:{n}" for n in JOINT_NAMES]
        assert set(names) <= set(bones)
        for f in FRAMES:
            frame = min(f, len(bvh) - 1)  # Quentin's 25 frames: Blender holds the last key after it
            err = max(
                np.linalg.norm(
                    np.array(bones[b]["frames"][str(f)][b]) - bvh[frame, JOINT_INDEX[b.split(":")[-1]]]
                )
                for b in names
            )
            assert err < 0.01, f"{source} {m.character} frame {f}: {err * 100:.3f} cm"


def test_the_animation_spans_the_same_frames_in_the_fbx_and_the_glb(read_back):
    assert read_back["fbx"]["frame_range"] == read_back["glb"]["frame_range"] == [0.0, 39.0]


def test_each_skin_is_weighted_to_its_own_characters_joints(read_back):
    meshes = read_back["fbx"]["meshes"]
    by_armature = {m["armature"]: m for m in meshes.values()}
    assert sorted(by_armature) == ["Eve", "Quentin"]
    for name, mesh in by_armature.items():
        assert sorted(mesh["vertex_groups"]) == sorted(f"{name}:{n}" for n in JOINT_NAMES)
        assert mesh["vertices"] == len(character_for(name).vertices)


def test_the_held_prop_and_the_camera_move_as_in_the_video(exported, read_back):
    _, _, scene, motions = exported
    moving = read_back["fbx"]["moving"]
    cup = next(v for k, v in moving.items() if k.startswith("cup"))
    held = from_wire(motions[0].props[0].position)
    assert np.allclose(cup["frames"]["15"], held[15 - 10], atol=0.01)
    assert np.allclose(cup["frames"]["0"], scene.objects[-1].position, atol=0.01)
    camera = next(v for v in moving.values() if v["type"] == "CAMERA")
    track = Staging.build(scene, motions, []).camera_track(640, 480)
    for f in FRAMES:
        assert np.allclose(camera["frames"][str(f)], track.eye[f], atol=0.01), f
