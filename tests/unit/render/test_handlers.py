"""The render service's handlers called in process, through the same frame handler the worker uses."""

from __future__ import annotations

import io

import msgspec
import numpy as np
import pytest
from PIL import Image

from proto.common import ErrorReply, Header
from proto.render import ExportReply, ExportRequest, RenderReply, RenderRequest
from services.render.demo import demo_scene, walk_motion
from services.render.handlers import CONTRACT
from wana.bus.service import make_frame_handler

handle = make_frame_handler(CONTRACT)


def _call(request):  # noqa: ANN001, ANN202
    return msgspec.msgpack.decode(
        handle(msgspec.msgpack.encode(request)), type=RenderReply | ExportReply | ErrorReply
    )


@pytest.mark.slow
def test_png_and_raw_frames_of_a_range_decode_to_the_same_picture():
    motion = walk_motion("Eve", (-1.0, 1.0), (1.0, 0.0), 12)
    base = dict(
        header=Header(doc_id="d"),
        scene=demo_scene(),
        motions=[motion],
        start_frame=3,
        end_frame=5,
        width=96,
        height=64,
    )
    png = _call(RenderRequest(**base, encoding="png"))
    raw = _call(RenderRequest(**base, encoding="raw"))
    assert isinstance(png, RenderReply) and png.n_frames == 12 and len(png.frames) == 2
    assert png.header.doc_id == "d"
    for p, r in zip(png.frames, raw.frames, strict=True):
        img = np.asarray(Image.open(io.BytesIO(p)).convert("RGB"))
        assert img.shape == (64, 96, 3)
        assert np.array_equal(img, np.frombuffer(r, np.uint8).reshape(64, 96, 3))


def test_bad_requests_get_e010_errors_not_crashes():
    scene = demo_scene()
    too_big = _call(RenderRequest(header=Header(), scene=scene, width=10_000, height=10))
    assert isinstance(too_big, ErrorReply) and too_big.code == "E010" and "pixels" in too_big.message
    no_bvh = _call(ExportRequest(header=Header(), format="bvh", scene=scene))
    assert isinstance(no_bvh, ErrorReply) and no_bvh.code == "E010"
    garbage = msgspec.msgpack.decode(handle(b"\x93\x01\x02"), type=ErrorReply)
    assert garbage.code == "E001"


@pytest.mark.slow
def test_out_of_range_frames_are_refused():
    reply = _call(
        RenderRequest(
            header=Header(),
            scene=demo_scene(),
            motions=[walk_motion("Eve", (0, 0), (1, 0), 8)],
            start_frame=4,
            end_frame=20,
            width=32,
            height=32,
        )
    )
    assert isinstance(reply, ErrorReply) and reply.code == "E010" and "outside" in reply.message


def test_glb_and_bvh_exports():
    m = walk_motion("Tom", (0, 0), (1, 0), 10)
    glb = _call(ExportRequest(header=Header(), format="glb", scene=demo_scene(), motions=[m]))
    assert glb.filename == "scene.glb" and glb.data[:4] == b"glTF"
    bvh = _call(
        ExportRequest(header=Header(), format="bvh", scene=demo_scene(), motions=[m], character="Tom")
    )
    assert bvh.filename == "Tom.bvh" and bvh.data.startswith(b"HIERARCHY")
