"""Document-level resolution of names and pronouns, on hand-built sentence graphs."""

from __future__ import annotations

from proto.common import Span
from proto.ssg import ActionNode, CharacterNode, ObjectNode, SentenceGraph, SocialNode
from services.nlp.resolve import resolve


def graph(text: str, *characters: CharacterNode, social=(), objects=()) -> SentenceGraph:
    return SentenceGraph(
        sentence_id=text[:8],
        text=text,
        kind="action",
        characters=list(characters),
        social=list(social),
        objects=list(objects),
    )


def act(action: str, target: str = "", start: int = 0) -> ActionNode:
    return ActionNode(verb=action, action=action, target=target, span=Span(start, start + 3))


def names(g: SentenceGraph) -> list[str]:
    return [c.name for c in g.characters]


def test_he_and_she_follow_the_gender_of_known_names():
    gs = resolve(
        [
            graph("Tom walks in.", CharacterNode(name="Tom", actions=[act("walk")], mention="Tom")),
            graph("Eve sits.", CharacterNode(name="Eve", actions=[act("sit")], mention="Eve")),
            graph("He waves at her.", CharacterNode(name="", actions=[act("wave", "her")], mention="He")),
        ]
    )
    assert names(gs[2]) == ["Tom"]
    assert gs[2].characters[0].actions[0].target == "Eve"
    assert gs[2].characters[0].mention == "He"


def test_they_expands_to_the_last_group_of_characters():
    gs = resolve(
        [
            graph(
                "Tom waves at Eve.", CharacterNode(name="Tom", actions=[act("wave", "Eve")], mention="Tom")
            ),
            graph("They dance.", CharacterNode(name="", actions=[act("dance")], mention="They")),
            graph(
                "They are friends.", social=[SocialNode(kind="relation", subjects=["they"], label="friends")]
            ),
        ]
    )
    assert names(gs[1]) == ["Tom", "Eve"]
    assert sorted(gs[2].social[0].subjects) == ["Eve", "Tom"]


def test_a_sentence_without_subject_goes_to_the_last_actor():
    gs = resolve(
        [
            graph("Mary sits.", CharacterNode(name="Mary", actions=[act("sit")], mention="Mary")),
            graph("Stand up.", CharacterNode(name="", actions=[act("stand")], mention="")),
        ]
    )
    assert names(gs[1]) == ["Mary"] and not gs[1].diagnostics


def test_unresolvable_pronoun_gets_w105_with_the_pronoun_span():
    text = "Then he sits."
    gs = resolve(
        [graph(text, CharacterNode(name="", actions=[act("sit", start=108)], mention="he"))], offsets=[100]
    )
    (d,) = gs[0].diagnostics
    assert d.code == "W105" and (d.span.start, d.span.end) == (105, 107)
    assert names(gs[0]) == [""]


def test_imperative_with_no_character_in_the_document_gets_w109():
    gs = resolve([graph("Walk to the door.", CharacterNode(name="", actions=[act("walk")], mention=""))])
    assert [d.code for d in gs[0].diagnostics] == ["W109"]


def test_it_refers_to_the_last_object():
    chair = ObjectNode(id="chair", category="chair", word="chair")
    gs = resolve(
        [
            graph(
                "Eve walks to the chair.",
                CharacterNode(name="Eve", actions=[act("walk", "chair")], mention="Eve"),
                objects=[chair],
            ),
            graph("She sits on it.", CharacterNode(name="", actions=[act("sit", "it")], mention="She")),
        ]
    )
    assert gs[1].characters[0].actions[0].target == "chair"


def test_resolution_is_pure_and_repeatable():
    gs = [
        graph("Tom sits.", CharacterNode(name="Tom", actions=[act("sit")], mention="Tom")),
        graph("He waves.", CharacterNode(name="", actions=[act("wave")], mention="He")),
    ]
    assert resolve(gs) == resolve(gs)
    assert gs[1].characters[0].name == ""  # inputs untouched
