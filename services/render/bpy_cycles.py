"""Blender's side of the final-quality render: run as a script by a Python that has ``bpy``.

It imports only ``bpy`` and the standard library and is never imported by the render worker
(services.render.cycles runs it in a subprocess, one per frame range):

    python bpy_cycles.py scene.glb job.json OUTDIR

``scene.glb`` is the GLB the pipeline writes (room, skinned characters, held props, the director's camera
keyed on every frame); ``job.json`` says which frames and how: ``{"start", "end", "width", "height",
"samples", "threads", "sun": [x, y, z] (Y up, towards the sun), "background": [r, g, b] (0..1 sRGB), "yfov": [radians per frame],
"denoise": bool, "hide_characters": bool}``
(hidden from the camera only: their shadows stay, as the preview's ``render(hide_characters=True)``). Frames [start, end) are written as OUTDIR/frame_00000.png... with Cycles on the CPU:
a soft sun (its disc 6 degrees wide), a grey-blue sky as bounce light, Filmic-free "Standard" colours so
the materials keep the open3d preview's colours, OpenImageDenoise when this Blender has it.
"""

from __future__ import annotations

import json
import math
import sys
import time

FRAME_RATE = 30  # wana.domain.units.FPS; this script runs in Blender's Python and cannot import wana
SUN_ANGLE_DEG = 6.0  # apparent size of the sun's disc: the shadows' penumbra
SUN_STRENGTH = 2.2
SKY_RGB = (0.62, 0.68, 0.78)
SKY_STRENGTH = 0.8  # the bounce light from the sky; what the camera sees there is the job's background
SRGB_GAMMA = 2.2  # our COLOR_0 holds the preview's sRGB bytes; Cycles shades in linear light


def _z_up(v: list[float]) -> tuple[float, float, float]:
    """Our Y-up (x, y, z) as Blender's Z-up (x, -z, y)."""
    return (float(v[0]), -float(v[2]), float(v[1]))


def _scene_from(glb: str):  # noqa: ANN202 - a bpy.types.Scene
    import bpy

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.fps, scene.render.fps_base = FRAME_RATE, 1.0
    bpy.ops.import_scene.gltf(filepath=glb)
    shapes = {pb.custom_shape for o in scene.objects if o.type == "ARMATURE" for pb in o.pose.bones}
    for shape in shapes - {None}:  # the importer's display shapes for bones: helpers, not scene
        bpy.data.objects.remove(shape, do_unlink=True)
    return scene


def _linear_colours() -> None:
    """Vertex colours through gamma 2.2 (sRGB bytes to linear light), so that after the view's sRGB
    transform a lit surface has the preview's colour; image textures keep their own colour space."""
    import bpy

    for mat in bpy.data.materials:
        if not mat.node_tree:
            continue
        nodes, links = mat.node_tree.nodes, mat.node_tree.links
        for source in [n for n in nodes if n.type == "VERTEX_COLOR"]:
            for link in list(source.outputs["Color"].links):
                gamma = nodes.new("ShaderNodeGamma")
                gamma.inputs["Gamma"].default_value = SRGB_GAMMA
                links.new(source.outputs["Color"], gamma.inputs["Color"])
                links.new(gamma.outputs["Color"], link.to_socket)


def _one_sided() -> None:
    """Every surface seen from behind is see-through, as the preview culls back faces: the room's walls face
    inwards, so a camera outside a wall looks through it into the room (closed meshes are unchanged)."""
    import bpy

    for mat in bpy.data.materials:
        if not mat.node_tree:
            continue
        nodes, links = mat.node_tree.nodes, mat.node_tree.links
        out = next((n for n in nodes if n.type == "OUTPUT_MATERIAL"), None)
        if out is None or not out.inputs["Surface"].links:
            continue
        shader = out.inputs["Surface"].links[0].from_socket
        geometry = nodes.new("ShaderNodeNewGeometry")
        clear = nodes.new("ShaderNodeBsdfTransparent")
        mix = nodes.new("ShaderNodeMixShader")
        links.new(geometry.outputs["Backfacing"], mix.inputs["Fac"])
        links.new(shader, mix.inputs[1])
        links.new(clear.outputs["BSDF"], mix.inputs[2])
        links.new(mix.outputs["Shader"], out.inputs["Surface"])


