"""The office story: Eve sits at the desk and her hands reach the laptop's keys (optimizer x motion)."""

from __future__ import annotations

import numpy as np
import pytest

from services.optimizer.body import motion_joint_positions
from services.optimizer.costs import LayoutBatch, SceneGeometry, contact_points_world
from services.orchestrator.backend import InProcessBackend
from services.orchestrator.session import Orchestrator
from wana.domain.skeleton import JOINT_INDEX

pytestmark = [pytest.mark.integration, pytest.mark.slow]

OFFICE = (
    "In the office there is a desk near a window$. A laptop is on the desk$. A chair is in front of the desk$.\n"
    "Eve walks to the chair. Eve sits on the chair. Eve types on the laptop.\n"
)
HANDS = ("RightHandMiddle1", "LeftHandMiddle1")


@pytest.fixture(scope="module")
def office(tmp_path_factory):
    orch = Orchestrator(tmp_path_factory.mktemp("db") / "s.db", InProcessBackend())
    try:
        yield orch.create(OFFICE).compute()
    finally:
        orch.close()


def _world_point(scene, object_id: str, point: str, joint: str) -> np.ndarray:
    geom = SceneGeometry.from_scene(scene)
    idx = np.array([geom.contact_index(object_id, point, joint)])
    return contact_points_world(geom, LayoutBatch.from_scenes([scene]), idx)[0, 0]


def _typing_frames(result) -> tuple[np.ndarray, range]:
    motion = result.motions["Eve"]
    typing = [s for s in motion.segments if s.action == "type"]
    assert typing, [s.action for s in motion.segments]
    return motion_joint_positions(motion), range(typing[-1].start_frame, typing[-1].end_frame)


def test_eves_hands_are_on_the_laptop_keys_while_she_types(office):
    positions, frames = _typing_frames(office)
    for joint in HANDS:
        keys = _world_point(office.scene, "laptop", "type", joint)
        miss = np.linalg.norm(positions[list(frames), JOINT_INDEX[joint]] - keys, axis=-1)
        assert np.median(miss) < 0.05, (joint, float(np.median(miss)))


def test_eve_types_seated_on_the_chair(office):
    positions, frames = _typing_frames(office)
    hips = positions[list(frames), JOINT_INDEX["Hips"]]
    seat = _world_point(office.scene, "chair", "sit", "Hips")
    assert np.all(hips[:, 1] < 0.7), "the hips stay at seat height while typing"
    # On the seat (the motion service may slide the hips forward on it, at most 15 cm).
    assert np.all(np.linalg.norm((hips - seat)[:, [0, 2]], axis=1) < 0.16)


def test_the_laptop_stays_on_the_desk_top(office):
    from wana.assets.catalog import world_bounds

    by_id = {o.id: o for o in office.scene.objects}
    lo, hi = world_bounds(by_id["laptop"])
    dlo, dhi = world_bounds(by_id["desk"])
    for axis in (0, 2):
        assert dlo[axis] - 0.021 <= lo[axis] and hi[axis] <= dhi[axis] + 0.021, axis
