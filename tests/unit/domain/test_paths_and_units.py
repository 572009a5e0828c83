"""One definition of the frame rate and one way to find packaged files, used by every stage."""

from __future__ import annotations

import ast
import json
import os
import subprocess
import sys
from pathlib import Path

import msgspec
import pytest

from proto.motion_data import Motion
from wana.domain import paths, units

REPO = Path(__file__).resolve().parents[3]
RUNTIME = [REPO / "proto", REPO / "services", REPO / "wana"]
# Modules that may still compute the checkout from __file__, and why.
CHECKOUT_READERS = {
    "services/gateway/settings.py": "the editor's dist/ is built beside the checkout, not packaged",
}


def _runtime_modules() -> list[Path]:
    return sorted(p for root in RUNTIME for p in root.rglob("*.py") if "_packaged" not in p.parts)


def test_the_frame_rate_is_defined_once():
    defining = []
    for path in _runtime_modules():
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Assign) and isinstance(node.value, ast.Constant):
                if any(isinstance(t, ast.Name) and t.id in ("FPS", "_FPS") for t in node.targets):
                    defining.append(str(path.relative_to(REPO)))
    assert defining == ["wana/domain/units.py"]


def test_the_wire_default_frame_rate_is_the_domain_one():
    fps = next(f for f in msgspec.inspect.type_info(Motion).fields if f.name == "fps")
    assert fps.default == units.FPS


def test_seconds_and_frames_convert_both_ways():
    assert units.seconds_to_frames(2.0) == 2 * units.FPS
    assert units.frames_to_seconds(units.seconds_to_frames(1.5)) == pytest.approx(1.5)


def test_no_runtime_module_finds_files_from_its_own_location():
    offenders = []
    for path in _runtime_modules():
        rel = str(path.relative_to(REPO))
        if "__file__).resolve().parents" in path.read_text() and rel not in CHECKOUT_READERS:
            offenders.append(rel)
    assert offenders == []


def test_in_a_checkout_the_folders_are_the_repositorys():
    assert paths.assets_dir() == REPO / "assets"
    assert paths.models_dir() == REPO / "models"
    assert paths.repo_root() == REPO
    assert (paths.asset_path("actions") / "sit.json").is_file()
    assert (paths.model_path("locomotion") / "meta.json").is_file()


def _in_subprocess(env: dict[str, str], code: str) -> subprocess.CompletedProcess[str]:
    full = {**os.environ, "PYTHONPATH": str(REPO), **env}
    return subprocess.run([sys.executable, "-c", code], env=full, capture_output=True, text=True, cwd="/")


def test_an_override_folder_is_what_the_action_catalogue_reads(tmp_path):
    actions = tmp_path / "actions"
    actions.mkdir()
    clip = json.loads((REPO / "assets" / "actions" / "wave.json").read_text())
    (actions / "only_one.json").write_text(json.dumps({**clip, "name": "only_one", "synonyms": ["solo"]}))
    done = _in_subprocess(
        {"WANA_ASSETS": str(tmp_path)},
        "from wana.domain.actions import load_library, get_clip; print(sorted(load_library()), get_clip('solo').name)",
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["['only_one']", "only_one"]


def test_an_override_that_is_no_folder_is_an_error_naming_the_variable(tmp_path):
    done = _in_subprocess(
        {"WANA_MODELS": str(tmp_path / "missing")}, "from wana.domain import paths; paths.models_dir()"
    )
    assert done.returncode != 0
    assert "WANA_MODELS" in done.stderr and "AssetsNotFound" in done.stderr
