"""Header, array wire form, status and error codes shared by every service's messages.

Schema-evolution rules (msgspec's): new fields get defaults and go last; never change a field's
type; never reorder array-like fields.
"""

from __future__ import annotations

import sys
import typing
import uuid
from enum import StrEnum
from typing import Any, Generic, Literal, TypeVar

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


class ErrorCode(StrEnum):
    """The bus and stage error codes; each is a key of ERROR_CODES (a str, so it goes on the wire as is)."""

    MALFORMED = "E001"
    TOO_LARGE = "E002"
    UNKNOWN_SERVICE = "E003"
    UNKNOWN_REQUEST = "E004"
    BUSY = "E005"
    DEADLINE = "E006"
    WORKER_DIED = "E007"
    STALE = "E008"
    HANDLER_FAILED = "E009"
    INVALID_INPUT = "E010"
    UNAVAILABLE = "E011"
    SCHEMA_VERSION = "E012"
    UNAUTHORISED = "E013"


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
    "E013": "unauthorised: this peer's key (or identity) may not do this",
    "W401": "the animation does not show this (a story check failed: wana.fidelity)",
    "W501": "over the document's compute budget: this part was cut (services/orchestrator/budget.py)",
}


ReplyT = TypeVar("ReplyT", covariant=True)


class Request(msgspec.Struct, Generic[ReplyT], frozen=True, kw_only=True):
    """Base of every request a service answers: ``ReplyT`` is the reply struct it gets when it succeeds.

    ``class ParseRequest(Request["ParseReply"], ...)`` is how a request names its reply, once, so that a
    typed caller (the orchestrator's ``Backend.call``) returns ``ParseReply`` for a ``ParseRequest``. The
    type parameter adds nothing to the wire.
    """


def reply_type(request_type: type) -> type:
    """The reply struct a request type declares through ``Request[ReplyT]``.

    Raises:
        TypeError: the type is not a ``Request[...]`` subclass.
    """
    for klass in request_type.__mro__:
        for base in getattr(klass, "__orig_bases__", ()):
            if typing.get_origin(base) is Request:
                (arg,) = typing.get_args(base)
                if isinstance(arg, typing.ForwardRef):  # Request["ParseReply"]: a name of its module
                    arg = getattr(sys.modules[klass.__module__], arg.__forward_arg__, None)
                if isinstance(arg, type):
                    return arg
    raise TypeError(f"{request_type.__name__} does not declare its reply type (subclass Request[Reply])")


def reply_header(request: Any) -> Header:
    """The header of a reply to ``request``: its msg_id as parent, the same document and revision (a fresh
    header when the request carries none)."""
    h = getattr(request, "header", None)
    if isinstance(h, Header):
        return Header(parent_id=h.msg_id, doc_id=h.doc_id, revision=h.revision)
    return Header()


class ErrorReply(msgspec.Struct, frozen=True, kw_only=True, tag="error_reply"):
    """The reply any service sends when it cannot answer a request."""

    header: Header
    status: Status = "error"
    code: str  # key of ERROR_CODES
    message: str  # human-readable detail
    retryable: bool = False
