"""One service list, and each request reaches the service whose proto module defines it, typed by its reply."""

from __future__ import annotations

import typing

import pytest

from proto.bus import EchoRequest
from proto.common import ErrorReply, Header, reply_type
from proto.nlp import ParseReply, ParseRequest
from services.gateway.settings import SERVICES as GATEWAY_SERVICES
from services.orchestrator.backend import InProcessBackend, ServiceSubset, StageUnavailable
from services.orchestrator.registry import SERVICES, contract, service_of
from wana.cli import SERVICES as CLI_SERVICES


def test_the_cli_the_gateway_and_the_orchestrator_share_one_service_list():
    assert CLI_SERVICES is SERVICES and GATEWAY_SERVICES is SERVICES


@pytest.mark.parametrize("service", SERVICES)
def test_every_contract_answers_its_own_proto_modules_requests_with_the_declared_reply(service):
    for request_type, handler in contract(service).items():
        assert service_of(request_type) == service
        returned = typing.get_type_hints(handler)["return"]
        declared = {t for t in typing.get_args(returned) or (returned,) if t is not ErrorReply}
        assert declared == {reply_type(request_type)}, f"{handler.__name__} returns {returned}"


def test_a_request_of_no_service_is_refused():
    with pytest.raises(KeyError, match="EchoRequest"):
        service_of(EchoRequest)


def test_an_in_process_call_returns_the_typed_reply():
    reply = InProcessBackend().call(
        ParseRequest(sentence_id="s1", text="Eve walks to the chair.", header=_header())
    )
    assert isinstance(reply, ParseReply) and reply.graph.characters[0].name == "Eve"


def test_a_service_left_out_of_a_subset_is_unavailable_at_once():
    backend = ServiceSubset(InProcessBackend(), {"nlp": "not enabled in this gateway"})
    with pytest.raises(StageUnavailable, match="not enabled"):
        backend.call(ParseRequest(sentence_id="s1", text="Eve walks.", header=_header()))


def _header() -> Header:
    return Header(doc_id="d", revision=1)
