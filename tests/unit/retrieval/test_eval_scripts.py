"""The eval's scene scripts are valid gold SSGs, and its query sampler draws exactly sized sub-SSGs."""

from __future__ import annotations

import importlib.util

import numpy as np
import pytest

from proto.ssg import RELATIONS
from wana.assets.catalog import categories


@pytest.fixture(scope="module")
def evaluation(repo_root):
    spec = importlib.util.spec_from_file_location("eval_retrieval", repo_root / "eval" / "retrieval.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_at_least_twenty_scripts_with_text_and_valid_gold(evaluation):
    scripts = evaluation.load_scripts()
    assert len(scripts) >= 20
    known = set(categories())
    for s in scripts:
        ids = [o.id for o in s["objects"]]
        assert len(ids) == len(set(ids)), s["id"]
        assert all(o.category in known for o in s["objects"]), s["id"]
        assert all(r.relation in RELATIONS and r.subject in ids and r.object in ids for r in s["relations"])
        assert s["text"].count("$") == len(s["text"].strip().splitlines()), s[
            "id"
        ]  # one scene sentence a line
        assert len(s["objects"]) + len(s["relations"]) >= 15


def test_queries_have_exactly_the_asked_number_of_nodes(evaluation):
    scripts = evaluation.load_scripts()
    rng = np.random.default_rng(7)
    for size in (5, 10, 15):
        for k in range(10):
            objects, relations = evaluation.draw_query(scripts[k], size, rng)
            ids = {o.id for o in objects}
            assert len(objects) + len(relations) == size
            assert all(r.subject in ids and r.object in ids for r in relations)
