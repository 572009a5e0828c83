"""The coverage-guided fuzz target (eval/fuzz_bus.py) runs a bounded number of inputs without a crash."""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]


@pytest.mark.skipif(importlib.util.find_spec("atheris") is None, reason="atheris is not installed")
def test_five_thousand_fuzzed_inputs_crash_nothing(tmp_path):
    out = tmp_path / "fuzz.json"
    proc = subprocess.run(
        [
            sys.executable,
            str(REPO / "eval" / "fuzz_bus.py"),
            "--runs",
            "5000",
            "--max-s",
            "120",
            "--json",
            str(out),
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    result = json.loads(out.read_text())
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert result["crashes"] == 0 and result["inputs"] == 5000
