"""Over a real WebSocket with the real services: an edit of one character's action resends only that character.

The other character's entry arrives as `{"name", "hash", "unchanged": true}`; a reconnecting client and one
that sends `resume` get every character in full again.
"""

from __future__ import annotations

import base64
import json
from typing import Any

import numpy as np
import pytest
from websockets.sync.client import connect

from tests.unit.gateway.test_live_socket import edit, new_doc, receive_until

# Eve's sentence comes first and Tom's two walks outlast her action before and after the edit, so her edit
# leaves Tom's timeline (and the length everyone is padded to) as it was.
TEXT = "Eve waves. Tom walks to the door. Tom walks to the window."
TIMEOUT_S = 180.0  # the first compute loads the parser and the motion models


def _animation(ws: Any, version: int) -> dict[str, Any]:
    return receive_until(
        ws, lambda m: m["type"] == "animation" and m["version"] == version, timeout=TIMEOUT_S
    )[-1]


def _by_name(message: dict[str, Any]) -> dict[str, dict[str, Any]]:
    return {c["name"]: c for c in message["characters"]}


def _rotations(entry: dict[str, Any]) -> np.ndarray:
    return np.frombuffer(base64.b64decode(entry["rotations"]), "<f4")


@pytest.fixture(scope="module")
def services_gateway(tmp_path_factory: pytest.TempPathFactory) -> Any:
    """A gateway whose pipeline runs every service in-process."""
    from services.gateway.server import GatewayThread
    from services.gateway.settings import Settings
    from tests.unit.gateway.conftest import _running

    settings = Settings(db=tmp_path_factory.mktemp("gw") / "s.sqlite", backend="inprocess", services=None)
    with GatewayThread(settings) as gw:
        r = _running(gw)
        yield r
        r.http.close()


def test_a_second_edit_of_one_characters_action_sends_the_other_character_as_unchanged(
    services_gateway: Any,
) -> None:
    gw = services_gateway
    doc_id = new_doc(gw, TEXT)
    url = f"{gw.ws_base}/api/documents/{doc_id}/live"
    with connect(url, max_size=None) as ws:
        first = _animation(ws, 0)
        assert len(first["characters"]) == 2, f"no motion for both characters: {first['unavailable']}"
        before = _by_name(first)
        assert not any(c.get("unchanged") for c in first["characters"])  # a new client gets everything
        at = TEXT.index("waves")
        edit(ws, 0, at, at + len("waves"), "drinks", seq=1)
        second = _animation(ws, 1)
        after = _by_name(second)
        assert "rotations" in after["Eve"] and after["Eve"]["hash"] != before["Eve"]["hash"]
        assert [s["action"] for s in after["Eve"]["segments"]] != [
            s["action"] for s in before["Eve"]["segments"]
        ]
        assert after["Tom"] == {"name": "Tom", "hash": before["Tom"]["hash"], "unchanged": True}
        assert len(json.dumps(second)) < 0.75 * len(json.dumps(first))

        # Edit back: Eve is sent again (the client holds only the last message's entries), Tom stays a stub.
        edit(ws, 1, at, at + len("drinks"), "waves", seq=2)
        third = _by_name(_animation(ws, 2))
        assert third["Eve"]["hash"] == before["Eve"]["hash"] and "rotations" in third["Eve"]
        assert third["Tom"].get("unchanged") is True

        # `resume` on the same connection: everything in full.
        ws.send(json.dumps({"type": "resume", "version": 2}))
        resumed = _by_name(_animation(ws, 2))
        assert not any(c.get("unchanged") for c in resumed.values())
        np.testing.assert_array_equal(_rotations(resumed["Tom"]), _rotations(before["Tom"]))

    # A reconnecting client (a new connection) holds nothing: both characters in full, Tom's arrays as before.
    with connect(f"{url}?version=2", max_size=None) as ws:
        again = _by_name(_animation(ws, 2))
        assert not any(c.get("unchanged") for c in again.values())
        np.testing.assert_array_equal(_rotations(again["Tom"]), _rotations(before["Tom"]))
        np.testing.assert_array_equal(_rotations(again["Eve"]), _rotations(before["Eve"]))


def test_two_clients_each_get_stubs_only_for_what_they_were_sent(services_gateway: Any) -> None:
    gw = services_gateway
    doc_id = new_doc(gw, TEXT)
    url = f"{gw.ws_base}/api/documents/{doc_id}/live"
    with connect(url, max_size=None) as alice:
        first = _animation(alice, 0)
        assert len(first["characters"]) == 2, f"no motion for both characters: {first['unavailable']}"
        at = TEXT.index("waves")
        edit(alice, 0, at, at + len("waves"), "drinks", seq=1)
        receive_until(alice, lambda m: m["type"] == "ack", timeout=TIMEOUT_S)
        with connect(url, max_size=None) as bob:  # joins after the edit: holds nothing yet
            bobs = _by_name(_animation(bob, 1))
            alices = _by_name(_animation(alice, 1))
        assert not any(c.get("unchanged") for c in bobs.values())
        assert alices["Tom"].get("unchanged") is True and "rotations" in alices["Eve"]
        assert bobs["Tom"]["hash"] == alices["Tom"]["hash"]
