"""The anchored surrogate moves the motion with its anchor; verification keeps only verified wins."""

from __future__ import annotations

import msgspec
import numpy as np

from proto.motion_data import Motion, Segment
from proto.optimizer import ContactPair, Interaction, OptimiseSettings
from proto.scene import PlacedObject, Room, Scene
from services.optimizer.costs import SceneGeometry
from services.optimizer.resynthesis import anchored_motion_fn
from services.optimizer.verify import optimise_and_verify
from wana.arrays import from_wire, to_wire
from wana.domain.skeleton import JOINT_NAMES, N_JOINTS

ROOM = Room(room_type="office", width=5.0, depth=5.0, height=3.0)
SEAT = (
    "stool",
    np.array([[[-0.2, 0.0, -0.2], [0.2, 0.45, 0.2]]]),
    {"sit": (np.array([0.0, 0.45, 0.0]), "Hips")},
)


def _walk_then_sit() -> Motion:
    walk = np.stack([np.linspace(2.0, 0.0, 40), np.full(40, 0.95), np.zeros(40)], axis=1)
    sit = np.tile([0.0, 0.45, 0.0], (30, 1))
    rot = np.zeros((70, N_JOINTS, 4), dtype=np.float32)
    rot[..., 3] = 1.0
    return Motion(
        character="Eve",
        joint_names=list(JOINT_NAMES),
        root_position=to_wire(np.vstack([walk, sit]).astype(np.float32)),
        rotations=to_wire(rot),
        segments=[
            Segment(index=0, action="walk", start_frame=0, end_frame=40),
            Segment(index=1, action="sit", start_frame=40, end_frame=70),
        ],
    )


def test_anchored_motion_follows_the_seat_from_the_action_on_and_ramps_in_over_the_walk():
    geom = SceneGeometry.from_arrays([SEAT])
    scene = Scene(room=ROOM, objects=[PlacedObject(id="stool", category="stool")])
    inter = Interaction(
        character="Eve",
        action="sit",
        targets=["stool"],
        contacts=[ContactPair(object_id="stool", point="sit")],
    )
    motion = _walk_then_sit()
    fn = anchored_motion_fn(scene, motion, inter, geom)
    moved = msgspec.structs.replace(
        scene,
        objects=[
            PlacedObject(id="stool", category="stool", position=(0.3, 0.0, -0.2), scale=(1.0, 1.2, 1.0))
        ],
    )
    r0, r1 = from_wire(motion.root_position), from_wire(fn(moved).root_position)
    np.testing.assert_allclose(
        r1[40:] - r0[40:], np.tile([0.3, 0.09, -0.2], (30, 1)), atol=1e-5
    )  # seat 0.45 -> 0.54
    np.testing.assert_allclose(r1[0], r0[0], atol=1e-6)  # the walk starts where it did
    assert np.all(np.diff(r1[:40, 0] - r0[:40, 0]) >= -1e-6) and np.allclose(r1[:40, 1], r0[:40, 1])
    assert fn(scene) is motion  # nothing moved: the same motion


def test_verification_rejects_a_winner_the_real_synthesis_makes_worse():
    geom = SceneGeometry.from_arrays([SEAT, ("crate", np.array([[[-0.2, 0.0, -0.2], [0.2, 1.6, 0.2]]]), {})])
    scene = Scene(
        room=ROOM,
        objects=[
            PlacedObject(id="stool", category="stool"),
            PlacedObject(id="crate", category="crate", position=(1.0, 0.0, 0.3)),
        ],
    )
    inter = Interaction(
        character="Eve",
        action="sit",
        targets=["stool"],
        movable=["crate"],
        contacts=[ContactPair(object_id="stool", point="sit")],
    )
    motion = _walk_then_sit()
    settings = OptimiseSettings(steps=40, seed=2)

    def stands_in_the_crate(s: Scene) -> Motion:  # a "synthesiser" that walks into wherever the crate is
        crate = next(o for o in s.objects if o.id == "crate")
        root = from_wire(motion.root_position).copy()
        root[:40, 0], root[:40, 2] = crate.position[0], crate.position[2]
        return msgspec.structs.replace(motion, root_position=to_wire(root))

    bad = optimise_and_verify(
        scene, inter, motion, settings=settings, verifier=stands_in_the_crate, geometry=geom
    )
    assert bad.search.after.cost < bad.search.before.cost  # the surrogate found a better layout...
    assert bad.made == "input" and bad.scene == scene and bad.motion is motion  # ...which did not verify
    good = optimise_and_verify(
        scene,
        inter,
        motion,
        settings=settings,
        verifier=anchored_motion_fn(scene, motion, inter, geom),
        geometry=geom,
    )
    assert good.made == "motion_service" and good.after.cost < good.search.before.cost and good.scene != scene
