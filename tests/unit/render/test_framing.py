"""The camera keeps its character in sight: sight lines against the scene's boxes, and cameras that move
around an occluder placed between the commanded camera and the character."""

from __future__ import annotations

import msgspec
import numpy as np
import pytest

from proto.scene import PlacedObject
from services.render.camera import TRANSITION_FRAMES, CameraKey, camera_at, clear_overview, overview_pose
from services.render.demo import demo_scene, walk_motion
from services.render.framing import (
    ADJUSTMENTS,
    Occluders,
    adjust_eye,
    near_fan,
    segments_hit_boxes,
    sight_points,
)
from services.render.renderer import FrameRenderer
from services.render.skinning import Rig

UNIT_BOX = np.array([[[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]]])
W, H = 320, 240
FRAME = 40


def test_a_segment_through_a_box_hits_it_and_one_beside_or_short_of_it_does_not():
    starts = np.array(
        [[-1.0, 0.5, 0.5], [-1.0, 1.5, 0.5], [-1.0, 0.5, 0.5], [0.5, 0.5, -1.0], [0.5, 2.0, 0.5]]
    )
    ends = np.array([[2.0, 0.5, 0.5], [2.0, 1.5, 0.5], [-0.1, 0.5, 0.5], [0.5, 0.5, 2.0], [0.5, 0.5, 0.5]])
    hit = segments_hit_boxes(starts, ends, UNIT_BOX)[:, 0]
    assert hit.tolist() == [True, False, False, True, True]


def test_an_eye_sees_a_point_unless_a_box_stands_between_them():
    occ = Occluders([UNIT_BOX[0][None]])
    eye = np.array([-2.0, 0.5, 0.5])
    assert occ.blocked_share(eye, np.array([[3.0, 0.5, 0.5]])) == 1.0
    assert occ.blocked_share(eye, np.array([[-1.0, 0.5, 0.5]])) == 0.0
    assert occ.blocked_share(eye, np.array([[3.0, 0.5, 0.5], [3.0, 2.5, 0.5]])) == 0.5


@pytest.fixture(scope="module")
def setting():
    """Eve walking through the demo office, and the same office with a wardrobe put between her and
    the commanded 'left' camera at FRAME."""
    scene = demo_scene()
    motion = walk_motion("Eve", (-1.5, 1.0), (0.5, 0.2), 80)
    track = Rig.from_motion(motion).track()
    keys = [CameraKey(frame=0, mode="left", character="Eve")]
    commanded = camera_at(FRAME, keys, {"Eve": track}, scene.room)
    hips, _, _ = track.at(FRAME)
    between = hips + (commanded.eye - hips) * 0.45
    line = commanded.eye - hips
    yaw = float(
        np.arctan2(line[0], line[2])
    )  # the wardrobe's front towards the camera: broad across the line
    wardrobe = PlacedObject(
        id="wardrobe", category="wardrobe", position=(float(between[0]), 0.0, float(between[2])), yaw=yaw
    )
    blocked_scene = msgspec.structs.replace(scene, objects=[*scene.objects, wardrobe])
    return scene, blocked_scene, motion, track, keys, commanded


def test_the_commanded_camera_is_blocked_by_the_wardrobe(setting):
    _, blocked_scene, _, track, _, commanded = setting
    hips, _, head = track.at(FRAME)
    occ = Occluders.from_scene(blocked_scene)
    assert occ.blocked_share(commanded.eye, sight_points(hips, head)) == 1.0


def test_a_blocked_camera_moves_until_it_sees_the_character_and_stays_on_the_commanded_side(setting):
    _, blocked_scene, _, track, keys, commanded = setting
    occ = Occluders.from_scene(blocked_scene)
    pose = camera_at(FRAME, keys, {"Eve": track}, blocked_scene.room, occ)
    hips, facing, head = track.at(FRAME)
    assert occ.blocked_share(pose.eye, sight_points(hips, head)) == 0.0
    assert not np.allclose(pose.eye, commanded.eye)
    left = np.array([facing[2], 0.0, -facing[0]])
    assert float((pose.eye - hips) @ left) > 0.5  # still a view of her left side


def test_an_unblocked_camera_keeps_the_commanded_pose(setting):
    scene, _, _, track, keys, commanded = setting
    pose = camera_at(FRAME, keys, {"Eve": track}, scene.room, Occluders.from_scene(scene))
    np.testing.assert_allclose(pose.eye, commanded.eye)


def test_moving_around_an_occluder_is_smooth_and_the_same_in_any_chunk(setting):
    _, blocked_scene, _, track, keys, _ = setting
    occ = Occluders.from_scene(blocked_scene)
    eyes = np.array([camera_at(f, keys, {"Eve": track}, blocked_scene.room, occ).eye for f in range(0, 80)])
    after_cut_in = np.diff(eyes[TRANSITION_FRAMES:], axis=0)  # (the ease from the overview is its own test)
    assert np.linalg.norm(after_cut_in, axis=1).max() < 0.15  # metres per frame: no cut
    fresh = Occluders.from_scene(blocked_scene)  # another worker, its own memo, frames out of order
    for f in (63, 17, 40):
        np.testing.assert_array_equal(
            camera_at(f, keys, {"Eve": track}, blocked_scene.room, fresh).eye, eyes[f]
        )


