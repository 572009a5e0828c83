"""USD export: read back with pxr (UsdSkel joint world positions against the BVH, skin, props, camera) and
USD's own validators (what `usdchecker` runs) report nothing."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from proto.common import Header
from proto.motion_data import Motion, PropTrack
from proto.render import ExportRequest
from proto.scene import PlacedObject, Scene
from services.render.bvh_export import motion_bvh
from services.render.demo import demo_scene, walk_motion
from services.render.handlers import handle_export
from services.render.skinning import Rig, character_for
from services.render.staging import Staging
from wana.arrays import from_wire, to_wire
from wana.domain.bvh import parse_bvh
from wana.domain.skeleton import JOINT_INDEX, JOINT_NAMES

pxr = pytest.importorskip("pxr", reason="needs Pixar's usd-core (pip install usd-core)")
from pxr import Gf, Usd, UsdGeom, UsdSkel, UsdValidation  # noqa: E402

FRAMES = (0, 7, 19, 33, 39)


def _scene_and_motions() -> tuple[Scene, list[Motion]]:
    base = demo_scene()
    cup = PlacedObject(id="cup", category="cup", position=(-1.0, 0.75, -1.5), yaw=0.0)
    scene = Scene(room=base.room, objects=[*base.objects, cup], seed=base.seed)
    eve = walk_motion("Eve", (-2.0, 1.0), (1.0, -1.0), 40)
    hand = Rig.from_motion(eve).joint_positions[10:30, JOINT_INDEX["RightHand"]]
    turn = Rotation.from_euler("y", np.linspace(0.0, 1.5, 20)[:, None]).as_quat()
    track = PropTrack(
        object_id="cup",
        joint="RightHand",
        start_frame=10,
        end_frame=30,
        position=to_wire(hand.astype(np.float32)),
        rotation=to_wire(turn.astype(np.float32)),
    )
    present = np.ones(25, dtype=np.uint8)
    present[:5] = 0  # Quentin walks on at frame 5
    quentin = walk_motion("Quentin", (1.0, 1.5), (0.0, 0.0), 25)
    eve = Motion(**{**{f: getattr(eve, f) for f in eve.__struct_fields__}, "props": [track]})
    quentin = Motion(
        **{**{f: getattr(quentin, f) for f in quentin.__struct_fields__}, "present": to_wire(present)}
    )
    return scene, [eve, quentin]


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    scene, motions = _scene_and_motions()
    reply = handle_export(ExportRequest(header=Header(), format="usd", scene=scene, motions=motions))
    path = tmp_path_factory.mktemp("usd") / reply.filename
    path.write_bytes(reply.data)
    return reply, path, scene, motions


def test_the_reply_is_a_binary_usd_named_animation_usdc(exported):
    reply, path, _, _ = exported
    assert reply.format == "usd" and reply.filename == "animation.usdc"
    assert reply.data[:8] == b"PXR-USDC"  # the crate file's magic
    assert reply.n_frames == 40 and reply.shots


def test_the_stage_is_in_metres_y_up_at_30_frames_per_second(exported):
    stage = Usd.Stage.Open(str(exported[1]))
    assert UsdGeom.GetStageUpAxis(stage) == UsdGeom.Tokens.y
    assert UsdGeom.GetStageMetersPerUnit(stage) == 1.0
    assert stage.GetTimeCodesPerSecond() == 30.0
    assert (stage.GetStartTimeCode(), stage.GetEndTimeCode()) == (0.0, 39.0)
    assert stage.GetDefaultPrim().GetPath() == "/World"


def _usd_joint_positions(
    stage: Usd.Stage, root: str, frames: tuple[int, ...]
) -> tuple[list[str], np.ndarray]:
    cache = UsdSkel.Cache()
    skel_root = UsdSkel.Root(stage.GetPrimAtPath(root))
    cache.Populate(skel_root, Usd.TraverseInstanceProxies())
    query = cache.GetSkelQuery(UsdSkel.Skeleton(stage.GetPrimAtPath(f"{root}/Skeleton")))
    assert query and query.GetAnimQuery()
    out = []
    for f in frames:
        xf = UsdGeom.XformCache(Usd.TimeCode(f))
        world = query.ComputeJointWorldTransforms(xf)
        out.append([np.array(m.ExtractTranslation()) for m in world])
    names = [str(t).split("/")[-1] for t in query.GetJointOrder()]
    return names, np.array(out)


@pytest.mark.parametrize("character", ["Eve", "Quentin"])
def test_every_joint_reads_back_within_1_cm_of_the_bvh(exported, character):
    _, path, _, motions = exported
    motion = next(m for m in motions if m.character == character)
    bvh = parse_bvh(motion_bvh(motion)).global_positions()
    frames = tuple(f for f in FRAMES if f < len(bvh))
    names, usd = _usd_joint_positions(Usd.Stage.Open(str(path)), f"/World/{character}", frames)
    assert sorted(names) == sorted(JOINT_NAMES)
    order = [JOINT_INDEX[n] for n in names]
    err = np.linalg.norm(usd - bvh[list(frames)][:, order], axis=-1)
    assert err.max() < 0.01, f"{character}: {err.max() * 100:.3f} cm"


def test_the_skinned_body_follows_the_skeleton(exported):
    """UsdSkel's own skinning of the body at a frame equals the renderer's linear-blend skinning."""
    _, path, _, motions = exported
    stage = Usd.Stage.Open(str(path))
    cache = UsdSkel.Cache()
    root = UsdSkel.Root(stage.GetPrimAtPath("/World/Eve"))
    cache.Populate(root, Usd.TraverseInstanceProxies())
    query = cache.GetSkelQuery(UsdSkel.Skeleton(stage.GetPrimAtPath("/World/Eve/Skeleton")))
    skinning = cache.GetSkinningQuery(stage.GetPrimAtPath("/World/Eve/Body"))
    assert skinning and skinning.HasBlendShapes()
    body = UsdGeom.Mesh(stage.GetPrimAtPath("/World/Eve/Body"))
    rig = Rig.from_motion(motions[0])
    frame = 21
    t = Usd.TimeCode(frame)
    points = body.GetPointsAttr().Get(t)
    xforms = query.ComputeSkinningTransforms(t)
    assert skinning.ComputeSkinnedPoints(xforms, points, t)
    want = rig.character.vertices.astype(np.float64)
    # the renderer's rule: sum_k w_k * (global_k * inverse_bind_k) applied to the rest vertex
    R = Rotation.from_quat(rig.joint_rotations[frame].reshape(-1, 4))
    rest = rig.character.rest_joint_positions()
    moved = np.zeros_like(want)
    for k in range(4):
        j = rig.character.joints[:, k].astype(int)
        w = rig.character.weights[:, k].astype(np.float64)[:, None]
        local = want - rest[j]
        moved += w * (Rotation.from_quat(R.as_quat()[j]).apply(local) + rig.joint_positions[frame][j])
    assert np.abs(np.array(points) - moved).max() < 0.005


def test_the_held_prop_moves_with_its_track_and_stays_put_otherwise(exported):
    _, path, scene, motions = exported
    stage = Usd.Stage.Open(str(path))
    prim = stage.GetPrimAtPath("/World/Props/cup")
    assert prim.IsValid() and stage.GetPrimAtPath("/World/Props/cup/Geom").IsA(UsdGeom.Mesh)
    assert not stage.GetPrimAtPath("/World/Room/cup").IsValid()  # not also drawn where it was placed
    track = motions[0].props[0]
    held = from_wire(track.position)
    xf = UsdGeom.Xformable(prim)
    at = {
        f: np.array(xf.ComputeLocalToWorldTransform(Usd.TimeCode(f)).ExtractTranslation())
        for f in (5, 15, 29)
    }
    assert np.allclose(at[15], held[15 - track.start_frame], atol=1e-4)
    assert np.allclose(at[29], held[29 - track.start_frame], atol=1e-4)
    assert np.allclose(at[5], scene.objects[-1].position, atol=1e-4)


def test_an_off_stage_character_is_invisible_until_it_walks_on(exported):
    stage = Usd.Stage.Open(str(exported[1]))
    quentin = UsdGeom.Imageable(stage.GetPrimAtPath("/World/Quentin"))
    eve = UsdGeom.Imageable(stage.GetPrimAtPath("/World/Eve"))
    assert quentin.ComputeVisibility(Usd.TimeCode(2)) == UsdGeom.Tokens.invisible
    assert quentin.ComputeVisibility(Usd.TimeCode(6)) == UsdGeom.Tokens.inherited
    assert eve.ComputeVisibility(Usd.TimeCode(2)) == UsdGeom.Tokens.inherited


def test_the_camera_is_the_videos_camera(exported):
    _, path, scene, motions = exported
    track = Staging.build(scene, motions, []).camera_track(640, 480)
    stage = Usd.Stage.Open(str(path))
    cam = UsdGeom.Camera(stage.GetPrimAtPath("/World/Camera"))
    for f in (0, 20, 39):
        t = Usd.TimeCode(f)
        gf = cam.GetCamera(t)
        m = gf.transform
        eye = np.array(m.ExtractTranslation())
        forward = np.array(m.TransformDir(Gf.Vec3d(0, 0, -1)))
        want = track.target[f] - track.eye[f]
        assert np.allclose(eye, track.eye[f], atol=1e-4)
        assert np.dot(forward / np.linalg.norm(forward), want / np.linalg.norm(want)) > 0.9999
        assert gf.GetFieldOfView(Gf.Camera.FOVVertical) == pytest.approx(track.fov_deg[f], abs=0.01)


def _validation_errors(stage: Usd.Stage) -> list[str]:
    validators = UsdValidation.ValidationRegistry().GetOrLoadAllValidators()
    errors = UsdValidation.ValidationContext(validators).Validate(stage)
    return [f"{e.GetName()}: {e.GetMessage()}" for e in errors if not e.HasNoError()]


def test_usds_validators_report_no_errors(exported):
    """Every validator usd-core registers (usdchecker's checks: stage metadata, encapsulation, skel binding)."""
    assert _validation_errors(Usd.Stage.Open(str(exported[1]))) == []


def test_the_validators_do_catch_a_stage_without_units_or_skel_binding(exported):
    """The check above can fail: strip the metadata and a binding and the same validators object."""
    stage = Usd.Stage.Open(str(exported[1]))
    layer = stage.GetRootLayer()
    layer.ClearDefaultPrim()
    stage.GetPrimAtPath("/World/Eve/Body").RemoveAPI(UsdSkel.BindingAPI)
    errors = _validation_errors(stage)
    assert any("StageMetadata" in e or "defaultPrim" in e for e in errors), errors
    assert any("SkelBinding" in e for e in errors), errors


def test_the_text_form_is_the_same_stage():
    from services.render.usd_export import scene_usd

    scene, motions = _scene_and_motions()
    text = scene_usd(scene, motions, suffix=".usda")
    assert text.startswith(b"#usda 1.0")
    layer = pxr.Sdf.Layer.CreateAnonymous(".usda")
    assert layer.ImportFromString(text.decode())
    stage = Usd.Stage.Open(layer)
    assert UsdSkel.Skeleton(stage.GetPrimAtPath("/World/Eve/Skeleton"))
    assert len(stage.GetPrimAtPath("/World/Eve/Anim").GetAttribute("rotations").GetTimeSamples()) == 40


@pytest.mark.slow
def test_blenders_usd_importer_reads_both_skeletons_within_1_cm(exported):
    """Blender's own USD importer (bpy 5.0.1, in a subprocess): one armature per SkelRoot, same joints."""
    from services.render import fbx_export

    try:
        fbx_export.blender_python()
    except ModuleNotFoundError as exc:
        pytest.skip(str(exc))
    _, path, _, motions = exported
    frames = [0, 15, 39]
    read = fbx_export.probe(path, frames)
    assert read["frame_range"] == [0.0, 39.0]
    by_character = {a["parent"]: a for a in read["armatures"].values()}
    assert sorted(by_character) == ["Eve", "Quentin"]
    skins = {read["armatures"][m["armature"]]["parent"]: m for m in read["meshes"].values()}
    assert sorted(skins) == ["Eve", "Quentin"]
    for name, skin in skins.items():
        assert sorted(skin["vertex_groups"]) == sorted(JOINT_NAMES)
        assert skin["vertices"] == len(character_for(name).vertices)
    for m in motions:
        bvh = parse_bvh(motion_bvh(m)).global_positions()
        got = by_character[m.character]
        assert sorted(got["bones"]) == sorted(JOINT_NAMES)
        for f in frames:
            pos = got["frames"][str(f)]
            err = max(
                np.linalg.norm(np.array(p) - bvh[min(f, len(bvh) - 1), JOINT_INDEX[b]])
                for b, p in pos.items()
            )
            assert err < 0.01, f"{m.character} frame {f}: {err * 100:.3f} cm"


def test_a_name_that_is_no_prim_name_is_kept_as_the_display_name(tmp_path):
    from services.render.usd_export import scene_usd

    path = tmp_path / "animation.usdc"
    path.write_bytes(scene_usd(demo_scene(), [walk_motion("Mary Ann", (0.0, 0.0), (1.0, 0.0), 10)]))
    stage = Usd.Stage.Open(str(path))
    prim = stage.GetPrimAtPath("/World/Mary_Ann")
    assert prim.IsA(UsdSkel.Root) and prim.GetDisplayName() == "Mary Ann"
