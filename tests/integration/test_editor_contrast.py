"""WCAG AA contrast of the editor as Chromium draws it (the page has one, dark, theme).

The colours are read from the rendered page (getComputedStyle, backgrounds composited up the tree:
tests/integration/contrast.js) with a story that has diagnostics of every severity, lint marks, the help
panel, the timeline's tracks and clips, the export buttons and a lint mark's hover text: text 4.5:1 (3:1
large), button and select boundaries, lint underlines and the focus ring of every element Tab reaches 3:1.
Disabled controls are exempt, as WCAG 1.4.3 says. Skips as test_editor_browser does.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from tests.integration.test_editor_browser import REPO, browser, wait_synced  # noqa: F401
from tests.integration.test_editor_panels import gateway, open_doc  # noqa: F401

pytestmark = [pytest.mark.browser, pytest.mark.slow, pytest.mark.integration]

CHECK = (Path(__file__).with_name("contrast.js")).read_text(encoding="utf-8")
# an error (a word the parser does not know), a warning or info from the checks, a camera command
STORY = (REPO / "examples" / "office.txt").read_text(encoding="utf-8") + "\nEve sitts on the armchair.\n"


def _failing(found: list[dict[str, Any]]) -> list[str]:
    return [
        f"{f['kind']} {f['element']} {f['text']!r}: {f['ratio']:.2f} < {f['need']}"
        for f in found
        if f["ratio"] < f["need"]
    ]


def test_text_controls_lint_marks_and_focus_rings_meet_wcag_aa_contrast(browser: Any, gateway: Any) -> None:  # noqa: F811
    errors: list[str] = []
    page = open_doc(browser, gateway, STORY, errors, title="contrast")
    page.set_viewport_size({"width": 1280, "height": 900})
    wait_synced(page, timeout_ms=180_000)
    page.wait_for_selector("#tracks .clip", timeout=120_000)
    page.wait_for_selector("#diagnostics .diag-item", timeout=120_000)
    page.click("#help-toggle")
    page.evaluate("() => wana.timeline.pause()")
    found = page.evaluate(CHECK, "all")
    kinds = {f["kind"] for f in found}
    assert {"text", "boundary", "lint mark"} <= kinds, kinds
    elements = " ".join(f["element"] for f in found)
    for part in ("diag-item", "clip", "track-name", "brand", "#time", "hint"):
        assert part in elements, part
    bad = _failing(found)
    for f in sorted(found, key=lambda f: f["ratio"] / f["need"])[:8]:  # the closest calls
        print(
            f"{f['kind']:<10}{f['element'][:40]:<42}{f['text'][:24]!r:<28}{f['ratio']:6.2f} (need {f['need']})"
        )

    # a lint mark's hover text
    page.locator(".cm-lintRange").first.hover()
    page.wait_for_selector(".cm-tooltip-hover .cm-diagnostic", timeout=10_000)
    bad += _failing([f for f in page.evaluate(CHECK, "all") if "cm-" in f["element"]])
    page.mouse.move(5, 5)

    # every stop Tab reaches has a focus ring that stands out from what is around it
    page.focus("#doc-picker")
    rings = []
    for _ in range(40):
        page.keyboard.press("Tab")
        page.wait_for_timeout(60)  # CodeMirror marks itself focused a moment after the focus event
        ring = page.evaluate(CHECK, "focus")
        if ring:
            rings.extend(ring)
    assert len({r["element"] for r in rings}) >= 10, rings
    bad += [f"no focus ring on {r['element']}" for r in rings if not r["ring"]]
    bad += _failing([r for r in rings if r["ring"]])
    assert not bad, "\n".join(sorted(set(bad)))
    assert not errors, errors
    page.close()
