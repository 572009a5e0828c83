"""Messages the editor sends over the document WebSocket (JSON, `type` is the tag).

Replies and pushes are plain dicts built in services.gateway.messages; README.md lists them all.
"""

from __future__ import annotations

from typing import Union

import msgspec


class Change(msgspec.Struct, frozen=True, kw_only=True):
    """Replace characters [start, end) of the base version by text (UTF-16 code unit offsets are NOT used:
    offsets count Unicode code points, as Python's str does)."""

    start: int
    end: int
    text: str


class Edit(msgspec.Struct, frozen=True, kw_only=True, tag="edit", tag_field="type"):
    base_version: int  # the document version the changes were made against
    changes: list[Change]
    client_seq: int = 0  # echoed in the ack so a client can match acks to its edits


class Resume(msgspec.Struct, frozen=True, kw_only=True, tag="resume", tag_field="type"):
    version: int = -1  # the last version the client saw; it gets the current text and results


class Ping(msgspec.Struct, frozen=True, kw_only=True, tag="ping", tag_field="type"):
    nonce: str = ""


class Presence(msgspec.Struct, frozen=True, kw_only=True, tag="presence", tag_field="type"):
    """Where this client's selection is (code points of `version`): relayed to the document's other clients."""

    version: int
    anchor: int
    head: int


ClientMessage = Union[Edit, Resume, Ping, Presence]  # noqa: UP007 - runtime union for the decoder
decoder = msgspec.json.Decoder(ClientMessage)
