"""Start-up: parsing imports no torch, and the parser's clip words equal the full library's."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]


def test_parsing_a_sentence_imports_no_torch() -> None:
    pytest.importorskip("torch")  # only meaningful where torch is installed (thinc would pull it in)
    code = (
        "import sys\n"
        "from services.nlp.parse import parse_sentence\n"
        "g = parse_sentence('Eve sits on the chair.')\n"
        "assert g.characters and g.characters[0].name == 'Eve', g\n"
        "print('torch' in sys.modules)\n"
    )
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "False"


def test_torch_still_imports_after_the_parser() -> None:
    pytest.importorskip("torch")
    code = "import services.nlp.parse\nimport torch\nprint(torch.zeros(2).sum().item())\n"
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "0.0"


def test_clip_headers_give_the_library_s_names_synonyms_and_tags() -> None:
    from services.nlp import lexicon
    from wana.domain.actions import action_names, load_library, synonym_index

    names, synonyms = lexicon._library()
    assert names == frozenset(action_names())
    assert synonyms == synonym_index()
    assert lexicon._clip_info() == {
        n: (frozenset(c.tags), c.interaction.object if c.interaction else "")
        for n, c in load_library().items()
    }
    assert "high-five" in lexicon.hyphenated_verbs()
