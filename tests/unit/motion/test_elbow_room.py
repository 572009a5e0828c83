"""Acting next to furniture: a tool swung or a gesture made beside a cabinet steps clear of it first, and a prop
on top of a tall cabinet is taken with a standing reach, not a bend down into it (issue 14, part 4)."""

from __future__ import annotations

import numpy as np

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.elbow_room import arm_hits, arm_path, obstacles, placed_path, roomy_spot
from services.motion.ik import global_transforms
from services.motion.planning import plan_actions
from services.motion.synthesis import synthesise
from wana.arrays import from_wire
from wana.domain.skeleton import JOINT_INDEX

CABINET = PlacedObject(id="filing_cabinet", category="filing_cabinet", position=(0.0, 0.0, 0.0), yaw=0.0)
ARM = [JOINT_INDEX[s + j] for s in ("Left", "Right") for j in ("ForeArm", "Hand", "HandMiddle1")]


def _room(*objects: PlacedObject) -> Scene:
    return Scene(room=Room(room_type="office", width=6, depth=6, height=3), objects=[CABINET, *objects])


def _poses(plan):
    motion, pieces, _ = synthesise(plan)
    pos, _ = global_transforms(
        from_wire(motion.rotations).astype(np.float64), from_wire(motion.root_position).astype(np.float64)
    )
    return pos, pieces


def test_the_arm_path_of_a_reaching_side_is_its_rest_pose_only():
    both = arm_path("sweep")
    left_reaches = arm_path("sweep", frozenset({"Left"}))
    assert len(left_reaches) < len(both)
    assert np.ptp(both[:, 2]) > 0.2  # the sweep swings the hands forward and back


def test_a_sweep_beside_a_filing_cabinet_steps_clear_before_the_broom_swings():
    broom = PlacedObject(id="broom", category="broom", position=(0.5, 0.0, 0.1), yaw=0.0)
    scene = _room(broom)
    start = (0.5, 0.0, 0.0)  # facing +z, the right arm over the cabinet's side
    fp = obstacles(scene, {"broom"})
    assert arm_hits(placed_path(arm_path("sweep"), np.array(start[:2]), start[2]), fp) > 0
    assert (
        roomy_spot(scene, "sweep", np.array(start[:2]), start[2], ignore={"broom"}, body_radius=0.25)
        is not None
    )
    ch = CharacterNode(name="Eve", actions=[ActionNode(verb="sweep", action="sweep", target="floor")])
    plan = plan_actions(ch, scene, start, holding="broom")
    assert [s.action for s in plan.segments] == ["walk", "sweep"]
    pos, pieces = _poses(plan)
    f0 = len(pieces[0].root)
    sweeping = pos[f0:, ARM].reshape(-1, 3)
    assert arm_hits(sweeping, obstacles(scene, {"broom"})) == 0


def test_papers_on_top_of_a_filing_cabinet_are_taken_with_a_standing_reach():
    top = float(obstacles(_room(), ()).outer.y_max.max())
    papers = PlacedObject(
        id="paper", category="paper", position=(0.0, top, 0.1), yaw=0.0, support="filing_cabinet"
    )
    scene = _room(papers)
    ch = CharacterNode(name="Eve", actions=[ActionNode(verb="take", action="pick_up", target="paper")])
    plan = plan_actions(ch, scene, (0.0, 1.5, np.pi))
    take = [s for s in plan.segments if s.action == "pick_up"]
    assert len(take) == 1 and take[0].upright  # the pick-up's arm, the trunk upright
    assert take[0].prop == "paper" and take[0].prop_span == "grasp"
    pos, pieces = _poses(plan)
    f0 = sum(len(p.root) for p in pieces[: take[0].index])
    frames = pos[f0 : f0 + len(pieces[take[0].index].root)]
    up = frames[:, JOINT_INDEX["Neck"]] - frames[:, JOINT_INDEX["Hips"]]
    assert np.degrees(np.arccos(np.clip(up[:, 1] / np.linalg.norm(up, axis=1), -1, 1))).max() <= 30.0
    head = frames[:, JOINT_INDEX["Head"]]
    assert arm_hits(head, obstacles(scene, {"paper"})) == 0  # the head stays out of the cabinet
    hand = frames[:, JOINT_INDEX[take[0].prop_joint]]
    assert np.linalg.norm(hand - np.asarray(take[0].targets[0][1]), axis=1).min() < 0.05


def test_papers_on_a_filing_cabinet_are_taken_from_its_front_not_beside_its_drawers():
    top = float(obstacles(_room(), ()).outer.y_max.max())
    papers = PlacedObject(
        id="paper", category="paper", position=(0.0, top, 0.0), yaw=0.0, support="filing_cabinet"
    )
    ch = CharacterNode(name="Eve", actions=[ActionNode(verb="take", action="pick_up", target="paper")])
    plan = plan_actions(ch, _room(papers), (2.0, 0.0, -np.pi / 2))  # coming from its side
    stop = np.asarray([s for s in plan.segments if s.kind == "locomotion"][-1].waypoints[-1])
    assert stop[1] > 0.3 and abs(stop[0]) < 0.3, stop  # in front of the cabinet (it faces +z)
