"""A missed contact brings its object toward the joint: reaching layouts, verified by re-synthesis."""

from __future__ import annotations

import msgspec
import numpy as np
import pytest

from proto.motion_data import Motion, Segment
from proto.optimizer import ContactPair, Interaction, OptimiseSettings
from proto.scene import PlacedObject, Room, Scene
from services.optimizer.costs import SceneGeometry
from services.optimizer.reaching import reaching_layouts
from services.optimizer.scoring import InteractionScorer
from services.optimizer.verify import optimise_and_verify
from wana.arrays import from_wire, to_wire
from wana.domain.skeleton import JOINT_NAMES, N_JOINTS

ROOM = Room(room_type="office", width=5.0, depth=5.0, height=3.0)
SEAT = (
    "stool",
    np.array([[[-0.2, 0.0, -0.2], [0.2, 0.45, 0.2]]]),
    {"sit": (np.array([0.0, 0.45, 0.0]), "Hips")},
)
PAINTING = ("painting", np.array([[[-0.3, 0.0, -0.02], [0.3, 0.5, 0.02]]]), {"sit": (np.zeros(3), "Hips")})
MISS = np.array([0.3, 0.0, 0.1])  # where the hips sit, relative to the seat's sit point


def _sit_beside(seat_xz: tuple[float, float], miss: np.ndarray = MISS) -> Motion:
    """Walk in from (2, 0), then sit 1 s at the seat's sit point + ``miss`` (a blocked approach)."""
    end = np.array([seat_xz[0], 0.45, seat_xz[1]]) + miss
    walk = np.stack([np.linspace(2.0, end[0], 40), np.full(40, 0.95), np.linspace(0.0, end[2], 40)], axis=1)
    root = np.vstack([walk, np.tile(end, (30, 1))]).astype(np.float32)
    rot = np.zeros((70, N_JOINTS, 4), dtype=np.float32)
    rot[..., 3] = 1.0
    return Motion(
        character="Eve",
        joint_names=list(JOINT_NAMES),
        root_position=to_wire(root),
        rotations=to_wire(rot),
        segments=[
            Segment(index=0, action="walk", start_frame=0, end_frame=40),
            Segment(index=1, action="sit", start_frame=40, end_frame=70),
        ],
    )


def _stool_scene(*extra: PlacedObject) -> Scene:
    return Scene(room=ROOM, objects=[PlacedObject(id="stool", category="seat_block"), *extra])


INTER = Interaction(
    character="Eve", action="sit", targets=["stool"], contacts=[ContactPair(object_id="stool", point="sit")]
)


def _report(scene: Scene, motion: Motion, geom: SceneGeometry):
    scorer = InteractionScorer(scene, INTER, frame_stride=1, geometry=geom)
    return scorer.score_scenes([scene], [motion]).report(0, scorer.pairs)


def test_reaching_moves_the_missed_object_toward_its_joint_in_steps_of_three_sigma_up_to_the_miss():
    geom = SceneGeometry.from_arrays([SEAT])
    scene, motion = _stool_scene(), _sit_beside((0.0, 0.0))
    report = _report(scene, motion, geom)
    assert report.contact_cost == pytest.approx(np.linalg.norm(MISS), abs=1e-3)
    layouts = reaching_layouts(scene, INTER, motion, report, geom, sigma=0.02)
    moves = np.array([[s.objects[0].position[0], s.objects[0].position[2]] for s in layouts])
    unit = MISS[[0, 2]] / np.linalg.norm(MISS[[0, 2]])
    np.testing.assert_allclose(moves / np.linalg.norm(moves, axis=1)[:, None], np.tile(unit, (len(moves), 1)))
    np.testing.assert_allclose(
        np.linalg.norm(moves, axis=1), [0.06, 0.12, 0.24, np.linalg.norm(MISS)], atol=1e-4
    )
    seated = _sit_beside((0.0, 0.0), np.zeros(3))
    assert reaching_layouts(scene, INTER, seated, _report(scene, seated, geom), geom) == []  # contact met


def test_reaching_keeps_wall_mounted_objects_and_the_room_and_what_the_interaction_forbids():
    geom = SceneGeometry.from_arrays([PAINTING])
    wall = Scene(room=ROOM, objects=[PlacedObject(id="painting", category="painting")])
    inter = msgspec.structs.replace(
        INTER, targets=["painting"], contacts=[ContactPair(object_id="painting", point="sit")]
    )
    motion = _sit_beside((0.0, -0.45))
    scorer = InteractionScorer(wall, inter, frame_stride=1, geometry=geom)
    report = scorer.score_scenes([wall], [motion]).report(0, scorer.pairs)
    assert report.contact_cost > 0.05 and reaching_layouts(wall, inter, motion, report, geom) == []
    geom = SceneGeometry.from_arrays([SEAT])
    at_wall = Scene(
        room=ROOM, objects=[PlacedObject(id="stool", category="seat_block", position=(2.49, 0.0, 0.0))]
    )
    # The hips beside the stool, outside the room: it only goes as far as the wall (a category the
    # catalog lacks counts as a point).
    motion = _sit_beside((2.49, 0.0))
    layouts = reaching_layouts(at_wall, INTER, motion, _report(at_wall, motion, geom), geom)
    assert layouts and all(2.49 < s.objects[0].position[0] <= ROOM.width / 2 + 1e-3 for s in layouts)
    fixed = msgspec.structs.replace(INTER, movable=["other"])
    scene, motion = _stool_scene(), _sit_beside((0.0, 0.0))
    assert reaching_layouts(scene, fixed, motion, _report(scene, motion, geom), geom) == []


