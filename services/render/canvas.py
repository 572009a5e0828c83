"""Headless open3d rasteriser: triangle meshes, lines and points drawn offscreen into RGB arrays.

Why the legacy ``open3d.visualization.Visualizer`` and not ``rendering.OffscreenRenderer``: on this
machine (no display, Mesa llvmpipe) the Filament renderer runs on its Vulkan backend and renders the
first frame, but the next ``render_to_image`` after any ``add_geometry`` / ``remove_geometry`` /
``show_geometry`` blocks forever in ``FilamentRenderer::BeginFrame`` (a condition wait seen with gdb);
only ``set_geometry_transform`` keeps working, which cannot deform a skinned mesh. The legacy
visualizer falls back to an EGL pbuffer context on Mesa ("EGLOffscreenContext") with no display,
updates vertex buffers in place every frame and reads back colour (as bytes: services.render.readback)
and depth, at about 10 frames per second at 640x480 on one llvmpipe core. Lighting there is the renderer's fixed Phong set; weather
is applied through colours, background, fog (from the depth buffer) and particle geometry, and
shadows are projected planar shadows (see ``services.render.shadows``).

One Canvas per process is open at a time (one GL context): opening a new one closes the previous
one, whose owner reopens a fresh canvas when it draws again (``FrameRenderer`` does).
"""

from __future__ import annotations

import os
import threading
from typing import TYPE_CHECKING, cast

import numpy as np
from PIL import Image

from services.render.camera import CameraPose, intrinsics
from services.render.readback import ByteReadback

if TYPE_CHECKING:
    import open3d

os.environ.setdefault("XDG_RUNTIME_DIR", "/tmp")

Z_NEAR, Z_FAR = 0.05, 100.0  # metres: the camera's clipping planes
_LOCK = threading.Lock()  # guards _ACTIVE
_ACTIVE: list[Canvas] = []  # the open canvas, if any


def to_uint8(rgb: np.ndarray, gain: np.ndarray | None = None) -> np.ndarray:
    """(H, W, 3) float read-back in [0, 1] -> uint8, rounded; in place on one float32 buffer.

    The legacy visualiser reads back only floats; one scaled float32 copy, clipped and added to in place,
    then one cast is half the cost of ``np.clip(rgb * 255 + 0.5, 0, 255)`` (float64 temporaries).
    ``gain`` (3,) multiplies each channel in the same pass: the weather's light colour graded for free,
    instead of a second pass over the uint8 picture.
    """
    scale = 255.0 if gain is None else (np.asarray(gain, dtype=np.float32) * np.float32(255.0))
    scaled = np.multiply(rgb, scale, dtype=np.float32)
    scaled += 0.5
    np.clip(scaled, 0.0, 255.0, out=scaled)
    return scaled.astype(np.uint8)


_LEVELS = (np.arange(256, dtype=np.float32) / np.float32(255.0))[None, :, None].repeat(3, axis=2)  # k / 255


def graded(rgb: np.ndarray, gain: np.ndarray | None) -> np.ndarray:
    """(H, W, 3) uint8 read back as bytes, with ``gain`` (3,) graded: the pixels ``to_uint8`` gives the same
    picture read back as floats (a per-channel table of its 256 levels, applied by Pillow in one pass)."""
    if gain is None:
        return rgb
    table = to_uint8(_LEVELS, gain)[0]  # (256, 3)
    return np.array(Image.fromarray(rgb).point(table.T.ravel().tolist()))


