"""Blender's side of FBX character input: run as a script by a Python that has ``bpy``; imports only bpy and
the standard library, so Blender never loads in a wana process.

    python bpy_to_glb.py eve.fbx eve.glb     # FBX importer -> glTF exporter (skins, no animation)
"""

from __future__ import annotations

import sys


def main(src: str, dst: str) -> None:
    import bpy

    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.fbx(filepath=src, automatic_bone_orientation=False)
    bpy.ops.export_scene.gltf(
        filepath=dst, export_format="GLB", export_skins=True, export_animations=False, export_yup=True
    )


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
