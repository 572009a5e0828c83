"""Property test over the gateway's WebSocket decode path: whatever an editor sends, it is answered and served.

Random text, random JSON of every shape, and well-formed messages with hostile values (huge or negative
offsets and versions, enormous change lists) go to one live socket of a real gateway; after each, a ping
must still get its pong, and nothing may have broken the connection.
"""

from __future__ import annotations

import json
import os

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from websockets.sync.client import connect

FUZZ = settings(
    max_examples=int(os.environ.get("WANA_FUZZ_EXAMPLES", "150")),
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)
hostile_ints = st.one_of(
    st.integers(min_value=-(2**70), max_value=2**70), st.sampled_from([0, -1, 2**31, 2**63, 2**64])
)
json_values = st.recursive(
    st.none() | st.booleans() | hostile_ints | st.floats(allow_nan=False) | st.text(max_size=30),
    lambda inner: st.lists(inner, max_size=5) | st.dictionaries(st.text(max_size=10), inner, max_size=5),
    max_leaves=20,
)
changes = st.lists(
    st.fixed_dictionaries({"start": hostile_ints, "end": hostile_ints, "text": st.text(max_size=20)}),
    max_size=4,
)
edits = st.fixed_dictionaries(
    {"type": st.just("edit"), "base_version": hostile_ints, "changes": changes, "client_seq": hostile_ints}
)
messages = st.one_of(
    st.text(max_size=200),
    json_values.map(json.dumps),
    edits.map(json.dumps),
    st.fixed_dictionaries(
        {"type": st.sampled_from(["resume", "ping", "edit", "nope"]), "version": hostile_ints}
    ).map(json.dumps),
)


@pytest.fixture(scope="module")
def live(gateway):
    doc_id = gateway.http.post("/api/documents", json={"text": "Eve walks."}).json()["doc_id"]
    with connect(f"{gateway.ws_base}/api/documents/{doc_id}/live", max_size=None) as ws:
        yield ws


_nonce = iter(range(10**9))


@FUZZ
@given(message=messages)
def test_any_message_is_answered_and_the_socket_keeps_serving(live, message):
    live.send(message)
    nonce = f"n{next(_nonce)}"
    live.send(json.dumps({"type": "ping", "nonce": nonce}))
    while True:  # acks, errors, states and animations may come first
        reply = json.loads(live.recv(timeout=20))
        assert reply["type"] != "error" or reply["code"] in ("E001", "E002", "E010"), reply
        if reply["type"] == "pong" and reply["nonce"] == nonce:
            break
