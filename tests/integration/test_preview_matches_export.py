"""Preview = export, in headless Chromium: with "Director" on, the editor shows the MP4's own picture.

The editor plays the render service's scene.glb (skinned characters, room, objects) under the director's
camera at the video's aspect. At the same frame, the characters' silhouette in the browser (canvas pixels
that change when the skinned bodies are hidden) is compared with the silhouette in the video's frame
(the render service's FrameRenderer, which writes the MP4, with and without the bodies): they must
overlap with an IoU of at least MIN_IOU and their centres lie within MAX_SHIFT pixels at 640x480.

Why these bounds: the two pictures come from two rasterisers (three.js on SwiftShader, open3d on Mesa),
with different antialiasing and lighting, and the browser canvas is scaled to 640x480. A character here
is about 60x170 pixels; a silhouette moved by 3 pixels sideways and 3 down keeps an IoU near 0.88, while
a camera off by a different shot, field of view or aspect puts it below 0.5. The issue asks the two to
agree "within a few pixels at 640x480": MAX_SHIFT says it directly, MIN_IOU that the shape agrees too.
The light is compared as a median colour difference (MAX_COLOUR; measured 22 when written).

Skips with a reason when Debian's chromium, the Playwright client or the built editor is missing.
"""

from __future__ import annotations

import tempfile
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from services.gateway.server import GatewayThread
from services.gateway.settings import Settings
from tests.integration import test_editor_browser as e2e
from tests.integration.test_editor_browser import ARTIFACTS, DIST, png_pixels, wait_synced

pytestmark = [pytest.mark.browser, pytest.mark.slow, pytest.mark.integration]
browser = e2e.browser  # the same headless Chromium fixture

STORY = "In the living room there is a sofa$. Eve walks to the sofa. Eve waves."
WIDTH, HEIGHT = 640, 480
MIN_IOU = 0.8
MAX_SHIFT = 4.0  # pixels between the silhouettes' centres
MAX_COLOUR = 45  # median summed RGB difference between the preview and the video frame
CHANGED = 40  # summed RGB difference that marks a pixel as belonging to a character


def silhouette(with_bodies: np.ndarray, without: np.ndarray) -> np.ndarray:
    """(H, W) True where hiding the characters changed the picture."""
    return np.abs(with_bodies.astype(np.int16) - without.astype(np.int16)).sum(axis=2) > CHANGED


def at_video_size(mask: np.ndarray) -> np.ndarray:
    """A mask resized to WIDTH x HEIGHT (nearest pixel)."""
    ys = (np.arange(HEIGHT) * mask.shape[0] / HEIGHT).astype(int)
    xs = (np.arange(WIDTH) * mask.shape[1] / WIDTH).astype(int)
    return mask[ys][:, xs]


def export_silhouette(text: str, frame: int, glb: bytes) -> tuple[np.ndarray, np.ndarray]:
    """The video's frame and its characters' silhouette, from the same inputs the gateway exported
    (checked: the same scene.glb)."""
    from services.orchestrator.backend import InProcessBackend
    from services.orchestrator.exports import export_request
    from services.orchestrator.session import Orchestrator
    from services.render.handlers import handle_export, placed
    from services.render.renderer import FrameRenderer

    with tempfile.TemporaryDirectory() as tmp:
        orchestrator = Orchestrator(Path(tmp) / "s.db", InProcessBackend())
        try:
            result = orchestrator.create(text).compute()
        finally:
            orchestrator.close()
    assert handle_export(export_request(result, "glb")).data == glb  # the gateway's very inputs
    req = export_request(result, "mp4", width=WIDTH, height=HEIGHT)
    commands, _ = placed(req)
    with FrameRenderer(req.scene, list(req.motions), commands, width=WIDTH, height=HEIGHT) as r:
        shown = r.render(frame)
        plate = r.render(frame, hide_characters=True)
    return shown, silhouette(shown, plate)


