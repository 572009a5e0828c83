"""Walkers give way to each other (services/motion/giveway.py on wana.domain.routes.Reservations), on real
synthesised walks that cross."""

from __future__ import annotations

import itertools

import msgspec
import numpy as np
import pytest

from proto.common import Header
from proto.motion import PairRequest, SynthesizeRequest
from proto.motion_data import Motion, Segment
from proto.scene import Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.giveway import give_way, sidestep
from services.motion.handlers import CONTRACT
from wana.arrays import from_wire, to_wire
from wana.bus.service import call_in_process
from wana.domain.routes import Reservations

EMPTY = Scene(room=Room(room_type="office", width=8, depth=8, height=3), objects=[])


def _walk(name: str, start: tuple[float, float, float], to: tuple[float, float]) -> Motion:
    """A walk from ``start`` to ``to`` (its route given, as the orchestrator gives entrances theirs)."""
    req = SynthesizeRequest(
        header=Header(),
        character=CharacterNode(name=name, actions=[ActionNode(verb="walk", action="walk", destination="x")]),
        scene=EMPTY,
        start=start,
        routes=[[start[:2], to]],
    )
    reply = call_in_process(CONTRACT, req)
    assert reply.status == "ok"
    return reply.motion


def _on_one_line(motions: dict[str, Motion], hold: int = 90) -> dict[str, Motion]:
    """Both motions from frame 0, each holding its last pose to a common length (+ ``hold`` frames)."""
    frames = max(m.root_position.shape[0] for m in motions.values()) + hold
    out = {}
    for name, m in motions.items():
        root, rot = from_wire(m.root_position), from_wire(m.rotations)
        tail = frames - len(root)
        out[name] = msgspec.structs.replace(
            m,
            root_position=to_wire(np.concatenate([root, np.repeat(root[-1:], tail, 0)]).astype(np.float32)),
            rotations=to_wire(np.concatenate([rot, np.repeat(rot[-1:], tail, 0)]).astype(np.float32)),
            foot_contact=to_wire(np.ones((frames, 2), np.uint8)),
            segments=[
                *m.segments,
                Segment(index=len(m.segments), action="hold", start_frame=len(root), end_frame=frames),
            ],
        )
    return out


def _closest(motions: dict[str, Motion]) -> float:
    a, b = (from_wire(m.root_position)[:, [0, 2]] for m in motions.values())
    return float(np.linalg.norm(a - b, axis=1).min())


@pytest.fixture(scope="module")
def crossing() -> dict[str, Motion]:
    """Tom walks east and Eve north through the same point at the same time."""
    tom = _walk("Tom", (-2.5, 0.0, np.pi / 2), (2.5, 0.0))
    eve = _walk("Eve", (0.0, -2.5, 0.0), (0.0, 2.5))
    return _on_one_line({"Tom": tom, "Eve": eve})


def test_the_reservation_table_finds_the_first_frame_two_bodies_meet():
    table = Reservations(clearance=0.5)
    t = np.arange(20, dtype=float)
    table.reserve("Tom", np.stack([t * 0.1 - 1.0, np.zeros(20)], axis=1))  # along x through the origin
    eve = np.stack([np.zeros(20), t * 0.1 - 1.0], axis=1)  # along z, the same frames
    hit = table.first_conflict(eve, range(20), exclude={"Eve"})
    assert hit is not None and hit[1] == "Tom"
    assert 5 <= hit[0] <= 8  # where the two are first less than 0.5 m apart
    eve_late = np.vstack([np.repeat(eve[:1], 15, axis=0), eve])[:20]  # Eve waits 15 frames
    assert table.first_conflict(eve_late, range(20), exclude={"Eve"}) is None
    off = eve.copy()
    off[:] = np.nan  # off stage: nothing to meet
    assert table.first_conflict(off, range(20)) is None


def test_two_walkers_crossing_pass_each_other_without_touching(crossing):
    assert _closest(crossing) < 0.3  # alone, each walks through the other
    after, notes = give_way(crossing)
    assert _closest(after) >= Reservations().clearance - 0.05
    assert len(notes) >= 1 and "waits" in notes[0]
    lengths = {m.root_position.shape[0] for m in after.values()}
    assert lengths == {crossing["Tom"].root_position.shape[0]}  # the wait came out of the final hold


def test_the_waiting_walker_still_arrives_where_it_was_going(crossing):
    after, _ = give_way(crossing)
    for name, m in after.items():
        end = from_wire(m.root_position)[-1]
        was = from_wire(crossing[name].root_position)[-1]
        assert np.allclose(end, was, atol=1e-5)
        walk = next(s for s in m.segments if s.action == "walk")
        assert walk.start_frame == 0 and all(
            a.end_frame <= b.start_frame for a, b in itertools.pairwise(m.segments)
        )


