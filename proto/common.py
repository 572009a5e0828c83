"""Header, array wire form, status and error codes shared by every service's messages.

Schema-evolution rules (msgspec's): new fields get defaults and go last; never change a field's
type; never reorder array-like fields.
"""

from __future__ import annotations

import uuid
from typing import Literal

import msgspec

from proto import SCHEMA_VERSION

Status = Literal["ok", "error"]


class Header(msgspec.Struct, frozen=True, kw_only=True):
    """Carried by every request and reply."""

    msg_id: str = msgspec.field(default_factory=lambda: uuid.uuid4().hex)
    parent_id: str = ""  # msg_id of the request a reply answers; "" on requests
    doc_id: str = ""  # document the work belongs to; "" for stateless calls
    revision: int = 0  # document revision the work was computed for
    version: int = SCHEMA_VERSION  # schema version of the sender


class NDArray(msgspec.Struct, frozen=True, kw_only=True):
    """A dense array on the wire: C-order little-endian bytes plus dtype and shape.

    Convert with wana.arrays.to_wire / from_wire (proto must not import numpy).
    """

    dtype: str  # numpy dtype string, e.g. "<f4"
    shape: list[int]
    data: bytes


class Span(msgspec.Struct, frozen=True, array_like=True):
    """Character range [start, end) in the document (or sentence) text."""

    start: int
    end: int


# One table of error codes for every service (spaCy-style numbered errors).
ERROR_CODES: dict[str, str] = {
    "E001": "malformed frame: could not decode the message",
    "E002": "frame too large",
    "E003": "unknown service",
    "E004": "unknown request type",
    "E005": "service busy: queue full, retry later",
    "E006": "deadline exceeded",
    "E007": "worker died too many times while handling the job",
    "E008": "stale revision: the document has moved on",
    "E009": "handler raised an exception",
    "E010": "invalid input",
    "E011": "stage not available yet",
    "E012": "schema version not supported",
    "W401": "the animation does not show this (a story check failed: wana.fidelity)",
}


class ErrorReply(msgspec.Struct, frozen=True, kw_only=True, tag="error_reply"):
    """The reply any service sends when it cannot answer a request."""

    header: Header
    status: Status = "error"
    code: str  # key of ERROR_CODES
    message: str  # human-readable detail
    retryable: bool = False
