"""The video's camera as an animated glTF camera node, so Blender and three.js play the same shots.

One perspective camera (``yfov`` of the first frame, ``aspectRatio`` of the video) on a node named
"camera" whose translation and rotation are keyed on every frame (glTF cameras look down their local
-Z with +Y up). The director's field of view changes between shots; the standard has no animated
``yfov``, so it is keyed through ``KHR_animation_pointer`` (listed as used, not required: a viewer
without it keeps the first shot's yfov) and every frame's value is also in the node's extras.

    add_camera(builder, track, animation, fps)  # services.render.gltf_export.scene_glb does this
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from services.render.staging import CameraTrack

FLOAT = 5126
ZNEAR, ZFAR = 0.05, 100.0  # metres: the renderer's clip planes
POINTER = "KHR_animation_pointer"


def camera_rotations(track: CameraTrack) -> np.ndarray:
    """(T, 4) glTF node rotations (x, y, z, w) whose local -Z looks from each eye to its target."""
    out = np.zeros((len(track), 4))
    for f in range(len(track)):
        rot = track.pose(f).rotation()  # rows: right, down, forward (OpenCV)
        world_from_local = np.stack([rot[0], -rot[1], -rot[2]], axis=1)  # columns: x right, y up, z back
        out[f] = Rotation.from_matrix(world_from_local).as_quat()
    return out


def add_camera(b: Any, track: CameraTrack, animation: dict, fps: float) -> int:
    """Add the camera node and its channels; returns the node index.

    Args:
        b: the GLB builder (services.render.gltf_export._Builder).
        track: every frame's camera (services.render.staging.Staging.camera_track).
        animation: the glTF animation the characters' channels go in (samplers, channels).
        fps: frames per second of the keys.
    """
    fov = np.radians(np.asarray(track.fov_deg, dtype=np.float64))
    b.doc.setdefault("cameras", []).append(
        {
            "name": "director",
            "type": "perspective",
            "perspective": {
                "yfov": float(fov[0]) if len(fov) else float(np.radians(55.0)),
                "aspectRatio": track.width / track.height,
                "znear": ZNEAR,
                "zfar": ZFAR,
            },
        }
    )
    cam = len(b.doc["cameras"]) - 1
    node = b.node(
        {
            "name": "camera",
            "camera": cam,
            "translation": [float(x) for x in track.eye[0]] if len(track) else [0.0, 0.0, 0.0],
            "extras": {"yfov_per_frame": [round(float(x), 6) for x in fov], "fps": fps},
        },
        root=True,
    )
    if not len(track):
        return node
    times = b.accessor((np.arange(len(track), dtype=np.float64) / fps).astype(np.float32), FLOAT, bounds=True)
    samplers, channels = animation["samplers"], animation["channels"]

    def sampler(values: np.ndarray) -> int:
        samplers.append(
            {
                "input": times,
                "output": b.accessor(values.astype(np.float32), FLOAT),
                "interpolation": "LINEAR",
            }
        )
        return len(samplers) - 1

    channels.append({"sampler": sampler(track.eye), "target": {"node": node, "path": "translation"}})
    channels.append(
        {"sampler": sampler(camera_rotations(track)), "target": {"node": node, "path": "rotation"}}
    )
    if np.ptp(fov) > 1e-6:
        pointer = {POINTER: {"pointer": f"/cameras/{cam}/perspective/yfov"}}
        channels.append({"sampler": sampler(fov), "target": {"path": "pointer", "extensions": pointer}})
        used = b.doc.setdefault("extensionsUsed", [])
        if POINTER not in used:
            used.append(POINTER)
    return node
