"""eval/agreement.py: its sample is seeded and stratified, and its comparison counts what the docstring says
(a check that no longer exists claims nothing; a label on a changed animation is stale, not counted)."""

from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]


@pytest.fixture(scope="module")
def agreement():
    spec = importlib.util.spec_from_file_location("agreement_eval", REPO / "eval" / "agreement.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules["agreement_eval"] = module
    spec.loader.exec_module(module)
    return module


def row(results):
    """One story row as eval/story.py writes it: sentence s1 with the given (name, ok, character) checks."""
    return {
        "story": "duo-x-01",
        "per_sentence": [
            {"id": "s1", "text": "Tom waves.", "results": [
                {"name": n, "ok": ok, "character": c, "reason": f"{n} {ok}", "frames": [3, 4]}
                for n, ok, c in results]},
        ],
    }  # fmt: skip


def test_a_unit_fails_when_any_check_of_its_name_about_its_character_fails(agreement):
    units = agreement.units(row([("penetration", True, "Tom"), ("penetration", False, "Tom")]), "abc", 0)
    (unit,) = units
    assert unit["check_verdict"] == "fail" and unit["reason"] == "penetration False"
    assert agreement.unit_key(unit) == ("duo-x-01", 0, "s1", "penetration", "Tom")


def test_the_sample_is_seeded_and_draws_every_stratum_before_a_second_of_any(agreement):
    pool = [
        {"story": f"s{i:02d}", "seed": 0, "sentence": "s1", "check": c, "character": "", "check_verdict": v}
        for i in range(30)
        for c, v in (("contact", "fail"), ("contact", "ok"), ("entrance", "ok"))
        if not (c == "entrance" and i > 1)
    ]
    first = agreement.stratified_sample(pool, 6, seed=3)
    assert first == agreement.stratified_sample(pool, 6, seed=3)
    assert first != agreement.stratified_sample(pool, 6, seed=4)
    strata = [(u["check"], u["check_verdict"]) for u in first]
    assert strata[:3] == [("contact", "fail"), ("contact", "ok"), ("entrance", "ok")]
    assert strata.count(("entrance", "ok")) == 2  # the rare stratum is drawn out, the rest fill up


def test_agreement_counts_false_alarms_misses_stale_and_skipped_labels(agreement):
    def unit(check, verdict, story="a"):
        return {"story": story, "seed": 0, "sentence": "s1", "check": check, "character": "Tom",
                "check_verdict": verdict, "reason": "r"}  # fmt: skip

    found = {agreement.unit_key(u): u for u in (unit("penetration", "fail"), unit("contact", "ok"))}
    labels = [
        {**unit("penetration", ""), "human": "ok", "why": "a graze", "animation": "f1"},  # false alarm
        {**unit("contact", ""), "human": "fail", "why": "empty hand", "animation": "f1"},  # miss
        {**unit("in_view", ""), "human": "ok", "why": "seen", "animation": "f1"},  # no such check: ok
        {**unit("contact", "", story="b"), "human": "ok", "why": "-", "animation": "old"},  # stale
        {**unit("contact", "", story="c"), "human": "ok", "why": "-", "animation": "f3"},  # not computed
    ]
    out = agreement.compare(labels, found, {("a", 0): "f1", ("b", 0): "new"})
    assert out["counted"] == 3 and out["check_agreement"] == pytest.approx(1 / 3)
    assert out["per_check"]["penetration"]["false_alarms"] == 1
    assert out["per_check"]["contact"]["misses"] == 1
    assert out["per_check"]["in_view"]["agreement"] == 1.0
    assert [k[0] for k in out["stale"]] == ["b"] and [k[0] for k in out["skipped"]] == ["c"]


def test_the_committed_labels_are_at_least_forty_and_each_says_why(agreement):
    data = json.loads(agreement.LABELS.read_text())
    labels = data["labels"]
    assert len(labels) >= 40
    for lab in labels:
        assert lab["human"] in ("ok", "fail") and lab["why"].strip() and lab["animation"]
        assert {"story", "seed", "sentence", "check", "character"} <= set(lab)
    keys = [agreement.unit_key(lab) for lab in labels]
    assert len(keys) == len(set(keys))
    quick = agreement.quick_stories(labels)
    assert len(quick) == agreement.QUICK_STORIES


def test_fresh_labels_are_counted_apart_from_the_split_their_story_is_in(agreement):
    """The target must hold on labels the checks were not fixed on: fresh ones are their own group."""
    unit = {"story": "a", "seed": 0, "sentence": "s1", "check": "contact", "character": "Tom"}
    found = {agreement.unit_key(unit): {**unit, "check_verdict": "fail", "reason": "r"}}
    labels = [
        {**unit, "human": "fail", "why": "-", "animation": "f1"},
        {**unit, "sentence": "s2", "human": "fail", "why": "-", "animation": "f1", "fresh": True},
        {**unit, "sentence": "s3", "human": "ok", "why": "-", "animation": "f1", "fresh": "fresh2"},
    ]
    groups = agreement.compare_groups(labels, found, {("a", 0): "f1"}, {"a": "test"})
    assert groups["test"] == {"agreement": 1.0, "counted": 1, "labels": 1}
    assert groups["fresh"] == {"agreement": 0.0, "counted": 1, "labels": 1}  # s2 has no failing check
    assert groups["fresh2"] == {"agreement": 1.0, "counted": 1, "labels": 1}  # a second blind set, apart


def story_result(tom_frames, pad=0, door=None):
    """A computed story's result as the fingerprint reads it: a room, one chair, Tom's motion over
    sentences s1 (frames 0..9) and s2 (the rest), ``pad`` still frames inserted before s1's."""
    import types

    import numpy as np

    from proto.motion_data import Motion, Segment
    from proto.scene import ObjectStateTrack, PlacedObject, Room, Scene
    from wana.arrays import to_wire

    root = np.concatenate([np.repeat(tom_frames[:1], pad, axis=0), tom_frames]).astype(np.float32)
    n = len(root)
    rotations = np.tile(np.array([0.0, 0.0, 0.0, 1.0], np.float32), (n, 3, 1))
    segments = [
        Segment(index=0, action="walk", start_frame=0, end_frame=pad + 10, sentence_id="s1"),
        Segment(index=1, action="wave", start_frame=pad + 10, end_frame=n, sentence_id="s2"),
    ]
    motion = Motion(
        character="Tom", root_position=to_wire(root), rotations=to_wire(rotations), segments=segments
    )
    states = (
        [ObjectStateTrack(object_id="door", state="open", frames=door, values=[0.0, 1.0])] if door else []
    )
    scene = Scene(
        room=Room(room_type="office", width=5, depth=4, height=3),
        objects=[PlacedObject(id="chair", category="office_chair"), PlacedObject(id="door", category="door")],
        states=states,
    )
    return types.SimpleNamespace(scene=scene, motions={"Tom": motion}, commands=[])


def test_a_unit_fingerprint_keys_the_frames_its_label_judged_not_the_whole_story(agreement):
    import numpy as np

    walk = np.linspace([0.1234, 0.9, 0.0], [2.1234, 0.9, 1.0], 20)
    key = agreement.unit_fingerprint(story_result(walk), "x", "s2", "penetration")
    assert key == agreement.unit_fingerprint(story_result(walk + 1e-7), "x", "s2", "penetration")  # noise
    earlier = walk.copy()
    earlier[:10, 2] += 0.3  # s1's walk changed: s2's frames did not
    assert key == agreement.unit_fingerprint(story_result(earlier), "x", "s2", "penetration")
    assert key == agreement.unit_fingerprint(story_result(walk, pad=5), "x", "s2", "penetration")  # later
    assert key != agreement.unit_fingerprint(story_result(earlier), "x", "s1", "penetration")
    moved = walk.copy()
    moved[15, 0] += 0.01  # a centimetre in s2's own frames
    assert key != agreement.unit_fingerprint(story_result(moved), "x", "s2", "penetration")
    opened = story_result(walk, door=[12, 16])  # the door opens during s2
    assert key != agreement.unit_fingerprint(opened, "x", "s2", "penetration")
    assert agreement.unit_fingerprint(story_result(walk, door=[2, 6]), "x", "s2", "penetration") != key
    # a continuity label looks at the frame before its sentence too; an entrance at every frame before
    assert agreement.unit_window(story_result(walk).motions, "s2", "continuity") == (9, 20)
    assert agreement.unit_window(story_result(walk).motions, "s2", "entrance") == (0, 20)


def test_a_label_keyed_by_its_unit_is_stale_only_when_its_unit_changed(agreement):
    lab = {"story": "a", "seed": 0, "sentence": "s1", "check": "contact", "character": "Tom", "human": "ok",
           "why": "-", "animation": "old", "unit": "u1"}  # fmt: skip
    key = agreement.unit_key(lab)
    found = {key: {**lab, "check_verdict": "ok", "reason": "r"}}
    same = agreement.compare([lab], found, {("a", 0): "new"}, unit_fps={key: "u1"})
    assert same["counted"] == 1 and not same["stale"]
    changed = agreement.compare([lab], found, {("a", 0): "new"}, unit_fps={key: "u2"})
    assert changed["counted"] == 0 and changed["stale"] == [list(key)]


def test_restale_draws_each_stale_label_as_its_unit_is_now_and_tells_nothing_of_the_former_verdict(agreement):
    """--restale: every stale label's unit once, in label order, with the check's current frames; a unit whose
    check is no longer made still gets its sentence drawn (to be judged again, not dropped)."""
    now = {"story": "a", "seed": 0, "sentence": "s1", "check": "contact", "character": "Tom", "text": "Tom sits.",
           "check_verdict": "fail", "reason": "r", "frames": [5], "animation": "f2"}  # fmt: skip
    found = {agreement.unit_key(now): now}
    rows = {
        ("a", 0): {"per_sentence": [{"id": "s1", "text": "Tom sits."}, {"id": "s2", "text": "Tom waves."}]}
    }
    labels = [
        {**{k: now[k] for k in ("story", "seed", "sentence", "character")}, "check": "entrance", "sentence": "s2",
         "human": "fail", "why": "gone"},
        {**{k: now[k] for k in ("story", "seed", "sentence", "check", "character")}, "human": "ok", "why": "w"},
        {**{k: now[k] for k in ("story", "seed", "sentence", "check", "character")}, "sentence": "s9",
         "human": "ok", "why": "not stale"},
    ]  # fmt: skip
    stale = [agreement.unit_key(lab) for lab in labels[:2]]
    first, second = agreement.restale_units(stale, labels, found, rows)
    assert (first["sentence"], first["check"], first["text"], first["frames"]) == (
        "s2",
        "entrance",
        "Tom waves.",
        [],
    )
    assert first["check_verdict"] == "ok"  # no such check now: it claims nothing
    assert second["frames"] == [5] and second["text"] == "Tom sits."
    assert "human" not in first and "why" not in second  # the sheet's unit carries no former verdict
    second["frames"].append(6)
    assert now["frames"] == [5]  # a copy: drawing does not change the computed unit
