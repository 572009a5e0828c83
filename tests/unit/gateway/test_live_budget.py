"""The gateway's compute budget: a hostile document is cut with W501 warnings, its other sentences still parse."""

from __future__ import annotations

import json

from websockets.sync.client import connect

from tests.unit.gateway.test_live_socket import new_doc, receive_until


def test_a_hostile_document_gets_w501_on_what_was_cut_and_the_rest_is_parsed(gateway_factory) -> None:
    gateway = gateway_factory(services=("nlp",), max_sentences=3, max_sentence_chars=200)
    text = "Eve waves. Eve " + "very " * 100 + "slowly sits. Tom waves. Tom sits. Eve walks."
    doc_id = new_doc(gateway, text)
    with connect(f"{gateway.ws_base}/api/documents/{doc_id}/live") as ws:
        assert json.loads(ws.recv(timeout=10))["type"] == "state"
        diags = receive_until(ws, lambda m: m["type"] == "diagnostics", timeout=60)[-1]
    ids = [s["id"] for s in diags["sentences"]]
    cut = {d["sentence_id"]: d["message"] for d in diags["diagnostics"] if d["code"] == "W501"}
    assert set(cut) == {ids[1], ids[3], ids[4]}
    assert "characters long" in cut[ids[1]] and "only the first 3" in cut[ids[3]]
    kinds = {s["id"]: s["kind"] for s in diags["sentences"]}
    assert kinds[ids[0]] == kinds[ids[2]] == "action"
