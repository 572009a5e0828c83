"""An 8-bit read-back for the legacy open3d visualiser: frames handed over as bytes, not floats.

``Visualizer.capture_screen_float_buffer(do_render=True)`` makes a framebuffer (an RGB texture and a
24-bit depth/stencil buffer) for every frame, draws into it, reads it back as float32 (3.7 MB at 640x480),
flips it row by row into a second float image and deletes the framebuffer; the caller then turns the floats
back into bytes. ``ByteReadback`` keeps one framebuffer of the same formats for the canvas's life, has the
visualiser draw into it (``update_renderer`` + ``poll_events`` draw into whatever framebuffer is bound), and
reads it back with ``glReadPixels(GL_RGB, GL_UNSIGNED_BYTE)``: the same pixels, since the colour buffer
holds 8 bits a channel either way, with no float buffers and no per-frame framebuffer.

Fog needs the frame's depth: it is read from the same framebuffer. (``capture_depth_float_buffer`` after
the float capture read the window's depth buffer, which nothing is drawn into offscreen: every pixel at the
near plane, so the fog was one flat veil, as thin near as far.)

GL is reached through ctypes in the process's libGL (the one open3d draws with); where it cannot be
loaded or the framebuffer is not complete, ``ByteReadback.open`` returns None and the canvas keeps the
float capture.
"""

from __future__ import annotations

import ctypes
import ctypes.util
from typing import Any

import numpy as np

GL_FRAMEBUFFER = 0x8D40
GL_RENDERBUFFER = 0x8D41
GL_TEXTURE_2D = 0x0DE1
GL_RGB = 0x1907
GL_FLOAT = 0x1406
GL_UNSIGNED_BYTE = 0x1401
GL_LINEAR = 0x2601
GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER = 0x2801, 0x2800
GL_COLOR_ATTACHMENT0 = 0x8CE0
GL_DEPTH24_STENCIL8 = 0x88F0
GL_DEPTH_STENCIL_ATTACHMENT = 0x821A
GL_FRAMEBUFFER_COMPLETE = 0x8CD5
GL_PACK_ALIGNMENT = 0x0D05
GL_DEPTH_COMPONENT = 0x1902

_UINT, _INT, _PTR = ctypes.c_uint, ctypes.c_int, ctypes.c_void_p
_SIGNATURES: dict[str, tuple[Any, list[Any]]] = {
    "glGenFramebuffers": (None, [_INT, ctypes.POINTER(_UINT)]),
    "glDeleteFramebuffers": (None, [_INT, ctypes.POINTER(_UINT)]),
    "glBindFramebuffer": (None, [_UINT, _UINT]),
    "glCheckFramebufferStatus": (_UINT, [_UINT]),
    "glGenTextures": (None, [_INT, ctypes.POINTER(_UINT)]),
    "glDeleteTextures": (None, [_INT, ctypes.POINTER(_UINT)]),
    "glBindTexture": (None, [_UINT, _UINT]),
    "glTexImage2D": (None, [_UINT, _INT, _INT, _INT, _INT, _INT, _UINT, _UINT, _PTR]),
    "glTexParameteri": (None, [_UINT, _UINT, _INT]),
    "glFramebufferTexture2D": (None, [_UINT, _UINT, _UINT, _UINT, _INT]),
    "glGenRenderbuffers": (None, [_INT, ctypes.POINTER(_UINT)]),
    "glDeleteRenderbuffers": (None, [_INT, ctypes.POINTER(_UINT)]),
    "glBindRenderbuffer": (None, [_UINT, _UINT]),
    "glRenderbufferStorage": (None, [_UINT, _UINT, _INT, _INT]),
    "glFramebufferRenderbuffer": (None, [_UINT, _UINT, _UINT, _UINT]),
    "glPixelStorei": (None, [_UINT, _INT]),
    "glReadPixels": (None, [_INT, _INT, _INT, _INT, _UINT, _UINT, _PTR]),
}


def _gl() -> Any | None:
    """libGL with the functions above typed, or None where it cannot be loaded."""
    try:
        lib = ctypes.CDLL(ctypes.util.find_library("GL") or "libGL.so.1")
        for name, (restype, argtypes) in _SIGNATURES.items():
            fn = getattr(lib, name)
            fn.restype, fn.argtypes = restype, argtypes
    except (OSError, AttributeError):
        return None
    return lib


