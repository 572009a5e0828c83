"""eval/story_diff.py: a check that flips is listed with both reasons, a check that stays is not, checks are
matched by name, character and rank (not by position), and a crashed story shows as its error."""

from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]


@pytest.fixture(scope="module")
def story_diff():
    spec = importlib.util.spec_from_file_location("story_diff_eval", REPO / "eval" / "story_diff.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules["story_diff_eval"] = module
    spec.loader.exec_module(module)
    return module


def run(results, verdict="ok", fidelity=1.0, error=""):
    """A story.py JSON with one story and one sentence s1 holding the given (name, ok, character, reason)."""
    sentence = {"id": "s1", "text": "Tom sits.", "verdict": verdict, "results": [
        {"name": n, "ok": ok, "character": c, "reason": r, "frames": []} for n, ok, c, r in results
    ]}  # fmt: skip
    story = {"story": "solo-x-01", "error": error, "per_sentence": [] if error else [sentence]}
    return {"sentence_fidelity": fidelity, "per_story": [story]}


def test_flips_both_ways_with_reasons(story_diff):
    a = run([("penetration", True, "Tom", "clear"), ("overlap", False, "Tom", "arm in Ann"),
             ("contact", True, "Tom", "on the chair")], verdict="failed", fidelity=0.0)  # fmt: skip
    b = run([("penetration", False, "Tom", "shin in chair"), ("overlap", True, "Tom", "clear"),
             ("contact", True, "Tom", "on the chair")], verdict="failed", fidelity=0.0)  # fmt: skip
    d = story_diff.diff(a, b)
    assert (d["broke"], d["fixed"]) == (1, 1)
    rows = {f["check"]: f for f in d["flips"]}
    assert set(rows) == {"penetration", "overlap"}  # contact stayed ok: not listed
    assert rows["penetration"]["reason_b"] == "shin in chair" and rows["penetration"]["a"] == "ok"
    assert d["sentences_broke"] == [] and d["sentences_fixed"] == []  # failed both times


def test_matched_by_name_character_and_rank_not_position(story_diff):
    a = run([("object_exists", True, "", "mug"), ("object_exists", False, "", "no table")], verdict="failed")
    b = run([("relation_holds", True, "", "x"), ("object_exists", True, "", "mug"),
             ("object_exists", True, "", "table")])  # fmt: skip
    d = story_diff.diff(a, b)
    assert [(f["check"], f["kind"]) for f in d["flips"]] == [
        ("object_exists", "fixed"),
        ("relation_holds", "appeared"),
    ]
    assert d["sentences_fixed"] == ["solo-x-01 s1"]


def test_crash_and_cli_table(story_diff, tmp_path, capsys):
    a, b = run([("performed", True, "Tom", "sits")]), run([], error="ValueError: boom")
    (tmp_path / "a.json").write_text(json.dumps(a))
    (tmp_path / "b.json").write_text(json.dumps(b))
    assert (
        story_diff.main(
            [str(tmp_path / "a.json"), str(tmp_path / "b.json"), "--json", str(tmp_path / "d.json")]
        )
        == 0
    )
    out = capsys.readouterr().out
    assert "solo-x-01 | * " in out and "ValueError: boom" in out and "performed (Tom) | ok -> -" in out
    assert json.loads((tmp_path / "d.json").read_text())["vanished"] == 1


def test_over_seeds_means_and_the_checks_leaning_one_way(story_diff, tmp_path, capsys):
    shin, clear = ("penetration", False, "Tom", "shin in chair"), ("penetration", True, "Tom", "clear")
    arm, apart = ("overlap", False, "Tom", "arm in Ann"), ("overlap", True, "Tom", "clear")
    pairs = [  # the shin fails 3 seeds of B and 1 of A (listed); the arm 1 of B and 0 of A (not listed)
        (run([clear, apart]), run([shin, arm], "failed", 0.0)),
        (run([clear, apart]), run([shin, apart], "failed", 0.0)),
        (run([shin, apart], "failed", 0.0), run([shin, apart], "failed", 0.0)),
    ]
    seeds = story_diff.over_seeds(pairs)
    assert (
        seeds["fidelity_a"] == [1.0, 1.0, 0.0]
        and seeds["mean_b"] == 0.0
        and abs(seeds["mean_a"] - 2 / 3) < 1e-12
    )
    assert [(r["check"], r["failed_a"], r["failed_b"]) for r in seeds["leaning"]] == [("penetration", 1, 3)]
    files = []
    for i, (a, b) in enumerate(pairs):
        for side, data in (("a", a), ("b", b)):
            (tmp_path / f"{side}{i}.json").write_text(json.dumps(data))
        files.append((str(tmp_path / f"a{i}.json"), str(tmp_path / f"b{i}.json")))
    more = [x for a, b in files[1:] for x in ("--more", a, b)]
    assert story_diff.main([*files[0], *more, "--json", str(tmp_path / "d.json")]) == 0
    assert "failed A 1 / B 3 of 3: solo-x-01 | s1 | penetration (Tom)" in capsys.readouterr().out
    assert json.loads((tmp_path / "d.json").read_text())["seeds"]["pairs"] == 3
