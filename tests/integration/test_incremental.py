"""Salsa-style tests of the whole pipeline: make one edit, assert exactly which query nodes re-ran.

The services run in-process (their real handlers: the trained parser, the composer, the optimiser and the
motion synthesiser); one session per test, so each starts from a cold memo.
"""

from __future__ import annotations

import pytest

from services.orchestrator.backend import InProcessBackend
from services.orchestrator.document import TextChange
from services.orchestrator.session import Orchestrator, Session

pytestmark = [pytest.mark.integration, pytest.mark.slow]

STORY = (
    "A desk is near the window$. A laptop is on the desk$. A chair is in front of the desk$.\n"
    "Eve walks to the chair. Eve sits on the chair.\n"
    "camera left\n"
    "Tom walks to the window. Tom waves.\n"
)


@pytest.fixture(scope="module")
def orchestrator(tmp_path_factory):
    orch = Orchestrator(tmp_path_factory.mktemp("db") / "sessions.db", InProcessBackend())
    yield orch
    orch.close()


@pytest.fixture
def session(orchestrator) -> Session:
    s = orchestrator.create(STORY)
    s.compute()
    return s


def replace(session: Session, old: str, new: str) -> None:
    at = session.doc.text.index(old)
    session.edit(session.doc.version, [TextChange(start=at, end=at + len(old), text=new)])


def sid_of(session: Session, fragment: str) -> str:
    return next(s.id for s in session.doc.sentences if fragment in s.text)


def test_the_first_compute_runs_every_node(orchestrator):
    s = orchestrator.create(STORY)
    result = s.compute()
    parses = [f"parse:{x.id}" for x in s.doc.sentences]
    assert result.ran[: len(parses) + 2] == parses + ["resolve", "scene"]
    assert {"segment:Eve:0", "segment:Tom:0"} <= set(result.ran)
    assert result.unavailable == {}
    assert set(result.motions) == {"Eve", "Tom"}


def test_editing_one_action_reruns_its_parse_and_that_action_of_that_character_only(session):
    replace(session, "Tom waves", "Tom claps")
    result = session.compute()
    assert result.ran == [
        f"parse:{sid_of(session, 'Tom claps')}",
        "resolve",
        "social",  # a new verb: Tom's emotions are sampled again; Eve never meets him, her face stays
        "segment:Tom:1",
        "cast",  # Tom passes within 0.6 m of Eve (the give-way clearance): the cast fit sees the new motion
        "motion",  # the story played again (its nodes above re-ran; the rest were not asked)
        "face:Tom",
    ]
    assert [seg.action for seg in result.motions["Tom"].segments][-1] == "clap"


def test_an_action_whose_end_state_changes_reruns_the_actions_after_it(session):
    replace(session, "Tom walks to the window", "Tom walks to the desk")
    result = session.compute()
    assert result.ran == [
        f"parse:{sid_of(session, 'Tom walks to the desk')}",
        "resolve",
        "segment:Tom:0",
        "segment:Tom:1",
        "cast",  # his walk to the desk now passes Eve at its chair: who gives way is asked again
        "motion",
        # the walk to the desk ends beside Eve's chair, not at the window: his face's timing changes
        "face:Tom",
    ]
    # the drafts' arms keep clear of the furniture (services/motion/arm_clearance.py), so the optimiser leaves
    # the desk where the wave has room beside it: no step out first (the walk goes round seated Eve's legs,
    # services/motion/routing: one frame longer than a route that ignored them)
    assert [(g.action, g.start_frame, g.end_frame) for g in result.motions["Tom"].segments][-3:] == [
        ("walk", 59, 129),
        ("walk", 129, 184),
        ("wave", 184, 270),
    ]


def test_an_action_whose_end_state_is_unchanged_stops_early(session):
    replace(session, "Tom walks to the window", "Tom walks slowly to the window")
    result = session.compute()
    assert result.ran == [
        f"parse:{sid_of(session, 'slowly')}",
        "resolve",
        "segment:Tom:0",
        "cast",
        "motion",
        "face:Tom",
    ]


