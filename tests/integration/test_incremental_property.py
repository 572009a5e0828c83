"""The safeguard of incremental recompute: after any sequence of edits, the incremental result equals a cold
computation of the final text, node by node.

Each example starts a session on a small story, applies a random sequence of edits as an editor sends them
(a text diff against the current version: sentences inserted, deleted, replaced, reordered, words swapped,
pronouns for names and back, whitespace) with a compute after some of them, then computes the final text
in a fresh session (nothing memoised) whose sentences carry the same ids. Both runs must touch the same
query nodes, every node's value must hash the same, and the results (graphs, diagnostics, commands, scene,
motions) must be equal. A dependency view that leaves out something its service reads (views.py) makes a
memo go stale and fails here.

Where it runs (the services are real, in-process):
- `test_incremental_parse_and_scene_equal_a_cold_run`: 500 sequences over parse, resolve and scene (the
  default suite, about a minute on one core);
- `test_incremental_motion_equals_a_cold_run` (slow): fewer sequences over every stage (social, drafts,
  optimisation, segments, faces).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator

import msgspec
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from proto.optimizer import OptimiseReply
from services.orchestrator.backend import InProcessBackend
from services.orchestrator.document import TextChange
from services.orchestrator.pipeline import PipelineResult
from services.orchestrator.queries import QueryEngine, content_hash
from services.orchestrator.session import Orchestrator, Session
from services.orchestrator.stages.motion import Animated

pytestmark = [pytest.mark.integration]

STORY = [
    "A desk is near the window$.",
    "A chair is in front of the desk$.",
    "Eve walks to the chair.",
    "Eve sits on the chair.",
    "camera left",
    "Tom walks to the window.",
    "Tom waves at Eve.",
    "They are friends.",
]
# Sentences an edit may insert or replace with: scene, action, command, social and pronoun sentences.
EXTRA = [
    "A lamp is on the desk$.",
    "A sofa is next to the window$.",
    "Eve stands up.",
    "She walks to the window.",
    "He sits on the sofa.",
    "Tom runs to the desk.",
    "Mary is Tom's boss.",
    "camera top",
    "Eve waves at Tom.",
    "Tom walks slowly to the chair.",
]
WORDS = [
    ("walks", "runs"),
    ("chair", "sofa"),
    ("desk", "table"),
    ("window", "door"),
    ("waves", "claps"),
    ("friends", "colleagues"),
]
PRONOUNS = [("Eve", "She"), ("Tom", "He"), ("She", "Eve"), ("He", "Tom")]
SPACES = [" ", "  ", "\n", "\n\n", "\t "]


@st.composite
def edit_ops(draw: st.DrawFn) -> tuple[str, int, int, int]:
    """(kind, which sentence, which variant, compute after?) ; indices are taken modulo the current sizes."""
    kind = draw(st.sampled_from(["insert", "delete", "replace", "reorder", "word", "pronoun", "space"]))
    return kind, draw(st.integers(0, 30)), draw(st.integers(0, 30)), draw(st.integers(0, 2))


def apply_op(sentences: list[str], op: tuple[str, int, int, int]) -> list[str]:
    """The story's sentences after one edit (a new list)."""
    kind, i, j, _ = op
    out = list(sentences)
    n = len(out)
    if kind == "insert":
        out.insert(i % (n + 1), EXTRA[j % len(EXTRA)])
    elif kind == "delete" and n > 1:
        del out[i % n]
    elif kind == "replace" and n:
        out[i % n] = EXTRA[j % len(EXTRA)]
    elif kind == "reorder" and n > 1:
        a = i % (n - 1)
        out[a], out[a + 1] = out[a + 1], out[a]
    elif kind in ("word", "pronoun"):
        # Every swap that applies somewhere in the story (either direction), one picked: an edit that does
        # something, as often as the story allows.
        pairs = WORDS if kind == "word" else PRONOUNS
        swaps = [
            (k, a, b)
            for k, sentence in enumerate(out)
            for old, new in pairs
            for a, b in ((old, new), (new, old))
            if a in sentence.split(" ") or f"{a}." in sentence.split(" ")
        ]
        if swaps:
            k, a, b = swaps[(i * 31 + j) % len(swaps)]
            out[k] = out[k].replace(a, b, 1)
    elif kind == "space" and n:
        k = i % n
        words = out[k].split(" ")
        at = j % len(words)
        words[at] = words[at] + SPACES[j % len(SPACES)]
        out[k] = " ".join(words).rstrip(" ")
    return out


def join(sentences: list[str]) -> str:
    return " ".join(sentences) + "\n"


def diff(old: str, new: str) -> TextChange:
    """The smallest single-range change from old to new (common prefix and suffix kept), as an editor sends."""
    start = 0
    while start < min(len(old), len(new)) and old[start] == new[start]:
        start += 1
    end_old, end_new = len(old), len(new)
    while end_old > start and end_new > start and old[end_old - 1] == new[end_new - 1]:
        end_old -= 1
        end_new -= 1
    return TextChange(start=start, end=end_old, text=new[start:end_new])


