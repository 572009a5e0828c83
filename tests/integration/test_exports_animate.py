"""`wana animate --export`: the asked formats are written and read back (USD with pxr, FBX with Blender), the
zip bundles them with report.json, and a format whose optional package is missing is refused up front."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import zipfile

import numpy as np
import pytest

from wana.domain.bvh import read_bvh
from wana.domain.skeleton import JOINT_INDEX, JOINT_NAMES

pytestmark = [pytest.mark.integration, pytest.mark.slow]

STORY = "A chair is near a desk$.\nEve walks to the chair. Eve sits on the chair.\n"


def _animate(story, out, *extra: str, env: dict | None = None) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "wana.cli", "animate", str(story), "-o", str(out), "--no-progress", *extra],
        capture_output=True,
        text=True,
        timeout=900,
        env=env,
    )


@pytest.fixture(scope="module")
def outputs(tmp_path_factory):
    pytest.importorskip("pxr", reason="needs usd-core")
    from services.render import fbx_export

    try:
        fbx_export.blender_python()
    except ModuleNotFoundError as exc:
        pytest.skip(str(exc))
    story = tmp_path_factory.mktemp("story") / "story.txt"
    story.write_text(STORY)
    out = tmp_path_factory.mktemp("out")
    proc = _animate(
        story, out, "--in-process", "--export", "bvh,usd,fbx,zip", "--width", "160", "--height", "120"
    )
    assert proc.returncode == 0, proc.stderr[-3000:]
    return out


def test_only_the_asked_formats_are_written_and_the_report_lists_them(outputs):
    names = sorted(p.name for p in outputs.iterdir())
    assert names == ["Eve.bvh", "animation.fbx", "animation.usdc", "animation.zip", "report.json"]
    report = json.loads((outputs / "report.json").read_text())
    assert report["render"]["files"] == names
    assert report["render"]["frames"] > 0 and report["render"]["shots"]  # from the USD's reply, no MP4


def test_the_zip_bundles_every_file_with_the_report(outputs):
    with zipfile.ZipFile(outputs / "animation.zip") as bundle:
        assert sorted(bundle.namelist()) == ["Eve.bvh", "animation.fbx", "animation.usdc", "report.json"]
        for name in bundle.namelist():
            assert bundle.read(name) == (outputs / name).read_bytes()


def test_the_usd_and_the_fbx_hold_the_bvhs_joints_within_1_cm(outputs):
    from pxr import Usd, UsdGeom, UsdSkel

    from services.render import fbx_export

    bvh = read_bvh(outputs / "Eve.bvh").global_positions()
    frames = [0, len(bvh) // 2, len(bvh) - 1]
    stage = Usd.Stage.Open(str(outputs / "animation.usdc"))
    cache = UsdSkel.Cache()
    cache.Populate(UsdSkel.Root(stage.GetPrimAtPath("/World/Eve")), Usd.TraverseInstanceProxies())
    query = cache.GetSkelQuery(UsdSkel.Skeleton(stage.GetPrimAtPath("/World/Eve/Skeleton")))
    order = [JOINT_INDEX[str(t).split("/")[-1]] for t in query.GetJointOrder()]
    fbx = fbx_export.probe(outputs / "animation.fbx", frames)["armatures"]["Eve"]["frames"]
    for f in frames:
        world = query.ComputeJointWorldTransforms(UsdGeom.XformCache(Usd.TimeCode(f)))
        usd = np.array([m.ExtractTranslation() for m in world])
        assert np.linalg.norm(usd - bvh[f][order], axis=1).max() < 0.01
        blender = np.array([fbx[str(f)][f"Eve:{n}"] for n in JOINT_NAMES])
        assert np.linalg.norm(blender - bvh[f], axis=1).max() < 0.01


def test_an_export_without_its_package_is_refused_before_any_work(tmp_path):
    story = tmp_path / "story.txt"
    story.write_text(STORY)
    env = {**os.environ, "WANA_BLENDER_PYTHON": str(tmp_path / "no-blender-here")}
    proc = _animate(story, tmp_path / "out", "--export", "mp4,fbx", env=env)
    assert proc.returncode == 2
    assert "--export fbx needs Blender" in proc.stderr
    assert not (tmp_path / "out").exists()


def test_an_unknown_export_is_a_usage_error(tmp_path):
    story = tmp_path / "story.txt"
    story.write_text(STORY)
    proc = _animate(story, tmp_path / "out", "--export", "mp4,obj")
    assert proc.returncode == 2 and "unknown export obj" in proc.stderr


def test_the_blender_renderer_without_blender_is_refused_before_any_work(tmp_path):
    story = tmp_path / "story.txt"
    story.write_text(STORY)
    env = {**os.environ, "WANA_BLENDER_PYTHON": str(tmp_path / "no-blender-here")}
    proc = _animate(story, tmp_path / "out", "--renderer", "blender", env=env)
    assert proc.returncode == 2
    assert "--renderer blender needs Blender" in proc.stderr
    assert not (tmp_path / "out").exists()
    # without the MP4 nothing is rendered, so nothing needs Blender
    ok = _animate(story, tmp_path / "glb", "--renderer", "blender", "--export", "glb", env=env)
    assert ok.returncode == 0, ok.stderr[-2000:]