def test_a_whitespace_only_edit_recomputes_nothing(session):
    replace(session, "Eve sits", "Eve   sits")
    assert session.compute().ran == []


def test_a_new_blank_line_recomputes_nothing(session):
    session.edit(session.doc.version, [TextChange(start=0, end=0, text="\n\n")])
    assert session.compute().ran == []


def test_changing_a_command_reruns_only_its_parse_and_resolve(session):
    replace(session, "camera left", "camera top")
    result = session.compute()
    assert result.ran == [f"parse:{sid_of(session, 'camera top')}", "resolve"]
    assert [c.value for _, c in result.commands] == ["top"]


def test_a_scene_edit_whose_graph_is_unchanged_stops_after_resolve(session):
    replace(session, "A laptop is on the desk$", "The laptop is on the desk$")
    result = session.compute()
    assert result.ran == [f"parse:{sid_of(session, 'The laptop')}", "resolve"]


def test_changing_a_scene_object_recomposes_the_scene_and_the_motion_in_it(session):
    before = session.compute()
    replace(session, "A laptop is on the desk$", "A lamp is on the desk$")
    result = session.compute()
    assert result.ran[:3] == [f"parse:{sid_of(session, 'A lamp')}", "resolve", "scene"]
    assert "optimise:Eve:1" in result.ran  # the layout around her sitting at the desk is optimised again
    # The walks neither name the lamp nor cross the desk's top: they re-run only if the optimised layout
    # moved the furniture on the floor.
    floor_moved = [o for o in result.scene.objects if o.support == ""] != [
        o for o in before.scene.objects if o.support == ""
    ]
    assert ("segment:Tom:0" in result.ran) == floor_moved
    assert "lamp" in {o.category for o in result.scene.objects}


def test_deleting_a_sentence_reruns_resolve_and_the_affected_character(session):
    replace(session, " Tom waves.", "")
    result = session.compute()
    assert result.ran == ["resolve", "social", "cast", "motion", "face:Tom"]
    assert all(seg.action != "wave" for seg in result.motions["Tom"].segments)


def test_recomputing_without_an_edit_runs_nothing(session):
    assert session.compute().ran == []


def test_the_same_text_gives_the_same_animation(orchestrator, session):
    other = orchestrator.create(STORY)
    a, b = session.compute(), other.compute()
    assert a.scene == b.scene
    assert a.motions == b.motions


def test_inserting_an_action_runs_only_its_parse_and_its_new_motion_node(session):
    at = session.doc.text.index("camera left")
    session.edit(session.doc.version, [TextChange(start=at, end=at, text="Eve waves. ")])
    result = session.compute()
    assert result.ran == [
        f"parse:{sid_of(session, 'Eve waves')}",
        "resolve",
        "social",
        "segment:Eve:2",
        "cast",
        "motion",
        "face:Eve",
        "face:Tom",  # his sentences now start after Eve's new one
    ]


def test_reordering_two_sentences_reparses_nothing_and_reruns_that_characters_motion(session):
    replace(session, "Tom walks to the window. Tom waves.", "Tom waves. Tom walks to the window.")
    result = session.compute()
    assert result.ran == [
        "resolve",
        "social",
        "segment:Tom:0",
        "segment:Tom:1",
        "cast",
        "motion",
        "face:Tom",
    ]
    # Tom's first action is now the wave (after the walk in at the door: he comes in with his sentence).
    assert [s.action for s in result.motions["Tom"].segments if s.action_index == 0][-1] == "wave"


def test_a_pronoun_that_names_the_same_character_changes_no_motion(session):
    replace(session, "Tom waves", "He waves")
    result = session.compute()
    assert result.ran == [f"parse:{sid_of(session, 'He waves')}", "resolve"]


