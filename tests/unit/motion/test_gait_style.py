"""Manner words change the walk: speed and stride, arm swing, trunk and head (services.motion.gait_style)."""

from __future__ import annotations

import numpy as np
import pytest

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.gait_style import GaitStyle, apply_gait_style, gait_style, scale_swing
from services.motion.ik import global_transforms
from services.motion.locomotion import locomote
from services.motion.locomotion_features import to_local
from services.motion.planning import plan_actions
from services.motion.synthesis import synthesise
from wana.arrays import from_wire
from wana.domain import quat
from wana.domain.skeleton import JOINT_INDEX

SCENE = Scene(
    room=Room(room_type="office", width=10, depth=10, height=3),
    objects=[PlacedObject(id="desk", category="desk", position=(0.0, 0.0, 4.0), yaw=0.0)],
)
LINE = np.array([[0.0, -4.0], [0.0, 4.0]])


def _walk(manner: str):
    """A straight 8 m walk at the planner's speed for the manner, styled by the manner."""
    return locomote(LINE, 1.3 * gait_style(manner).speed, 0.0, manner=manner)


def _stride(loco) -> float:
    """Metres travelled per gait cycle (the network's phase going once round) over the walk's middle half."""
    t = len(loco.phase)
    mid = slice(t // 4, 3 * t // 4)
    cycles = np.sum(np.mod(np.diff(loco.phase[mid]), 1.0))
    dist = np.sum(np.linalg.norm(np.diff(loco.root_position[mid][:, [0, 2]], axis=0), axis=1))
    return float(dist / max(cycles, 1e-6))


def _arm_swing(loco) -> float:
    """Forward-back range (m) of the wrists in the body frame, median of the two hands over the walk's middle."""
    pos, _ = global_transforms(loco.rotations, loco.root_position)
    t = len(pos)
    mid = slice(t // 4, 3 * t // 4)
    local = to_local(pos[mid], loco.root_position[mid][:, [0, 2]], loco.heading[mid])
    return float(np.mean([np.ptp(local[:, JOINT_INDEX[h], 2]) for h in ("LeftHand", "RightHand")]))


def _head_drop(loco) -> float:
    """Mean height (m) of the head above the neck: lower when the head hangs."""
    pos, _ = global_transforms(loco.rotations, loco.root_position)
    return float(np.mean(pos[:, JOINT_INDEX["Head"], 1] - pos[:, JOINT_INDEX["Neck"], 1]))


def test_manner_words_map_to_distinct_walks_and_unknown_ones_to_neutral():
    assert gait_style("Briskly").speed > gait_style("").speed > gait_style("slowly").speed
    assert gait_style("tiredly").arm_swing < 1 < gait_style("happily").arm_swing
    assert gait_style("madly") == GaitStyle()


def test_the_planner_gives_the_manner_speed_and_word_to_the_walk():
    speeds = {}
    for manner in ("slowly", "", "briskly"):
        ch = CharacterNode(
            name="Eve", actions=[ActionNode(verb="walk", action="walk", destination="desk", manner=manner)]
        )
        seg = next(s for s in plan_actions(ch, SCENE, (0.0, -3.0, 0.0)).segments if s.kind == "locomotion")
        assert seg.manner == manner
        speeds[manner] = seg.speed
    assert speeds["slowly"] < speeds[""] < speeds["briskly"]


def test_brisk_walks_take_longer_strides_than_slow_ones():
    slow, plain, brisk = (_stride(_walk(m)) for m in ("slowly", "", "briskly"))
    assert slow < plain < brisk
    assert brisk - slow > 0.15  # metres: visibly different, not noise


def test_arm_swing_grows_when_happy_and_shrinks_when_tired():
    tired, plain, happy = (_arm_swing(_walk(m)) for m in ("tiredly", "", "happily"))
    assert tired < 0.8 * plain
    assert happy > 1.1 * plain


def test_a_tired_walk_hangs_the_head_and_the_feet_stay_planted():
    tired, plain = _walk("tiredly"), _walk("")
    assert _head_drop(tired) < _head_drop(plain) - 0.005
    # Only the upper body is restyled: the legs are the network's.
    styled = apply_gait_style(plain.rotations, gait_style("tiredly"))
    legs = [JOINT_INDEX[n] for n in JOINT_INDEX if "Leg" in n or "Foot" in n or "Toe" in n or n == "Hips"]
    assert np.allclose(styled[:, legs], plain.rotations[:, legs])


def test_scaling_the_swing_scales_the_angle_about_the_mean():
    t = np.arange(90)
    angle = 0.3 + 0.2 * np.sin(2 * np.pi * t / 30)
    q = quat.from_axis_angle(np.array([1.0, 0.0, 0.0]), angle)
    doubled = scale_swing(q, 2.0)
    got = 2 * np.arctan2(doubled[:, 0], doubled[:, 3])
    assert np.allclose(got[15:-15], 0.3 + 0.4 * np.sin(2 * np.pi * t[15:-15] / 30), atol=0.02)


@pytest.mark.parametrize("manner", ["tiredly", "happily"])
def test_synthesis_carries_the_manner_into_the_frames(manner):
    ch = CharacterNode(
        name="Eve", actions=[ActionNode(verb="walk", action="walk", destination="desk", manner=manner)]
    )
    plain = CharacterNode(name="Eve", actions=[ActionNode(verb="walk", action="walk", destination="desk")])
    a = from_wire(synthesise(plan_actions(ch, SCENE, (0.0, -3.0, 0.0)))[0].rotations)
    b = from_wire(synthesise(plan_actions(plain, SCENE, (0.0, -3.0, 0.0)))[0].rotations)
    assert a.shape != b.shape or not np.allclose(a, b)  # different speed or a different upper body
