"""Manner and emotion change the motion: an angry wave is fast and high, a sad walk slow with the head down."""

from __future__ import annotations

import numpy as np

from proto.motion_data import Motion, Segment
from proto.scene import Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.ik import global_transforms
from services.motion.planning import plan_actions
from services.motion.style import Style, apply_style, mood_of, style_of
from services.motion.synthesis import (
    MotionPiece,
    PlannedSegment,
    SegmentState,
    synthesise,
    synthesise_segment,
)
from wana.arrays import from_wire, to_wire
from wana.domain import quat
from wana.domain.actions import neutral_rotations
from wana.domain.skeleton import JOINT_INDEX
from wana.domain.style import restyle_motion

ANGRY = (-0.7, 0.8)
SAD = (-0.7, -0.5)
EMPTY = Scene(room=Room(room_type="office", width=8, depth=8, height=3), objects=[])


def _piece(action: str, mood: tuple[float, float] = (0.0, 0.0)):
    from services.motion.synthesis import MotionPlan

    plan = MotionPlan(
        character="c", start=(0.0, 0.0, 0.0), segments=(PlannedSegment(0, "action", action, mood=mood),)
    )
    piece, _ = synthesise_segment(plan, 0, SegmentState())
    pos, _ = global_transforms(piece.rotations, piece.root)
    return piece, pos


def test_a_neutral_mood_leaves_the_motion_as_authored_and_strong_ones_set_all_four_parameters():
    assert style_of(0.1, -0.1) == Style()
    angry, sad, happy = style_of(*ANGRY), style_of(*SAD), style_of(0.8, 0.4)
    assert angry.tempo > 1.2 and angry.amplitude > 1.1
    assert sad.tempo < 0.9 and sad.amplitude < 0.95 and sad.chest < -3 and sad.head > 5
    assert happy.chest > 3 and happy.head <= 0


def test_the_manner_word_wins_over_the_social_emotion():
    assert mood_of("angrily", (0.5, -0.5)) == (-0.7, 0.8)
    assert mood_of("", (0.5, -0.5)) == (0.5, -0.5)
    assert mood_of("slowly", None) == (0.0, 0.0)  # a speed word is locomotion's, not a mood


def test_an_angry_wave_is_faster_and_its_hand_goes_higher():
    plain, plain_pos = _piece("wave")
    angry, angry_pos = _piece("wave", ANGRY)
    assert len(angry.root) < 0.85 * len(plain.root)
    hand = JOINT_INDEX["RightHand"]
    assert angry_pos[:, hand, 1].max() > plain_pos[:, hand, 1].max() + 0.03


def test_a_sad_wave_is_slower_smaller_and_the_head_hangs():
    plain, plain_pos = _piece("wave")
    sad, sad_pos = _piece("wave", SAD)
    assert len(sad.root) > 1.1 * len(plain.root)
    hand = JOINT_INDEX["RightHand"]
    assert sad_pos[:, hand, 1].max() < plain_pos[:, hand, 1].max()
    assert _gaze_drop(sad) > _gaze_drop(plain) + np.sin(np.radians(5.0))  # the head hangs


