"""Keyboard only, in headless Chromium: every control has a name, and Tab and keys reach it all.

From the document picker, Tab reaches the text, the diagnostics, the 3D view, the timeline's play
button, its clips and the export buttons. In the 3D view the arrow keys orbit the camera round its target
(same distance, another angle), Space plays and pauses; Enter on a clip seeks to it and selects its
sentence; Enter on a diagnostic selects its words. No console errors. Skips as test_editor_browser does.
"""

from __future__ import annotations

import math
from typing import Any

import pytest

from tests.integration.test_editor_browser import REPO, browser, wait_synced  # noqa: F401
from tests.integration.test_editor_panels import gateway, open_doc  # noqa: F401

pytestmark = [pytest.mark.browser, pytest.mark.slow, pytest.mark.integration]

STORY = (REPO / "examples" / "office.txt").read_text(encoding="utf-8") + "\nEve sitts on the armchair.\n"

NAMES = """() => [...document.querySelectorAll('button, select, input, [tabindex], [contenteditable=true]')]
    .filter((el) => el.getClientRects().length && !el.closest('[hidden]'))
    .map((el) => {
        const by = el.getAttribute('aria-labelledby');
        const name = el.getAttribute('aria-label') || (by && document.getElementById(by)?.textContent)
            || [...(el.labels || [])].map((l) => l.textContent).join(' ') || el.title || el.innerText
            || (el.closest('[aria-label]') !== el && el.matches('.cm-content') ? el.closest('[aria-label]')?.getAttribute('aria-label') : '');
        return {el: el.tagName + (el.id ? '#' + el.id : '') + '.' + el.className, name: (name || '').trim()};
    })"""

CAMERA = """() => { const c = wana.viewer.camera.position, t = wana.viewer.controls.target;
    const d = c.clone().sub(t); return {distance: d.length(), azimuth: Math.atan2(d.x, d.z),
    elevation: Math.asin(d.y / d.length())}; }"""


def _tab_to(page: Any, test: str, limit: int = 60) -> None:
    for _ in range(limit):
        page.keyboard.press("Tab")
        if page.evaluate(f"() => {{ const el = document.activeElement; return !!({test}); }}"):
            return
    raise AssertionError(f"Tab never reached {test}")


def test_every_control_is_named_and_reached_and_worked_by_keyboard(browser: Any, gateway: Any) -> None:  # noqa: F811
    errors: list[str] = []
    page = open_doc(browser, gateway, STORY, errors, title="keys")
    page.set_viewport_size({"width": 1280, "height": 900})
    wait_synced(page, timeout_ms=180_000)
    page.wait_for_selector("#tracks .clip", timeout=120_000)
    page.wait_for_selector("#diagnostics .diag-item", timeout=120_000)
    unnamed = [c["el"] for c in page.evaluate(NAMES) if not c["name"]]
    assert not unnamed, unnamed

    page.focus("#doc-picker")
    _tab_to(page, "el.classList.contains('cm-content')")
    _tab_to(page, "el.classList.contains('diag-item') && el.textContent.includes('sitts')")
    page.keyboard.press("Enter")
    sel = page.evaluate(
        "() => { const s = wana.pane.view.state, r = s.selection.main; return s.sliceDoc(r.from, r.to); }"
    )
    assert "sitts" in sel, sel

    _tab_to(page, "el.id === 'viewport'")
    page.evaluate("() => wana.timeline.pause()")
    before = page.evaluate(CAMERA)
    for _ in range(3):
        page.keyboard.press("ArrowLeft")
    page.keyboard.press("ArrowUp")
    page.wait_for_timeout(100)
    after = page.evaluate(CAMERA)
    assert abs(after["distance"] - before["distance"]) < 1e-3 * before["distance"], (before, after)
    turned = (after["azimuth"] - before["azimuth"] + math.pi) % (2 * math.pi) - math.pi
    assert abs(abs(turned) - 3 * math.pi / 18) < 0.05, (before, after)
    assert after["elevation"] > before["elevation"] + 0.05, (before, after)
    page.keyboard.press(" ")
    assert page.evaluate("() => wana.timeline.playing") is True
    page.keyboard.press(" ")
    assert page.evaluate("() => wana.timeline.playing") is False

    _tab_to(page, "el.id === 'play'")
    page.keyboard.press("Enter")
    assert page.evaluate("() => wana.timeline.playing") is True
    _tab_to(page, "el.classList.contains('clip')")
    clip = page.evaluate("() => document.activeElement.textContent")
    page.keyboard.press("Enter")
    frame = page.evaluate("() => wana.timeline.frame")
    starts = page.evaluate(
        "() => wana.state.animation.characters.flatMap(c => c.segments.map(s => s.start_frame))"
        ".concat(wana.state.animation.commands.map(() => 0))"
    )
    assert page.evaluate("() => wana.timeline.playing") is False and frame in starts, (clip, frame)
    sel = page.evaluate(
        "() => { const s = wana.pane.view.state, r = s.selection.main; return s.sliceDoc(r.from, r.to); }"
    )
    assert sel.strip() and sel.strip().split()[0] in clip, (clip, sel)

    _tab_to(page, "el.dataset && el.dataset.format === 'mp4'")
    assert not errors, errors
    page.close()
