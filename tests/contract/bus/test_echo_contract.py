"""The built-in echo service through the contract harness: the example other services copy."""

from __future__ import annotations

import msgspec
import pytest

from proto.bus import EchoReply, EchoRequest
from proto.common import ErrorReply, Header
from tests.contract.harness import check_contract, service_fixture
from wana.bus.echo import CONTRACT

pytestmark = pytest.mark.contract

echo = service_fixture("echo", "wana.bus.echo:main")


def test_echo_request_gets_an_echo_reply_with_the_same_text(echo):
    request = EchoRequest(header=Header(doc_id="doc-1", revision=3), text="Eve walks to the chair.")
    reply = check_contract(CONTRACT, request, echo.request("echo", msgspec.msgpack.encode(request)))
    assert isinstance(reply, EchoReply)
    assert reply.text == "Eve walks to the chair."
    assert (reply.header.doc_id, reply.header.revision) == ("doc-1", 3)
    assert reply.worker_pid == echo.processes[0].pid


def test_invalid_input_gets_an_e010_error_reply(echo):
    request = EchoRequest(header=Header(), text="x", sleep_s=-1.0)
    reply = echo.call(CONTRACT, request, expect="error", code="E010")
    assert isinstance(reply, ErrorReply)
    assert reply.header.parent_id == request.header.msg_id


def test_undecodable_frame_gets_an_e001_error_reply_and_the_worker_keeps_serving(echo):
    garbage = b"\xc1 not msgpack"
    reply = msgspec.msgpack.decode(echo.request("echo", garbage), type=ErrorReply)
    assert reply.code == "E001"
    request = EchoRequest(header=Header(), text="still here")
    assert echo.call(CONTRACT, request).text == "still here"


def test_check_contract_rejects_a_reply_that_does_not_answer_the_request():
    request = EchoRequest(header=Header(), text="a")
    wrong_parent = msgspec.msgpack.encode(EchoReply(header=Header(parent_id="someone-else"), text="a"))
    with pytest.raises(AssertionError, match="parent_id"):
        check_contract(CONTRACT, request, wrong_parent)
    not_a_reply = msgspec.msgpack.encode({"type": "echo_reply", "text": 5})
    with pytest.raises(AssertionError, match="decodes into none"):
        check_contract(CONTRACT, request, not_a_reply)
    error = msgspec.msgpack.encode(ErrorReply(header=Header(), code="E010", message="bad"))
    with pytest.raises(AssertionError, match="expected an ok reply"):
        check_contract(CONTRACT, request, error)