def test_a_walker_blocked_by_someone_standing_still_does_not_wait_forever():
    tom = _walk("Tom", (-2.5, 0.0, np.pi / 2), (2.5, 0.0))
    eve = _walk("Eve", (0.0, 0.0, 0.0), (0.0, 0.0))  # stays where Tom passes
    motions = _on_one_line({"Tom": tom, "Eve": eve})
    after, notes = give_way(motions)
    assert notes == []
    assert after["Tom"] == motions["Tom"]


def test_the_pair_request_gives_way_by_default(crossing):
    reply = call_in_process(CONTRACT, PairRequest(header=Header(), motions=crossing))
    assert reply.status == "ok"
    assert _closest(reply.motions) >= Reservations().clearance - 0.05


@pytest.fixture(scope="module")
def head_on() -> dict[str, Motion]:
    """Tom walks east and Eve west along the same line at the same time: waiting helps neither."""
    tom = _walk("Tom", (-2.5, 0.0, np.pi / 2), (2.5, 0.0))
    eve = _walk("Eve", (2.5, 0.0, -np.pi / 2), (-2.5, 0.0))
    return _on_one_line({"Tom": tom, "Eve": eve})


def test_two_walking_head_on_step_aside_and_pass_where_the_room_is_known(head_on):
    assert _closest(head_on) < 0.3
    kept, _ = give_way(head_on)  # without the scene nobody may step aside
    assert _closest(kept) < 0.3
    after, notes = give_way(head_on, EMPTY)
    assert _closest(after) >= Reservations().clearance - 0.05
    assert any("steps aside" in n for n in notes)
    for name, m in after.items():  # the walk keeps its timing, its start and its end
        was = from_wire(head_on[name].root_position)
        now = from_wire(m.root_position)
        assert now.shape == was.shape
        assert np.allclose(now[0], was[0]) and np.allclose(now[-1], was[-1])


def test_a_walker_steps_round_someone_standing_still_on_its_way_where_the_room_is_known():
    tom = _walk("Tom", (-2.5, 0.0, np.pi / 2), (2.5, 0.0))
    eve = _walk("Eve", (0.0, 0.0, 0.0), (0.0, 0.0))
    motions = _on_one_line({"Tom": tom, "Eve": eve})
    after, notes = give_way(motions, EMPTY)
    assert notes and "steps round" in notes[0]
    assert _closest(after) >= Reservations().clearance - 0.05


def test_a_sidestep_does_not_bend_into_the_furniture():
    seg = Segment(index=0, action="walk", start_frame=0, end_frame=100)
    t = np.linspace(-2.0, 2.0, 100)
    mine = np.stack([t, np.zeros(100)], axis=1)
    theirs = mine[::-1].copy()
    walled = lambda p: np.asarray(p)[:, 1] < 0.05  # noqa: E731 - nothing fits on the +z side
    offset = sidestep(mine, seg, theirs, 0.6, walled)
    assert offset is not None and offset[:, 1].max() <= 1e-9 and offset[:, 1].min() < -0.3
    assert np.allclose(offset[0], 0) and np.allclose(offset[-1], 0)
    corridor = lambda p: np.abs(np.asarray(p)[:, 1]) < 0.05  # noqa: E731 - a corridor one body wide
    assert sidestep(mine, seg, theirs, 0.6, corridor) is None


def test_one_setting_off_beside_another_waits_behind_it_rather_than_walking_through():
    tom = _walk("Tom", (0.0, 0.0, np.pi / 2), (3.0, 0.0))
    eve = _walk("Eve", (-0.4, 0.0, np.pi / 2), (2.6, 0.0))  # right behind him, walking the same way
    motions = _on_one_line({"Tom": tom, "Eve": eve})
    after, notes = give_way(motions)
    assert notes and "waits" in notes[0]
    a, b = (from_wire(after[n].root_position)[:, [0, 2]] for n in ("Tom", "Eve"))
    moving = np.linalg.norm(np.diff(b, axis=0), axis=1) > 1e-3
    assert float(np.linalg.norm(a - b, axis=1)[1:][moving].min()) >= 0.4


def test_one_getting_up_from_beside_someone_seated_walks_off_without_stepping_round_them():
    tom = _walk("Tom", (0.45, 0.0, np.pi / 2), (3.0, 0.0))  # sets off from beside Eve, away from her
    eve = _walk("Eve", (0.0, 0.0, 0.0), (0.0, 0.0))  # stays where she is (seated)
    motions = _on_one_line({"Tom": tom, "Eve": eve})
    after, notes = give_way(motions, EMPTY)
    assert notes == []
    assert after["Tom"] == motions["Tom"]
