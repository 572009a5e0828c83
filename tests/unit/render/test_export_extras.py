"""An export whose optional package is missing is refused with a message that says how to get it."""

from __future__ import annotations

import pytest

from proto.common import Header
from proto.render import ExportRequest
from services.render.demo import demo_scene, walk_motion
from services.render.handlers import handle_export
from wana.bus.service import InvalidInput


def test_an_fbx_export_without_blender_names_the_package_and_the_setup_step(monkeypatch, tmp_path):
    monkeypatch.setenv("WANA_BLENDER_PYTHON", str(tmp_path / "no-python-here"))
    req = ExportRequest(
        header=Header(), format="fbx", scene=demo_scene(), motions=[walk_motion("Eve", (0, 0), (1, 0), 10)]
    )
    with pytest.raises(InvalidInput, match=r"bpy==5\.0\.1.*make setup"):
        handle_export(req)


def test_a_blender_python_that_fails_is_reported_with_its_output(monkeypatch, tmp_path):
    """A WANA_BLENDER_PYTHON that is no Blender fails in the subprocess; the error carries its last lines."""
    fake = tmp_path / "python"
    fake.write_text("#!/bin/sh\necho 'no bpy in here' >&2\nexit 3\n")
    fake.chmod(0o755)
    monkeypatch.setenv("WANA_BLENDER_PYTHON", str(fake))
    req = ExportRequest(
        header=Header(), format="fbx", scene=demo_scene(), motions=[walk_motion("Eve", (0, 0), (1, 0), 10)]
    )
    with pytest.raises(RuntimeError, match="no bpy in here"):
        handle_export(req)