class Canvas:
    """An offscreen drawing surface of a fixed size.

    Args:
        width: image width in pixels.
        height: image height in pixels.
        byte_readback: read frames back as bytes (services.render.readback) where GL allows; False: the
            visualiser's float capture (the same pixels, slower; for comparing the two).
    """

    def __init__(self, width: int = 640, height: int = 480, *, byte_readback: bool = True) -> None:
        import open3d as o3d

        if not (16 <= width <= 4096 and 16 <= height <= 4096):
            raise ValueError(f"image size must be 16..4096 pixels a side, got {width}x{height}")
        self._o3d = o3d
        o3d.utility.set_verbosity_level(o3d.utility.VerbosityLevel.Error)
        self._closed = True
        with _LOCK:
            while _ACTIVE:
                _ACTIVE.pop().close()
            self.width, self.height = int(width), int(height)
            self._vis = o3d.visualization.Visualizer()
            if not self._vis.create_window(
                window_name="wana", width=self.width, height=self.height, visible=False
            ):
                raise RuntimeError("open3d could not create an offscreen (EGL) rendering context")
            _ACTIVE.append(self)
        self._bytes = ByteReadback.open(self.width, self.height) if byte_readback else None
        opt = self._vis.get_render_option()
        opt.mesh_show_back_face = False  # walls are one-sided: the camera sees into the room through them
        opt.point_size = 3.0
        opt.line_width = 1.0
        opt.light_on = True
        self._geoms: dict[str, open3d.geometry.Geometry] = {}
        self._closed = False

    @property
    def closed(self) -> bool:
        return self._closed

    # ------------------------------------------------------------------ geometry
    def set_mesh(
        self,
        name: str,
        vertices: np.ndarray,
        faces: np.ndarray | None = None,
        colours: np.ndarray | None = None,
    ) -> None:
        """Add or update a triangle mesh.

        Args:
            name: key; a second call with the same name updates the mesh in place.
            vertices: (V, 3) world positions, metres.
            faces: (F, 3) vertex indices; only needed when the mesh is new or its topology changes.
            colours: (V, 3) RGB in [0, 1]; only needed when new or changed.
        """
        o3d = self._o3d
        old = self._geoms.get(name)
        new = old is None or faces is not None
        geom: open3d.geometry.TriangleMesh
        if new:
            if faces is None:
                raise ValueError(f"mesh {name!r} is new: faces are required")
            if old is not None:
                self._vis.remove_geometry(old, reset_bounding_box=False)
            geom = o3d.geometry.TriangleMesh()
            geom.triangles = o3d.utility.Vector3iVector(np.ascontiguousarray(faces, dtype=np.int32))
        else:
            geom = cast("open3d.geometry.TriangleMesh", old)  # a name set by set_mesh holds a triangle mesh
        geom.vertices = o3d.utility.Vector3dVector(np.ascontiguousarray(vertices, dtype=np.float64))
        if colours is not None:
            geom.vertex_colors = o3d.utility.Vector3dVector(
                np.ascontiguousarray(colours[:, :3], dtype=np.float64)
            )
        geom.compute_vertex_normals()
        if new:
            # the first geometry sets the view volume; with an empty one open3d's camera turns to NaN
            self._vis.add_geometry(geom, reset_bounding_box=not self._geoms)
            self._geoms[name] = geom
        else:
            self._vis.update_geometry(geom)

    def set_lines(self, name: str, points: np.ndarray, colour: tuple[float, float, float]) -> None:
        """Add or replace line segments: points (2N, 3), segment i joins points 2i and 2i+1."""
        o3d = self._o3d
        self.remove(name)
        if len(points) == 0:
            return
        n = len(points) // 2
        ls = o3d.geometry.LineSet(
            o3d.utility.Vector3dVector(np.asarray(points, np.float64)),
            o3d.utility.Vector2iVector(np.arange(2 * n, dtype=np.int32).reshape(n, 2)),
        )
        ls.paint_uniform_color(colour)
        self._vis.add_geometry(ls, reset_bounding_box=False)
        self._geoms[name] = ls

    def set_points(self, name: str, points: np.ndarray, colour: tuple[float, float, float]) -> None:
        """Add or replace a point cloud: points (N, 3)."""
        o3d = self._o3d
        self.remove(name)
        if len(points) == 0:
            return
        pc = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(np.asarray(points, np.float64)))
        pc.paint_uniform_color(colour)
        self._vis.add_geometry(pc, reset_bounding_box=False)
        self._geoms[name] = pc

    def remove(self, name: str) -> None:
        geom = self._geoms.pop(name, None)
        if geom is not None:
            self._vis.remove_geometry(geom, reset_bounding_box=False)

    def names(self) -> list[str]:
        return list(self._geoms)

    # ------------------------------------------------------------------ drawing
    def draw(
        self,
        pose: CameraPose,
        background: tuple[float, float, float] = (0.8, 0.85, 0.9),
        *,
        with_depth: bool = False,
        gain: np.ndarray | None = None,
    ) -> tuple[np.ndarray, np.ndarray | None]:
        """Render one frame.

        Args:
            pose: camera.
            background: RGB in [0, 1].
            with_depth: also read back the depth buffer.
            gain: (3,) per-channel light multiplier applied while converting to uint8 (None: none).

        Returns:
            rgb (H, W, 3) uint8 and, when asked, depth (H, W) float32 metres along the view axis
            (0 where nothing was drawn).
        """
        o3d = self._o3d
        opt = self._vis.get_render_option()
        opt.background_color = np.asarray(background, dtype=np.float64)
        ctl = self._vis.get_view_control()
        params = o3d.camera.PinholeCameraParameters()
        fx, fy, cx, cy = intrinsics(pose.fov_deg, self.width, self.height)
        params.intrinsic = o3d.camera.PinholeCameraIntrinsic(self.width, self.height, fx, fy, cx, cy)
        params.extrinsic = pose.extrinsic()
        ctl.set_constant_z_near(Z_NEAR)
        ctl.set_constant_z_far(Z_FAR)
        ctl.convert_from_pinhole_camera_parameters(params, allow_arbitrary=True)
        if self._bytes is not None:  # drawn into our framebuffer, read back as bytes (and depth)
            rgb, depth = self._bytes.draw(self._vis, (Z_NEAR, Z_FAR) if with_depth else None)
            return graded(rgb, gain), depth
        self._vis.update_renderer()
        frame = to_uint8(np.asarray(self._vis.capture_screen_float_buffer(do_render=True)), gain)
        depth = None
        if with_depth:
            depth = np.asarray(self._vis.capture_depth_float_buffer(do_render=False), dtype=np.float32)
        return frame, depth

    def close(self) -> None:
        if not self._closed:
            self._closed = True
            if self._bytes is not None:
                self._bytes.close()
                self._bytes = None
            self._vis.clear_geometries()
            self._vis.destroy_window()
            self._geoms.clear()
            if self in _ACTIVE:
                _ACTIVE.remove(self)

    def __enter__(self) -> Canvas:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __del__(self) -> None:  # pragma: no cover - best effort
        try:
            self.close()
        except Exception:
            pass