def test_painting_an_object_recomposes_the_scene_and_no_motion(session):
    before = session.compute()
    replace(session, "A chair is in front", "A red chair is in front")
    result = session.compute()
    # motion, the optimiser and the routes read shapes only (views.geometry_view): no motion node re-runs
    assert result.ran == [f"parse:{sid_of(session, 'A red chair')}", "resolve", "scene"]
    chair = next(o for o in result.scene.objects if o.category == "chair")
    assert chair.attributes.get("colour") == "red"  # the paint is back on the final layout
    assert result.motions == before.motions
    old = next(o for o in before.scene.objects if o.id == chair.id)
    assert (chair.position, chair.yaw) == (old.position, old.yaw)


LONG = (
    "In the office there is a desk near a window$. A chair is in front of the desk$. "
    "A sofa is next to the bookshelf$.\n"
    + "\n".join(
        ["Eve walks to the chair.", "Tom waves at Eve.", "Eve nods.", "Tom walks to the sofa.", "Eve waves."][
            i % 5
        ]
        for i in range(70)
    )
)


def test_an_action_edit_in_a_long_story_reruns_only_motion_near_it(orchestrator):
    s = orchestrator.create(LONG)
    s.compute()
    target = [x for x in s.doc.sentences if x.text.startswith("Eve nods")][-2]
    at = s.doc.text.index("nods", target.start)
    s.edit(s.doc.version, [TextChange(start=at, end=at + 4, text="cheers")])
    result = s.compute()
    motion = [k for k in result.ran if k.split(":")[0] in ("draft", "optimise", "segment")]
    assert any(k.startswith("segment:Eve:") for k in motion)
    # the social plan is re-sampled in the edit's window only (services/social/windows.py): the actions of
    # the story's first window keep their distances, so none of their motion nodes re-runs
    assert all(int(k.rsplit(":", 1)[1]) >= 10 for k in motion), motion
    assert len(motion) < 12


SCENE = (
    "In the office there is a desk near a window$. A laptop is on the desk$. A chair is in front of the desk$. "
    "A sofa is next to the bookshelf$. A green plant is in the corner$.\n"  # no action uses the plant
)
TURNS = [
    "Eve walks to the chair.",
    "Tom walks to the sofa.",
    "Eve sits on the chair.",
    "Tom waves at Eve.",
    "Eve types on the laptop.",
    "Tom sits on the sofa.",
    "Eve stands up.",
    "Tom stands up.",
    "Eve walks to the window.",
    "Tom walks to the sofa.",
]


def _edits_at(orchestrator, actions: int) -> dict[str, list[str]]:
    """The nodes an action edit (a verb in the middle) and a paint edit of an object no action uses ran, in a
    document of ``actions`` action sentences (bench/scale.py's document, smaller)."""
    s = orchestrator.create(SCENE + "\n".join(TURNS[i % len(TURNS)] for i in range(actions)))
    s.compute()
    at = s.doc.text.index("walks", len(s.doc.text) // 2)
    s.edit(s.doc.version, [TextChange(start=at, end=at + 5, text="runs")])
    action = s.compute().ran
    at = s.doc.text.index("green plant")
    s.edit(s.doc.version, [TextChange(start=at, end=at + 5, text="red")])
    paint = s.compute().ran
    orchestrator.delete(s.doc_id)
    return {"action": action, "paint": paint}


def test_an_edit_reruns_as_many_nodes_in_a_long_document_as_in_a_short_one(orchestrator):
    short, long = _edits_at(orchestrator, 48), _edits_at(orchestrator, 96)
    # a verb: its parse, resolve, the social plan's window (services/social/windows.py: 24 to 96 character
    # sentences), the motion nodes whose distances or timing that window's plan changed (the waves at Eve in
    # it), the played story and the faces; never more in the longer document
    assert len(long["action"]) <= len(short["action"]) + 1, (short["action"], long["action"])
    assert len(long["action"]) <= 14, long["action"]
    # the plant's colour: its parse, resolve and the room; no motion node, the story is not played again
    assert [k.split(":")[0] for k in short["paint"]] == ["parse", "resolve", "scene"]
    assert [k.split(":")[0] for k in long["paint"]] == ["parse", "resolve", "scene"]
