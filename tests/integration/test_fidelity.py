"""Story checks on animations the real pipeline made (in-process services), and where users see them."""

from __future__ import annotations

import subprocess
import sys

import pytest

from services.gateway.messages import diagnostics_message
from services.orchestrator.animate import summary
from services.orchestrator.backend import InProcessBackend
from services.orchestrator.session import Orchestrator
from wana.fidelity import story_checks, verdicts

pytestmark = [pytest.mark.integration, pytest.mark.slow]

SOFA = "A sofa is near a window$.\nEve sits on the sofa.\nTom sits on the sofa.\nEve drinks from the cup.\n"


@pytest.fixture(scope="module")
def orchestrator(tmp_path_factory):
    orch = Orchestrator(tmp_path_factory.mktemp("db") / "s.db", InProcessBackend())
    yield orch
    orch.close()


def checks_of(result):
    return story_checks(
        [(s.id, s.kind) for s in result.sentences],
        result.graphs,
        result.scene,
        result.motions,
        result.unavailable,
    )


def failing(checks, name):
    return [c for c in checks if c.name == name and not c.ok]


@pytest.fixture(scope="module")
def office(orchestrator, repo_root):
    session = orchestrator.create((repo_root / "examples" / "office.txt").read_text())
    return session, session.compute()


@pytest.fixture(scope="module")
def sofa(orchestrator):
    session = orchestrator.create(SOFA)
    return session, session.compute()


def test_the_office_shows_its_room_and_eve_seated_at_the_laptop(office):
    _, result = office
    checks = checks_of(result)
    by_text = {s.text: checks[s.id] for s in result.sentences}
    for scene_sentence in [s for s in result.sentences if s.kind == "scene"]:
        assert all(c.ok for c in checks[scene_sentence.id]), checks[scene_sentence.id]
    sits = by_text["Eve sits on the chair and types on the laptop."]
    contacts = [c for c in sits if c.name == "contact"]
    assert len(contacts) == 2 and all(c.ok for c in contacts), contacts
    assert [c.ok for c in sits if c.name == "supported"] == [True]


def test_tom_who_walks_in_comes_in_at_the_door_and_passes_the_entrance_check(office):
    _, result = office
    walks_in = next(s for s in result.sentences if s.text == "Tom walks in.")
    (entrance,) = [c for c in checks_of(result)[walks_in.id] if c.name == "entrance"]
    assert entrance.ok and entrance.character == "Tom", entrance


def test_two_characters_sent_to_one_sofa_keep_apart_and_a_cup_never_placed_is_not_drunk(sofa):
    _, result = sofa
    checks = checks_of(result)
    eve_sits, tom_sits, drinks = (s.id for s in result.sentences[1:])
    assert [c.name for c in checks[tom_sits] if c.name == "overlap"] == ["overlap"]
    assert not failing(checks[tom_sits], "overlap") and not failing(checks[eve_sits], "overlap")
    (cup,) = failing(checks[drinks], "contact")
    assert cup.essential and cup.reason.startswith("there is no cup in the room")
    assert verdicts(checks)[drinks].verdict == "failed"


def test_the_report_carries_each_sentence_verdict_and_what_was_dropped(sofa):
    _, result = sofa
    report = summary(result)
    rows = {s["text"]: s for s in report["sentences"]}
    drink = rows["Eve drinks from the cup."]
    assert drink["verdict"] == "failed"
    assert {"name", "ok", "reason", "frames", "character"} <= set(drink["checks"][0])
    assert "no cup" in report["unavailable"][drink["id"]]
    assert rows["A sofa is near a window$."]["verdict"] == "ok"


def test_the_editor_gets_a_w401_warning_on_the_span_of_each_sentence_not_shown(sofa):
    session, result = sofa
    msg = diagnostics_message(result, session.doc)
    spans = {s.id: (s.start, s.end) for s in result.sentences}
    warnings = [d for d in msg["diagnostics"] if d["code"] == "W401"]
    assert warnings and all(d["severity"] == "warning" for d in warnings)
    assert all((d["start"], d["end"]) == spans[d["sentence_id"]] for d in warnings)
    drink = next(s.id for s in result.sentences if "cup" in s.text)
    assert any("no cup" in d["message"] for d in warnings if d["sentence_id"] == drink)
    assert {v["sentence_id"]: v["verdict"] for v in msg["verdicts"]}[drink] == "failed"


@pytest.mark.parametrize("text", ["", "  \n", "Der Hund läuft schnell.", "camera left\n"])
def test_a_story_with_nothing_to_animate_exits_non_zero_and_writes_nothing(tmp_path, text):
    story = tmp_path / "story.txt"
    story.write_text(text)
    out = tmp_path / "out"
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "wana.cli",
            "animate",
            str(story),
            "-o",
            str(out),
            "--in-process",
            "--no-progress",
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert proc.returncode == 2, proc.stderr[-2000:]
    assert "nothing" in proc.stderr and not (out / "report.json").exists()


def test_sitting_again_while_seated_keeps_sitting_and_with_no_free_seat_stands_and_says_so(orchestrator):
    result = orchestrator.create(
        "A chair is near a desk$.\nEve sits on the chair. Eve sits.\nTom sits.\n"
    ).compute()
    checks = checks_of(result)
    again = next(s.id for s in result.sentences if s.text == "Eve sits.")
    tom = next(s.id for s in result.sentences if s.text == "Tom sits.")
    assert not failing(checks[again], "continuity")  # no replayed sit-down, no pop
    assert not failing(checks[again], "supported")  # still on the seat
    assert not failing(checks[tom], "supported")  # Tom never sits on air ...
    (shown,) = failing(checks[tom], "performed")  # ... the verdict says he did not sit
    assert "Tom" in shown.reason
    assert any("stands instead" in d.message for d in result.diagnostics[tom])


def test_walking_into_the_room_asks_for_no_object_called_room(orchestrator):
    result = orchestrator.create("A table is near a window$.\nAnna and Tom walk into the room.\n").compute()
    checks = [c for items in checks_of(result).values() for c in items]
    assert not [c for c in checks if "no room in the room" in c.reason]
    assert not [c for c in checks if c.name == "contact" and not c.ok and "room" in c.reason]


POUR = (
    "In the kitchen there is a table$. A kettle is on the counter$. A cup is on the table$.\n"
    "Mira picks up the kettle.\nMira pours coffee into the cup.\n"
)


def test_pouring_from_a_kettle_in_hand_walks_to_the_cup_and_holds_the_kettle_over_it(orchestrator):
    """The kettle taken at the counter is poured over the cup on the table (it was poured into the air where
    the character stood, and the check only asked for the kettle in the hand)."""
    from wana.arrays import from_wire

    result = orchestrator.create(POUR).compute()
    pours = next(s for s in result.sentences if "pours" in s.text)
    (contact,) = [c for c in checks_of(result)[pours.id] if c.name == "contact"]
    assert contact.ok, contact
    motion = result.motions["Mira"]
    (seg,) = [s for s in motion.segments if s.action == "pour"]
    cup = next(o for o in result.scene.objects if o.category == "cup")
    track = next(
        p for p in motion.props if p.start_frame <= (seg.start_frame + seg.end_frame) // 2 < p.end_frame
    )
    at = from_wire(track.position)[(seg.start_frame + seg.end_frame) // 2 - track.start_frame]
    assert track.object_id.split("/")[0] == "kettle"
    assert float(((at[0] - cup.position[0]) ** 2 + (at[2] - cup.position[2]) ** 2) ** 0.5) < 0.3
