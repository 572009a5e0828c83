import pytest

from services.orchestrator.document import BadEdit, Document, StaleEdit, TextChange, split_spans

STORY = (
    "In the office there is a desk$. A laptop is on the desk$.\n"
    "Eve walks to the chair. Eve sits.\ncamera left\nTom waves"
)


def texts(doc: Document) -> list[str]:
    return [s.text for s in doc.sentences]


def test_sentences_end_at_terminators_and_newlines():
    spans = split_spans(STORY)
    assert [STORY[s:e] for s, e in spans] == [
        "In the office there is a desk$.",
        "A laptop is on the desk$.",
        "Eve walks to the chair.",
        "Eve sits.",
        "camera left",
        "Tom waves",
    ]


def test_scene_marker_without_period_ends_a_sentence():
    assert [t for t in texts(Document.from_text("d", "A desk$ A chair$"))] == ["A desk$", "A chair$"]


def test_editing_inside_a_sentence_keeps_every_id():
    doc = Document.from_text("d", STORY)
    before = [s.id for s in doc.sentences]
    at = STORY.index("sits")
    changed = doc.apply(0, [TextChange(start=at, end=at + 4, text="types")])
    assert [s.id for s in doc.sentences] == before
    assert changed == [before[3]]
    assert doc.sentences[3].text == "Eve types."
    assert doc.version == 1


def test_inserting_text_before_shifts_offsets_and_changes_nothing_else():
    doc = Document.from_text("d", STORY)
    before = [(s.id, s.text) for s in doc.sentences]
    changed = doc.apply(0, [TextChange(start=0, end=0, text="   ")])
    assert changed == []
    assert [(s.id, s.text) for s in doc.sentences] == before
    assert doc.sentences[0].start == 3


def test_inserting_a_sentence_gets_a_new_id_and_keeps_the_neighbours():
    doc = Document.from_text("d", STORY)
    ids = [s.id for s in doc.sentences]
    at = STORY.index("Eve walks")
    changed = doc.apply(0, [TextChange(start=at, end=at, text="Tom sits. ")])
    assert len(changed) == 1 and changed[0] not in ids
    assert [s.id for s in doc.sentences] == ids[:2] + changed + ids[2:]


def test_deleting_a_sentence_removes_only_its_id():
    doc = Document.from_text("d", STORY)
    ids = [s.id for s in doc.sentences]
    at = STORY.index("Eve sits.")
    doc.apply(0, [TextChange(start=at, end=at + len("Eve sits."), text="")])
    assert [s.id for s in doc.sentences] == ids[:3] + ids[4:]


def test_removing_a_terminator_merges_two_sentences():
    doc = Document.from_text("d", "Eve walks. Eve sits.")
    at = doc.text.index(".")
    doc.apply(0, [TextChange(start=at, end=at + 1, text=" and")])
    assert texts(doc) == ["Eve walks and Eve sits."]


def test_a_stale_edit_is_rejected_naming_the_current_version():
    doc = Document.from_text("d", STORY)
    doc.apply(0, [TextChange(start=0, end=0, text="x")])
    with pytest.raises(StaleEdit, match="version 1"):
        doc.apply(0, [TextChange(start=0, end=0, text="y")])
    assert doc.text.startswith("xIn")


def test_out_of_range_and_overlapping_edits_are_refused_and_change_nothing():
    doc = Document.from_text("d", "Eve sits.")
    with pytest.raises(BadEdit):
        doc.apply(0, [TextChange(start=5, end=50, text="")])
    with pytest.raises(BadEdit):
        doc.apply(0, [TextChange(start=0, end=4, text=""), TextChange(start=2, end=6, text="")])
    assert doc.text == "Eve sits." and doc.version == 0


def test_several_changes_in_one_edit_apply_in_base_offsets():
    doc = Document.from_text("d", "Eve sits. Tom waves.")
    doc.apply(0, [TextChange(start=0, end=3, text="Ann"), TextChange(start=10, end=13, text="Bob")])
    assert doc.text == "Ann sits. Bob waves."


def test_random_edits_always_match_a_fresh_split():
    import random

    rng = random.Random(7)
    doc = Document.from_text("d", STORY)
    alphabet = "abc .$\n"
    for _ in range(300):
        n = len(doc.text)
        s = rng.randint(0, n)
        e = min(n, s + rng.randint(0, 6))
        text = "".join(rng.choice(alphabet) for _ in range(rng.randint(0, 5)))
        doc.apply(doc.version, [TextChange(start=s, end=e, text=text)])
        assert [(x.start, x.end) for x in doc.sentences] == split_spans(doc.text)
        assert all(doc.text[x.start : x.end] == x.text for x in doc.sentences)
        assert len({x.id for x in doc.sentences}) == len(doc.sentences)


def test_a_titled_name_is_one_sentence():
    text = "Dr. Jones walks in. Mrs. Brown sits on the sofa.\nMr. Takahashi waves at Ms. Lee. Prof. Kim sits."
    assert [text[s:e] for s, e in split_spans(text)] == [
        "Dr. Jones walks in.",
        "Mrs. Brown sits on the sofa.",
        "Mr. Takahashi waves at Ms. Lee.",
        "Prof. Kim sits.",
    ]


def test_a_lower_case_abbreviation_before_a_new_sentence_still_ends_it():
    assert texts(Document.from_text("d", "Eve calls the dr. Tom sits.")) == ["Eve calls the dr.", "Tom sits."]


def test_an_edit_that_writes_a_title_joins_the_name_to_it():
    doc = Document.from_text("d", "Eve sees Tom. Jones waves.")
    doc.apply(0, [TextChange(start=9, end=13, text="Dr.")])
    assert texts(doc) == ["Eve sees Dr. Jones waves."]
    assert [(x.start, x.end) for x in doc.sentences] == split_spans(doc.text)
