"""The preview does not wait for the story checks: the animation first, the verdicts as their own delta."""

from __future__ import annotations

from typing import Any

import pytest
from websockets.sync.client import connect

from services.gateway.settings import SERVICES
from tests.unit.gateway.test_live_socket import edit, new_doc, receive_until

pytestmark = pytest.mark.slow  # the whole pipeline, to have a story check that fails

STORY = "A sofa is near a window$. Eve drinks from the cup. Eve sits on the sofa."


def merge(state: dict[str, Any], msg: dict[str, Any]) -> dict[str, Any]:
    """editor/src/diagmerge.js in Python: sentence id -> (its entries, its verdict)."""
    starts = {s["id"]: s["start"] for s in msg["sentences"]}
    entries: dict[str, list[dict[str, Any]]] = {}
    verdicts: dict[str, Any] = {}
    if msg["base_seq"] is not None:
        assert msg["base_seq"] == state["seq"], "a delta on a state this client does not hold"
        for sid, items in state["entries"].items():
            if sid in msg["changed"] or sid in msg["dropped"]:
                continue
            shift = starts.get(sid, 0) - state["starts"].get(sid, 0)
            entries[sid] = [{**d, "start": d["start"] + shift, "end": d["end"] + shift} for d in items]
        verdicts = {
            k: v for k, v in state["verdicts"].items() if k not in msg["changed"] and k not in msg["dropped"]
        }
    for d in msg["diagnostics"]:
        entries.setdefault(d["sentence_id"], []).append(d)
    verdicts.update({v["sentence_id"]: v for v in msg["verdicts"]})
    return {"seq": msg["seq"], "starts": starts, "entries": entries, "verdicts": verdicts}


def judged(ws: Any, version: int, state: dict[str, Any], seen: list[dict[str, Any]]) -> dict[str, Any]:
    got = receive_until(
        ws,
        lambda m: m["type"] == "diagnostics" and m["version"] == version and not m["verdicts_pending"],
        timeout=300,
    )
    seen.extend(got)
    for m in got:
        if m["type"] == "diagnostics":
            state = merge(state, m)
    return state


def test_the_animation_comes_before_the_verdicts_and_the_verdicts_reach_the_lint_marks(
    gateway_factory,
) -> None:
    pytest.importorskip("services.nlp.handlers", reason="needs the NLP service")
    gw = gateway_factory(services=SERVICES)
    doc_id = new_doc(gw, STORY)
    seen: list[dict[str, Any]] = []
    with connect(f"{gw.ws_base}/api/documents/{doc_id}/live", max_size=None) as ws:
        state = judged(ws, 0, {"seq": None, "starts": {}, "entries": {}, "verdicts": {}}, seen)
        kinds = [m["type"] for m in seen if m["type"] in ("animation", "diagnostics")]
        assert kinds[0] == "animation" and kinds[-1] == "diagnostics"
        drink = next(sid for sid, start in state["starts"].items() if STORY[start:].startswith("Eve drinks"))
        assert state["verdicts"][drink]["verdict"] == "failed"
        assert any(d["code"] == "W401" and "cup" in d["message"] for d in state["entries"][drink])

        # an edit of the last sentence: the drink sentence is not sent again, and keeps its W401 mark
        at = STORY.index("sits")
        edit(ws, 0, at, at + 4, "stands")
        seen.clear()
        state = judged(ws, 1, state, seen)
        deltas = [m for m in seen if m["type"] == "diagnostics"]
        assert deltas and all(drink not in m["changed"] for m in deltas)
        assert any(d["code"] == "W401" for d in state["entries"][drink])

    # the merged marks are what a new client gets whole
    with connect(f"{gw.ws_base}/api/documents/{doc_id}/live", max_size=None) as ws:
        fresh = judged(ws, 1, {"seq": None, "starts": {}, "entries": {}, "verdicts": {}}, [])
    assert fresh["entries"] == state["entries"] and fresh["verdicts"] == state["verdicts"]
