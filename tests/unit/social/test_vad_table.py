"""The committed VAD table and its rebuild from the Glasgow Norms."""

from __future__ import annotations

import pytest

from services.social.face import FACE_MATRIX, face_weights
from services.social.lexicon import TABLE, action_vad, load_table, response_candidates, word_vad
from tools.authoring import build_vad
from wana.assets.characters import EXPRESSIONS


def test_the_table_cites_its_source_and_stays_in_range():
    head = TABLE.read_text(encoding="utf-8").splitlines()[:3]
    assert any("Glasgow Norms" in line and "Scott" in line for line in head)
    words, actions = load_table()
    assert 300 <= len(words) + len(actions) <= 1000
    for vad in [*words.values(), *(a.vad for a in actions.values())]:
        assert all(-1.0 <= v <= 1.0 for v in vad)


def test_every_library_action_has_a_row():
    from wana.domain.actions import action_names

    _, actions = load_table()
    assert set(action_names()) <= set(actions)


def test_emotion_words_order_as_people_rate_them():
    assert word_vad("happy")[0] > 0.5 > -0.5 > word_vad("sad")[0]
    assert word_vad("furious")[1] > word_vad("calm")[1]  # arousal
    assert word_vad("proud")[2] > word_vad("scared")[2]  # dominance
    assert word_vad("criticizes") == word_vad("criticize") == word_vad("criticiz")  # inflections, NLP stems
    assert word_vad("qwzx") is None


def test_action_rows_score_hugs_above_punches_and_candidates_are_reactions():
    assert action_vad("hug")[0] > 0.3 > -0.3 > action_vad("punch")[0]
    assert action_vad("", "love")[0] > 0.5  # an unknown action falls back to its verb
    names = {c.name for c in response_candidates()}
    assert {"nod", "shake_head", "cry", "hug"} <= names
    assert not names & {"sit", "type", "walk", "sweep", "drink"}


def test_the_face_model_is_linear_and_neutral_at_zero():
    assert FACE_MATRIX.shape == (len(EXPRESSIONS), 3)
    assert face_weights((0.0, 0.0, 0.0)).tolist() == [0.0] * len(EXPRESSIONS)
    batch = face_weights([[0.2, 0.1, 0.0], [-0.4, 0.3, 0.2]])
    assert batch.shape == (2, len(EXPRESSIONS))
    with pytest.raises(ValueError, match="3 values"):
        face_weights((0.1, 0.2))


@pytest.mark.data
def test_the_build_script_reproduces_the_committed_table(shared_data, tmp_path):
    out = tmp_path / "vad.tsv"
    assert (
        build_vad.main(
            [
                "--glasgow",
                str(shared_data / "glasgow_norms" / "glasgow_norms.csv"),
                "--vader",
                str(shared_data / "vader_lexicon" / "vader_lexicon.txt"),
                "-o",
                str(out),
            ]
        )
        == 0
    )
    assert out.read_text(encoding="utf-8") == TABLE.read_text(encoding="utf-8")


def test_the_build_script_says_when_the_data_is_missing(tmp_path, capsys):
    assert build_vad.main(["--glasgow", str(tmp_path / "none.csv"), "-o", str(tmp_path / "x.tsv")]) == 2
    assert "not found" in capsys.readouterr().err
