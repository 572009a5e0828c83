"""The embedded bus starts without importing any service's handlers: each worker imports its own on its
first job, so `wana animate` reaches its first compute without waiting for render, motion or optimiser."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

CHILD = """
import sys
from proto.common import Header
from proto.nlp import ParseReply, ParseRequest
from services.orchestrator.embedded import Embedded

with Embedded() as backend:
    before = sorted(m for m in sys.modules if m.endswith(".handlers") and m.startswith("services."))
    reply = backend.call(ParseRequest(sentence_id="s1", text="Eve walks to the chair.",
                                      header=Header(doc_id="d", revision=1)))
    after = sorted(m for m in sys.modules if m.endswith(".handlers") and m.startswith("services."))
    assert isinstance(reply, ParseReply), reply
    print(reply.graph.characters[0].name)
    print(",".join(before))
    print(",".join(after))
    print("torch" in sys.modules)
"""


def test_workers_import_their_handlers_on_their_first_job_and_parsing_needs_no_torch() -> None:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    out = subprocess.run([sys.executable, "-c", CHILD], env=env, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-3000:]
    name, before, after, torch_loaded = out.stdout.strip().splitlines()[-4:]
    assert name == "Eve"
    assert before == ""  # no service's handlers before any job
    assert after == "services.nlp.handlers"  # the parse job imported the NLP service's, and only those
    assert torch_loaded == "False"


def test_the_animate_entry_point_leaves_mesh_and_spatial_libraries_to_the_first_object_built() -> None:
    """trimesh and scipy.spatial cost 0.4-0.6 s of imports: the pipeline imports them when it builds the first
    object or judges the first body, not before the parse (issue 22's start-up)."""
    child = "import sys, services.orchestrator.animate\nprint(sorted(m for m in ('trimesh', 'scipy.spatial') if m in sys.modules))"
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    out = subprocess.run([sys.executable, "-c", child], env=env, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr[-3000:]
    assert out.stdout.strip().splitlines()[-1] == "[]"
