"""The document list and export panel in headless Chromium, and typing while the animation plays.

Rename shows the new title with the live version in the picker; the BVH button downloads every character's
BVH in one zip; keystroke to screen stays under 50 ms (p95) while the animation plays; no console errors.
Skips as test_editor_browser does.
"""

from __future__ import annotations

import io
import zipfile
from typing import Any

import httpx
import numpy as np
import pytest

from services.gateway.server import GatewayThread
from services.gateway.settings import Settings
from services.gateway.videojobs import CHUNK_FRAMES
from tests.integration.test_editor_browser import DIST, browser, wait_synced  # noqa: F401

pytestmark = [pytest.mark.browser, pytest.mark.slow, pytest.mark.integration]

STORY = "In the office there is a desk near a window$. Eve walks to the desk. Tom walks to the window."
LONG_STORY = (
    STORY
    + " Eve walks to the window. Tom walks to the desk. Eve walks to the desk. Tom walks to the window." * 3
)
KEYSTROKE_P95_MS = 50.0  # issue 20's target, while the animation plays


@pytest.fixture(scope="module")
def gateway(tmp_path_factory: pytest.TempPathFactory) -> Any:
    db = tmp_path_factory.mktemp("panels") / "sessions.sqlite"
    with GatewayThread(Settings(db=db, backend="inprocess", editor_dist=DIST)) as gw:
        yield gw


def open_doc(browser: Any, gw: Any, text: str, errors: list[str], title: str = "untitled") -> Any:  # noqa: F811
    doc_id = httpx.post(f"{gw.base_url}/api/documents", json={"title": title, "text": text}).json()["doc_id"]
    page = browser.new_page(viewport={"width": 1280, "height": 720}, accept_downloads=True)
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    page.goto(f"{gw.base_url}/#doc={doc_id}")
    page.wait_for_function("() => window.wana && wana.state.live && wana.state.live.ready", timeout=60_000)
    return page


def test_rename_shows_the_new_title_with_the_live_version(browser: Any, gateway: Any) -> None:  # noqa: F811
    errors: list[str] = []
    page = open_doc(browser, gateway, "", errors)
    page.click("#text .cm-content")
    page.keyboard.type("Eve waves. ", delay=20)
    page.wait_for_function("() => wana.state.live.version >= 5 && !wana.state.live.inFlight", timeout=60_000)
    page.once("dialog", lambda d: d.accept("the office"))
    page.click("#rename-doc")
    page.wait_for_function(
        """() => { const o = document.querySelector('#doc-picker').selectedOptions[0];
            return o && o.textContent === 'the office (v' + wana.state.live.version + ')'; }""",
        timeout=60_000,
    )
    doc_id = page.evaluate("() => wana.state.docId")
    assert httpx.get(f"{gateway.base_url}/api/documents/{doc_id}").json()["title"] == "the office"
    renamed_at = page.evaluate("() => wana.state.live.version")
    page.focus("#text .cm-content")
    page.keyboard.type("Eve waves.", delay=20)  # the picker follows the live version as it grows
    page.wait_for_function(
        f"""() => document.querySelector('#doc-picker').selectedOptions[0].textContent
            === 'the office (v' + wana.state.live.version + ')' && wana.state.live.version > {renamed_at}
            && !wana.state.live.inFlight && !wana.state.live.unconfirmed().length""",
        timeout=60_000,
    )
    assert not errors, errors
    page.close()


def test_the_bvh_button_downloads_every_characters_bvh_in_one_zip(browser: Any, gateway: Any) -> None:  # noqa: F811
    errors: list[str] = []
    page = open_doc(browser, gateway, STORY, errors)
    synced = wait_synced(page, timeout_ms=180_000)
    names = sorted(c["name"] for c in synced["characters"])
    if not names:
        pytest.skip(f"no character motion in this build: {synced['unavailable']}")
    with page.expect_download(timeout=180_000) as download:
        page.click("#exports button[data-format=bvh]")
    assert download.value.suggested_filename == "characters-bvh.zip"
    with zipfile.ZipFile(io.BytesIO(open(download.value.path(), "rb").read())) as zf:
        assert sorted(zf.namelist()) == [f"{n}.bvh" for n in names]
        assert all(zf.read(n).startswith(b"HIERARCHY") for n in zf.namelist())
    page.wait_for_function(
        "() => document.getElementById('export-status').textContent === 'saved characters-bvh.zip'"
    )
    assert not errors, errors
    page.close()


