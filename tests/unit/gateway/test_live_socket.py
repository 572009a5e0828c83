"""The document WebSocket over a real server: acks, stale rebase, errors, resume, other clients, coalescing."""

from __future__ import annotations

import json
import time
from typing import Any

import pytest
from websockets.exceptions import ConnectionClosed, InvalidStatus
from websockets.sync.client import connect

from services.gateway.app import ServiceSubset
from services.gateway.settings import SERVICES
from services.orchestrator.backend import InProcessBackend
from services.orchestrator.session import Orchestrator


def receive_until(ws: Any, wanted: Any, *, timeout: float = 20.0) -> list[dict[str, Any]]:
    """Messages up to and including the first for which wanted(msg) is true."""
    seen: list[dict[str, Any]] = []
    deadline = time.monotonic() + timeout
    while True:
        msg = json.loads(ws.recv(timeout=max(deadline - time.monotonic(), 0.01)))
        seen.append(msg)
        if wanted(msg):
            return seen


def new_doc(gateway: Any, text: str) -> str:
    return str(gateway.http.post("/api/documents", json={"text": text}).json()["doc_id"])


def edit(ws: Any, base: int, start: int, end: int, text: str, seq: int = 0) -> None:
    ws.send(
        json.dumps(
            {
                "type": "edit",
                "base_version": base,
                "client_seq": seq,
                "changes": [{"start": start, "end": end, "text": text}],
            }
        )
    )


def test_connecting_sends_the_text_then_diagnostics_and_animation_for_that_version(gateway) -> None:
    doc_id = new_doc(gateway, "A desk$. Eve walks.")
    with connect(f"{gateway.ws_base}/api/documents/{doc_id}/live") as ws:
        first = json.loads(ws.recv(timeout=10))
        assert first["type"] == "state" and first["text"] == "A desk$. Eve walks." and first["version"] == 0
        seen = receive_until(ws, lambda m: m["type"] == "diagnostics" and not m["verdicts_pending"])
        animation = next(m for m in seen if m["type"] == "animation")
        diags = [m for m in seen if m["type"] == "diagnostics"]
        assert diags and diags[-1]["version"] == 0 and animation["version"] == 0
        assert seen.index(animation) < seen.index(diags[0])  # the preview does not wait for diagnostics
        assert [(s["start"], s["end"]) for s in diags[-1]["sentences"]] == [(0, 8), (9, 19)]


def test_an_edit_is_acknowledged_persisted_and_followed_by_the_new_animation(gateway) -> None:
    doc_id = new_doc(gateway, "Eve walks.")
    with connect(f"{gateway.ws_base}/api/documents/{doc_id}/live") as ws:
        receive_until(ws, lambda m: m["type"] == "animation")
        edit(ws, 0, 4, 9, "runs", seq=7)
        seen = receive_until(ws, lambda m: m["type"] == "animation" and m["version"] == 1)
        ack = next(m for m in seen if m["type"] == "ack")
        assert ack["version"] == 1 and ack["client_seq"] == 7 and ack["changed"]
        assert seen.index(ack) < len(seen) - 1
    assert gateway.http.get(f"/api/documents/{doc_id}").json()["text"] == "Eve runs."


def test_a_stale_edit_gets_the_current_version_and_text_to_rebase_on(gateway) -> None:
    doc_id = new_doc(gateway, "Eve walks.")
    with connect(f"{gateway.ws_base}/api/documents/{doc_id}/live") as ws:
        edit(ws, 0, 0, 3, "Tom")
        receive_until(ws, lambda m: m["type"] == "ack")
        edit(ws, 0, 0, 3, "Ann")
        stale = receive_until(ws, lambda m: m["type"] == "stale")[-1]
        assert stale["current_version"] == 1 and stale["text"] == "Tom walks."
        edit(ws, 1, 0, 3, "Ann")
        assert receive_until(ws, lambda m: m["type"] == "ack")[-1]["version"] == 2
    assert gateway.http.get(f"/api/documents/{doc_id}").json()["text"] == "Ann walks."


def test_a_stale_edit_gets_the_edits_it_missed_as_they_were_made(gateway) -> None:
    doc_id = new_doc(gateway, "Eve walks.")
    with connect(f"{gateway.ws_base}/api/documents/{doc_id}/live") as ws:
        edit(ws, 0, 0, 3, "Tom")
        receive_until(ws, lambda m: m["type"] == "ack")
        edit(ws, 1, 10, 10, " Ann sits.")
        receive_until(ws, lambda m: m["type"] == "ack")
        edit(ws, 0, 0, 0, "x")
        stale = receive_until(ws, lambda m: m["type"] == "stale")[-1]
        assert stale["updates"] == [
            {"base_version": 0, "version": 1, "changes": [{"start": 0, "end": 3, "text": "Tom"}]},
            {"base_version": 1, "version": 2, "changes": [{"start": 10, "end": 10, "text": " Ann sits."}]},
        ]
        edit(ws, 2, 0, 0, "x")  # nothing missed: no stale
        assert receive_until(ws, lambda m: m["type"] in ("ack", "stale"))[-1]["type"] == "ack"


