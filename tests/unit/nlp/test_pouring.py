"""What is poured and what it is poured into: a drink word the catalog reads as its cup ("tea" -> cup) is the
liquid, not a cup to fetch; the vessel named after "into" is the action's target and destination."""

from __future__ import annotations

import pytest

from services.nlp.parse import parse_document


def pours(text: str) -> list[tuple[str, str, str]]:
    return [
        (a.action, a.target, a.destination)
        for g in parse_document(text)
        for c in g.characters
        for a in c.actions
        if a.action == "pour"
    ]


@pytest.mark.parametrize(
    ("text", "vessel"),
    [
        ("Hana pours tea into the mug.", "mug"),
        ("Omar pours coffee into his cup.", "cup"),  # the coffee took the id cup; his cup is that cup
        ("The girl pours some milk into a glass.", "glass"),
        ("He pours juice into the glass.", "glass"),
    ],
)
def test_a_drink_poured_into_a_vessel_is_the_liquid_and_the_vessel_is_the_target(text, vessel):
    ((action, target, destination),) = pours(text)
    assert target == vessel and destination in (vessel, "")  # juice, no catalog word: "into" names the target


def test_a_bottle_poured_from_stays_what_is_poured():
    ((_, target, destination),) = pours("Ben pours the bottle into the sink.")
    assert target.split("#")[0] == "bottle"
