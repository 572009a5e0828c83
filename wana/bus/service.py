"""Turn a service's typed contract into a bytes -> bytes frame handler for the bus.

A contract maps each request struct type to a pure handler returning a reply struct. Request
types are tagged msgspec structs, so one decoder over their union picks the type; anything that
does not decode, or a handler that raises, becomes an ErrorReply and the worker keeps serving.
"""

from __future__ import annotations

import logging
import traceback
from collections.abc import Callable
from typing import Any, Union

import msgspec

from proto import SCHEMA_VERSION
from proto.common import ErrorCode, ErrorReply, Header, reply_header

log = logging.getLogger(__name__)

Contract = dict[type, Callable[[Any], Any]]


class InvalidInput(ValueError):
    """Raised by a handler for input it refuses; becomes an E010 error reply."""


def make_frame_handler(contract: Contract) -> Callable[[bytes], bytes]:
    """Build the worker's frame handler: decode -> dispatch by type -> encode."""
    types = tuple(contract)
    if not types:
        raise ValueError("a contract needs at least one request type")
    union = types[0] if len(types) == 1 else Union[types]  # noqa: UP007 - runtime union of types
    decoder = msgspec.msgpack.Decoder(union)
    encoder = msgspec.msgpack.Encoder()

    def handle_frame(payload: bytes) -> bytes:
        try:
            request = decoder.decode(payload)
        except (msgspec.DecodeError, ValueError) as exc:  # ValueError: e.g. a string that is not UTF-8
            return encoder.encode(ErrorReply(header=Header(), code=ErrorCode.MALFORMED, message=str(exc)))
        header = getattr(request, "header", None)
        if isinstance(header, Header) and header.version != SCHEMA_VERSION:
            why = f"schema version {header.version} is not supported (this worker speaks {SCHEMA_VERSION})"
            return encoder.encode(
                ErrorReply(header=reply_header(request), code=ErrorCode.SCHEMA_VERSION, message=why)
            )
        try:
            reply = contract[type(request)](request)
        except InvalidInput as exc:
            return encoder.encode(
                ErrorReply(header=reply_header(request), code=ErrorCode.INVALID_INPUT, message=str(exc))
            )
        except Exception as exc:  # a handler bug must not take the worker down
            log.error("handler failed: %s", traceback.format_exc())
            return encoder.encode(
                ErrorReply(
                    header=reply_header(request),
                    code=ErrorCode.HANDLER_FAILED,
                    message=f"{type(exc).__name__}: {exc}",
                )
            )
        return encoder.encode(reply)

    return handle_frame


def call_in_process(contract: Contract, request: Any) -> Any:
    """Dispatch a request struct to its handler without the bus (embedded default, unit tests)."""
    handler = contract.get(type(request))
    if handler is None:
        raise TypeError(f"{type(request).__name__} is not in this contract")
    return handler(request)
