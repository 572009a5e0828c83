"""Inline help, layout and keyboard access in headless Chromium.

Diagnostics are CodeMirror lint marks under exactly the words they are about (also in a long, scrolled
document), with hover text and a "did you mean" quick fix; completion offers characters and actions; "Load
example" opens a story; exports are disabled on an empty document; the layout stacks at 390x844 without a
sideways scroll (screenshot in test-artifacts/editor-phone.png); diagnostics are reached by keyboard.
Skips as test_editor_browser does.
"""

from __future__ import annotations

import re
from typing import Any

import httpx
import pytest

from services.gateway.server import GatewayThread
from services.gateway.settings import Settings
from tests.integration.test_editor_browser import ARTIFACTS, DIST, REPO, browser  # noqa: F401

pytestmark = [pytest.mark.browser, pytest.mark.slow, pytest.mark.integration]

TYPO = "Eve sitts on the chair."
FILLER = "In the office there is a desk near a window$. Eve walks to the desk. " * 25


@pytest.fixture(scope="module")
def gateway(tmp_path_factory: pytest.TempPathFactory) -> Any:
    db = tmp_path_factory.mktemp("help") / "sessions.sqlite"
    with GatewayThread(Settings(db=db, backend="inprocess", editor_dist=DIST)) as gw:
        yield gw


def open_doc(browser: Any, gw: Any, text: str, viewport: dict[str, int], errors: list[str]) -> Any:  # noqa: F811
    doc_id = httpx.post(f"{gw.base_url}/api/documents", json={"title": "help", "text": text}).json()["doc_id"]
    page = browser.new_page(viewport=viewport)
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    page.goto(f"{gw.base_url}/#doc={doc_id}")
    page.wait_for_function("() => window.wana && wana.state.live && wana.state.live.ready", timeout=60_000)
    return page


def lint_marks(page: Any) -> list[dict[str, Any]]:
    return list(
        page.evaluate(
            """() => [...document.querySelectorAll('.cm-lintRange')].map(e => ({text: e.textContent,
                cls: e.className, top: e.getBoundingClientRect().top}))"""
        )
    )


def test_a_typo_is_marked_under_its_word_with_hover_text_and_a_quick_fix(browser: Any, gateway: Any) -> None:  # noqa: F811
    errors: list[str] = []
    page = open_doc(browser, gateway, FILLER + TYPO, {"width": 1280, "height": 720}, errors)
    page.wait_for_function(
        "() => [...document.querySelectorAll('.cm-lintRange')].some(e => e.textContent.includes('sitts'))",
        timeout=120_000,
    )
    page.evaluate(
        "() => { const v = wana.pane.view; v.dispatch({selection: {anchor: v.state.doc.length}, scrollIntoView: true}); }"
    )
    assert page.evaluate("() => wana.pane.view.scrollDOM.scrollTop") > 0  # a long, scrolled document
    marks = [m for m in lint_marks(page) if "sitts" in m["text"]]
    assert marks and marks[0]["text"].strip(" .") in ("sitts", "Eve sitts", "sitts on the chair")
    # the mark is the word's own element: the underline is drawn under exactly these characters
    mark = page.locator(".cm-lintRange", has_text="sitts").first
    mark.hover()
    page.wait_for_selector(".cm-tooltip-hover .cm-diagnostic", timeout=10_000)
    hover = page.text_content(".cm-tooltip-hover")
    assert "'sitts'" in hover and "did you mean" in hover, hover
    page.click(".cm-tooltip-hover .cm-diagnosticAction:has-text('did you mean')")
    page.wait_for_function("() => wana.pane.getText().endsWith('Eve sits on the chair.')")
    assert "sitts" not in page.evaluate("() => wana.pane.getText()")
    assert not errors, errors
    page.close()


def test_completion_offers_characters_and_actions(browser: Any, gateway: Any) -> None:  # noqa: F811
    errors: list[str] = []
    page = open_doc(browser, gateway, "", {"width": 1280, "height": 720}, errors)
    page.click("#text .cm-content")
    page.keyboard.type("Eve wa")
    page.keyboard.press("Control+Space")
    options = page.wait_for_selector(".cm-tooltip-autocomplete", timeout=10_000).text_content()
    assert "walks to" in options and "waves" in options
    page.keyboard.press("Escape")
    page.close()


