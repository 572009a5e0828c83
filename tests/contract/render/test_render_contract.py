"""The render worker on a real broker and socket: replies checked against its contract."""

from __future__ import annotations

import io

import msgspec
import pytest

from proto.common import Header
from proto.render import ExportRequest, RenderRequest
from services.render.demo import demo_scene, walk_motion
from services.render.handlers import CONTRACT
from services.render.timeline import chunk_ranges
from services.render.video import join_chunks, probe
from tests.contract.harness import check_contract, service_fixture

render = service_fixture("render", workers=2)

MOTION = walk_motion("Eve", (-1.5, 1.0), (1.0, -0.5), 18)


@pytest.mark.contract
def test_render_request_gets_png_frames(render):
    req = RenderRequest(
        header=Header(doc_id="doc"),
        scene=demo_scene(),
        motions=[MOTION],
        start_frame=0,
        end_frame=2,
        width=80,
        height=60,
    )
    reply = check_contract(
        CONTRACT, req, render.request("render", msgspec.msgpack.encode(req), deadline_s=120)
    )
    assert reply.status == "ok" and len(reply.frames) == 2 and reply.frames[0][:4] == b"\x89PNG"
    assert (reply.start_frame, reply.end_frame, reply.n_frames) == (0, 2, 18)


@pytest.mark.contract
def test_mp4_chunks_from_two_workers_join_into_the_whole_video(render):
    chunks = []
    jobs = []
    for a, b in chunk_ranges(18, 2):
        req = RenderRequest(
            header=Header(),
            scene=demo_scene(),
            motions=[MOTION],
            start_frame=a,
            end_frame=b,
            width=80,
            height=60,
            encoding="mp4",
        )
        jobs.append((req, render.client.submit("render", msgspec.msgpack.encode(req), deadline_s=120)))
    for req, job in jobs:
        reply = check_contract(CONTRACT, req, render.client.result(job, timeout=120))
        assert reply.encoding == "mp4" and not reply.frames
        chunks.append(reply.video)
    out = io.BytesIO()
    assert join_chunks(chunks, out) == 18
    assert probe(out.getvalue())["frames"] == 18


@pytest.mark.contract
def test_errors_are_contract_errors(render):
    req = RenderRequest(header=Header(), scene=demo_scene(), width=5, height=5)
    reply = check_contract(
        CONTRACT, req, render.request("render", msgspec.msgpack.encode(req)), expect="error", code="E010"
    )
    assert "pixels" in reply.message
    exp = ExportRequest(header=Header(), format="glb", scene=demo_scene(), motions=[MOTION])
    glb = check_contract(CONTRACT, exp, render.request("render", msgspec.msgpack.encode(exp), deadline_s=120))
    assert glb.data[:4] == b"glTF"


@pytest.mark.contract
def test_mp4_export_carries_the_videos_camera_checks(render):
    from proto.render import Caption, ExportReply, TimedCommand
    from proto.ssg import Command
    from services.render.timeline import COMMAND_HOLD_FRAMES

    exp = ExportRequest(
        header=Header(doc_id="doc"),
        format="mp4",
        scene=demo_scene(),
        motions=[MOTION],
        commands=[TimedCommand(frame=18, command=Command(kind="camera", value="top"), sentence_id="s2")],
        captions=[Caption(start_frame=0, end_frame=18, text="Eve walks.", sentence_id="s1")],
        width=80,
        height=60,
    )
    raw = render.request("render", msgspec.msgpack.encode(exp), deadline_s=120)
    reply = check_contract(CONTRACT, exp, raw)
    assert isinstance(reply, ExportReply) and probe(reply.data)["frames"] == 18 + COMMAND_HOLD_FRAMES
    assert [c.name for c in reply.checks["s2"]] == ["command_visible"] and reply.checks["s2"][0].ok
    assert [(c.name, c.character) for c in reply.checks["s1"]] == [("in_view", "Eve")]
