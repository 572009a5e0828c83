"""The gateway's readiness endpoint and its /metrics, as the probe and Prometheus see them."""

from __future__ import annotations

from fastapi.testclient import TestClient
from prometheus_client.parser import text_string_to_metric_families

from services.gateway.app import create_app
from services.gateway.settings import Settings, parse_services


def edit_acks(client: TestClient) -> float:
    response = client.get("/metrics")
    assert response.status_code == 200 and response.headers["content-type"].startswith("text/plain")
    for family in text_string_to_metric_families(response.text):
        for sample in family.samples:
            if sample.name == "wana_gateway_edit_ack_seconds_count":
                return sample.value
    raise AssertionError("no wana_gateway_edit_ack_seconds in /metrics")


def test_healthz_is_unready_until_the_session_database_is_open_then_ready(tmp_path):
    settings = Settings(
        db=tmp_path / "s.sqlite", backend="inprocess", services=parse_services("nlp"), token="t"
    )
    app = create_app(settings)
    before = TestClient(app)  # no lifespan: the orchestrator is not open
    assert before.get("/healthz").status_code == 503
    with TestClient(app) as client:
        response = client.get("/healthz")  # no token needed: the kubelet has none
        assert response.status_code == 200 and response.json() == {"status": "ok"}


def test_an_acknowledged_edit_is_counted_in_the_edit_ack_histogram(tmp_path):
    settings = Settings(db=tmp_path / "s.sqlite", backend="inprocess", services=parse_services("nlp"))
    with TestClient(create_app(settings)) as client:
        start = edit_acks(client)
        assert client.post("/api/documents", json={"text": "", "doc_id": "d"}).status_code == 201
        for text in ("Eve sits.", "Eve sits. Tom waves."):
            assert client.put("/api/documents/d/text", json={"text": text}).status_code == 200
        assert edit_acks(client) == start + 2
        refused = client.put("/api/documents/d/text", json={"text": "x", "base_version": 99})
        assert refused.status_code == 409
        assert edit_acks(client) == start + 2  # a stale edit is not acknowledged
