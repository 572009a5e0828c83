"""A long story is planned window by window: cuts fall only where nothing social crosses them, an edit
re-plans only its window, and the merged plan numbers actions and steps over the whole document."""

from __future__ import annotations

import msgspec

from services.social import windows
from services.social.plan import _plan_group, plan_social
from services.social.sketch import sketch_graphs


def long_story(lines: int, verb: str = "cry") -> str:
    """Two friends taking turns; every fifth sentence one waves at the other, the rest act alone."""
    items = ["rel Tom Mary friends"]
    for i in range(lines):
        who, other = ("Tom", "Mary") if i % 2 == 0 else ("Mary", "Tom")
        items.append(
            f"act {who} wave {other}" if i % 5 == 0 else f"act {who} {verb if i == lines - 3 else 'nod'}"
        )
    return "; ".join(items)


def test_a_short_story_is_one_window_planned_as_before():
    graphs = sketch_graphs("rel Tom Mary friends; act Tom talk Mary; act Mary cry; act Tom hug Mary")
    assert windows.story_windows(graphs) == [graphs]
    assert plan_social(graphs, seed=3) == _plan_group(graphs, [], 3, 0)


def test_a_long_story_is_cut_only_after_quiet_sentences_and_every_graph_is_in_one_window():
    graphs = sketch_graphs(long_story(100))
    wins = windows.story_windows(graphs)
    assert len(wins) >= 3
    assert [g for w in wins for g in w] == graphs
    names = {"Tom", "Mary"}
    for w in wins[:-1]:
        assert len(w) >= windows.WINDOW_MIN_STEPS
        assert windows._quiet(w[-1], names)  # no wave (which the next sentence answers) at a cut
    # the relation stated in the first sentence holds in every later window
    assert [s.label for s in windows.relations_before(wins, 2)] == ["friends"]


def test_the_merged_plan_numbers_each_characters_actions_over_the_whole_story():
    graphs = sketch_graphs(long_story(100))
    p = plan_social(graphs, seed=0)
    actions: dict[str, list] = {}
    for g in graphs:
        for c in g.characters:
            actions.setdefault(c.name, []).extend(c.actions)
    assert len(windows.story_windows(graphs)) > 1
    waves = [(n, k) for n, acts in actions.items() for k, a in enumerate(acts) if a.target]
    assert sorted((d.character, d.action_index) for d in p.action_distances) == sorted(waves)
    for d in p.action_distances:
        assert actions[d.character][d.action_index].target == d.other
    for r in p.responses:
        assert actions[r.actor][r.action_index].target == r.responder
        assert r.response_index < len(actions[r.responder])
    steps = [e.step for e in next(c for c in p.characters if c.name == "Tom").emotions]
    assert steps == sorted(steps) and len(set(steps)) == len(steps)
    assert [c.name for c in p.characters] == ["Tom", "Mary"]


def test_an_edit_in_the_last_window_leaves_the_plan_of_the_others_as_it_was():
    before = sketch_graphs(long_story(100))
    after = sketch_graphs(long_story(100, verb="laugh"))
    cut = len(windows.story_windows(before)[0])
    assert windows.story_windows(after)[0] == windows.story_windows(before)[0]
    a, b = plan_social(before, seed=0), plan_social(after, seed=0)
    assert a != b
    first = {g.sentence_id for g in before[:cut]}
    for ca, cb in zip(a.characters, b.characters, strict=True):
        assert [e for e in ca.emotions if e.sentence_id in first] == [
            e for e in cb.emotions if e.sentence_id in first
        ]
    early = [d for d in a.action_distances if d.action_index < 10]
    assert early and early == [d for d in b.action_distances if d.action_index < 10]


def test_a_window_planned_before_comes_from_the_memo():
    graphs = sketch_graphs(long_story(60))
    calls: list[int] = []

    def plan(g, context, seed, steps):  # noqa: ANN001, ANN202
        calls.append(len(g))
        return _plan_group(g, context, seed, steps)

    win = windows.story_windows(graphs)[0]
    one = windows.plan_window(win, [], 11, 0, plan)
    two = windows.plan_window([msgspec.structs.replace(g) for g in win], [], 11, 0, plan)
    assert one is two and calls == [len(win)]
