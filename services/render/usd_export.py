"""The animation as a USD stage (Pixar's ``usd-core``): UsdSkel characters, animated props, the camera.

Film pipelines interchange USD; this writes what they expect (metres, Y up, 30 time codes per second):

    /World                        Xform, the default prim
      /Room/<mesh>                the floor, walls and placed objects (displayColor per face)
      /Props/<id>                 each held prop: an Xform keyed per frame (translate, orient), its mesh below
      /<character>                SkelRoot (visibility keyed off stage)
        /Skeleton                 UsdSkel.Skeleton: joint paths "Hips/Spine/...", bind and rest transforms
        /Anim                     UsdSkel.SkelAnimation: per-frame joint translations, rotations, face weights
        /Body                     the skinned mesh (jointIndices/jointWeights, 4 per vertex) with its
          /<expression>           UsdSkel.BlendShape per face expression
      /Camera                     UsdGeom.Camera: the video's camera keyed per frame (transform, focal length)

The skeleton's rest pose has identity rotations (as in the GLB), so a bind transform is the joint's rest
position and the skinned mesh needs no geomBindTransform beyond identity. A user's own character (``--cast``)
has its own joints (names in jointNames), bind transforms from its file and one /Body per skinned primitive. pxr is imported here only, so
the render service runs without ``usd-core`` until a USD export is asked for.
"""

from __future__ import annotations

import tempfile
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from proto.motion_data import Motion
from proto.scene import Scene
from services.render.cast_gltf import CastCharacter
from services.render.gltf_camera import ZFAR, ZNEAR, camera_rotations
from services.render.scene_geometry import (
    ColouredMesh,
    held_ids,
    object_meshes,
    prop_mesh,
    prop_track,
    room_meshes,
)
from services.render.skinning import Rig
from services.render.staging import CameraTrack
from wana.arrays import from_wire
from wana.assets.characters import EXPRESSIONS
from wana.domain.skeleton import JOINT_NAMES, N_JOINTS, PARENTS

HORIZONTAL_APERTURE = (
    20.955  # millimetres, USD's default (a 35 mm film back); the focal length follows the fov
)
MISSING = "a USD export needs Pixar's usd-core (pip install usd-core, or `make setup`)"


def _pxr() -> Any:
    try:
        from pxr import Gf, Sdf, Usd, UsdGeom, UsdSkel, Vt
    except ImportError as exc:  # the optional dependency
        raise ModuleNotFoundError(MISSING) from exc
    return Gf, Sdf, Usd, UsdGeom, UsdSkel, Vt


def joint_paths() -> list[str]:
    """UsdSkel joint tokens of the canonical skeleton: each joint's path from the Hips ("Hips/Spine")."""
    paths: list[str] = []
    for j in range(N_JOINTS):
        p = int(PARENTS[j])
        paths.append(JOINT_NAMES[j] if p < 0 else f"{paths[p]}/{JOINT_NAMES[j]}")
    return paths


def _unique(name: str, taken: set[str]) -> str:
    from pxr import Tf

    base = Tf.MakeValidIdentifier(name) or "prim"
    out, k = base, 1
    while out in taken:
        k += 1
        out = f"{base}_{k}"
    taken.add(out)
    return out


def _mesh(stage: Any, path: str, mesh: ColouredMesh) -> Any:
    """A UsdGeom.Mesh of a ColouredMesh (points, triangles, per-vertex displayColor, extent)."""
    _, _, _, UsdGeom, _, Vt = _pxr()
    m = UsdGeom.Mesh.Define(stage, path)
    points = Vt.Vec3fArray.FromNumpy(np.ascontiguousarray(mesh.vertices, dtype=np.float32))
    m.CreatePointsAttr(points)
    m.CreateFaceVertexCountsAttr(Vt.IntArray.FromNumpy(np.full(len(mesh.faces), 3, dtype=np.int32)))
    m.CreateFaceVertexIndicesAttr(Vt.IntArray.FromNumpy(mesh.faces.reshape(-1).astype(np.int32)))
    m.CreateSubdivisionSchemeAttr(UsdGeom.Tokens.none)
    m.CreateExtentAttr(UsdGeom.PointBased.ComputeExtent(points))
    colours = np.ascontiguousarray(mesh.colours[:, :3], dtype=np.float32) / 255.0
    m.CreateDisplayColorPrimvar(UsdGeom.Tokens.vertex).Set(Vt.Vec3fArray.FromNumpy(colours))
    return m


