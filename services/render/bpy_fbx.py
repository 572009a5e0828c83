"""Blender's side of the FBX export: run as a script by a Python that has ``bpy`` (Blender as a module).

It imports only ``bpy`` and the standard library and is never imported by the render worker
(services.render.fbx_export runs it in a subprocess), so Blender never loads in a worker's process.

    python bpy_fbx.py export scene.glb animation.fbx     # glTF importer -> FBX exporter, animation baked
    python bpy_fbx.py probe animation.fbx 0 15 30        # JSON: joint world positions at those frames,
                                                         # the skin's joint names, the frame range

The probe re-imports a file (.fbx, .glb or .usdc/.usda) with Blender's own importer; the round-trip tests
and the README's compatibility table are made with it.
"""

from __future__ import annotations

import json
import sys

FRAME_RATE = 30  # wana.domain.units.FPS; this script runs in Blender's Python and cannot import wana


def _y_up(v) -> list[float]:  # noqa: ANN001 - a mathutils.Vector
    """Blender's Z-up world (x, y, z) as ours and glTF's Y-up (x, z, -y)."""
    return [float(v[0]), float(v[2]), -float(v[1])]


def _fresh_scene() -> None:
    import bpy

    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.context.scene.render.fps = FRAME_RATE
    bpy.context.scene.render.fps_base = 1.0


def _import(path: str) -> None:
    import bpy

    if path.lower().endswith((".glb", ".gltf")):
        bpy.ops.import_scene.gltf(filepath=path)
    elif path.lower().endswith((".usd", ".usdc", ".usda")):
        bpy.ops.wm.usd_import(filepath=path, import_skeletons=True, import_blendshapes=True)
    else:
        bpy.ops.import_scene.fbx(filepath=path, use_anim=True, anim_offset=0.0)


def export(glb: str, fbx: str) -> None:
    """Our GLB through Blender's glTF importer, out through its FBX exporter (metres, Y up, -Z forward)."""
    import bpy

    _fresh_scene()
    _import(glb)
    scene = bpy.context.scene
    # the importer's display shapes for bones are helper meshes, not part of the scene
    shapes = {pb.custom_shape for o in scene.objects if o.type == "ARMATURE" for pb in o.pose.bones}
    for pb_shape in shapes - {None}:
        bpy.data.objects.remove(pb_shape, do_unlink=True)
    ends = [a.frame_range[1] for a in bpy.data.actions]
    scene.frame_start, scene.frame_end = 0, int(round(max(ends, default=0)))
    bpy.ops.export_scene.fbx(
        filepath=fbx,
        use_selection=False,
        object_types={"ARMATURE", "MESH", "CAMERA", "EMPTY"},
        apply_unit_scale=True,
        apply_scale_options="FBX_SCALE_UNITS",
        axis_forward="-Z",
        axis_up="Y",
        add_leaf_bones=False,
        use_armature_deform_only=False,
        bake_anim=True,
        bake_anim_use_all_bones=True,
        bake_anim_use_nla_strips=False,
        bake_anim_use_all_actions=False,
        bake_anim_force_startend_keying=False,  # else every static object gets keys too
        bake_anim_step=1.0,
        bake_anim_simplify_factor=0.0,  # every frame kept: the round trip is held to 1 cm
        path_mode="AUTO",
    )


def probe(path: str, frames: list[int]) -> dict:
    """What Blender reads from a file: per armature, joint world positions (metres, Y up) at the frames."""
    import bpy

    _fresh_scene()
    _import(path)
    scene = bpy.context.scene
    out: dict = {"armatures": {}, "meshes": {}, "cameras": [], "frame_range": [], "actions": {}, "moving": {}}
    ranges = [a.frame_range for a in bpy.data.actions]
    if ranges:
        out["frame_range"] = [min(r[0] for r in ranges), max(r[1] for r in ranges)]
    out["actions"] = {a.name: list(a.frame_range) for a in bpy.data.actions}
    armatures = [o for o in scene.objects if o.type == "ARMATURE"]
    for arm in armatures:
        out["armatures"][arm.name] = {
            "bones": [b.name for b in arm.pose.bones],
            "parent": arm.parent.name if arm.parent else "",  # a USD SkelRoot comes in as the parent
            "frames": {},
        }
    # objects animated on their own (held props, the camera): world positions per frame
    moving = [
        o for o in scene.objects if o.type != "ARMATURE" and o.animation_data and o.animation_data.action
    ]
    for o in moving:
        out["moving"][o.name] = {"type": o.type, "frames": {}}
    for f in frames:
        scene.frame_set(f)
        for o in moving:
            out["moving"][o.name]["frames"][str(f)] = _y_up(o.matrix_world.translation)
        for arm in armatures:
            out["armatures"][arm.name]["frames"][str(f)] = {
                b.name: _y_up(arm.matrix_world @ b.head) for b in arm.pose.bones
            }
    for o in scene.objects:
        if o.type == "MESH" and any(m.type == "ARMATURE" for m in o.modifiers):
            arm = next(m.object for m in o.modifiers if m.type == "ARMATURE")
            out["meshes"][o.name] = {
                "armature": arm.name if arm else "",
                "vertex_groups": [g.name for g in o.vertex_groups],
                "vertices": len(o.data.vertices),
            }
        if o.type == "CAMERA":
            out["cameras"].append(o.name)
    return out


def main(argv: list[str]) -> int:
    if len(argv) == 3 and argv[0] == "export":
        export(argv[1], argv[2])
        return 0
    if len(argv) >= 2 and argv[0] == "probe":
        result = probe(argv[1], [int(x) for x in argv[2:]])
        print("WANA_PROBE " + json.dumps(result))
        return 0
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