def _light(scene, sun: list[float], background: list[float]) -> None:  # noqa: ANN001
    import bpy
    from mathutils import Vector

    data = bpy.data.lights.new("wana_sun", type="SUN")
    data.energy = SUN_STRENGTH
    data.angle = math.radians(SUN_ANGLE_DEG)
    lamp = bpy.data.objects.new("wana_sun", data)
    scene.collection.objects.link(lamp)
    towards = Vector(_z_up(sun)).normalized()
    lamp.rotation_euler = (-towards).to_track_quat("-Z", "Y").to_euler()  # the light shines down its -Z
    world = bpy.data.worlds.new("wana_sky")
    if hasattr(world, "use_nodes"):
        world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    sky = next(n for n in nodes if n.type == "BACKGROUND")
    sky.inputs["Color"].default_value = (*SKY_RGB, 1.0)
    sky.inputs["Strength"].default_value = SKY_STRENGTH
    seen = nodes.new("ShaderNodeBackground")  # what camera rays see: the preview's background colour
    seen.inputs["Color"].default_value = (*(c**SRGB_GAMMA for c in background), 1.0)
    seen.inputs["Strength"].default_value = 1.0
    path = nodes.new("ShaderNodeLightPath")
    mix = nodes.new("ShaderNodeMixShader")
    out = next(n for n in nodes if n.type == "OUTPUT_WORLD")
    links.new(path.outputs["Is Camera Ray"], mix.inputs["Fac"])
    links.new(sky.outputs["Background"], mix.inputs[1])
    links.new(seen.outputs["Background"], mix.inputs[2])
    links.new(mix.outputs["Shader"], out.inputs["Surface"])
    scene.world = world


def _cycles(scene, job: dict) -> bool:  # noqa: ANN001
    """Cycles on the CPU with the job's samples; whether the denoiser is on."""

    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = int(job["samples"])
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.max_bounces = 4
    scene.cycles.diffuse_bounces = 2
    scene.cycles.glossy_bounces = 1
    scene.cycles.transmission_bounces = 2
    scene.cycles.seed = 0
    if job.get("threads"):
        scene.render.threads_mode = "FIXED"
        scene.render.threads = int(job["threads"])
    denoise = bool(job.get("denoise", True))
    if denoise:
        try:
            scene.cycles.denoiser = "OPENIMAGEDENOISE"
        except TypeError:  # a Blender built without OpenImageDenoise
            denoise = False
    scene.cycles.use_denoising = denoise
    scene.render.resolution_x, scene.render.resolution_y = int(job["width"]), int(job["height"])
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_mode = "RGB"
    return denoise


def render(glb: str, job_path: str, outdir: str) -> dict:
    """Frames [start, end) of the GLB's camera as PNGs; what was done (frames, seconds, denoiser)."""
    import bpy

    with open(job_path, encoding="utf-8") as f:
        job = json.load(f)
    t0 = time.perf_counter()
    scene = _scene_from(glb)
    cameras = [o for o in scene.objects if o.type == "CAMERA"]
    if not cameras:
        raise SystemExit("the GLB has no camera (scene_glb is given the director's camera track)")
    cam = next((o for o in cameras if o.name == "camera"), cameras[0])
    scene.camera = cam
    cam.data.sensor_fit = "VERTICAL"
    cam.data.clip_start, cam.data.clip_end = 0.05, 100.0
    if job.get("hide_characters"):
        for o in scene.objects:
            if o.type == "MESH" and any(m.type == "ARMATURE" for m in o.modifiers):
                o.visible_camera = False
    _linear_colours()
    _one_sided()
    _light(scene, job["sun"], job.get("background", list(SKY_RGB)))
    denoise = _cycles(scene, job)
    yfov = job.get("yfov") or []
    t_setup = time.perf_counter() - t0
    done = 0
    for frame in range(int(job["start"]), int(job["end"])):
        scene.frame_set(frame)
        if yfov:
            cam.data.angle_y = float(yfov[min(frame, len(yfov) - 1)])
        scene.render.filepath = f"{outdir}/frame_{frame:05d}.png"
        bpy.ops.render.render(write_still=True)
        done += 1
    return {
        "frames": done,
        "setup_s": t_setup,
        "render_s": time.perf_counter() - t0 - t_setup,
        "denoise": denoise,
        "blender": bpy.app.version_string,
    }


def main(argv: list[str]) -> int:
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    print("WANA_CYCLES " + json.dumps(render(*argv)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