def _matrix(translation: np.ndarray) -> Any:
    Gf = _pxr()[0]
    return Gf.Matrix4d(1.0).SetTranslate(Gf.Vec3d(*(float(x) for x in translation)))


def _quats(q: np.ndarray) -> Any:
    """(N, 4) quaternions (x, y, z, w) as a Vt.QuatfArray."""
    Gf, _, _, _, _, Vt = _pxr()
    return Vt.QuatfArray([Gf.Quatf(float(w), float(x), float(y), float(z)) for x, y, z, w in q])


def _add_character(stage: Any, root: str, rig: Rig) -> None:
    _, _, _, UsdGeom, UsdSkel, Vt = _pxr()
    ch = rig.character
    skel_root = UsdSkel.Root.Define(stage, root)
    skel_root.GetPrim().SetDisplayName(
        rig.name or ch.name
    )  # the story's name, e.g. "Mary Ann" at /World/Mary_Ann
    skel = UsdSkel.Skeleton.Define(stage, f"{root}/Skeleton")
    joints = joint_paths()
    offsets = ch.offsets.astype(np.float64)
    rest = ch.rest_joint_positions()
    skel.CreateJointsAttr(joints)
    skel.CreateJointNamesAttr(list(JOINT_NAMES))
    skel.CreateBindTransformsAttr(Vt.Matrix4dArray([_matrix(p) for p in rest]))
    skel.CreateRestTransformsAttr(Vt.Matrix4dArray([_matrix(o) for o in offsets]))

    anim = UsdSkel.Animation.Define(stage, f"{root}/Anim")
    anim.CreateJointsAttr(joints)
    anim.CreateScalesAttr(Vt.Vec3hArray.FromNumpy(np.ones((N_JOINTS, 3), dtype=np.float16)))
    anim.CreateBlendShapesAttr(list(EXPRESSIONS))
    translations_attr = anim.CreateTranslationsAttr()
    rotations_attr = anim.CreateRotationsAttr()
    weights_attr = anim.CreateBlendShapeWeightsAttr()
    quats = rig.rotations / np.linalg.norm(rig.rotations, axis=-1, keepdims=True)
    local = np.tile(offsets.astype(np.float32), (rig.n_frames, 1, 1))
    local[:, 0] = rig.root
    expr = np.zeros((rig.n_frames, len(EXPRESSIONS)), dtype=np.float32)
    if rig.expression is not None:
        e = rig.expression[:, : len(EXPRESSIONS)]
        expr[:, : e.shape[1]] = np.clip(e, 0.0, 1.0)
    for f in range(rig.n_frames):
        translations_attr.Set(Vt.Vec3fArray.FromNumpy(np.ascontiguousarray(local[f])), f)
        rotations_attr.Set(_quats(quats[f]), f)
        weights_attr.Set(Vt.FloatArray.FromNumpy(expr[f]), f)
    skel_binding = UsdSkel.BindingAPI.Apply(skel.GetPrim())
    skel_binding.CreateAnimationSourceRel().SetTargets([anim.GetPath()])

    body = _mesh(
        stage,
        f"{root}/Body",
        ColouredMesh(
            name=rig.name, vertices=ch.vertices, faces=ch.faces.astype(np.int64), colours=ch.colours
        ),
    )
    binding = UsdSkel.BindingAPI.Apply(body.GetPrim())
    binding.CreateSkeletonRel().SetTargets([skel.GetPath()])
    binding.CreateJointIndicesPrimvar(False, 4).Set(
        Vt.IntArray.FromNumpy(ch.joints.astype(np.int32).reshape(-1))
    )
    binding.CreateJointWeightsPrimvar(False, 4).Set(
        Vt.FloatArray.FromNumpy(ch.weights.astype(np.float32).reshape(-1))
    )
    binding.CreateGeomBindTransformAttr(_matrix(np.zeros(3)))
    shapes = []
    for k in EXPRESSIONS:
        shape = UsdSkel.BlendShape.Define(stage, f"{root}/Body/{k}")
        offsets_k = ch.blendshapes.get(k, np.zeros_like(ch.vertices))
        shape.CreateOffsetsAttr(Vt.Vec3fArray.FromNumpy(np.ascontiguousarray(offsets_k, dtype=np.float32)))
        shapes.append(shape.GetPath())
    binding.CreateBlendShapesAttr(list(EXPRESSIONS))
    binding.CreateBlendShapeTargetsRel().SetTargets(shapes)

    if rig.present is not None and len(rig.present) == rig.n_frames and not rig.present.all():
        visibility = skel_root.CreateVisibilityAttr()  # a token holds its value: off and on, never faded
        for f in range(rig.n_frames):
            if f == 0 or rig.present[f] != rig.present[f - 1]:
                visibility.Set(UsdGeom.Tokens.inherited if rig.present[f] else UsdGeom.Tokens.invisible, f)


