"""In headless Chromium: the story verdicts, sent after the animation as diagnostics deltas, reach the lint marks.

The drinking sentence has no cup to drink from: its W401 warning is marked in the text once the story
checks ran. An edit of another sentence does not resend it (it is not in the delta), and the mark stays on
the drinking sentence, moved with it.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from services.gateway.server import GatewayThread
from services.gateway.settings import Settings
from tests.integration.test_editor_browser import DIST, browser, wait_synced  # noqa: F401

pytestmark = [pytest.mark.browser, pytest.mark.slow, pytest.mark.integration]

STORY = "A sofa is near a window$. Tom sits on the sofa. Eve drinks from the cup."

MARKS = """() => { const out = []; const view = wana.pane.view;
    view.dom.querySelectorAll('.cm-lintRange-warning').forEach(el => {
        const from = view.posAtDOM(el, 0); out.push(view.state.doc.sliceString(from, from + el.textContent.length)); });
    return {marks: out, pending: wana.state.diagnostics.verdicts_pending,
            w401: wana.state.diagnostics.diagnostics.filter(d => d.code === 'W401').map(d => d.message),
            verdicts: wana.state.diagnostics.verdicts.length}; }"""


def judged(page: Any) -> dict[str, Any]:
    page.wait_for_function(
        "() => wana.state.diagnostics && !wana.state.diagnostics.verdicts_pending"
        " && wana.state.diagnostics.version === wana.state.live.version",
        timeout=180_000,
    )
    page.wait_for_timeout(200)
    return page.evaluate(MARKS)


def test_the_verdicts_reach_the_lint_marks_and_survive_an_edit_elsewhere(
    browser: Any,  # noqa: F811
    tmp_path: Path,
) -> None:
    settings = Settings(db=tmp_path / "sessions.sqlite", backend="inprocess", editor_dist=DIST)
    with GatewayThread(settings) as gw:
        import httpx

        doc_id = httpx.post(f"{gw.base_url}/api/documents", json={"title": "verdicts", "text": STORY}).json()[
            "doc_id"
        ]
        page = browser.new_page(viewport={"width": 1280, "height": 720})
        errors: list[str] = []
        page.on("pageerror", lambda e: errors.append(str(e)))
        received: list[Any] = []
        page.on("websocket", lambda ws: ws.on("framereceived", lambda f: received.append(f)))
        page.goto(f"{gw.base_url}/#doc={doc_id}")
        wait_synced(page, timeout_ms=180_000)
        first = judged(page)
        if not first["verdicts"]:
            pytest.skip("no story verdicts: the pipeline's stages are not available in this build")
        assert any("cup" in m for m in first["w401"]), first
        assert any(m.startswith("Eve drinks") for m in first["marks"]), first["marks"]

        # an edit of Tom's sentence (before Eve's): Eve's sentence moves, its mark moves with it
        received.clear()
        page.evaluate(
            "() => { const t = wana.pane.getText(); const at = t.indexOf('sits');"
            " wana.pane.view.dispatch({changes: {from: at, to: at + 4, insert: 'sat down'}}); }"
        )
        wait_synced(page, timeout_ms=180_000)
        after = judged(page)
        assert any("cup" in m for m in after["w401"]), after
        assert any(m.startswith("Eve drinks") for m in after["marks"]), after["marks"]
        import json

        deltas = [json.loads(f) for f in received if isinstance(f, str) and '"diagnostics"' in f]
        deltas = [d for d in deltas if d.get("type") == "diagnostics"]
        assert deltas and all(d["base_seq"] is not None for d in deltas)
        eve = page.evaluate(
            "() => { const t = wana.pane.getText();"
            " return wana.state.diagnostics.sentences.find(s => t.slice(s.start).startsWith('Eve drinks')).id; }"
        )
        assert all(eve not in d["changed"] for d in deltas), deltas
        assert not errors, errors