def test_a_contact_missed_because_the_approach_is_blocked_is_reached_by_a_small_verified_move():
    # The piano-bench case: re-synthesis sits beside the seat (where the walk could get to) until
    # the seat has moved at least 4 cm toward that spot, which frees its approach. The anchored
    # search cannot see that (it carries the miss along with the seat); reaching can.
    geom = SceneGeometry.from_arrays([SEAT])
    scene = _stool_scene()
    motion = _sit_beside((0.0, 0.0))
    toward = MISS[[0, 2]] / np.linalg.norm(MISS[[0, 2]])

    def blocked_unless_moved(s: Scene) -> Motion:
        x, _, z = s.objects[0].position
        return _sit_beside((x, z), MISS if float(np.dot([x, z], toward)) < 0.04 else np.zeros(3))

    res = optimise_and_verify(
        scene,
        INTER,
        motion,
        settings=OptimiseSettings(steps=30, seed=1),
        verifier=blocked_unless_moved,
        geometry=geom,
    )
    assert res.search.before.contact_cost > 0.3
    assert res.made == "motion_service" and res.after.contact_cost <= 0.05
    moved = np.hypot(res.scene.objects[0].position[0], res.scene.objects[0].position[2])
    assert 0.04 <= moved <= 0.07  # the smallest move that works: one 3σ step
    x, _, z = res.scene.objects[0].position
    np.testing.assert_allclose(from_wire(res.motion.root_position)[-1], [x, 0.45, z], atol=1e-5)
    again = optimise_and_verify(
        scene,
        INTER,
        motion,
        settings=OptimiseSettings(steps=30, seed=1),
        verifier=blocked_unless_moved,
        geometry=geom,
    )
    assert again.scene == res.scene  # deterministic


@pytest.mark.parametrize(
    "case",
    ["piano_bench_0.35_m_from_the_keys", "laptop_with_the_chair_0.25_m_back"],
)
def test_eval_contact_cases_come_within_reach_through_the_motion_service(case):
    from proto.ssg import ActionNode, CharacterNode
    from services.optimizer.resynthesis import motion_service_fn, planned_contacts

    pi = float(np.pi)

    def obj(id_: str, cat: str, x: float, z: float, yaw: float = 0.0, y: float = 0.0, support: str = ""):
        return PlacedObject(id=id_, category=cat, position=(x, y, z), yaw=yaw, support=support)

    if case.startswith("piano"):  # eval/optimizer.py play_piano(0.35, 0.0)
        objs = [obj("piano", "piano", 0.0, -2.15), obj("bench", "piano_bench", 0.0, -2.15 + 0.31 + 0.35, pi)]
        steps, start, action = [("sit", "bench"), ("play_piano", "piano")], (1.5, 1.5, pi), "play_piano"
    else:  # eval/optimizer.py type_on_laptop(0.25, -0.2)
        objs = [
            obj("desk", "desk", 0.0, -0.9),
            obj("chair", "office_chair", 0.0, -0.9 + 0.78 + 0.25, pi),
            obj("laptop", "laptop", -0.2, -1.0, y=0.75, support="desk"),
        ]
        steps, start, action = [("sit", "chair"), ("type", "laptop")], (1.8, 1.8, pi), "type"
    scene = Scene(room=ROOM, objects=objs)
    character = CharacterNode(name="Eve", actions=[ActionNode(verb=a, action=a, target=t) for a, t in steps])
    targets = [t for _, t in steps]
    contacts = [p for p in planned_contacts(character, scene) if p.object_id in targets]
    inter = Interaction(character="Eve", action=action, targets=targets, contacts=contacts)
    synth = motion_service_fn(character, start)
    motion = synth(scene)
    res = optimise_and_verify(
        scene, inter, motion, settings=OptimiseSettings(seed=0, steps=100), verifier=synth, candidates=4
    )
    before = res.search.before
    # With the motion service as committed, both end within 5 cm (eval/optimizer.py); the bound below
    # also holds while the motion service changes how it approaches and places the hands. Before
    # reaching, both came back unchanged (C_T 49 cm and 8 cm).
    if before.contact_cost > 0.05:
        bound = max(0.05, 0.6 * before.contact_cost)
        assert res.after.contact_cost <= bound, (case, before.contact_distances, res.after.contact_distances)
        assert res.made == "motion_service" and res.after.cost < before.cost
    assert res.after.contact_cost <= max(0.05, before.contact_cost)
    assert res.after.locomotion_collided_boxes <= before.locomotion_collided_boxes
