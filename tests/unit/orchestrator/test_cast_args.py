"""`wana animate --cast` refuses a missing file, a rig the map cannot cover, a bad map and an FBX without
Blender before any pipeline work, with messages that say what to do; an unknown name gets a "did you mean"."""

from __future__ import annotations

import json

import pytest

from proto.render import CastMember
from services.orchestrator.animate import main
from services.orchestrator.cast import load_cast, unknown_names
from tests.unit.cast_rigs import CUSTOM, UNREAL, rig_glb, rig_joints
from wana.cast import CastError


@pytest.fixture()
def story(tmp_path):
    p = tmp_path / "story.txt"
    p.write_text("Eve walks to the window.\n")
    return p


def test_a_missing_character_file_stops_before_the_pipeline(story, tmp_path, capsys):
    assert main([str(story), "-o", str(tmp_path / "out"), "--cast", f"Eve={tmp_path / 'nope.glb'}"]) == 2
    assert "no such character file for Eve" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_a_rig_with_unknown_names_lists_the_missing_joints_and_a_map_fixes_it(story, tmp_path, capsys):
    rig = tmp_path / "odd.glb"
    rig.write_bytes(rig_glb(rig_joints(CUSTOM)))
    assert main([str(story), "-o", str(tmp_path / "out"), "--cast", f"Eve={rig}"]) == 2
    err = capsys.readouterr().err
    assert "no joint for the canonical Hips, Spine, Head" in err and "--cast-map" in err
    joint_map = tmp_path / "map.json"
    joint_map.write_text(json.dumps(CUSTOM))
    (member,) = load_cast([f"Eve={rig}"], [str(joint_map)])
    assert member.name == "Eve" and member.joint_map["Hips"] == "jnt_00"
    joint_map.write_text("[1, 2]")
    with pytest.raises(CastError, match="one JSON object"):
        load_cast([f"Eve={rig}"], [str(joint_map)])


def test_usage_errors_are_named(tmp_path):
    rig = tmp_path / "eve.glb"
    rig.write_bytes(rig_glb(rig_joints(UNREAL)))
    with pytest.raises(CastError, match="NAME=FILE"):
        load_cast([str(rig)])
    with pytest.raises(CastError, match="twice"):
        load_cast([f"Eve={rig}", f"Eve={rig}"])
    with pytest.raises(CastError, match="one of .glb, .vrm, .fbx"):
        (tmp_path / "eve.obj").write_text("")
        load_cast([f"Eve={tmp_path / 'eve.obj'}"])


def test_an_fbx_without_blender_says_how_to_get_it(tmp_path, monkeypatch):
    import importlib.util

    fbx = tmp_path / "eve.fbx"
    fbx.write_bytes(b"Kaydara FBX Binary  \x00")
    monkeypatch.setenv("WANA_BLENDER_PYTHON", str(tmp_path / "no-python"))
    with pytest.raises(CastError, match="needs Blender as a Python module"):
        load_cast([f"Eve={fbx}"])
    monkeypatch.delenv("WANA_BLENDER_PYTHON")
    if importlib.util.find_spec("bpy") is None:
        with pytest.raises(CastError, match="export the character as GLB"):
            load_cast([f"Eve={fbx}"])


def test_a_name_the_story_lacks_gets_the_nearest_one():
    member = CastMember(name="Evee", glb=b"")
    assert unknown_names([member], ["Eve", "Tom"]) == [
        "--cast Evee: the story has no character Evee; did you mean Eve?"
    ]
    assert (
        "the story's characters: Eve, Tom"
        in unknown_names([CastMember(name="Zed", glb=b"")], ["Eve", "Tom"])[0]
    )
