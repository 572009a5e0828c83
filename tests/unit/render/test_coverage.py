"""The director's scorer measures a candidate camera as the in_view check measures the video (issue 16).

Seen on the sheets: "Anna is 47% hidden behind the table" while she sat at it; the scorer counted her
legs under the table, so every candidate failed alike and the first one, level with the table top, won.
"""

from __future__ import annotations

import numpy as np
import pytest

from proto.scene import Room, Scene
from services.render.camera import CameraPose
from services.render.coverage import Coverage
from services.render.demo import walk_motion
from services.render.sightlines import Furniture
from services.render.staging import CameraTrack, Staging
from services.render.visibility import VISIBLE_SHARE, body_view
from wana.domain.skeleton import JOINT_INDEX

ROOM = Room(room_type="meeting_room", width=6.0, depth=5.0, height=2.8)
TABLE = np.array([[[-0.8, 0.0, 0.35], [0.8, 0.75, 1.05]]])  # between the sitter (z = 0) and the cameras (+z)


@pytest.fixture(scope="module")
def seated() -> dict[str, np.ndarray]:
    """Anna standing still, lowered so her hips are at seat height (0.55 m): a sitter's trunk, head and
    arms where a seated person's are, her legs under the table."""
    stage = Staging.build(Scene(room=ROOM, objects=[]), [walk_motion("Anna", (0.0, 0.0), (0.0, 0.0), 4)])
    j = stage.rigs["Anna"].joint_positions[:1].copy()
    j[..., 1] -= j[0, JOINT_INDEX["Hips"], 1] - 0.55
    return {"Anna": j}


def cover(joints: dict[str, np.ndarray]) -> Coverage:
    return Coverage(joints=joints, furniture=Furniture.from_boxes([TABLE], ["table"]), room=ROOM, radii={})


def camera(eye_y: float) -> CameraPose:
    return CameraPose(
        eye=np.array([0.0, eye_y, 2.4]), target=np.array([0.0, 0.8, 0.0]), up=np.array([0.0, 1.0, 0.0])
    )


def test_a_sitter_seen_over_the_table_counts_as_shown_though_the_table_hides_her_legs(seated) -> None:
    high = camera(2.2)
    assert cover(seated).shown_each([high], [0], ["Anna"]).tolist() == [[True]]
    c = cover(seated)
    track = CameraTrack(
        eye=high.eye[None], target=high.target[None], up=high.up[None], fov_deg=np.array([high.fov_deg])
    )
    whole = body_view("Anna", np.array([0]), seated, track, c.furniture, ROOM, 640, 480).visible
    assert whole.mean() < VISIBLE_SHARE  # the whole body's points: her legs under the table fail her


def test_a_camera_level_with_the_table_top_does_not_show_the_sitter_and_a_higher_one_wins(seated) -> None:
    low, high = camera(0.7), camera(2.2)
    c = cover(seated)
    assert c.shown_each([low], [0], ["Anna"]).tolist() == [[False]]  # the table hides hands and chest
    assert c.shown([high], [0], ["Anna"]) > c.shown([low], [0], ["Anna"])
