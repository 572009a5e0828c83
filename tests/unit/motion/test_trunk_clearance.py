"""A trunk bent over a table straightens up until the chest and the head are out of it; an upright trunk, and
the object sat on, are left alone (issue 14: 0 heads or torsos inside furniture)."""

from __future__ import annotations

import numpy as np

from proto.scene import PlacedObject, Room, Scene
from services.motion.arm_clearance import furniture
from services.motion.ik import global_transforms, lean_spine
from services.motion.synthesis import SegmentState, rest_frame
from services.motion.trunk_clearance import hands_back, straighten, trunk_spheres
from wana.domain.skeleton import JOINT_INDEX, REST_OFFSETS
from wana.fidelity.body_checks import visible_depth
from wana.fidelity.solids import depth_inside

FRAMES = 40
BOWED = slice(12, 28)  # the frames the trunk bows over the desk


def _desk_in_front(z: float = 0.45) -> Scene:
    desk = PlacedObject(id="desk", category="desk", position=(0.0, 0.0, z))
    return Scene(room=Room(room_type="office", width=6, depth=6, height=3), objects=[desk])


def _bowing() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Hips at a seat's height facing +z, the trunk bowing 80 degrees forward over the middle frames (eased)."""
    rot, root = rest_frame(SegmentState())
    rots = np.repeat(rot[None], FRAMES, 0)
    roots = np.repeat(root[None], FRAMES, 0)
    roots[:, 1] = 0.45
    weight = np.zeros(FRAMES)
    weight[BOWED] = 1.0
    weight = np.convolve(weight, np.ones(5) / 5, mode="same")
    return lean_spine(rots, np.radians(80.0), weight), roots, weight


def _excess(rot: np.ndarray, root: np.ndarray, scene: Scene) -> np.ndarray:
    """(T,) how far the worst chest / head sphere is past what looks inside the desk, metres."""
    pos, grot = global_transforms(rot, root, REST_OFFSETS)
    centres, radii = trunk_spheres(pos, grot)
    depth = depth_inside(scene.objects[0], centres.reshape(-1, 3), np.tile(radii, FRAMES)).reshape(FRAMES, -1)
    return (depth - visible_depth(radii)).max(axis=1)


def test_a_head_bowed_into_the_desk_in_front_comes_up_out_of_it():
    scene = _desk_in_front()
    rot, root, _ = _bowing()
    assert _excess(rot, root, scene)[BOWED].max() > 0.05  # the fault: the head deep in the desk
    cleared, changed = straighten(rot, root, REST_OFFSETS, furniture(scene))
    assert changed
    assert (_excess(cleared, root, scene) <= 0.0).all()
    spine = JOINT_INDEX["Spine1"]
    step = 2 * np.arccos(np.clip(np.abs(np.sum(cleared[1:, spine] * cleared[:-1, spine], axis=1)), 0, 1))
    assert step.max() < np.radians(6.0)  # eased, no pop


def test_an_upright_trunk_and_a_bow_clear_of_furniture_are_left_as_played():
    rot, root, _ = _bowing()
    far, changed = straighten(rot, root, REST_OFFSETS, furniture(_desk_in_front(z=3.0)))
    assert not changed and np.allclose(far, rot)
    upright, root0 = rest_frame(SegmentState())
    rots, roots = np.repeat(upright[None], FRAMES, 0), np.repeat(root0[None], FRAMES, 0)
    roots[:, 1], roots[:, 2] = 0.45, 0.1  # the chest in the desk's edge, the trunk upright ...
    assert (_excess(rots, roots, _desk_in_front()) > 0.0).all()
    same, _ = straighten(
        rots, roots, REST_OFFSETS, furniture(_desk_in_front())
    )  # ... never leant back past it
    assert np.allclose(same, rots)


def test_the_object_sat_on_is_not_in_the_way():
    scene = _desk_in_front()
    rot, root, _ = _bowing()
    root = root.copy()
    root[:, 1] = 0.5  # hips low, over the desk's footprint: sitting on it (the stated contact)
    root[:, 2] = 0.45
    cleared, changed = straighten(rot, root, REST_OFFSETS, furniture(scene))
    assert not changed and np.allclose(cleared, rot)


def test_a_hand_on_its_contact_point_reaches_it_again_after_the_trunk_straightened():
    scene = _desk_in_front()
    rot, root, _ = _bowing()
    pos, _ = global_transforms(rot, root, REST_OFFSETS)
    hand = JOINT_INDEX["RightHand"]
    target = pos[20, hand] + np.array([0.0, 0.0, -0.15])  # on the desk, nearer the body
    cleared, _ = straighten(rot, root, REST_OFFSETS, furniture(scene))
    frames = np.arange(16, 25)
    back = hands_back(cleared, root, {"RightHand": (frames, target)})
    got, _ = global_transforms(back, root, REST_OFFSETS)
    assert np.linalg.norm(got[frames, hand] - target, axis=1).max() < 0.02