class ByteReadback:
    """One offscreen framebuffer of the visualiser's capture formats, read back as (H, W, 3) uint8.

    Open it while the visualiser's GL context is current (right after ``create_window``).
    """

    def __init__(self, gl: Any, width: int, height: int) -> None:
        self._gl, self.width, self.height = gl, int(width), int(height)
        self._fbo, self._tex, self._rbo = _UINT(), _UINT(), _UINT()

    @classmethod
    def open(cls, width: int, height: int) -> ByteReadback | None:
        gl = _gl()
        if gl is None:
            return None
        rb = cls(gl, width, height)
        gl.glGenFramebuffers(1, ctypes.byref(rb._fbo))
        gl.glBindFramebuffer(GL_FRAMEBUFFER, rb._fbo)
        gl.glGenTextures(1, ctypes.byref(rb._tex))  # the colour target open3d's capture makes
        gl.glBindTexture(GL_TEXTURE_2D, rb._tex)
        gl.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB, rb.width, rb.height, 0, GL_RGB, GL_FLOAT, None)
        gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR)
        gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR)
        gl.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, rb._tex, 0)
        gl.glGenRenderbuffers(1, ctypes.byref(rb._rbo))
        gl.glBindRenderbuffer(GL_RENDERBUFFER, rb._rbo)
        gl.glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, rb.width, rb.height)
        gl.glBindRenderbuffer(GL_RENDERBUFFER, 0)
        gl.glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, rb._rbo)
        complete = gl.glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE
        gl.glBindFramebuffer(GL_FRAMEBUFFER, 0)
        if not complete:
            rb.close()
            return None
        return rb

    def draw(
        self, vis: Any, depth_range: tuple[float, float] | None = None
    ) -> tuple[np.ndarray, np.ndarray | None]:
        """Have the visualiser draw one frame into the framebuffer: (H, W, 3) uint8, top row first, and with
        ``depth_range`` (the camera's near and far planes, metres) (H, W) float32 depth in metres along the
        view axis, 0 where nothing was drawn (as open3d's ``capture_depth_float_buffer`` converts it)."""
        gl = self._gl
        gl.glBindFramebuffer(GL_FRAMEBUFFER, self._fbo)
        try:
            vis.update_renderer()
            vis.poll_events()  # draws (the redraw update_renderer asked for) into the bound framebuffer
            buf = np.empty((self.height, self.width, 3), dtype=np.uint8)
            gl.glPixelStorei(GL_PACK_ALIGNMENT, 1)  # rows of 3 * width bytes, no padding (open3d's own)
            gl.glReadPixels(0, 0, self.width, self.height, GL_RGB, GL_UNSIGNED_BYTE, buf.ctypes.data)
            z = None
            if depth_range is not None:
                z = np.empty((self.height, self.width), dtype=np.float32)
                gl.glReadPixels(0, 0, self.width, self.height, GL_DEPTH_COMPONENT, GL_FLOAT, z.ctypes.data)
        finally:
            gl.glBindFramebuffer(GL_FRAMEBUFFER, 0)
        rgb = np.ascontiguousarray(buf[::-1])  # GL's first row is the bottom one
        if z is None or depth_range is None:
            return rgb, None
        near, far = depth_range
        d = z[::-1].astype(np.float64)
        metres = 2.0 * near * far / (far + near - (2.0 * d - 1.0) * (far - near))
        return rgb, np.where(d >= 1.0, 0.0, metres).astype(np.float32)  # 1.0: the cleared background

    def close(self) -> None:
        """Free the framebuffer (while the context is still current)."""
        gl = self._gl
        if self._fbo.value:
            gl.glDeleteFramebuffers(1, ctypes.byref(self._fbo))
        if self._tex.value:
            gl.glDeleteTextures(1, ctypes.byref(self._tex))
        if self._rbo.value:
            gl.glDeleteRenderbuffers(1, ctypes.byref(self._rbo))
        self._fbo, self._tex, self._rbo = _UINT(), _UINT(), _UINT()