def test_the_director_preview_frames_the_characters_as_the_video_does(browser: Any, tmp_path: Path) -> None:
    ARTIFACTS.mkdir(exist_ok=True)
    settings = Settings(db=tmp_path / "sessions.sqlite", backend="inprocess", editor_dist=DIST)
    with GatewayThread(settings) as gw:
        import httpx

        doc_id = httpx.post(f"{gw.base_url}/api/documents", json={"title": "preview"}).json()["doc_id"]
        page = browser.new_page(viewport={"width": 1600, "height": 900})
        errors: list[str] = []
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.goto(f"{gw.base_url}/#doc={doc_id}")
        page.wait_for_function("() => window.wana && window.wana.state.live && window.wana.state.live.ready")
        page.click("#text .cm-content")
        page.keyboard.insert_text(STORY)
        summary = wait_synced(page)
        if not summary["characters"]:
            pytest.skip(f"no character to see: stages not available in this build: {summary['unavailable']}")
        frame = summary["frames"] // 2
        page.click("#director")
        page.wait_for_function(
            "() => wana.viewer.exportScene && wana.viewer.exportVersion === wana.state.version",
            timeout=120_000,
        )
        page.evaluate(f"() => {{ wana.timeline.pause(); wana.timeline.seek({frame} / 30); }}")
        page.evaluate("() => wana.viewer.render(true)")
        canvas = page.locator("#viewport canvas")
        size = page.evaluate(
            "() => [wana.viewer.renderer.domElement.width, wana.viewer.renderer.domElement.height]"
        )
        assert abs(size[0] / size[1] - WIDTH / HEIGHT) < 0.01, size  # the video's aspect
        figures = page.evaluate("() => wana.viewer.exportCharacters.map((m) => m.name)")
        assert figures and page.evaluate("() => wana.viewer.characterGroup.visible") is False
        with_bodies = png_pixels(canvas.screenshot())
        page.evaluate(
            "() => { for (const m of wana.viewer.exportCharacters) m.visible = false; wana.viewer.render(true); }"
        )
        without = png_pixels(canvas.screenshot())
        page.evaluate(
            "() => { for (const m of wana.viewer.exportCharacters) m.visible = true; wana.viewer.render(true); }"
        )
        glb = httpx.get(f"{gw.base_url}/api/documents/{doc_id}/export/glb").content
        page.click("#director")  # back to the free camera: still the export's skinned bodies, to orbit
        free = page.evaluate(
            "() => [wana.viewer.controls.enabled, wana.viewer.characterGroup.visible, !!wana.viewer.exportScene]"
        )
        assert free == [True, False, True], free
        assert not errors, errors
        page.close()
    preview = at_video_size(silhouette(with_bodies, without))
    video, exported = export_silhouette(STORY, frame, glb)
    from PIL import Image

    Image.fromarray(video).save(ARTIFACTS / "preview_export_video.png")
    Image.fromarray(with_bodies.astype(np.uint8)).save(ARTIFACTS / "preview_export_browser.png")
    assert exported.sum() > 1500 and preview.sum() > 1500, (exported.sum(), preview.sum())
    iou = float((preview & exported).sum() / (preview | exported).sum())
    centres = [np.argwhere(m).mean(axis=0) for m in (preview, exported)]
    shift = float(np.linalg.norm(centres[0] - centres[1]))
    print(f"preview vs export at frame {frame}: silhouette IoU {iou:.3f}, centres {shift:.2f} px apart")
    assert iou >= MIN_IOU and shift <= MAX_SHIFT, f"silhouette IoU {iou:.3f}, centres {shift:.1f} px apart"
    # The same light: the preview's colours at the video's size against the video frame's (the planar
    # shadows and the weather's colour grade are the video's alone).
    browser_rgb = np.asarray(
        Image.fromarray(with_bodies.astype(np.uint8)).resize((WIDTH, HEIGHT), Image.BILINEAR)
    ).astype(np.int16)
    colour = float(np.median(np.abs(browser_rgb - video.astype(np.int16)).sum(axis=2)))
    print(f"median summed RGB difference {colour:.0f}")
    assert colour <= MAX_COLOUR, colour