def node_hash(value: object) -> str:
    """The hash of a node's value, leaving out how long the optimiser took (a measurement, not a result)."""
    if isinstance(value, OptimiseReply):
        value = msgspec.structs.replace(value, elapsed_ms=0.0)
    if isinstance(value, Animated):  # the `motion` node: the story played, its optimisations among it
        value = dataclasses.replace(value, optimisations=[node_hash(o) for o in value.optimisations])
    return content_hash(value)


def final_nodes(engine: QueryEngine) -> dict[str, str]:
    """Node key -> hash of its value, for every node the latest compute ran or reused."""
    keys = engine.ran() + engine.reused()
    return {key: node_hash(engine.memos[key].value) for key in keys if key in engine.memos}


PLAYED = ("draft", "optimise", "segment", "cast")  # the nodes the `motion` node asks (stages/motion.py)


def played_nodes(engine: QueryEngine, nodes: dict[str, str]) -> dict[str, str]:
    """``nodes`` with the nodes a reused `motion` node did not ask again: their memos, as the compute that
    played the story last asked them (a cold run asks every one of them)."""
    if "motion" not in engine.reused():
        return nodes
    last = max(r for r in range(engine.revision + 1) if "motion" in engine.ran(r))
    played = [k for k in engine.ran(last) + engine.reused(last) if k.split(":")[0] in PLAYED]
    asked = {key: value for key, value in nodes.items() if key.split(":")[0] not in PLAYED}
    return {**asked, **{k: node_hash(engine.memos[k].value) for k in played}}


def result_hashes(result: PipelineResult) -> dict[str, str]:
    return {
        "graphs": content_hash(result.graphs),
        "diagnostics": content_hash(result.diagnostics),
        "commands": content_hash(result.commands),
        "sentences": content_hash([dataclasses.astuple(s) for s in result.sentences]),
        "scene": content_hash(result.scene),
        "motions": content_hash(result.motions),
        "unavailable": content_hash(sorted(result.unavailable)),
    }


def cold_twin(orch: Orchestrator, session: Session) -> Session:
    """A fresh session on the same text (nothing memoised) whose sentences carry the same ids."""
    cold = orch.create(session.doc.text)
    spans = [(s.start, s.end) for s in session.doc.sentences]
    assert [(s.start, s.end) for s in cold.doc.sentences] == spans, (
        "the incremental split differs from a cold one"
    )
    cold.doc.sentences = [
        dataclasses.replace(c, id=s.id)
        for c, s in zip(cold.doc.sentences, session.doc.sentences, strict=True)
    ]
    return cold


def check_sequence(orch: Orchestrator, ops: list[tuple[str, int, int, int]], stages: tuple[str, ...]) -> None:
    sentences = list(STORY)
    session = orch.create(join(sentences))
    session.compute(stages=stages)
    for op in ops:
        new = apply_op(sentences, op)
        change = diff(session.doc.text, join(new))
        session.edit(session.doc.version, [change])
        sentences = new
        if op[3]:  # compute after two edits in three; the others pile up for the next compute
            session.compute(stages=stages)
    assert session.doc.text == join(sentences)
    incremental = session.compute(stages=stages)
    cold_session = cold_twin(orch, session)
    cold = cold_session.compute(stages=stages)
    assert played_nodes(session.engine, final_nodes(session.engine)) == final_nodes(cold_session.engine)
    assert result_hashes(incremental) == result_hashes(cold)
    orch.delete(session.doc_id)
    orch.delete(cold_session.doc_id)


@pytest.fixture(scope="module")
def orchestrator(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Orchestrator]:
    orch = Orchestrator(tmp_path_factory.mktemp("db") / "sessions.db", InProcessBackend())
    yield orch
    orch.close()


@settings(
    max_examples=500,
    deadline=None,
    derandomize=True,  # the same 500 sequences on every run: a failure reproduces
    database=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)
@given(ops=st.lists(edit_ops(), min_size=1, max_size=6))
def test_incremental_parse_and_scene_equal_a_cold_run(orchestrator: Orchestrator, ops) -> None:
    check_sequence(orchestrator, ops, ("parse", "scene"))


@pytest.mark.slow
@settings(
    max_examples=100,
    deadline=None,
    derandomize=True,
    database=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)
@given(ops=st.lists(edit_ops(), min_size=1, max_size=4))
def test_incremental_motion_equals_a_cold_run(orchestrator: Orchestrator, ops) -> None:
    check_sequence(orchestrator, ops, ("parse", "scene", "motion"))


def test_the_check_sees_a_stale_node(orchestrator: Orchestrator) -> None:
    """The comparison can fail: a node that missed an edit (as a forgotten input would leave it) is caught."""
    session = orchestrator.create(join(STORY))
    session.compute(stages=("parse", "scene"))
    old = session.engine.memos["scene"]
    at = session.doc.text.index("window")
    session.edit(session.doc.version, [TextChange(start=at, end=at + len("window"), text="door")])
    session.compute(stages=("parse", "scene"))
    fresh = session.engine.memos["scene"]
    assert fresh.result_hash != old.result_hash
    session.engine.memos["scene"] = dataclasses.replace(old, input_hash=fresh.input_hash)
    session.compute(stages=("parse", "scene"))
    cold = cold_twin(orchestrator, session)
    cold.compute(stages=("parse", "scene"))
    assert final_nodes(session.engine) != final_nodes(cold.engine)
