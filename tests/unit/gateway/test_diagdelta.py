"""Diagnostics as deltas: a message carries only the sentences whose diagnostics or verdicts changed."""

from __future__ import annotations

from typing import Any

from services.gateway.diagdelta import DiagnosticsState


def sentence(sid: str, start: int, end: int) -> dict[str, Any]:
    return {"id": sid, "start": start, "end": end, "kind": "action"}


def diag(sid: str, start: int, end: int, code: str = "W101", **extra: Any) -> dict[str, Any]:
    return {
        "sentence_id": sid,
        "code": code,
        "message": "m",
        "severity": "warning",
        "start": start,
        "end": end,
        **extra,
    }


def w401(sid: str, start: int, end: int) -> dict[str, Any]:
    return diag(sid, start, end, code="W401", check="object_used")


def merge(
    held: dict[str, list[dict[str, Any]]], starts: dict[str, int], msg: dict[str, Any]
) -> dict[str, list]:
    """What the editor (editor/src/diagmerge.js) does with a message: keep, move, replace, drop."""
    new_starts = {s["id"]: s["start"] for s in msg["sentences"]}
    out: dict[str, list[dict[str, Any]]] = {}
    if msg["base_seq"] is not None:
        for sid, items in held.items():
            if sid in msg["changed"] or sid in msg["dropped"]:
                continue
            shift = new_starts.get(sid, 0) - starts.get(sid, 0)
            out[sid] = [{**d, "start": d["start"] + shift, "end": d["end"] + shift} for d in items]
    for d in msg["diagnostics"]:
        out.setdefault(d["sentence_id"], []).append(d)
    return out


def test_a_sentence_that_only_moved_is_not_sent_again_and_the_client_moves_its_marks() -> None:
    v0 = DiagnosticsState(
        0,
        [sentence("a", 0, 10), sentence("b", 11, 20)],
        {},
        {"a": [diag("a", 2, 4)], "b": [diag("b", 12, 14)]},
        {},
        False,
    )
    full = v0.message(None)
    assert full["base_seq"] is None and full["changed"] == ["a", "b"] and len(full["diagnostics"]) == 2
    # "a" grew by 3 characters: its own warning changed, "b" only moved
    v1 = DiagnosticsState(
        1,
        [sentence("a", 0, 13), sentence("b", 14, 23)],
        {},
        {"a": [diag("a", 2, 7)], "b": [diag("b", 15, 17)]},
        {},
        False,
    )
    delta = v1.message(v0)
    assert delta["base_seq"] == v0.seq and delta["changed"] == ["a"] and delta["dropped"] == []
    assert [d["sentence_id"] for d in delta["diagnostics"]] == ["a"]
    held = merge(merge({}, {}, full), {"a": 0, "b": 11}, delta)
    assert held == {"a": [diag("a", 2, 7)], "b": [diag("b", 15, 17)]}


def test_a_removed_sentence_is_dropped_and_a_cleared_one_is_sent_empty() -> None:
    v0 = DiagnosticsState(
        0,
        [sentence("a", 0, 10), sentence("b", 11, 20)],
        {},
        {"a": [diag("a", 2, 4)], "b": [diag("b", 12, 14)]},
        {},
        False,
    )
    v1 = DiagnosticsState(1, [sentence("a", 0, 10)], {}, {}, {}, False)
    delta = v1.message(v0)
    assert delta["changed"] == ["a"] and delta["dropped"] == ["b"] and delta["diagnostics"] == []
    assert merge(merge({}, {}, v0.message(None)), {"a": 0, "b": 11}, delta) == {}


def test_verdicts_are_kept_moved_until_the_new_version_is_judged_then_only_changes_are_sent() -> None:
    verdict = {"sentence_id": "b", "verdict": "failed", "checks": []}
    judged = DiagnosticsState(
        0,
        [sentence("a", 0, 10), sentence("b", 11, 20)],
        {},
        {"b": [w401("b", 11, 20)]},
        {"b": verdict},
        False,
    )
    # an edit inside "a" moves "b" by 2: the pipeline's state keeps b's verdict and warning, moved
    pipeline = judged.carried_into(1, [sentence("a", 0, 12), sentence("b", 13, 22)], {}, {})
    assert pipeline.verdicts_pending and pipeline.verdicts == {"b": verdict}
    assert pipeline.entries == {"b": [w401("b", 13, 22)]}
    assert pipeline.message(judged)["changed"] == []  # nothing to send but the new sentences
    # the story checks of version 1 agree about "b": the verdicts message changes nothing either
    done = DiagnosticsState(1, pipeline.sentences, {}, {"b": [w401("b", 13, 22)]}, {"b": verdict}, False)
    msg = done.message(pipeline)
    assert msg["changed"] == [] and msg["verdicts"] == [] and not msg["verdicts_pending"]
    # now "b" passes: only it is sent, with no entries and its new verdict
    ok = {"sentence_id": "b", "verdict": "ok", "checks": []}
    passed = DiagnosticsState(2, pipeline.sentences, {}, {}, {"b": ok}, False).message(done)
    assert passed["changed"] == ["b"] and passed["diagnostics"] == [] and passed["verdicts"] == [ok]