def _gaze_drop(piece) -> float:
    """Median downward component of where the head faces over the middle of a piece."""
    _, grot = global_transforms(piece.rotations, piece.root)
    facing = quat.rotate(grot[:, JOINT_INDEX["Head"]], np.array([0.0, 0.0, 1.0]))
    n = len(facing)
    return float(-np.median(facing[n // 4 : 3 * n // 4, 1]))


def test_a_sad_walk_is_slower_with_the_head_down():
    def walk(manner: str):
        node = ActionNode(verb="walk", action="walk", manner=manner)
        plan = plan_actions(CharacterNode(name="c", actions=[node]), EMPTY, (0.0, 0.0, 0.0))
        motion, pieces, _ = synthesise(plan)
        pos, grot = global_transforms(pieces[0].rotations, pieces[0].root)
        facing = quat.rotate(grot[:, JOINT_INDEX["Head"]], np.array([0.0, 0.0, 1.0]))
        return plan.segments[0].speed, len(pieces[0].root), float(np.median(facing[:, 1]))

    speed, frames, look = walk("")
    sad_speed, sad_frames, sad_look = walk("sadly")
    assert sad_speed < 0.9 * speed and sad_frames > frames
    assert sad_look < look - np.sin(np.radians(5.0))  # the eyes drop more than 5 degrees


def test_a_contact_clip_keeps_its_timing_under_a_mood():
    plain, _ = _piece("type")
    angry, _ = _piece("type", ANGRY)
    assert len(angry.root) == len(plain.root)


def test_the_style_keeps_the_legs_and_amplifies_only_the_departure_from_rest():
    rest = neutral_rotations()
    rot = np.repeat(rest[None], 4, 0)
    out = apply_style(rot, rest, style_of(*ANGRY))
    for j in ("LeftUpLeg", "RightLeg", "Hips", "LeftArm"):  # at rest there is nothing to amplify
        assert np.allclose(out[:, JOINT_INDEX[j]], rot[:, JOINT_INDEX[j]])
    assert not np.allclose(out[:, JOINT_INDEX["Spine1"]], rot[:, JOINT_INDEX["Spine1"]])  # posture


def _composed(action: str) -> Motion:
    """One action then a hold, as the orchestrator's time line lays them out."""
    piece, _ = _piece(action)
    n = len(piece.root)
    rot = np.concatenate([piece.rotations, np.repeat(piece.rotations[-1:], 30, 0)])
    root = np.concatenate([piece.root, np.repeat(piece.root[-1:], 30, 0)])
    return Motion(
        character="c",
        root_position=to_wire(root.astype(np.float32)),
        rotations=to_wire(rot.astype(np.float32)),
        segments=[
            Segment(index=0, action=action, start_frame=0, end_frame=n, action_index=0),
            Segment(index=1, action="hold", start_frame=n, end_frame=n + 30),
        ],
    )


def test_the_social_emotion_restyles_the_composed_motion_without_a_pop():
    plain = _composed("wave")
    angry = restyle_motion(plain, {0: ANGRY})
    sad = restyle_motion(plain, {0: SAD})
    assert restyle_motion(plain, {}) is plain
    hand = JOINT_INDEX["RightHand"]
    heights, steps = {}, {}
    for name, m in (("plain", plain), ("angry", angry), ("sad", sad)):
        pos, _ = global_transforms(from_wire(m.rotations).astype(np.float64), from_wire(m.root_position))
        heights[name] = pos[:, hand, 1].max()
        steps[name] = np.linalg.norm(np.diff(pos, axis=0), axis=-1).max()
    # metres per frame: the mood eases in, no joint jumps more than the (amplified) gesture itself moves
    assert steps["angry"] < 1.35 * steps["plain"] + 0.01 and steps["sad"] < steps["plain"] + 0.01
    assert heights["angry"] > heights["plain"] + 0.02 > heights["sad"] + 0.02
    sad_piece = MotionPiece(from_wire(sad.root_position), from_wire(sad.rotations), None, None)  # type: ignore[arg-type]
    assert (
        _gaze_drop(sad_piece)
        > _gaze_drop(MotionPiece(from_wire(plain.root_position), from_wire(plain.rotations), None, None))
        + 0.05
    )  # type: ignore[arg-type]


def test_a_mood_keeps_the_hands_on_what_they_touch():
    plain = _composed("type")
    sad = restyle_motion(plain, {0: SAD})
    pos_p, _ = global_transforms(
        from_wire(plain.rotations).astype(np.float64), from_wire(plain.root_position)
    )
    pos_s, _ = global_transforms(from_wire(sad.rotations).astype(np.float64), from_wire(sad.root_position))
    n = plain.segments[0].end_frame
    for j in ("LeftHandMiddle1", "RightHandMiddle1"):
        assert np.abs(pos_s[20 : n - 20, JOINT_INDEX[j]] - pos_p[20 : n - 20, JOINT_INDEX[j]]).max() < 0.005
    head = JOINT_INDEX["Head"]
    assert not np.allclose(from_wire(sad.rotations)[:, head], from_wire(plain.rotations)[:, head])


def test_a_happy_jump_is_wider_but_no_hand_moves_faster_than_a_body_can():
    """ "Ivy jumps happily" played the jump 14 % faster and wider: its hands swung at 11 m/s (the story checks
    allow 10). The mood still shows (wider), within the limit; a wave, far from it, keeps its whole style."""
    from wana.domain.body_limits import HANDS_MAX_MS

    happy = mood_of("happily")
    piece, pos = _piece("jump", happy)
    plain, plain_pos = _piece("jump")
    speed = np.linalg.norm(np.diff(pos[:, JOINT_INDEX["LeftHand"]], axis=0), axis=1).max() * 30
    assert speed <= HANDS_MAX_MS
    assert len(piece.rotations) >= len(plain.rotations)  # never played faster than authored
    wave, _ = _piece("wave", happy)
    assert len(wave.rotations) < len(_piece("wave")[0].rotations)  # the wave keeps its quicker tempo