def test_a_clients_selection_is_relayed_to_the_others_and_its_leaving_too(gateway) -> None:
    doc_id = new_doc(gateway, "Eve walks.")
    url = f"{gateway.ws_base}/api/documents/{doc_id}/live"
    with connect(url) as a, connect(url) as b:
        receive_until(a, lambda m: m["type"] == "state")
        receive_until(b, lambda m: m["type"] == "state")
        a.send(json.dumps({"type": "presence", "version": 0, "anchor": 4, "head": 9}))
        seen = receive_until(b, lambda m: m["type"] == "presence")[-1]
        assert (seen["version"], seen["anchor"], seen["head"]) == (0, 4, 9) and seen["client"]
        a.close()
        gone = receive_until(b, lambda m: m["type"] == "presence" and m.get("gone"))[-1]
        assert gone["client"] == seen["client"]


def test_bad_messages_get_errors_and_the_connection_keeps_serving(gateway) -> None:
    doc_id = new_doc(gateway, "Eve walks.")
    with connect(f"{gateway.ws_base}/api/documents/{doc_id}/live") as ws:
        ws.send("not json")
        assert receive_until(ws, lambda m: m["type"] == "error")[-1]["code"] == "E001"
        ws.send(json.dumps({"type": "edit", "base_version": 0}))
        assert receive_until(ws, lambda m: m["type"] == "error")[-1]["code"] == "E001"
        edit(ws, 0, 5, 500, "x")
        error = receive_until(ws, lambda m: m["type"] == "error")[-1]
        assert error["code"] == "E010" and "outside the document" in error["message"]
        ws.send(json.dumps({"type": "ping", "nonce": "n1"}))
        pong = receive_until(ws, lambda m: m["type"] == "pong")[-1]
        assert pong == {"type": "pong", "nonce": "n1", "version": 0}


def test_too_many_changes_or_a_too_large_message_are_refused(gateway_factory) -> None:
    gw = gateway_factory(max_changes=2, max_message_bytes=2048)
    doc_id = new_doc(gw, "Eve walks.")
    with connect(f"{gw.ws_base}/api/documents/{doc_id}/live", max_size=None) as ws:
        changes = [{"start": i, "end": i, "text": "a"} for i in range(3)]
        ws.send(json.dumps({"type": "edit", "base_version": 0, "changes": changes}))
        assert "at most 2 changes" in receive_until(ws, lambda m: m["type"] == "error")[-1]["message"]
        edit(ws, 0, 0, 0, "y" * 5000)  # over max_message_bytes: the app answers E002 and keeps serving
        error = receive_until(ws, lambda m: m["type"] == "error")[-1]
        assert error["code"] == "E002" and "2048" in error["message"]
        ws.send(json.dumps({"type": "ping", "nonce": "still"}))
        assert receive_until(ws, lambda m: m["type"] == "pong")[-1]["nonce"] == "still"
        edit(ws, 0, 0, 0, "y" * 20000)
        with pytest.raises(ConnectionClosed):  # over uvicorn's hard cap (4x): closed with 1009
            receive_until(ws, lambda m: False, timeout=5)
    assert gw.http.get(f"/api/documents/{doc_id}").json()["version"] == 0


def test_a_reconnecting_client_resumes_with_the_current_text_and_results(gateway) -> None:
    doc_id = new_doc(gateway, "Eve walks.")
    with connect(f"{gateway.ws_base}/api/documents/{doc_id}/live") as ws:
        edit(ws, 0, 0, 3, "Tom")
        receive_until(ws, lambda m: m["type"] == "animation" and m["version"] == 1)
    gateway.http.put(f"/api/documents/{doc_id}/text", json={"text": "Tom sits."})  # changed while away
    with connect(f"{gateway.ws_base}/api/documents/{doc_id}/live?version=1") as ws:
        state = json.loads(ws.recv(timeout=10))
        assert state["type"] == "state" and state["resumed_from"] == 1
        assert (state["version"], state["text"]) == (2, "Tom sits.")
        assert receive_until(ws, lambda m: m["type"] == "animation")[-1]["version"] == 2


def test_other_clients_of_the_document_receive_each_edit(gateway) -> None:
    doc_id = new_doc(gateway, "Eve walks.")
    url = f"{gateway.ws_base}/api/documents/{doc_id}/live"
    with connect(url) as alice, connect(url) as bob:
        receive_until(bob, lambda m: m["type"] == "state")
        edit(alice, 0, 0, 3, "Tom")
        remote = receive_until(bob, lambda m: m["type"] == "remote_edit")[-1]
        assert (remote["base_version"], remote["version"]) == (0, 1)
        assert remote["changes"] == [{"start": 0, "end": 3, "text": "Tom"}]
        assert all(m["type"] != "remote_edit" for m in receive_until(alice, lambda m: m["type"] == "ack"))