def test_exports_are_disabled_on_an_empty_document_and_an_example_loads(browser: Any, gateway: Any) -> None:  # noqa: F811
    errors: list[str] = []
    page = open_doc(browser, gateway, "", {"width": 1280, "height": 720}, errors)
    assert page.evaluate(
        "() => [...document.querySelectorAll('#exports button[data-format]')].every(b => b.disabled)"
    )
    page.select_option("#example-picker", index=1)
    page.wait_for_function("() => wana.pane.getText().includes('$')", timeout=30_000)
    assert page.evaluate("() => document.querySelector('#exports button[data-format=glb]').disabled") is False
    # an MP4 shows its progress and can be cancelled
    page.click("#exports button[data-format=mp4]")
    page.wait_for_selector("#export-cancel", state="visible")
    page.click("#export-cancel")
    page.wait_for_function("() => document.getElementById('export-status').textContent === 'MP4 cancelled'")
    assert page.is_hidden("#export-cancel")
    page.click("#help-toggle")
    assert page.is_visible("#help") and "ending in $" in page.text_content("#help")
    # the picker shows the open document's live version; Delete removes it and opens another
    example_doc = page.evaluate("() => wana.state.docId")
    page.wait_for_function(
        "() => document.querySelector('#doc-picker').selectedOptions[0].textContent.endsWith('(v' + wana.state.live.version + ')')"
    )
    page.once("dialog", lambda d: d.accept())
    page.click("#delete-doc")
    page.wait_for_function(f"() => wana.state.docId !== {example_doc!r} && wana.state.live.ready")
    assert httpx.get(f"{gateway.base_url}/api/documents/{example_doc}").status_code == 404
    assert not errors, errors
    page.close()


def test_the_phone_layout_stacks_and_diagnostics_are_reached_by_keyboard(browser: Any, gateway: Any) -> None:  # noqa: F811
    ARTIFACTS.mkdir(exist_ok=True)
    errors: list[str] = []
    page = open_doc(
        browser, gateway, "In the office there is a desk$. " + TYPO, {"width": 390, "height": 844}, errors
    )
    page.wait_for_selector("#diagnostics .diag-item", timeout=120_000)
    box = page.evaluate(
        """() => { const r = (id) => document.getElementById(id).getBoundingClientRect();
            return {scroll: document.documentElement.scrollWidth, text: r('text-pane'), view: r('viewport')}; }"""
    )
    assert box["scroll"] <= 390
    assert box["text"]["width"] >= 380 and box["view"]["width"] >= 380
    assert box["view"]["top"] >= box["text"]["bottom"] - 1  # stacked: the 3D view below the text
    assert box["view"]["height"] >= 250
    page.screenshot(path=str(ARTIFACTS / "editor-phone.png"), full_page=True)
    # keyboard only: Tab from the text reaches a diagnostic; Enter selects its words in the text
    page.click("#text .cm-content")
    for _ in range(6):
        page.keyboard.press("Tab")
        if page.evaluate("() => document.activeElement.classList.contains('diag-item')"):
            break
    assert page.evaluate("() => document.activeElement.classList.contains('diag-item')")
    page.keyboard.press("Enter")
    selected = page.evaluate(
        "() => { const s = wana.pane.view.state; const r = s.selection.main; return s.sliceDoc(r.from, r.to); }"
    )
    assert "sitts" in selected
    assert not errors, errors
    page.close()


def test_the_timeline_has_a_track_per_character_and_a_clip_seeks_and_selects_its_sentence(
    browser: Any,  # noqa: F811
    gateway: Any,
) -> None:
    story = (REPO / "examples" / "office.txt").read_text(encoding="utf-8")
    errors: list[str] = []
    page = open_doc(browser, gateway, story, {"width": 1280, "height": 800}, errors)
    page.wait_for_function(
        "() => wana.state.animation && wana.state.animation.characters.length >= 2 && document.querySelector('#tracks .clip')",
        timeout=180_000,
    )
    names = page.evaluate(
        "() => [...document.querySelectorAll('#tracks .track-name')].map(e => e.textContent)"
    )
    characters = page.evaluate("() => wana.state.animation.characters.map(c => c.name)")
    assert names[: len(characters)] == characters and names[-1] == "camera"
    clip = page.locator("#tracks .clip", has_text=re.compile(r"^wave.*: Tom waves")).first
    clip.focus()
    page.keyboard.press("Enter")  # keyboard reaches the timeline
    start = page.evaluate(
        """() => { const c = wana.state.animation.characters.find(c => c.name === 'Tom');
            return c.segments.find(s => s.action.startsWith('wave')).start_frame; }"""
    )
    assert page.evaluate("() => wana.timeline.frame") == start
    selected = page.evaluate(
        "() => { const s = wana.pane.view.state; const r = s.selection.main; return s.sliceDoc(r.from, r.to); }"
    )
    assert selected.strip() == "Tom waves at Eve."
    page.screenshot(path=str(ARTIFACTS / "editor-timeline.png"))
    page.select_option("#speed", "2")
    assert page.evaluate("() => wana.timeline.speed") == 2
    assert not errors, errors
    page.close()
