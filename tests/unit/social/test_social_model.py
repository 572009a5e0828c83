"""The social model: orderings it promises, determinism, shapes, and clear errors for bad input."""

from __future__ import annotations

import numpy as np
import pytest

from proto.motion_data import Segment
from proto.ssg import ActionNode, CharacterNode, SentenceGraph, SocialNode
from services.social.face import face_weights
from services.social.plan import expression_track, plan_social, social_groups
from services.social.sketch import sketch_graphs
from services.social.story import StoryError
from wana.assets.characters import EXPRESSIONS

SMILE, FROWN = EXPRESSIONS.index("smile"), EXPRESSIONS.index("frown")


def plan(text: str, seed: int = 0):
    return plan_social(sketch_graphs(text), seed=seed)


def emotion(p, who, step=-1):
    return next(c for c in p.characters if c.name == who).emotions[step].vad


def distance(p, a="Tom", b="Mary"):
    return next(x.distance_m for x in p.pairs if x.character == a and x.other == b)


def test_friends_stand_closer_than_a_boss_and_an_employee():
    friends = plan("rel Tom Mary friends; act Tom talk Mary")
    boss = plan("rel Mary Tom boss; act Tom talk Mary")
    assert distance(friends) < distance(boss) - 0.2
    assert friends.action_distances[0].distance_m < boss.action_distances[0].distance_m


def test_a_relation_is_listed_from_both_sides_with_the_inverse_label():
    p = plan("rel Mary Tom boss; act Mary talk Tom")
    by = {(x.character, x.other): x for x in p.pairs}
    assert by[("Mary", "Tom")].relation == "boss" and by[("Tom", "Mary")].relation == "employee"
    assert by[("Mary", "Tom")].dominance > 0.3 > -0.3 > by[("Tom", "Mary")].dominance
    assert by[("Mary", "Tom")].distance_m == by[("Tom", "Mary")].distance_m


def test_an_angry_character_frowns_and_a_happy_one_smiles():
    p = plan("emo Tom angry; emo Mary happy")
    tom, mary = face_weights(emotion(p, "Tom")), face_weights(emotion(p, "Mary"))
    assert tom[FROWN] > tom[SMILE] and emotion(p, "Tom")[0] < -0.2
    assert mary[SMILE] > mary[FROWN] and emotion(p, "Mary")[0] > 0.2


def test_an_apology_lowers_the_apologisers_dominance():
    sorry = plan("act Tom talk Mary; act Mary apologize Tom")
    talk = plan("act Tom talk Mary; act Mary talk Tom")
    assert emotion(sorry, "Mary", 1)[2] < emotion(talk, "Mary", 1)[2] - 0.1


def test_criticism_gets_a_proposed_negative_reaction_flagged_as_proposed():
    p = plan("act Tom criticize Mary")
    assert len(p.proposals) == 1
    r = p.proposals[0]
    assert (r.character, r.after, r.after_action_index, r.proposed) == ("Mary", "Tom", 0, True)
    assert r.vad[0] < 0 and 0.1 <= r.delay_s <= 3.0
    assert emotion(p, "Mary")[0] < 0


def test_a_reaction_the_text_gives_is_not_proposed_and_is_timed():
    p = plan("act Tom criticize Mary; act Mary apologize Tom")
    assert not [x for x in p.proposals if x.character == "Mary"]
    (timing,) = [r for r in p.responses if r.responder == "Mary"]
    assert timing.response_index == 0 and 0.1 <= timing.delay_s <= 3.0


def test_an_employee_answers_the_boss_sooner():
    p = plan("rel Mary Tom boss; act Mary talk Tom; act Tom talk Mary; act Mary talk Tom")
    tom = next(r for r in p.responses if r.responder == "Tom")
    mary = next(r for r in p.responses if r.responder == "Mary")
    assert tom.delay_s < mary.delay_s


def test_they_quarrel_aims_each_at_the_other():
    p = plan("rel Tom Mary enemies; both Tom Mary quarrel")
    assert {(d.character, d.other) for d in p.action_distances} == {("Tom", "Mary"), ("Mary", "Tom")}
    assert emotion(p, "Tom")[0] < 0 and emotion(p, "Mary")[0] < 0


def test_the_same_seed_gives_the_same_plan_and_the_sampler_lowers_the_energy():
    text = "rel Tom Mary colleagues; act Tom wave Mary; emo Tom angry; act Tom criticize Mary; act Mary cry"
    a, b = plan(text, seed=3), plan(text, seed=3)
    assert a == b
    assert a.energy_final < 0.5 * a.energy_initial
    assert a.steps >= 300 and 0 < a.accepted <= a.steps