def test_unknown_document_and_foreign_origin_are_closed(gateway_factory) -> None:
    gw = gateway_factory(token="tok")
    with pytest.raises(InvalidStatus):
        with connect(f"{gw.ws_base}/api/documents/x/live"):
            pass
    doc_id = str(
        gw.http.post("/api/documents", json={}, headers={"Authorization": "Bearer tok"}).json()["doc_id"]
    )
    with pytest.raises(InvalidStatus):
        with connect(
            f"{gw.ws_base}/api/documents/{doc_id}/live",
            origin="http://evil.example",
            additional_headers={"Authorization": "Bearer tok"},
        ):
            pass
    with pytest.raises(InvalidStatus):  # the token in the URL is no longer accepted
        with connect(f"{gw.ws_base}/api/documents/{doc_id}/live?token=tok"):
            pass
    login = gw.http.post("/api/session", headers={"Authorization": "Bearer tok"})
    cookie = f"wana_session={login.cookies['wana_session']}"
    with connect(f"{gw.ws_base}/api/documents/nope/live", additional_headers={"Cookie": cookie}) as ws:
        assert json.loads(ws.recv(timeout=10))["code"] == "E010"
        with pytest.raises(ConnectionClosed) as closed:
            ws.recv(timeout=10)
        assert closed.value.rcvd is not None and closed.value.rcvd.code == 4404


class SlowBackend(ServiceSubset):
    """The gateway's service-subset backend (no service enabled), slowed down so that edits land while a
    compute runs."""

    def __init__(self) -> None:
        super().__init__(InProcessBackend(), {s: "disabled in this test" for s in SERVICES})

    def call(self, request: Any) -> Any:
        time.sleep(0.15)
        return super().call(request)


def test_edits_during_a_compute_are_coalesced_and_only_the_newest_version_is_pushed(
    gateway_factory, tmp_path
) -> None:
    orch = Orchestrator(tmp_path / "slow.sqlite", SlowBackend())
    gw = gateway_factory(orchestrator=orch)
    doc_id = orch.create("Eve walks.").doc_id
    with connect(f"{gw.ws_base}/api/documents/{doc_id}/live") as ws:
        receive_until(ws, lambda m: m["type"] == "animation")
        for v in range(6):
            edit(ws, v, 10 + v, 10 + v, "!")
        seen = receive_until(ws, lambda m: m["type"] == "animation" and m["version"] == 6, timeout=30)
    animations = [m["version"] for m in seen if m["type"] == "animation"]
    assert [m["version"] for m in seen if m["type"] == "ack"] == [1, 2, 3, 4, 5, 6]
    assert animations == sorted(animations) and len(animations) < 6
    orch.close()


@pytest.mark.slow
def test_with_only_the_parser_enabled_sentences_get_kinds_and_the_rest_is_reported_unavailable(
    gateway_factory,
) -> None:
    pytest.importorskip("services.nlp.handlers", reason="needs the NLP service")
    gw = gateway_factory(services=("nlp",))
    doc_id = new_doc(gw, "In the office there is a desk$. Eve walks to the desk.")
    with connect(f"{gw.ws_base}/api/documents/{doc_id}/live") as ws:
        seen = receive_until(ws, lambda m: m["type"] == "diagnostics", timeout=120)
    diags = seen[-1]
    assert [s["kind"] for s in diags["sentences"]] == ["scene", "action"]
    assert "parse" not in diags["unavailable"] and "scene" in diags["unavailable"]
    assert "not enabled" in diags["unavailable"]["scene"]


class BlockedBackend(ServiceSubset):
    """A backend whose first call waits until the test releases it: a compute that runs as long as needed."""

    def __init__(self) -> None:
        super().__init__(InProcessBackend(), {s: "disabled in this test" for s in SERVICES})
        import threading

        self.entered = threading.Event()
        self.release = threading.Event()

    def call(self, request: Any) -> Any:
        self.entered.set()
        assert self.release.wait(60), "the test never released the compute"
        return super().call(request)


def test_edits_and_reads_are_answered_while_a_compute_runs(gateway_factory, tmp_path) -> None:
    backend = BlockedBackend()
    orch = Orchestrator(tmp_path / "blocked.sqlite", backend)
    gw = gateway_factory(orchestrator=orch)
    doc_id = orch.create("Eve walks.").doc_id
    try:
        with connect(f"{gw.ws_base}/api/documents/{doc_id}/live") as ws:
            assert backend.entered.wait(20)  # the compute runs, and stays inside the pipeline
            assert gw.http.get(f"/api/documents/{doc_id}", timeout=5).json()["version"] == 0
            edit(ws, 0, 10, 10, "!")
            acks = receive_until(ws, lambda m: m["type"] == "ack", timeout=5)
            assert acks[-1]["version"] == 1 and not backend.release.is_set()
            assert gw.http.get(f"/api/documents/{doc_id}", timeout=5).json()["text"] == "Eve walks.!"
            backend.release.set()
            receive_until(ws, lambda m: m["type"] == "animation" and m["version"] == 1, timeout=30)
    finally:
        backend.release.set()
        orch.close()
