"""REST for whole documents over a real server and a real SQLite file."""

from __future__ import annotations

import io
import json

import numpy as np
import pytest

from services.gateway.openapi import SPEC_PATH, current_spec, render


def test_create_then_get_returns_the_text_version_sentences_and_export_links(gateway) -> None:
    r = gateway.http.post("/api/documents", json={"text": "A desk$. Eve walks.", "title": "office"})
    assert r.status_code == 201
    doc = r.json()
    got = gateway.http.get(f"/api/documents/{doc['doc_id']}").json()
    assert got["text"] == "A desk$. Eve walks." and got["version"] == 0 and got["title"] == "office"
    assert [(s["start"], s["end"]) for s in got["sentences"]] == [(0, 8), (9, 19)]
    assert set(got["exports"]) == {"mp4", "glb", "bvh", "usd", "fbx", "zip"}
    assert got["live"] == f"/api/documents/{doc['doc_id']}/live"


def test_list_shows_created_documents(gateway) -> None:
    ids = {gateway.http.post("/api/documents", json={"text": f"t{i}."}).json()["doc_id"] for i in range(3)}
    listed = {d["doc_id"] for d in gateway.http.get("/api/documents").json()}
    assert ids <= listed


def test_a_chosen_id_is_kept_and_a_duplicate_is_refused(gateway) -> None:
    assert gateway.http.post("/api/documents", json={"doc_id": "story-1"}).status_code == 201
    r = gateway.http.post("/api/documents", json={"doc_id": "story-1"})
    assert r.status_code == 409 and "already exists" in r.json()["detail"]["message"]
    assert gateway.http.post("/api/documents", json={"doc_id": "../etc"}).status_code == 422


def test_replace_text_bumps_the_version_and_refuses_a_stale_base(gateway) -> None:
    doc_id = gateway.http.post("/api/documents", json={"text": "Eve walks."}).json()["doc_id"]
    r = gateway.http.put(f"/api/documents/{doc_id}/text", json={"text": "Tom runs.", "base_version": 0})
    assert r.status_code == 200 and r.json()["version"] == 1 and r.json()["text"] == "Tom runs."
    stale = gateway.http.put(f"/api/documents/{doc_id}/text", json={"text": "x", "base_version": 0})
    assert stale.status_code == 409 and stale.json()["detail"]["code"] == "E008"
    assert gateway.http.get(f"/api/documents/{doc_id}").json()["text"] == "Tom runs."


def test_rename_sets_the_title_the_list_shows_and_an_unknown_id_is_404(gateway) -> None:
    doc = gateway.http.post("/api/documents", json={"text": "Eve walks.", "title": "untitled"}).json()
    r = gateway.http.patch(f"/api/documents/{doc['doc_id']}", json={"title": "  the office  "})
    assert r.status_code == 200 and r.json()["title"] == "the office"
    listed = {d["doc_id"]: d["title"] for d in gateway.http.get("/api/documents").json()}
    assert listed[doc["doc_id"]] == "the office"
    assert gateway.http.patch("/api/documents/nosuchdoc", json={"title": "x"}).status_code == 404
    assert gateway.http.patch(f"/api/documents/{doc['doc_id']}", json={"title": "x" * 201}).status_code == 422


def test_delete_removes_the_document(gateway) -> None:
    doc_id = gateway.http.post("/api/documents", json={"text": "x."}).json()["doc_id"]
    assert gateway.http.delete(f"/api/documents/{doc_id}").status_code == 204
    assert gateway.http.get(f"/api/documents/{doc_id}").status_code == 404
    assert gateway.http.delete(f"/api/documents/{doc_id}").status_code == 404


def test_unknown_documents_are_404_with_a_code(gateway) -> None:
    r = gateway.http.get("/api/documents/nope")
    assert r.status_code == 404 and r.json()["detail"]["code"] == "E010"
    assert gateway.http.put("/api/documents/nope/text", json={"text": ""}).status_code == 404


def test_exports_answer_503_when_the_render_service_is_not_available(gateway) -> None:
    doc_id = gateway.http.post("/api/documents", json={"text": "Eve walks."}).json()["doc_id"]
    for fmt in ("mp4", "glb", "bvh", "usd", "fbx"):
        r = gateway.http.get(f"/api/documents/{doc_id}/export/{fmt}")
        assert r.status_code == 503 and r.json()["detail"]["code"] == "E011"
        assert f"{fmt.upper()} export is not available" in r.json()["detail"]["message"]
    assert gateway.http.get(f"/api/documents/{doc_id}/export/avi").status_code == 422
    assert gateway.http.get("/api/documents/nope/export/glb").status_code == 404


def test_exports_answer_409_while_there_is_no_scene_to_export(gateway_factory) -> None:
    pytest.importorskip("services.render.handlers", reason="needs the render service")
    gw = gateway_factory(services=("render",))
    doc_id = gw.http.post("/api/documents", json={"text": "Eve walks."}).json()["doc_id"]
    r = gw.http.get(f"/api/documents/{doc_id}/export/glb")
    assert r.status_code == 409 and "nothing to export yet" in r.json()["detail"]["message"]


def test_state_changing_requests_from_another_origin_are_refused(gateway) -> None:
    evil = {"Origin": "http://evil.example"}
    assert gateway.http.post("/api/documents", json={}, headers=evil).status_code == 403
    same = {"Origin": gateway.base}
    assert gateway.http.post("/api/documents", json={}, headers=same).status_code == 201
    assert gateway.http.get("/api/documents", headers=evil).status_code == 200  # reads are not state-changing


