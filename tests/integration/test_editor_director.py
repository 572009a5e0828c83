"""In headless Chromium: the editor's "Director" toggle plays the camera of the render service's export.

After typing a story and switching to "Director", the three.js camera at a frame stands where the GLB's
camera node (the camera the MP4 is rendered with) stands at that frame, looks the same way and has its
field of view; "Free camera" gives the orbit back. Skips as test_editor_browser does.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from services.gateway.server import GatewayThread
from services.gateway.settings import Settings
from tests.integration.test_editor_browser import ACTIONS, DIST, SCENE, browser, wait_synced  # noqa: F401
from tests.unit.render.test_gltf_camera import accessor, read_glb

pytestmark = [pytest.mark.browser, pytest.mark.slow, pytest.mark.integration]


def test_the_director_toggle_plays_the_exported_camera(browser: Any, tmp_path: Path) -> None:  # noqa: F811
    settings = Settings(db=tmp_path / "sessions.sqlite", backend="inprocess", editor_dist=DIST)
    with GatewayThread(settings) as gw:
        import httpx

        doc_id = httpx.post(f"{gw.base_url}/api/documents", json={"title": "director"}).json()["doc_id"]
        page = browser.new_page(viewport={"width": 1280, "height": 720})
        errors: list[str] = []
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.goto(f"{gw.base_url}/#doc={doc_id}")
        page.wait_for_function("() => window.wana && window.wana.state.live && window.wana.state.live.ready")
        page.click("#text .cm-content")
        page.keyboard.type(SCENE + ACTIONS)
        first = wait_synced(page)
        if not first["characters"]:
            pytest.skip(f"no character to see: stages not available in this build: {first['unavailable']}")
        page.evaluate("() => wana.timeline.pause()")
        page.click("#director")
        page.wait_for_function("() => wana.viewer.director !== null", timeout=120_000)
        assert page.inner_text("#director") == "Director"
        glb = httpx.get(f"{gw.base_url}/api/documents/{doc_id}/export/glb", timeout=120).content
        doc, blob = read_glb(glb)
        index = next(i for i, n in enumerate(doc["nodes"]) if n.get("name") == "camera")
        anim = doc["animations"][0]
        ch = {c["target"]["path"]: c for c in anim["channels"] if c["target"].get("node") == index}
        trans = accessor(doc, blob, anim["samplers"][ch["translation"]["sampler"]]["output"])
        rots = accessor(doc, blob, anim["samplers"][ch["rotation"]["sampler"]]["output"])
        fovs = doc["nodes"][index]["extras"]["yfov_per_frame"]
        for f in (10, first["frames"] // 2):
            page.evaluate(f"() => {{ wana.timeline.seek({f} / 30); wana.viewer.setFrame({f}); }}")
            cam = page.evaluate(
                "() => { const c = wana.viewer.camera; return {p: c.position.toArray(), q: c.quaternion.toArray(), fov: c.fov}; }"
            )
            np.testing.assert_allclose(cam["p"], trans[f], atol=1e-4)
            forward = Rotation.from_quat(cam["q"]).apply([0.0, 0.0, -1.0])
            np.testing.assert_allclose(
                forward, Rotation.from_quat(rots[f]).apply([0.0, 0.0, -1.0]), atol=1e-4
            )
            assert abs(cam["fov"] - np.degrees(fovs[f])) < 1e-3
        page.click("#director")
        page.wait_for_function("() => wana.viewer.director === null")
        assert page.evaluate("() => wana.viewer.controls.enabled") is True
        assert not errors, errors
