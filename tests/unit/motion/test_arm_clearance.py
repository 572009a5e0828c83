"""A free arm turns out of the furniture beside it, smoothly, and a hand at its contact point stays (issue 14.4)."""

from __future__ import annotations

import numpy as np

from proto.scene import PlacedObject, Room, Scene
from services.motion.arm_clearance import _spheres, clear_arms, furniture, seated_on
from services.motion.ik import global_transforms
from services.motion.synthesis import SegmentState, rest_frame
from wana.domain import quat
from wana.domain.skeleton import JOINT_INDEX, REST_OFFSETS
from wana.fidelity.body_checks import visible_depth
from wana.fidelity.solids import depth_inside

FRAMES = 40
PASSING = slice(15, 25)  # the frames the left hand is beside the cabinet


def _scene() -> Scene:
    # the standing left hand hangs at x = 0.233: the cabinet's side (half width 0.235) is 3 cm past it
    cabinet = PlacedObject(id="filing_cabinet", category="filing_cabinet", position=(0.438, 0.0, 0.0))
    return Scene(room=Room(room_type="office", width=6, depth=6, height=3), objects=[cabinet])


def _passing_pose() -> tuple[np.ndarray, np.ndarray]:
    rot, root = rest_frame(SegmentState())
    roots = np.repeat(root[None], FRAMES, 0)
    roots[:, 0] = -0.12  # clear of the cabinet ...
    roots[PASSING, 0] = 0.0  # ... but for a few frames, the hand in its side
    return np.repeat(rot[None], FRAMES, 0), roots


def _excess(rot: np.ndarray, root: np.ndarray, scene: Scene) -> np.ndarray:
    """(T,) how far the left arm's worst sphere is past what looks inside the cabinet, metres."""
    pos, _ = global_transforms(rot, root, REST_OFFSETS)
    centres, radii = _spheres(pos, "Left")
    placed = scene.objects[0]
    depth = depth_inside(placed, centres.reshape(-1, 3), np.tile(radii, FRAMES)).reshape(FRAMES, -1)
    return (depth - visible_depth(radii)).max(axis=1)


def test_the_hanging_hand_of_a_character_beside_a_cabinet_turns_out_of_it():
    scene = _scene()
    rot, root = _passing_pose()
    assert (_excess(rot, root, scene)[PASSING] > 0.01).all()  # the fault: the hand 3 cm inside the side
    cleared = clear_arms(rot, root, REST_OFFSETS, furniture(scene))
    assert (_excess(cleared, root, scene) <= 0.0).all()


def test_the_turn_eases_in_and_out_and_touches_only_the_arm_that_was_inside():
    scene = _scene()
    rot, root = _passing_pose()
    cleared = clear_arms(rot, root, REST_OFFSETS, furniture(scene))
    left, right = JOINT_INDEX["LeftArm"], JOINT_INDEX["RightArm"]
    assert np.allclose(cleared[:, right], rot[:, right])
    angle = 2 * np.arccos(np.clip(np.abs(np.sum(cleared[:, left] * rot[:, left], axis=1)), 0, 1))
    assert angle[PASSING].min() > np.radians(1.0)
    assert angle[:5].max() < 1e-6  # far from the cabinet: as played
    step = 2 * np.arccos(np.clip(np.abs(np.sum(cleared[1:, left] * cleared[:-1, left], axis=1)), 0, 1))
    assert step.max() < np.radians(1.5)  # no pop into the turn


def test_a_hand_at_its_contact_point_is_left_where_it_is():
    scene = _scene()
    rot, root = _passing_pose()
    keep = {"Left": np.ones(FRAMES, bool)}
    cleared = clear_arms(rot, root, REST_OFFSETS, furniture(scene), keep)
    assert np.allclose(quat.canonical(cleared), quat.canonical(rot))


def test_the_object_sat_on_and_the_one_a_hand_works_at_are_not_in_the_way():
    scene = _scene()
    rot, root = _passing_pose()
    worked = clear_arms(
        rot, root, REST_OFFSETS, furniture(scene), worked={"Left": frozenset({"filing_cabinet"})}
    )
    assert np.allclose(worked, rot)  # the hammering hand at the bench under the nail
    low = root.copy()
    low[:, 0] = 0.438  # hips over the cabinet and low: sitting on it
    low[:, 1] = 0.5
    assert seated_on(low, furniture(scene)).all()
    assert not seated_on(root, furniture(scene)).any()  # standing beside it


def test_a_piece_shorter_than_the_easing_is_cleared_too():
    scene = _scene()
    rot, root = _passing_pose()
    short = clear_arms(rot[PASSING][:3], root[PASSING][:3], REST_OFFSETS, furniture(scene))
    assert short.shape == (3, *rot.shape[1:])


def test_an_arm_through_a_thin_panel_leaves_it_on_the_shoulders_side():
    # an office chair turned side on: its back (local z -0.30..-0.24) across the hanging hand, whose centre is
    # just past the back's middle, so that the nearer face is the far one; the hand comes out toward the body
    chair = PlacedObject(id="chair", category="office_chair", position=(0.493, 0.0, 0.0), yaw=np.pi / 2)
    scene = Scene(room=Room(room_type="office", width=6, depth=6, height=3), objects=[chair])
    rot, root = _passing_pose()
    cleared = clear_arms(rot, root, REST_OFFSETS, furniture(scene))
    pos, _ = global_transforms(cleared, root, REST_OFFSETS)
    hand = pos[PASSING, JOINT_INDEX["LeftHand"]]
    assert (hand[:, 0] < 0.493 - 0.30).all()  # turned in, not pushed on out through the back