def test_a_dns_rebinding_page_whose_origin_equals_the_host_is_refused(gateway) -> None:
    port = gateway.base.rsplit(":", 1)[1]
    rebound = {"Host": f"evil.example:{port}", "Origin": f"http://evil.example:{port}"}
    assert gateway.http.post("/api/documents", json={}, headers=rebound).status_code == 403


def test_a_body_over_the_size_cap_is_refused_with_413(gateway_factory) -> None:
    gw = gateway_factory(max_message_bytes=4096)
    r = gw.http.post(
        "/api/documents",
        content=json.dumps({"text": "x" * 10000}),
        headers={"Content-Type": "application/json"},
    )
    assert r.status_code == 413 and r.json()["detail"]["code"] == "E002"


def test_with_a_token_every_api_call_needs_it(gateway_factory) -> None:
    gw = gateway_factory(token="s3cret")
    assert gw.http.get("/api/documents").status_code == 401
    assert gw.http.get("/api/documents", headers={"Authorization": "Bearer wrong"}).status_code == 401
    assert gw.http.get("/api/documents", headers={"Authorization": "Bearer s3cret"}).status_code == 200
    assert gw.http.get("/api/documents?token=s3cret").status_code == 401  # never in a URL (logs)
    assert gw.http.get("/api/health").status_code == 200


def test_a_browser_logs_in_with_the_token_and_then_uses_a_short_lived_cookie(gateway_factory) -> None:
    gw = gateway_factory(token="s3cret")
    form = {"Content-Type": "application/x-www-form-urlencoded"}
    assert gw.http.post("/api/session", content="token=wrong", headers=form).status_code == 401
    r = gw.http.post("/api/session", content="token=s3cret", headers=form)
    assert r.status_code == 303 and r.headers["location"] == "/"
    cookie = r.headers["set-cookie"]
    assert "HttpOnly" in cookie and "SameSite=strict" in cookie and "Max-Age=43200" in cookie
    assert "s3cret" not in cookie
    assert gw.http.get("/api/documents").status_code == 200  # the client kept the cookie
    assert gw.http.delete("/api/session").status_code == 204
    gw.http.cookies.clear()
    assert gw.http.get("/api/documents").status_code == 401
    evil = {**form, "Origin": "http://evil.example"}
    assert gw.http.post("/api/session", content="token=s3cret", headers=evil).status_code == 403


def test_meshes_of_unknown_categories_are_not_found_or_unavailable(gateway) -> None:
    r = gateway.http.get("/api/meshes/no_such_thing.glb", params={"seed": 0})
    assert r.status_code in (404, 503)
    assert gateway.http.get("/api/meshes/desk.glb", params={"attributes": "[1]"}).status_code == 404


def test_the_committed_openapi_spec_is_current() -> None:
    assert SPEC_PATH.read_text() == render(current_spec()), "run: python -m services.gateway.openapi"


def test_a_catalog_object_is_served_as_glb_with_the_catalogs_geometry(gateway) -> None:
    catalog = pytest.importorskip("wana.assets.catalog", reason="needs the asset catalog")
    trimesh = pytest.importorskip("trimesh")
    url = "/api/meshes/desk.glb"
    r = gateway.http.get(url, params={"seed": 0})
    assert r.status_code == 200 and r.headers["content-type"] == "model/gltf-binary"
    assert r.content[:4] == b"glTF"
    assert gateway.http.get(url, params={"seed": 0}).content == r.content
    loaded = trimesh.load(io.BytesIO(r.content), file_type="glb", force="mesh")
    expected = catalog.make_object("desk", seed=0).mesh
    np.testing.assert_allclose(loaded.bounds, expected.bounds, atol=1e-5)
    assert gateway.http.get("/api/meshes/no_such_thing.glb").status_code == 404


def test_a_chunked_body_over_the_size_cap_is_refused_with_413(gateway_factory) -> None:
    gw = gateway_factory(max_message_bytes=4096)

    def chunks():
        yield b'{"text": "'
        for _ in range(10):
            yield b"x" * 1000
        yield b'"}'

    r = gw.http.post("/api/documents", content=chunks(), headers={"Content-Type": "application/json"})
    assert r.status_code == 413 and r.json()["detail"]["code"] == "E002"


FOUNTAIN = """INT. KITCHEN - NIGHT

ADA walks to the fridge.

ADA
(angrily)
Where is the milk?
"""


def test_a_fountain_screenplay_becomes_the_story_it_tells(gateway) -> None:
    pytest.importorskip("screenplain")
    r = gateway.http.post("/api/documents", json={"text": FOUNTAIN, "title": "milk.fountain"})
    assert r.status_code == 201
    text = r.json()["text"]
    assert text.splitlines()[:2] == ["In the kitchen$.", "night"]
    assert "Ada walks to the fridge." in text and 'Ada angrily says "Where is the milk"' in text
    doc_id = r.json()["doc_id"]
    replaced = gateway.http.put(
        f"/api/documents/{doc_id}/text", json={"text": FOUNTAIN.replace("ADA walks", "ADA runs")}
    )
    assert "Ada runs to the fridge." in replaced.json()["text"]
    plain = gateway.http.post("/api/documents", json={"text": "ADA walks to the fridge.", "title": "notes"})
    assert plain.json()["text"] == "ADA walks to the fridge."  # no heading, no cue: kept as written
