"""Things named only in action sentences are catalog objects (issue 14): food one chops, a jug one pours
from, the elevator one walks to; "the head of the table" is the table."""

from __future__ import annotations

import pytest

from services.nlp.parse import parse_document


def acts(text: str) -> list[tuple[str, str]]:
    return [(a.action, a.target or a.destination) for g in parse_document(text) for c in g.characters
            for a in c.actions]  # fmt: skip


def categories(text: str) -> list[str]:
    return [o.category for g in parse_document(text) for o in g.objects]


@pytest.mark.parametrize(
    ("text", "category"),
    [
        ("Nora chops onions on the cutting board.", "vegetable"),
        ("She chops vegetables.", "vegetable"),
        ("Tom slices the carrots.", "vegetable"),
        ("Tom slices the bread.", "bread"),
        ("She pours milk from the jug.", "jug"),
    ],
)
def test_food_to_cut_and_vessels_to_pour_from_are_objects(text, category):
    assert category in categories(text)
    assert not any(d.code == "W101" for g in parse_document(text) for d in g.diagnostics)


def test_chopping_onions_aims_at_the_vegetables():
    assert acts("Nora chops onions on the cutting board.") == [("chop", "vegetable")]


def test_the_head_or_end_of_a_table_is_the_table():
    assert acts("Mr Van Loon sits at the head of the table.") == [("sit", "table")]
    assert acts("Tom sits at the end of the bench.") == [("sit", "bench")]


def test_the_elevator_is_a_door_one_walks_to():
    assert categories("In the lobby there is an elevator door$.") == ["door"]
    assert acts("Walter walks to the elevator.") == [("walk", "door")]


def test_a_scene_sentence_on_the_end_of_a_thing_is_not_read_as_beside_it():
    graphs = parse_document("A vise is on the end of the workbench$.")
    assert not [r for g in graphs for r in g.relations if r.relation == "next_to"]
