"""Action words -> template clips, on a hand-made library and on the project's action library."""

from __future__ import annotations

from dataclasses import dataclass

import pytest

from proto.retrieval import ActionQuery
from services.retrieval.actions import match_action, prepare_clips


@dataclass(frozen=True)
class Clip:
    tags: tuple[str, ...]
    synonyms: tuple[str, ...]
    interaction: object = None


LIBRARY = {
    "sit": Clip(("pose", "seat"), ("sit down", "take a seat")),
    "play_piano": Clip(("music", "instrument"), ("play the piano",)),
    "play_guitar": Clip(("music", "instrument"), ("strum",)),
    "sing_with_microphone": Clip(("music", "voice"), ("sing", "sing into the microphone")),
    "walk": Clip(("locomotion",), ("stroll",)),
    "walk_slowly": Clip(("locomotion", "slowly"), ()),
}


@pytest.fixture(scope="module")
def clips():
    return prepare_clips(LIBRARY)


def test_the_object_picks_the_clip_made_for_it(clips):
    result = match_action(ActionQuery(verb="play", object="piano"), clips)
    assert [c.clip for c in result.clips][:2] == ["play_piano", "play_guitar"]
    assert result.clips[0].score > result.clips[1].score
    assert "object" in result.clips[0].matched_on and not result.diagnostic


def test_a_hypernym_or_synonym_of_the_object_still_counts(clips):
    grand = match_action(ActionQuery(verb="play", object="grand_piano"), clips)
    assert grand.clips[0].clip == "play_piano"
    word = match_action(ActionQuery(verb="plays", object="pianoforte"), clips)  # a synonym, inflected verb
    assert word.clips[0].clip == "play_piano"


def test_the_instrument_and_a_verb_synonym_find_the_clip(clips):
    result = match_action(ActionQuery(verb="sing", instrument="mic"), clips)
    assert result.clips[0].clip == "sing_with_microphone"
    assert {"synonym", "instrument"} <= set(result.clips[0].matched_on)


def test_the_manner_prefers_the_clip_made_for_it(clips):
    slow = match_action(ActionQuery(verb="walk", manner="slowly"), clips)
    assert slow.clips[0].clip == "walk_slowly"
    plain = match_action(ActionQuery(verb="walk"), clips)
    assert plain.clips[0].clip == "walk"


def test_an_unknown_verb_gets_no_clip_and_a_diagnostic_naming_close_ones(clips):
    result = match_action(ActionQuery(verb="juggle"), clips)
    assert result.clips == []
    assert "juggle" in result.diagnostic
    close = match_action(ActionQuery(verb="sitt"), clips)
    assert close.clips == [] and "sit" in close.diagnostic


def test_top_k_limits_the_clips(clips):
    assert len(match_action(ActionQuery(verb="play"), clips, top_k=1).clips) == 1


def test_the_project_library_answers_the_papers_examples():
    from wana.domain.actions import load_library

    library = load_library()
    if not library:
        pytest.skip("the action library has no clips yet (assets/actions is empty)")
    clips = prepare_clips(library)
    expect = {
        ("sing", "", "microphone"): "sing_with_microphone",
        ("play", "piano", ""): "play_piano",
        ("sit", "sofa", ""): "sit",
        ("type", "laptop", ""): "type",
    }
    for (verb, obj, instrument), clip in expect.items():
        if clip not in library:
            continue
        result = match_action(ActionQuery(verb=verb, object=obj, instrument=instrument), clips)
        assert result.clips and result.clips[0].clip == clip, (verb, obj, instrument, result)