def test_keystrokes_reach_the_screen_within_50_ms_while_the_animation_plays(
    browser: Any,  # noqa: F811
    gateway: Any,
) -> None:
    errors: list[str] = []
    page = open_doc(browser, gateway, STORY, errors)
    synced = wait_synced(page, timeout_ms=180_000)
    if not synced["characters"]:
        pytest.skip(f"no character motion in this build: {synced['unavailable']}")
    page.evaluate(
        """() => { wana.timeline.play(); window.keyMs = [];
            document.querySelector('#text .cm-content').addEventListener('keydown', () => {
                const t0 = performance.now();  // two frames later, the key's text has been painted
                requestAnimationFrame(() => requestAnimationFrame(() => window.keyMs.push(performance.now() - t0)));
            }, true); }"""
    )
    # Up to three rounds of 40 keys: on a machine whose cores are all taken, the browser itself is not
    # scheduled now and then; the editor must keep the target in a round it gets the CPU in.
    rounds = []
    for _ in range(3):
        page.evaluate(
            "() => { window.keyMs = []; wana.pane.view.dispatch({selection: {anchor: wana.pane.view.state.doc.length}}); }"
        )
        page.focus("#text .cm-content")
        page.keyboard.type(" Eve waves at Tom. Tom waves back at Eve.", delay=70)
        page.wait_for_timeout(300)
        assert page.evaluate("() => wana.timeline.playing") is True
        times = np.asarray(page.evaluate("() => window.keyMs"))
        assert len(times) >= 35
        rounds.append(float(np.percentile(times, 95)))
        print(f"keystroke to screen while playing: p50 {np.median(times):.1f} ms, p95 {rounds[-1]:.1f} ms")
        if rounds[-1] <= KEYSTROKE_P95_MS:
            break
    assert min(rounds) <= KEYSTROKE_P95_MS, rounds
    wait_synced(page, timeout_ms=180_000)
    assert not errors, errors
    page.close()


def test_the_mp4_button_shows_the_frames_rendered_as_a_percentage_and_cancel_stops_it(
    browser: Any,  # noqa: F811
    gateway: Any,
) -> None:
    pytest.importorskip("services.render.handlers", reason="needs the render service")
    errors: list[str] = []
    page = open_doc(browser, gateway, STORY, errors)
    synced = wait_synced(page, timeout_ms=180_000)
    if not synced["characters"]:
        pytest.skip(f"no character motion in this build: {synced['unavailable']}")
    page.evaluate(
        """() => { window.seenStatus = []; new MutationObserver(() => window.seenStatus.push(
            document.getElementById('export-status').textContent)).observe(
            document.getElementById('export-status'), {childList: true, characterData: true, subtree: true}); }"""
    )
    with page.expect_download(timeout=300_000) as download:
        page.click("#exports button[data-format=mp4]")
    assert download.value.suggested_filename == "animation.mp4"
    assert open(download.value.path(), "rb").read()[4:8] == b"ftyp"
    page.wait_for_function(
        "() => document.getElementById('export-status').textContent === 'saved animation.mp4'", timeout=60_000
    )
    seen = page.evaluate("() => window.seenStatus")
    percents = [s for s in seen if "%" in s and " of " in s]
    assert percents, seen
    values = [float(s.split("MP4 ")[1].split("%")[0]) for s in percents]
    assert values == sorted(values) and values[0] < 100, values  # it grows, from below 100
    assert any(f"of {synced['frames']} frames" in s for s in percents), (percents, synced["frames"])
    assert page.evaluate("() => document.getElementById('export-progress').hidden") is True

    # cancel: the job stops on the gateway (its state is cancelled, with frames left unrendered). A longer story
    # than the one above, so that several chunks are still to render when the click lands even on a fast machine.
    page.close()
    page = open_doc(browser, gateway, LONG_STORY, errors)
    longer = wait_synced(page, timeout_ms=180_000)
    assert longer["frames"] >= 4 * CHUNK_FRAMES, longer["frames"]
    page.evaluate(
        "() => { window.jobs = []; const f = window.fetch; window.fetch = (u, o) => {"
        " if (String(u).endsWith('/mp4/jobs')) return f(u, o).then(r => { r.clone().json().then(j => jobs.push(j.job_id)); return r; });"
        " return f(u, o); }; }"
    )
    page.click("#exports button[data-format=mp4]")
    page.wait_for_function(
        "() => /MP4 \\d+% \\(\\d+ of/.test(document.getElementById('export-status').textContent)"
        " && !/100%/.test(document.getElementById('export-status').textContent)",
        timeout=300_000,
        polling=20,
    )
    assert page.evaluate("() => document.getElementById('export-progress').hidden") is False
    # one export at a time: the buttons wait while this one runs
    assert page.evaluate(
        "() => [...document.querySelectorAll('#exports button[data-format]')].every(b => b.disabled)"
    )
    page.click("#export-cancel")
    page.wait_for_function(
        "() => document.getElementById('export-status').textContent === 'MP4 cancelled'", timeout=60_000
    )
    assert page.evaluate("() => document.querySelector('#exports button[data-format=mp4]').disabled") is False
    doc_id = page.evaluate("() => wana.state.docId")
    job = page.evaluate("() => window.jobs[0]")
    status = httpx.get(f"{gateway.base_url}/api/documents/{doc_id}/export/mp4/jobs/{job}").json()
    assert status["state"] == "cancelled" and status["done"] < status["total"], status
    assert not errors, errors
    page.close()
