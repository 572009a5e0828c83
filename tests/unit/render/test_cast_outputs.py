"""`--cast` in every output: the MP4 (open3d) draws the user's mesh skinned on its own joints, the BVH has the
rig's joint names, hierarchy and bones, and both put the joints where the GLB puts them. The rigs are the
ones tests/unit/render/test_cast.py builds (Mixamo in centimetres; Unreal, A-pose, long legs, twist and
finger joints; unknown names with a map)."""

from __future__ import annotations

import numpy as np
import pytest

from proto.common import Header
from proto.render import CastMember, ExportRequest
from services.render.camera import project
from services.render.cast_gltf import load_cast
from services.render.cast_skin import CastBody, posed_world
from services.render.demo import demo_scene, walk_motion
from services.render.gltf_export import scene_glb
from services.render.handlers import handle_export
from services.render.renderer import FrameRenderer
from services.render.video import probe
from tests.unit.render.test_cast import RIGS, _glb, _world_at
from wana.cast import read_rig
from wana.domain.bvh import parse_bvh

W, H = 160, 120
FRAMES = [0, 17, 35]


@pytest.fixture(scope="module")
def walk():
    return walk_motion("Eve", (-2.0, 1.0), (1.0, -1.0), 40)


def _member(kind: str) -> CastMember:
    data, joint_map = RIGS[kind]
    return CastMember(name="Eve", glb=data, joint_map=joint_map)


@pytest.mark.parametrize("kind", sorted(RIGS))
def test_the_bodys_joints_are_the_glbs(kind, walk):
    """The renderer's and the BVH's joints are the GLB's (read by glTF's rules) on every sampled frame."""
    cast = load_cast([_member(kind)])
    doc, blob = _glb(scene_glb(demo_scene(), [walk], cast=cast))
    names = cast["Eve"].rig.names
    world = posed_world(cast["Eve"], walk)
    for f in FRAMES:
        glb = _world_at(doc, blob, f, names)
        ours = world[f, :, :3, 3]
        assert max(np.linalg.norm(ours[j] - glb[n]) for j, n in enumerate(names)) < 1e-4


@pytest.mark.parametrize("kind", sorted(RIGS))
def test_the_bvh_has_the_users_skeleton(kind, walk):
    member = _member(kind)
    reply = handle_export(
        ExportRequest(header=Header(), format="bvh", scene=demo_scene(), motions=[walk], cast=[member])
    )
    clip = parse_bvh(reply.data.decode())
    rig = read_rig(member.glb)
    assert sorted(clip.joint_names) == sorted(rig.names)  # twist and finger joints included
    assert clip.n_frames == 40
    pos, _ = clip.global_transforms()
    world = posed_world(load_cast([member])["Eve"], walk)[..., :3, 3]
    order = [clip.joint_names.index(n) for n in rig.names]
    assert np.abs(pos[:, order] - world).max() < 1e-4  # metres, every joint, every frame
    for j, n in enumerate(rig.names):  # each joint under its own parent
        p = int(rig.parents[j])
        expect = rig.names[p] if p >= 0 else None
        got = clip.parents[clip.joint_names.index(n)]
        assert (clip.joint_names[got] if got >= 0 else None) == expect


def _silhouette(r: FrameRenderer, f: int) -> np.ndarray:
    a, b = r.render(f).astype(int), r.render(f, hide_characters=True).astype(int)
    return np.abs(a - b).sum(axis=2) > 30


@pytest.mark.parametrize("kind", ["mixamo", "unreal"])
def test_the_video_draws_the_users_mesh(kind, walk):
    cast = load_cast([_member(kind)])
    body = CastBody.build(cast["Eve"], walk)
    with (
        FrameRenderer(demo_scene(), [walk], width=W, height=H, cast=cast) as own,
        FrameRenderer(demo_scene(), [walk], width=W, height=H) as builtin,
    ):
        assert own.n_frames == builtin.n_frames
        for f in FRAMES:
            mask = _silhouette(own, f)
            assert mask.sum() > 30
            uv, z = project(body.vertices([f])[0], own.camera(f), W, H)
            inside = (z > 0) & (uv[:, 0] >= 0) & (uv[:, 0] < W) & (uv[:, 1] >= 0) & (uv[:, 1] < H)
            near = mask.copy()  # a vertex on the outline may round to the pixel beside the body
            near[1:] |= mask[:-1]
            near[:-1] |= mask[1:]
            near[:, 1:] |= near[:, :-1].copy()
            near[:, :-1] |= near[:, 1:].copy()
            px = np.clip(np.round(uv[inside]).astype(int), 0, [W - 1, H - 1])
            assert near[px[:, 1], px[:, 0]].mean() > 0.9, "the user's vertices land on the drawn body"
            ys, xs = np.nonzero(mask)
            assert np.abs(np.array([xs.mean(), ys.mean()]) - uv[inside].mean(axis=0)).max() < 0.05 * W
            theirs = _silhouette(builtin, f)
            assert (mask != theirs).sum() > 0.2 * mask.sum(), "not the built-in body"


