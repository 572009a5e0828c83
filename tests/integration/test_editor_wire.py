"""The binary wire in headless Chromium: a patched preview plays exactly as a freshly loaded one.

Tab A holds a 3-character story and an edit of one word reaches it as patches (filtered, deflated
residuals: services/gateway/animwire.py) and compressed diagnostics; tab B opens the same version and
is sent every frame in full. Both hold the same frames bit for bit, both play, and paused at the same
time with the same camera they draw the same picture. No console errors. Skips as test_editor_browser does.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from PIL import Image

from tests.integration.test_editor_browser import ARTIFACTS, browser, png_pixels, wait_synced  # noqa: F401
from tests.integration.test_editor_panels import gateway, open_doc  # noqa: F401

pytestmark = [pytest.mark.browser, pytest.mark.slow, pytest.mark.integration]

# a story of three characters, the first sentence of Ann's edited: everyone's later frames move in time
STORY = (
    "In the living room there is a sofa near a window$. A lamp is next to the sofa$. "
    "Ann walks to the sofa. Ben waves at Ann. Cleo walks to the window. Ann sits on the sofa. "
    "Ben walks to the lamp. Cleo waves at Ben."
)

HELD = """() => Object.fromEntries(wana.state.animation.characters.map((c) => [c.name,
    {hash: c.hash, frames: c.frames, rot: Array.from(c._q ? c._q.rot : []),
     root: Array.from(new Uint32Array(c.root_position.buffer, c.root_position.byteOffset, c.root_position.length)),
     present: c.present ? Array.from(c.present) : null}]))"""


def _still(page: Any, seconds: float) -> np.ndarray:
    """The 3D view paused at `seconds`, drawn now, with the default camera."""
    page.evaluate(
        f"""() => {{ wana.timeline.pause(); wana.timeline.seek({seconds}); wana.viewer.render(true); }}"""
    )
    page.wait_for_timeout(300)
    return png_pixels(page.locator("#viewport canvas").screenshot())


def test_a_patched_preview_holds_and_draws_what_a_fresh_tab_is_sent_in_full(
    browser: Any,  # noqa: F811
    gateway: Any,  # noqa: F811
) -> None:
    errors: list[str] = []
    a = open_doc(browser, gateway, STORY, errors, title="wire")
    first = wait_synced(a, timeout_ms=180_000)
    if len(first["characters"]) < 3:
        pytest.skip(f"needs three characters' motion: {first['unavailable']}")
    text = a.evaluate("() => wana.pane.getText()")
    at = text.index("Ann walks") + len("Ann ")
    a.focus("#text .cm-content")
    a.evaluate(f"() => wana.pane.view.dispatch({{selection: {{anchor: {at}, head: {at + len('walks')}}}}})")
    a.keyboard.insert_text("runs")
    second = wait_synced(a, timeout_ms=180_000)
    assert second["version"] > first["version"]
    patched = a.evaluate("() => wana.state.received.patched")
    assert "Ann" in patched, a.evaluate("() => wana.state.received")
    held_a = a.evaluate(HELD)

    doc = a.evaluate("() => wana.state.docId")
    b = browser.new_page(viewport={"width": 1280, "height": 720})
    b.on("pageerror", lambda e: errors.append(str(e)))
    b.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    b.goto(a.url.split("#")[0] + f"#doc={doc}")
    third = wait_synced(b, timeout_ms=180_000)
    assert third["version"] == second["version"]
    assert b.evaluate("() => wana.state.received.patched") == []  # a new tab is sent every frame
    held_b = b.evaluate(HELD)
    assert sorted(held_a) == sorted(held_b) == ["Ann", "Ben", "Cleo"]
    for name in held_a:
        assert held_a[name]["hash"] == held_b[name]["hash"], name
        for key in ("frames", "rot", "root", "present"):
            assert held_a[name][key] == held_b[name][key], (name, key)

    # both play: the clock runs and the figures move
    for page in (a, b):
        page.evaluate("() => { wana.timeline.seek(0); wana.timeline.play(); }")
    a.wait_for_timeout(1500)
    for page in (a, b):
        assert page.evaluate("() => wana.timeline.playing && wana.timeline.time > 0.3")
    # paused at the same moments, the same camera: the same picture of the figures the frames pose (the
    # live figures, not the render service's skinned scene, which is drawn from the server's own frames)
    a.keyboard.press("Escape")  # no completion list over the view
    for page in (a, b):
        page.evaluate("() => document.activeElement?.blur()")
        page.wait_for_function(
            "() => wana.viewer.exportScene && wana.viewer.exportVersion === wana.state.version",
            timeout=120_000,
        )
        page.evaluate("() => wana.viewer.useExport(null)")
        assert page.evaluate("() => wana.viewer.characterGroup.visible") is True
    for seconds in (2.0, second["frames"] / 30 * 0.6):
        pa, pb = _still(a, seconds), _still(b, seconds)
        ARTIFACTS.mkdir(exist_ok=True)
        Image.fromarray(np.concatenate([pa, pb], axis=1).astype(np.uint8)).save(
            ARTIFACTS / f"editor_wire_{seconds:.1f}s.png"
        )
        differ = int((np.abs(pa - pb).sum(axis=2) > 30).sum())
        assert differ < 0.001 * pa.shape[0] * pa.shape[1], (seconds, differ)
    assert not errors, errors
    a.close()
    b.close()
