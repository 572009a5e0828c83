"""Over a real WebSocket with the real services: `?wire=binary` animation frames, patched per changed frames.

A client holding version N of a character is sent a patch against it; rebuilt, it equals what a new client
is sent in full for N + 1. The editor's bundle is served gzipped to a browser that accepts it.
"""

from __future__ import annotations

import json
import time
from pathlib import Path
from typing import Any

from websockets.sync.client import connect

from services.gateway import animwire
from tests.unit.gateway.test_live_delta import services_gateway  # noqa: F401  (the fixture)
from tests.unit.gateway.test_live_socket import edit, new_doc

TEXT = "Eve walks to the door. Eve waves. Tom waves. Eve walks to the window."  # the edit: the last walk
TIMEOUT_S = 180.0


def _until_animation(ws: Any, version: int | None) -> tuple[dict[str, Any], list[Any], int]:
    """The binary animation frame of `version` (None: the first): header, blobs, its size."""
    deadline = time.monotonic() + TIMEOUT_S
    while True:
        raw = ws.recv(timeout=max(deadline - time.monotonic(), 0.01))
        if isinstance(raw, bytes) and raw[:4] == animwire.TEXT_MAGIC:
            assert json.loads(animwire.decompress_text(raw))["type"] != "animation"
        elif isinstance(raw, bytes):
            header, blobs = animwire.unpack(raw)
            if version is None or header["version"] == version:
                return header, blobs, len(raw)
        elif json.loads(raw)["type"] == "ack":
            version = json.loads(raw)["version"]


def test_a_client_holding_the_last_version_is_sent_patches_that_rebuild_the_new_one(
    services_gateway: Any,  # noqa: F811
) -> None:
    doc = new_doc(services_gateway, TEXT)
    url = f"{services_gateway.ws_base}/api/documents/{doc}/live?wire=binary"
    with connect(url, max_size=None) as ws:
        first, blobs, full_size = _until_animation(ws, None)
        held = {c["hash"]: animwire.entry_frames(c, blobs, None) for c in first["characters"]}
        assert all("patch" not in c for c in first["characters"])
        at = TEXT.rindex("walks")
        edit(ws, first["version"], at, at + len("walks"), "runs")
        second, blobs2, patch_size = _until_animation(ws, first["version"] + 1)
    by_name = {c["name"]: c for c in second["characters"]}
    assert "patch" in by_name["Eve"], "Eve's run changed her frames: a patch of what this client held"
    rebuilt = {
        c["name"]: held[c["hash"]]
        if c.get("unchanged")
        else animwire.entry_frames(c, blobs2, held.get(c.get("patch", "")))
        for c in second["characters"]
    }
    with connect(url, max_size=None) as fresh:
        full, blobs3, _ = _until_animation(fresh, second["version"])
    for c in full["characters"]:
        want = animwire.entry_frames(c, blobs3, None)
        got = rebuilt[c["name"]]
        assert (
            got.rotations.tobytes() == want.rotations.tobytes() and got.root.tobytes() == want.root.tobytes()
        )
        assert c["hash"] == by_name[c["name"]]["hash"]
    assert patch_size < full_size / 2, (patch_size, full_size)


def test_the_editor_bundle_is_served_gzipped(gateway_factory: Any, tmp_path: Path) -> None:
    dist = tmp_path / "dist"
    (dist / "assets").mkdir(parents=True)
    (dist / "index.html").write_text("<!doctype html><title>wana</title>")
    bundle = "export const words = [" + ",".join(f'"word{i}"' for i in range(5000)) + "];\n"
    (dist / "assets" / "index.js").write_text(bundle)
    gw = gateway_factory(editor_dist=dist)
    zipped = gw.http.get("/assets/index.js", headers={"Accept-Encoding": "gzip"})
    assert zipped.status_code == 200 and zipped.headers["content-encoding"] == "gzip"
    assert zipped.text == bundle  # httpx inflates it
    assert int(zipped.headers["content-length"]) < len(bundle) / 3
    plain = gw.http.get("/assets/index.js", headers={"Accept-Encoding": "identity"})
    assert "content-encoding" not in plain.headers and plain.text == bundle