def test_the_mp4_export_wears_the_cast(walk):
    base = {"header": Header(), "format": "mp4", "scene": demo_scene(), "motions": [walk], "width": 96}
    own = handle_export(ExportRequest(**base, height=72, cast=[_member("unreal")]))
    builtin = handle_export(ExportRequest(**base, height=72))
    assert own.n_frames == builtin.n_frames == probe(own.data)["frames"]
    assert own.data != builtin.data


@pytest.mark.parametrize("kind", sorted(RIGS))
def test_the_usd_has_the_users_skeleton_and_skin(kind, walk, tmp_path):
    pytest.importorskip("pxr", reason="needs Pixar's usd-core (pip install usd-core)")
    from pxr import Usd, UsdGeom, UsdSkel

    from tests.unit.render.test_export_usd import _validation_errors

    member = _member(kind)
    reply = handle_export(
        ExportRequest(header=Header(), format="usd", scene=demo_scene(), motions=[walk], cast=[member])
    )
    path = tmp_path / "animation.usdc"
    path.write_bytes(reply.data)
    stage = Usd.Stage.Open(str(path))
    assert _validation_errors(stage) == []
    cast = load_cast([member])["Eve"]
    skel = UsdSkel.Skeleton(stage.GetPrimAtPath("/World/Eve/Skeleton"))
    assert sorted(skel.GetJointNamesAttr().Get()) == sorted(cast.rig.names)  # the file's own names
    cache = UsdSkel.Cache()
    cache.Populate(UsdSkel.Root(stage.GetPrimAtPath("/World/Eve")), Usd.TraverseInstanceProxies())
    query = cache.GetSkelQuery(skel)
    order = [list(cast.rig.names).index(n) for n in skel.GetJointNamesAttr().Get()]
    world = posed_world(cast, walk)
    body = CastBody.build(cast, walk)
    for f in FRAMES:
        t = Usd.TimeCode(f)
        joints = np.array(
            [m.ExtractTranslation() for m in query.ComputeJointWorldTransforms(UsdGeom.XformCache(t))]
        )
        # 1 mm: UsdSkel's scales are half floats, and a Mixamo rig's root carries its armature's 0.01
        assert np.abs(joints - world[f][order][:, :3, 3]).max() < 1e-3
        xforms = query.ComputeSkinningTransforms(t)
        skinned = []
        for k in range(len(cast.rig.primitives)):
            prim = stage.GetPrimAtPath("/World/Eve/Body" if k == 0 else f"/World/Eve/Body_{k}")
            points = UsdGeom.Mesh(prim).GetPointsAttr().Get(t)
            assert cache.GetSkinningQuery(prim).ComputeSkinnedPoints(xforms, points, t)
            skinned.append(np.array(points))
        assert np.abs(np.concatenate(skinned) - body.vertices([f])[0]).max() < 1e-3  # the MP4's mesh


def test_a_render_request_chunk_wears_the_cast_too(walk):
    """The frame-range protocol (one RenderRequest per range, any worker) carries the cast as exports do."""
    from proto.render import RenderRequest
    from services.render.handlers import handle_render

    base = {"header": Header(), "scene": demo_scene(), "motions": [walk], "width": 96, "height": 72}
    own = handle_render(RenderRequest(**base, start_frame=10, end_frame=12, cast=[_member("mixamo")]))
    builtin = handle_render(RenderRequest(**base, start_frame=10, end_frame=12))
    assert len(own.frames) == len(builtin.frames) == 2
    assert own.frames[0] != builtin.frames[0]
    with FrameRenderer(demo_scene(), [walk], width=96, height=72, cast=load_cast([_member("mixamo")])) as r:
        import io

        from PIL import Image

        got = np.asarray(Image.open(io.BytesIO(own.frames[0])).convert("RGB"))
        assert np.abs(got.astype(int) - r.render(10).astype(int)).max() <= 2  # PNG: the same pixels