def test_the_overview_turns_away_from_a_wall_of_cabinets_in_front_of_the_characters(setting):
    scene, _, _, track, _, _ = setting
    base = overview_pose(scene.room)
    hips, _, head = track.at(0)
    # Wardrobes side by side across the line from the overview camera to Eve's start.
    mid = hips + (base.eye - hips) * 0.4
    wall = [
        PlacedObject(
            id=f"w{k}", category="wardrobe", position=(float(mid[0]) + 1.2 * k, 0.0, float(mid[2])), yaw=0.0
        )
        for k in (-1, 0, 1)
    ]
    crowded = msgspec.structs.replace(scene, objects=[*scene.objects, *wall])
    occ = Occluders.from_scene(crowded)
    assert occ.blocked_share(base.eye, sight_points(hips, head)) > 0.0
    pose = clear_overview(crowded.room, {"Eve": track}, occ, until=1)
    assert occ.blocked_share(pose.eye, sight_points(hips, head)) == 0.0


@pytest.mark.slow
def test_the_rendered_frame_shows_the_character_the_wardrobe_hides_from_the_commanded_camera(setting):
    _, blocked_scene, motion, _, _, commanded = setting
    from proto.render import TimedCommand
    from proto.ssg import Command

    cmd = [TimedCommand(frame=0, command=Command(kind="camera", value="left", target="Eve"))]
    with FrameRenderer(blocked_scene, [motion], cmd, width=W, height=H) as r:
        cleared_pose = r.camera(FRAME)
        cleared, hidden = r.render(FRAME), r.render(FRAME, commanded)
    with FrameRenderer(blocked_scene, [], [], n_frames=80, width=W, height=H) as r:
        empty_cleared, empty_hidden = r.render(FRAME, cleared_pose), r.render(FRAME, commanded)

    def character_pixels(a: np.ndarray, b: np.ndarray) -> int:
        return int((np.abs(a.astype(int) - b.astype(int)).max(axis=2) > 25).sum())

    assert character_pixels(hidden, empty_hidden) < 40  # behind the wardrobe (a shadow edge at most)
    assert character_pixels(cleared, empty_cleared) > 300


def test_a_box_close_in_front_of_the_lens_makes_the_camera_move_though_the_character_stays_in_sight():
    hips, head = np.array([0.0, 0.9, 0.0]), np.array([0.0, 1.6, 0.0])
    eye, target = np.array([3.2, 1.6, 0.0]), hips + np.array([0.0, 0.35, 0.0])
    # A cabinet beside the eye, 0.6-1.4 m in front of it, filling the right of the frame: no sight line
    # to the character crosses it.
    cabinet = np.array([[[2.0, 0.0, -1.4], [2.6, 1.7, -0.15]]])
    occ = Occluders([cabinet])
    assert occ.blocked_share(eye, sight_points(hips, head)) == 0.0
    views = [(eye, target, sight_points(hips, head))]
    assert occ.shares(views, ADJUSTMENTS)[0] > 0.0  # the commanded pose counts as cluttered
    chosen = occ.choose(views, ADJUSTMENTS)
    assert chosen != ADJUSTMENTS[0]
    moved = adjust_eye(eye, target, chosen)
    assert occ.blocked(np.broadcast_to(moved, (8, 3)), near_fan(moved, target)).sum() <= 1
    assert occ.blocked_share(moved, sight_points(hips, head)) == 0.0
    # nothing near the lens: the commanded pose stays
    assert Occluders([cabinet + np.array([0.0, 0.0, -3.0])]).choose(views, ADJUSTMENTS) == ADJUSTMENTS[0]


def test_another_character_between_the_camera_and_its_character_moves_the_camera():
    from services.render.framing import person_box

    hips, head = np.array([0.0, 0.9, 0.0]), np.array([0.0, 1.6, 0.0])
    eye, target = np.array([0.0, 1.62, 0.9]), head  # a close-up of the face from the front
    tom = person_box(np.array([0.0, 0.9, 0.45]), np.array([0.0, 1.7, 0.45]))  # hugging her, his back to us
    empty = Occluders([])
    face = sight_points(hips, head)[:1]
    assert empty.shares([(eye, target, face)], ADJUSTMENTS)[0] == 0.0
    views = [(eye, target, face, tom[None])]
    assert empty.shares(views, ADJUSTMENTS)[0] > 0.0
    chosen = empty.choose(views, ADJUSTMENTS)
    assert chosen != ADJUSTMENTS[0]
    assert empty.shares([(eye, target, face, tom[None])], [chosen])[0] == 0.0
