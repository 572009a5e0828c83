"""`wana animate --cast`: three stories' characters played by three rigs the test builds (Mixamo names in
centimetres; Unreal names, A-pose, long legs, twist and finger joints; unknown names with a --cast-map),
through the real CLI and pipeline: the GLB wears them on their own joint names, and the story's fidelity
checks are the same as with the built-in cast."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from tests.unit.cast_rigs import CUSTOM, MIXAMO, UNREAL, rig_glb, rig_joints
from wana.assets.gltf import read_glb

pytestmark = [pytest.mark.integration, pytest.mark.slow]

STORY = "A sofa is near a window$.\nEve walks to the window.\nTom sits on the sofa.\nMary waves at Tom.\n"


def _animate(story, out, *extra: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [
            sys.executable,
            "-m",
            "wana.cli",
            "animate",
            str(story),
            "-o",
            str(out),
            "--no-progress",
            "--in-process",
            "--export",
            "glb,bvh,mp4",
            "--width",
            "96",
            "--height",
            "72",
            *extra,
        ],
        capture_output=True,
        text=True,
        timeout=900,
    )


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("cast")
    story = tmp / "story.txt"
    story.write_text(STORY)
    (tmp / "eve.glb").write_bytes(rig_glb(rig_joints(MIXAMO), centimetres=True))
    (tmp / "tom.glb").write_bytes(
        rig_glb(rig_joints(UNREAL, legs=1.15, torso=0.85, extras=True), a_pose=True)
    )
    (tmp / "mary.glb").write_bytes(rig_glb(rig_joints(CUSTOM, legs=0.8, arms=1.1)))
    (tmp / "mary.json").write_text(json.dumps(CUSTOM))
    cast = [
        "--cast",
        f"Eve={tmp / 'eve.glb'}",
        "--cast",
        f"Tom={tmp / 'tom.glb'}",
        "--cast",
        f"Mary={tmp / 'mary.glb'}",
        "--cast-map",
        f"Mary={tmp / 'mary.json'}",
    ]
    own = _animate(story, tmp / "own", *cast)
    assert own.returncode == 0, own.stderr[-3000:]
    plain = _animate(story, tmp / "plain")
    assert plain.returncode == 0, plain.stderr[-3000:]
    return tmp


def test_the_glb_wears_each_users_rig_on_its_own_joint_names(runs):
    doc, _ = read_glb(runs / "own" / "scene.glb")
    names = {n.get("name") for n in doc["nodes"]}
    assert {"mixamorig:Hips", "pelvis", "jnt_00", "LeftUpperArmTwist", "LeftHandIndex2"} <= names
    assert {"Eve_body", "Tom_body", "Mary_body"} <= names
    assert not any(str(n).startswith(("Eve:", "Tom:", "Mary:")) for n in names)  # no built-in bodies
    assert len(doc["skins"]) == 3


def test_the_story_checks_are_those_of_the_built_in_cast(runs):
    own = json.loads((runs / "own" / "report.json").read_text())
    plain = json.loads((runs / "plain" / "report.json").read_text())

    def checks(report: dict) -> list:
        return [
            (s["id"], s["verdict"], [(c["name"], c["ok"]) for c in s["checks"]]) for s in report["sentences"]
        ]

    assert checks(own) == checks(plain)
    assert any(s["checks"] for s in own["sentences"])


def test_the_bvh_and_the_video_wear_the_users_rigs_too(runs):
    from services.render.video import decode_frames, probe
    from wana.domain.bvh import read_bvh

    assert read_bvh(runs / "own" / "Eve.bvh").joint_names[0] == "mixamorig:Hips"
    assert "LeftHandIndex2" in read_bvh(runs / "own" / "Tom.bvh").joint_names
    assert read_bvh(runs / "plain" / "Eve.bvh").joint_names[0] == "Hips"
    own, plain = runs / "own" / "animation.mp4", runs / "plain" / "animation.mp4"
    assert probe(own)["frames"] == probe(plain)["frames"]
    a, b = decode_frames(own), decode_frames(plain)
    differ = [
        i for i in range(0, len(a), 15) if abs(a[i].astype(int) - b[i].astype(int)).sum(axis=2).max() > 60
    ]
    assert len(differ) > len(range(0, len(a), 15)) // 2  # the bodies differ wherever a character is in view