def _trs(m: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(T, J, 4, 4) matrices without shear as translations (T, J, 3), rotations (T, J, 4) x, y, z, w and
    scales (T, J, 3)."""
    from scipy.spatial.transform import Rotation

    scale = np.linalg.norm(m[..., :3, :3], axis=-2)
    rot = m[..., :3, :3] / np.maximum(scale[..., None, :], 1e-12)
    quats = Rotation.from_matrix(rot.reshape(-1, 3, 3)).as_quat().reshape(*m.shape[:-2], 4)
    return m[..., :3, 3], quats, scale


def _add_cast_character(stage: Any, root: str, name: str, cast: CastCharacter, motion: Motion) -> None:
    """The user's own character (services.render.cast_gltf): its joints (names kept as jointNames, paths made
    of valid identifiers, parents first as UsdSkel wants), the retargeted motion, one skinned mesh per
    primitive bound as glTF binds it (skinning in world space: the rig's base matrix is in the root joints)."""
    from pxr import Gf, Tf

    from services.render.cast_skin import posed_local, vertex_colours
    from wana.cast.glb_rig import topological

    _, _, _, UsdGeom, UsdSkel, Vt = _pxr()
    rig = cast.rig
    order = topological(rig.parents)  # USD joint k is rig joint order[k]
    index = {j: k for k, j in enumerate(order)}
    paths: dict[int, str] = {}
    siblings: dict[str, set[str]] = {}
    for j in order:
        p = int(rig.parents[j])
        above = paths[p] if p >= 0 else ""
        leaf = _unique(Tf.MakeValidIdentifier(rig.names[j]), siblings.setdefault(above, set()))
        paths[j] = f"{above}/{leaf}" if above else leaf
    joints = [paths[j] for j in order]
    skel_root = UsdSkel.Root.Define(stage, root)
    skel_root.GetPrim().SetDisplayName(name)
    skel = UsdSkel.Skeleton.Define(stage, f"{root}/Skeleton")
    skel.CreateJointsAttr(joints)
    skel.CreateJointNamesAttr([rig.names[j] for j in order])
    rest = rig.local_matrices()
    roots = rig.parents < 0
    rest[roots] = rig.base @ rest[roots]
    bind = {j: np.linalg.inv(skin.inverse_bind[k]) for skin in rig.skins for k, j in enumerate(skin.joints)}
    world_rest = rig.rest_world()

    def mats(ms: list[np.ndarray]) -> Any:
        return Vt.Matrix4dArray([Gf.Matrix4d(*(float(x) for x in m.T.reshape(-1))) for m in ms])

    skel.CreateRestTransformsAttr(mats([rest[j] for j in order]))
    skel.CreateBindTransformsAttr(mats([bind.get(j, world_rest[j]) for j in order]))
    local = posed_local(cast, motion, off_stage_scale=False)
    local[:, roots] = rig.base[None] @ local[:, roots]
    translations, rotations, scales = _trs(local[:, order])
    anim = UsdSkel.Animation.Define(stage, f"{root}/Anim")
    anim.CreateJointsAttr(joints)
    t_attr, r_attr, s_attr = (
        anim.CreateTranslationsAttr(),
        anim.CreateRotationsAttr(),
        anim.CreateScalesAttr(),
    )
    for f in range(local.shape[0]):
        t_attr.Set(Vt.Vec3fArray.FromNumpy(np.ascontiguousarray(translations[f], dtype=np.float32)), f)
        r_attr.Set(_quats(rotations[f]), f)
        s_attr.Set(Vt.Vec3hArray.FromNumpy(np.ascontiguousarray(scales[f], dtype=np.float16)), f)
    UsdSkel.BindingAPI.Apply(skel.GetPrim()).CreateAnimationSourceRel().SetTargets([anim.GetPath()])
    for k, prim in enumerate(rig.primitives):
        skin = rig.skins[prim.skin]
        mesh = _mesh(
            stage,
            f"{root}/Body" if k == 0 else f"{root}/Body_{k}",
            ColouredMesh(
                name=name,
                vertices=prim.positions.astype(np.float64),
                faces=prim.indices.reshape(-1, 3).astype(np.int64),
                colours=np.round(vertex_colours(prim) * 255.0).astype(np.uint8),
            ),
        )
        binding = UsdSkel.BindingAPI.Apply(mesh.GetPrim())
        binding.CreateSkeletonRel().SetTargets([skel.GetPath()])
        to_skel = np.array([index[int(j)] for j in skin.joints], dtype=np.int32)
        weights = prim.weights.astype(np.float32)
        weights = weights / np.maximum(weights.sum(axis=1, keepdims=True), 1e-9)
        binding.CreateJointIndicesPrimvar(False, 4).Set(
            Vt.IntArray.FromNumpy(np.where(weights > 0, to_skel[prim.joints.astype(np.int64)], 0).reshape(-1))
        )
        binding.CreateJointWeightsPrimvar(False, 4).Set(Vt.FloatArray.FromNumpy(weights.reshape(-1)))
        binding.CreateGeomBindTransformAttr(_matrix(np.zeros(3)))
    if motion.present is not None:
        present = from_wire(motion.present).astype(bool)
        if len(present) == local.shape[0] and not present.all():
            visibility = skel_root.CreateVisibilityAttr()
            for f in range(len(present)):
                if f == 0 or present[f] != present[f - 1]:
                    visibility.Set(UsdGeom.Tokens.inherited if present[f] else UsdGeom.Tokens.invisible, f)


def _add_props(stage: Any, scene: Scene, motions: list[Motion], n_frames: int) -> None:
    Gf, _, _, UsdGeom, _, _ = _pxr()
    held = held_ids(motions)
    if not held or n_frames == 0:
        return
    UsdGeom.Scope.Define(stage, "/World/Props")
    taken: set[str] = set()
    for placed in scene.objects:
        if placed.id not in held:
            continue
        path = f"/World/Props/{_unique(placed.id, taken)}"
        xf = UsdGeom.Xform.Define(stage, path)
        translate, orient = xf.AddTranslateOp(), xf.AddOrientOp()
        pos, rot = prop_track(placed, motions, n_frames)
        rot = rot / np.linalg.norm(rot, axis=-1, keepdims=True)
        for f in range(n_frames):
            translate.Set(Gf.Vec3d(*(float(x) for x in pos[f])), f)
            x, y, z, w = (float(v) for v in rot[f])
            orient.Set(Gf.Quatf(w, x, y, z), f)
        _mesh(stage, f"{path}/Geom", prop_mesh(placed))


def focal_lengths(track: CameraTrack) -> np.ndarray:
    """(T,) focal lengths in millimetres that give the track's vertical field of view on our film back."""
    vertical = HORIZONTAL_APERTURE * track.height / track.width
    return vertical / (2.0 * np.tan(np.radians(np.asarray(track.fov_deg, dtype=np.float64)) / 2.0))


def _add_camera(stage: Any, track: CameraTrack) -> None:
    Gf, _, _, UsdGeom, _, _ = _pxr()
    cam = UsdGeom.Camera.Define(stage, "/World/Camera")
    cam.CreateProjectionAttr(UsdGeom.Tokens.perspective)
    cam.CreateHorizontalApertureAttr(HORIZONTAL_APERTURE)
    cam.CreateVerticalApertureAttr(HORIZONTAL_APERTURE * track.height / track.width)
    cam.CreateClippingRangeAttr(Gf.Vec2f(ZNEAR, ZFAR))
    if not len(track):
        return
    focal = focal_lengths(track)
    focal_attr = cam.CreateFocalLengthAttr(float(focal[0]))
    op = cam.AddTransformOp()
    quats = camera_rotations(track)  # local -Z looks at the target, +Y up: USD's camera convention too
    from scipy.spatial.transform import Rotation

    for f in range(len(track)):
        m = np.eye(4)
        m[:3, :3] = Rotation.from_quat(quats[f]).as_matrix().T  # USD matrices act on row vectors
        m[3, :3] = track.eye[f]
        op.Set(Gf.Matrix4d(m.tolist()), f)
        if np.ptp(focal) > 1e-6:
            focal_attr.Set(float(focal[f]), f)


def build_stage(
    scene: Scene,
    motions: list[Motion],
    camera: CameraTrack | None = None,
    fps: float = 30.0,
    cast: Mapping[str, CastCharacter] | None = None,
) -> Any:
    """The in-memory ``Usd.Stage`` of the animation (layout in the module docstring); ``cast`` characters
    are the user's own skeleton and mesh (``_add_cast_character``).

    Raises:
        ModuleNotFoundError: usd-core is not installed (the message says how to install it).
    """
    _, _, Usd, UsdGeom, _, _ = _pxr()
    stage = Usd.Stage.CreateInMemory()
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.y)
    UsdGeom.SetStageMetersPerUnit(stage, 1.0)
    world = UsdGeom.Xform.Define(stage, "/World")
    stage.SetDefaultPrim(world.GetPrim())
    rigs = [Rig.from_motion(m) for m in motions]
    n = max([r.n_frames for r in rigs] + [len(camera) if camera is not None else 0])
    stage.SetTimeCodesPerSecond(fps)
    stage.SetFramesPerSecond(fps)
    stage.SetStartTimeCode(0)
    stage.SetEndTimeCode(max(n - 1, 0))
    UsdGeom.Scope.Define(stage, "/World/Room")
    taken: set[str] = {"Room", "Props", "Camera"}
    room_taken: set[str] = set()
    for mesh in room_meshes(scene.room) + object_meshes(scene, held_ids(motions)):
        if len(mesh.faces):
            _mesh(stage, f"/World/Room/{_unique(mesh.name, room_taken)}", mesh)
    _add_props(stage, scene, motions, max([r.n_frames for r in rigs], default=0))
    by_name = {m.character: m for m in motions}
    for rig in rigs:
        path = f"/World/{_unique(rig.name or rig.character.name, taken)}"
        if cast and rig.name in cast:
            _add_cast_character(stage, path, rig.name, cast[rig.name], by_name[rig.name])
        else:
            _add_character(stage, path, rig)
    if camera is not None:
        _add_camera(stage, camera)
    return stage


def scene_usd(
    scene: Scene,
    motions: list[Motion],
    camera: CameraTrack | None = None,
    fps: float = 30.0,
    suffix: str = ".usdc",
    cast: Mapping[str, CastCharacter] | None = None,
) -> bytes:
    """The bytes of the stage as a USD file: binary crate for ".usdc", text for ".usda"."""
    stage = build_stage(scene, motions, camera, fps, cast)
    with tempfile.TemporaryDirectory(prefix="wana-usd-") as tmp:
        path = Path(tmp) / f"animation{suffix}"
        stage.GetRootLayer().Export(str(path))
        return path.read_bytes()
