"""`wana animate` end to end on a short story: every output is written and reads back."""

from __future__ import annotations

import json
import subprocess
import sys

import av
import pytest
import trimesh

from wana.domain.bvh import read_bvh

pytestmark = [pytest.mark.integration, pytest.mark.slow]

STORY = "A chair is near a desk$.\nEve walks to the chair. Eve sits on the chair.\ncamera top\n"


@pytest.fixture(scope="module")
def outputs(tmp_path_factory):
    story = tmp_path_factory.mktemp("story") / "story.txt"
    story.write_text(STORY)
    out = tmp_path_factory.mktemp("out")
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "wana.cli",
            "animate",
            str(story),
            "-o",
            str(out),
            "--width",
            "160",
            "--height",
            "120",
            "--no-progress",
        ],
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert proc.returncode == 0, proc.stderr[-3000:]
    return out


def test_the_report_names_every_sentence_and_no_missing_stage(outputs):
    report = json.loads((outputs / "report.json").read_text())
    assert report["unavailable"] == {}
    assert [s["kind"] for s in report["sentences"]] == ["scene", "action", "action", "command"]
    assert report["characters"] == ["Eve"]
    assert {o["category"] for o in report["scene"]["objects"]} >= {"chair", "desk"}


def test_the_video_has_the_motion_length_at_the_asked_size(outputs):
    report = json.loads((outputs / "report.json").read_text())
    with av.open(str(outputs / "animation.mp4")) as container:
        stream = container.streams.video[0]
        frames = sum(1 for _ in container.decode(stream))
        assert (stream.codec_context.width, stream.codec_context.height) == (160, 120)
    assert frames == report["render"]["frames"] > 30


def test_the_glb_and_the_bvh_read_back(outputs):
    scene = trimesh.load(outputs / "scene.glb")
    assert len(scene.geometry) >= 3
    clip = read_bvh(outputs / "Eve.bvh")
    assert clip.motion.shape[0] > 30 and "Hips" in clip.joint_names


def test_the_same_story_gives_the_same_animation(outputs, tmp_path):
    story = tmp_path / "story.txt"
    story.write_text(STORY)
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "wana.cli",
            "animate",
            str(story),
            "-o",
            str(tmp_path / "again"),
            "--width",
            "160",
            "--height",
            "120",
            "--no-progress",
            "--in-process",
        ],
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert (tmp_path / "again" / "Eve.bvh").read_bytes() == (outputs / "Eve.bvh").read_bytes()
    first = json.loads((outputs / "report.json").read_text())
    second = json.loads((tmp_path / "again" / "report.json").read_text())
    assert first["scene"] == second["scene"] and first["sentences"] == second["sentences"]
