"""`wana assets` lists, shows and exports objects, scenes and characters."""

from __future__ import annotations

import trimesh

from wana.assets.cli import main


def test_list_and_show(capsys):
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    assert "office_chair" in out and "categories" in out
    assert main(["list", "scenes", "--room", "gym"]) == 0
    assert "gym-000" in capsys.readouterr().out
    assert main(["show", "couch", "--attr", "colour=red"]) == 0
    out = capsys.readouterr().out
    assert "category   sofa" in out and "contact    sit" in out
    assert main(["show", "office-000"]) == 0
    out = capsys.readouterr().out
    assert "scene office-000" in out and " at [" in out
    assert main(["show", "Eve"]) == 0
    assert "smile" in capsys.readouterr().out


def test_export_scene_object_and_character_to_glb(tmp_path):
    assert main(["export", "office-000", "-o", str(tmp_path / "s.glb")]) == 0
    scene = trimesh.load(tmp_path / "s.glb")
    assert len(scene.geometry) >= 5
    assert main(["export", "piano", "-o", str(tmp_path / "p.glb"), "--png", str(tmp_path / "p.png")]) == 0
    assert (tmp_path / "p.png").stat().st_size > 1000
    assert main(["export", "Tom", "-o", str(tmp_path / "t.glb")]) == 0
    assert (tmp_path / "t.glb").stat().st_size > 10000


def test_bad_input_is_an_error_code_not_a_crash(tmp_path, capsys):
    assert main(["show", "spaceship"]) == 2
    assert "not a category" in capsys.readouterr().err
    assert main(["show", "chair", "--attr", "red"]) == 2
