"""The editor's cast row and ZIP button in headless Chromium: a GLB chosen for a story character is uploaded,
listed and worn by the 3D view and the exports (the ZIP's BVH has the rig's joint names); a file that is no character is
refused with the reason; × brings the built-in character back. Skips as test_editor_browser does."""

from __future__ import annotations

import io
import zipfile
from pathlib import Path
from typing import Any

import httpx
import pytest

from tests.integration.test_editor_browser import browser, wait_synced  # noqa: F401
from tests.integration.test_editor_panels import gateway, open_doc  # noqa: F401
from tests.unit.cast_rigs import MIXAMO, rig_glb, rig_joints

pytestmark = [pytest.mark.browser, pytest.mark.slow, pytest.mark.integration]

STORY = "In the office there is a desk$. Eve walks to the desk."


def test_a_cast_file_is_worn_by_the_zip_and_can_be_removed(
    browser: Any,  # noqa: F811
    gateway: Any,  # noqa: F811
    tmp_path: Path,
) -> None:
    errors: list[str] = []
    page = open_doc(browser, gateway, STORY, errors)
    synced = wait_synced(page, timeout_ms=180_000)
    if not synced["characters"]:
        pytest.skip(f"no character motion in this build: {synced['unavailable']}")
    page.wait_for_function("() => document.querySelector('#cast-name').value === 'Eve'", timeout=30_000)
    junk = tmp_path / "junk.glb"
    junk.write_bytes(b"not a character")
    page.set_input_files("#cast-file", str(junk))
    page.wait_for_function("() => /Eve: .*GLB/.test(document.getElementById('cast-status').textContent)")
    rig = tmp_path / "eve.glb"
    rig.write_bytes(rig_glb(rig_joints(MIXAMO), centimetres=True))
    page.set_input_files("#cast-file", str(rig))
    page.wait_for_function("() => document.querySelector('#cast-list li[data-name=Eve]')", timeout=60_000)
    assert "eve.glb" in page.text_content("#cast-status")
    page.wait_for_function(  # the 3D view fetches scene.glb again, now with the user's rig
        "() => { let found = false; wana.viewer.exportScene?.traverse((o) => { found ||= o.name.includes('mixamorig'); });"
        " return found; }",
        timeout=120_000,
    )
    doc_id = page.evaluate("() => wana.state.docId")
    assert list(httpx.get(f"{gateway.base_url}/api/documents/{doc_id}/cast").json()) == ["Eve"]
    with page.expect_download(timeout=300_000) as download:
        page.click("#exports button[data-format=zip]")
    assert download.value.suggested_filename == "animation.zip"
    with zipfile.ZipFile(io.BytesIO(Path(download.value.path()).read_bytes())) as zf:
        assert sorted(zf.namelist()) == ["Eve.bvh", "animation.mp4", "scene.glb"]
        assert "ROOT mixamorig:Hips" in zf.read("Eve.bvh").decode()
    page.click("#cast-list li[data-name=Eve] button")
    page.wait_for_function("() => !document.querySelector('#cast-list li')", timeout=30_000)
    assert httpx.get(f"{gateway.base_url}/api/documents/{doc_id}/cast").json() == {}
    assert not [e for e in errors if "422" not in e], errors  # the refused upload logs its 422
    page.close()
