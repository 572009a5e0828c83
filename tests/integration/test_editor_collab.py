"""Two tabs of one document in headless Chromium: CodeMirror collab against the gateway's versions.

Tab A types at the start while tab B types at the end, one key each in turn, without waiting for acks: both
tabs and the server must end with exactly the text both intended (10 of 10 runs). Undo in a tab after another
tab's edit undoes that tab's own change only. Skips as test_editor_browser does.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import httpx
import pytest

from services.gateway.server import GatewayThread
from services.gateway.settings import Settings
from tests.integration.test_editor_browser import DIST, browser  # noqa: F401

pytestmark = [pytest.mark.browser, pytest.mark.slow, pytest.mark.integration]

BASE = "Anna walks to the door."
AT_START = "It is night. "
AT_END = " Ben walks in."

RUNS = int(os.environ.get("WANA_COLLAB_RUNS", "10"))
SETTLED = """() => { const l = window.wana && wana.state.live;
    return l && l.ready && !l.inFlight && !l.unconfirmed().length && l.confirmed === wana.pane.getText(); }"""


def open_tab(context: Any, url: str, errors: list[str]) -> Any:
    page = context.new_page()
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    page.goto(url)
    page.wait_for_function("() => window.wana && wana.state.live && wana.state.live.ready", timeout=60_000)
    return page


def settled_text(page: Any, version: int | None = None) -> str:
    """The tab's text once it has nothing unsent or unacknowledged (and has reached `version`, if given)."""
    page.wait_for_function(SETTLED, timeout=60_000)
    if version is not None:
        page.wait_for_function(f"() => wana.state.live.version >= {version}", timeout=60_000)
        page.wait_for_function(SETTLED, timeout=60_000)
    return str(page.evaluate("() => wana.pane.getText()"))


def server_version_when_both_settle(url: str, a: Any, b: Any) -> int:
    """The server's version once both tabs have sent everything (nothing more can come after it)."""
    a.wait_for_function(SETTLED, timeout=60_000)
    b.wait_for_function(SETTLED, timeout=60_000)
    return int(httpx.get(url).json()["version"])


def put_caret(page: Any, where: str) -> None:
    page.click("#text .cm-content")
    page.evaluate(
        "(w) => { const v = wana.pane.view; v.dispatch({selection: {anchor: w === 'start' ? 0 : v.state.doc.length}}); }",
        where,
    )


def test_two_tabs_typing_at_the_start_and_the_end_converge_to_the_intended_text(
    browser: Any,  # noqa: F811
    tmp_path: Path,
) -> None:
    settings = Settings(db=tmp_path / "sessions.sqlite", backend="inprocess", editor_dist=DIST)
    results = []
    with GatewayThread(settings) as gw:
        context = browser.new_context(viewport={"width": 1000, "height": 700})
        errors: list[str] = []
        for run in range(RUNS):
            doc_id = httpx.post(
                f"{gw.base_url}/api/documents", json={"title": f"collab {run}", "text": BASE}
            ).json()["doc_id"]
            a = open_tab(context, f"{gw.base_url}/#doc={doc_id}", errors)
            b = open_tab(context, f"{gw.base_url}/#doc={doc_id}", errors)
            assert settled_text(a) == BASE and settled_text(b) == BASE
            put_caret(a, "start")
            put_caret(b, "end")
            for i in range(max(len(AT_START), len(AT_END))):
                if i < len(AT_START):
                    a.keyboard.type(AT_START[i])
                if i < len(AT_END):
                    b.keyboard.type(AT_END[i])
            intended = AT_START + BASE + AT_END
            url = f"{gw.base_url}/api/documents/{doc_id}"
            version = server_version_when_both_settle(url, a, b)
            texts = (settled_text(a, version), settled_text(b, version))
            server = httpx.get(url).json()["text"]
            results.append((texts, server))
            if os.environ.get("WANA_COLLAB_DEBUG"):
                dump = "() => { const l = wana.state.live; return {v: l.version, pending: [...l.pending.keys()], wait: l.waitFor, inFlight: l.inFlight}; }"
                print(
                    "DEBUG",
                    run,
                    a.evaluate(dump),
                    b.evaluate(dump),
                    httpx.get(f"{gw.base_url}/api/documents/{doc_id}").json()["version"],
                    errors,
                )
            a.close()
            b.close()
        context.close()
    converged = sum(1 for (ta, tb), server in results if ta == tb == server == intended)
    assert converged == RUNS, [r for r in results if not (r[0][0] == r[0][1] == r[1] == intended)]
    assert not [e for e in errors if "WebSocket" not in e], errors


def test_undo_after_a_remote_edit_undoes_only_the_local_change(browser: Any, tmp_path: Path) -> None:  # noqa: F811
    settings = Settings(db=tmp_path / "sessions.sqlite", backend="inprocess", editor_dist=DIST)
    with GatewayThread(settings) as gw:
        doc_id = httpx.post(f"{gw.base_url}/api/documents", json={"title": "undo", "text": BASE}).json()[
            "doc_id"
        ]
        context = browser.new_context()
        errors: list[str] = []
        a = open_tab(context, f"{gw.base_url}/#doc={doc_id}", errors)
        b = open_tab(context, f"{gw.base_url}/#doc={doc_id}", errors)
        put_caret(a, "start")
        a.keyboard.type(AT_START)
        assert settled_text(a) == AT_START + BASE
        b.wait_for_function(f"() => wana.pane.getText() === {AT_START + BASE!r}")
        # B shows A's caret where A left it
        b.wait_for_selector(".cm-remote-caret", state="attached", timeout=10_000)
        caret_at = "() => wana.pane.view.posAtDOM(document.querySelector('.cm-remote-caret'))"
        b.wait_for_function(f"() => ({caret_at})() === {len(AT_START)}", timeout=10_000)
        put_caret(b, "end")
        b.keyboard.type(AT_END)
        a.wait_for_function(f"() => wana.pane.getText() === {AT_START + BASE + AT_END!r}")
        # A's caret stayed where A left it (after its own text), not pushed by B's edit at the end
        assert a.evaluate("() => wana.pane.view.state.selection.main.head") == len(AT_START)
        a.focus("#text .cm-content")
        a.keyboard.press("Control+z")
        assert settled_text(a) == BASE + AT_END
        b.wait_for_function(f"() => wana.pane.getText() === {BASE + AT_END!r}")
        assert settled_text(b) == BASE + AT_END
        # B's undo then takes back B's own typing only
        b.focus("#text .cm-content")
        b.keyboard.press("Control+z")
        assert settled_text(b) == BASE
        a.wait_for_function(f"() => wana.pane.getText() === {BASE!r}")
        assert httpx.get(f"{gw.base_url}/api/documents/{doc_id}").json()["text"] == BASE
        context.close()
        assert not [e for e in errors if "WebSocket" not in e], errors
