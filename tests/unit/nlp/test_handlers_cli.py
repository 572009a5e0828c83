"""Handlers called in-process (as the orchestrator does) and the `wana parse` CLI."""

from __future__ import annotations

import io
import json
import sys

import pytest

from proto.common import Header
from proto.nlp import ParseBatchRequest, ParseDocumentRequest, ParseRequest, ResolveRequest, SentenceInput
from services.nlp.cli import main
from services.nlp.handlers import CONTRACT
from wana.bus.service import InvalidInput, call_in_process


def test_parse_handler_echoes_the_header_and_shifts_spans():
    req = ParseRequest(header=Header(doc_id="d", revision=2), sentence_id="s3", text="Eve sits.", offset=10)
    reply = call_in_process(CONTRACT, req)
    assert reply.header.parent_id == req.header.msg_id and reply.header.revision == 2
    assert reply.graph.sentence_id == "s3" and reply.graph.characters[0].actions[0].span.start >= 10
    assert reply.model_version


def test_batch_and_resolve_handlers_keep_order_and_resolve():
    batch = call_in_process(
        CONTRACT,
        ParseBatchRequest(
            header=Header(),
            sentences=[
                SentenceInput(sentence_id="a", text="Tom walks in."),
                SentenceInput(sentence_id="b", text="He waves.", offset=14),
            ],
        ),
    )
    assert [g.sentence_id for g in batch.graphs] == ["a", "b"]
    resolved = call_in_process(CONTRACT, ResolveRequest(header=Header(), graphs=batch.graphs))
    assert resolved.graphs[1].characters[0].name == "Tom"


def test_document_handler_splits_and_refuses_oversized_input():
    reply = call_in_process(CONTRACT, ParseDocumentRequest(header=Header(), text="camera left\nEve sits."))
    assert [g.kind for g in reply.graphs] == ["command", "action"]
    with pytest.raises(InvalidInput):
        call_in_process(CONTRACT, ParseDocumentRequest(header=Header(), text="a" * 1_000_001))


def test_cli_prints_one_json_entry_per_sentence(capsys):
    assert main(["A laptop is on the desk$. Eve sits on the chair.", "--compact"]) == 0
    entries = json.loads(capsys.readouterr().out)
    assert [e["kind"] for e in entries] == ["scene", "action"]
    assert entries[1]["start"] == 26 and entries[0]["relations"][0]["relation"] == "on"


def test_cli_reads_stdin_and_reports_garbage_as_a_diagnostic(capsys, monkeypatch):
    monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(b"\xff\xfe\x00\x01\x02\x03\nEve sits.\n")))
    assert main(["-"]) == 0
    entries = json.loads(capsys.readouterr().out)
    assert entries[0]["diagnostics"][0]["code"] == "E110" and entries[1]["characters"][0]["name"] == "Eve"
    monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(b"\x00\x01\x02\x03\x04")))
    assert main(["-", "--strict"]) == 1


def test_cli_help_describes_the_command(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["--help"])
    assert exc.value.code == 0 and "scene graph" in capsys.readouterr().out