def test_no_characters_give_an_empty_plan():
    p = plan_social([SentenceGraph(sentence_id="s0", text="A desk$.", kind="scene")])
    assert p.characters == [] and p.pairs == [] and p.expression_names == list(EXPRESSIONS)


def test_unknown_words_become_notes_not_errors():
    g = SentenceGraph(
        sentence_id="s0",
        text="Tom blorfs Mary.",
        kind="action",
        characters=[CharacterNode(name="Tom", actions=[ActionNode(verb="blorf", action="", target="Mary")])],
        social=[SocialNode(kind="relation", subjects=["Tom", "Mary"], label="zorblings")],
    )
    p = plan_social([g])
    assert any("blorf" in n for n in p.notes) and any("zorblings" in n for n in p.notes)
    assert [x.relation for x in p.pairs] == ["default", "default"]


def test_too_many_characters_is_a_clear_error():
    text = "; ".join(f"act P{i} wave P{i + 1}" for i in range(9))
    with pytest.raises(StoryError, match="at most 8 characters"):
        plan(text)


def test_bad_sketch_and_bad_steps_are_clear_errors():
    with pytest.raises(ValueError, match="cannot read sketch item"):
        sketch_graphs("dance Tom")
    with pytest.raises(ValueError, match="steps must be"):
        plan_social(sketch_graphs("act Tom wave Mary"), steps=-1)


def test_expression_track_follows_the_plan_over_the_segments():
    p = plan("emo Tom angry; act Tom criticize Mary; act Tom hug Mary")
    segs = [
        Segment(index=0, action="criticize", start_frame=0, end_frame=90, action_index=0),
        Segment(index=1, action="walk", start_frame=90, end_frame=120, action_index=1),
        Segment(index=2, action="hug", start_frame=120, end_frame=210, action_index=1),
        Segment(index=3, action="idle", start_frame=210, end_frame=240),
    ]
    track = expression_track(p, "Tom", segs)
    assert track.shape == (240, len(EXPRESSIONS)) and track.dtype == np.float32
    assert track.min() >= 0.0 and track.max() <= 1.0
    assert track[60, FROWN] > track[60, SMILE]  # while criticising
    assert track[200, SMILE] > track[60, SMILE]  # the hug is warmer
    assert np.abs(np.diff(track, axis=0)).max() < 0.1  # no jumps between frames
    assert expression_track(p, "Tom", segs, frames=300).shape == (300, len(EXPRESSIONS))


def test_reaction_keys_need_the_other_characters_segments():
    p = plan("act Tom criticize Mary")
    mary_idle = [Segment(index=0, action="idle", start_frame=0, end_frame=150)]
    tom = [Segment(index=0, action="criticize", start_frame=0, end_frame=100, action_index=0)]
    alone = expression_track(p, "Mary", mary_idle)
    placed = expression_track(p, "Mary", mary_idle, others={"Tom": tom})
    assert np.allclose(alone, alone[0])  # only the rest face
    assert not np.allclose(placed[0], placed[-1])  # the face changes when she reacts


def test_expression_track_rejects_bad_input():
    p = plan("act Tom wave Mary")
    with pytest.raises(ValueError, match="not a character"):
        expression_track(p, "Zed", [])
    with pytest.raises(ValueError, match="fps"):
        expression_track(p, "Tom", [], fps=0)
    with pytest.raises(ValueError, match="frames"):
        expression_track(p, "Tom", [Segment(index=0, action="wave", start_frame=10, end_frame=5)])


def test_characters_who_never_meet_are_planned_apart():
    pair = sketch_graphs("rel Tom Mary friends; act Tom hug Mary; emo Mary happy")
    more = sketch_graphs("rel Tom Mary friends; act Tom hug Mary; emo Mary happy; emo Eve angry; act Eve cry")
    assert social_groups(more) == [["Tom", "Mary"], ["Eve"]]
    alone, together = plan_social(pair, seed=3), plan_social(more, seed=3)
    by_name = {c.name: c for c in together.characters}
    for c in alone.characters:  # Eve's story changes nothing of Tom's and Mary's plan
        assert by_name[c.name] == c
    assert [c.name for c in together.characters] == ["Tom", "Mary", "Eve"]
    assert not any("Eve" in (p.character, p.other) for p in together.pairs)


def test_an_action_aimed_at_a_character_joins_their_groups():
    assert social_groups(sketch_graphs("act Tom cry; act Eve wave; act Eve point Tom")) == [["Tom", "Eve"]]
