"""The editor's text diff and rebase (editor/src/textdiff.js), run with node's built-in test runner."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

EDITOR = Path(__file__).resolve().parents[3] / "editor"


def test_the_editors_diff_and_rebase_tests_pass() -> None:
    node = shutil.which("node")
    if node is None:
        pytest.skip("needs node to run editor/tests")
    run = subprocess.run([node, "--test", "tests/"], cwd=EDITOR, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "# fail 0" in run.stdout
