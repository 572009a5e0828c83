"""The idle layer: a character holding a pose breathes, shifts its weight and looks around, and nothing else changes."""

from __future__ import annotations

import numpy as np
import pytest

from proto.motion_data import Motion, PropTrack, Segment
from wana.arrays import from_wire, to_wire
from wana.domain import idle, quat
from wana.domain.actions import get_clip, neutral_rotations
from wana.domain.skeleton import JOINT_INDEX, REST_OFFSETS, forward_kinematics


def _standing(frames: int, yaw: float = 0.4) -> tuple[np.ndarray, np.ndarray]:
    rot = np.repeat(neutral_rotations()[None], frames, 0)
    rot[:, 0] = quat.mul(quat.yaw(np.full(frames, yaw)), rot[:, 0])
    root = np.tile([1.0, REST_OFFSETS[0, 1], -2.0], (frames, 1))
    return rot, root


def _frozen_share(rot: np.ndarray, root: np.ndarray) -> float:
    """Share of frames in which no joint turns more than 0.1 degree in the world (eval/motion.py's measure)."""
    _, g = forward_kinematics(rot, root)
    turn = np.degrees(2 * np.arccos(np.clip(np.abs(np.sum(g[1:] * g[:-1], -1)), 0, 1)))
    return float((turn.max(axis=1) <= 0.1).mean())


def _sitting(frames: int) -> tuple[np.ndarray, np.ndarray]:
    rot, offs, _ = get_clip("sit").sample()
    return np.repeat(rot[-1:], frames, 0), np.repeat(offs[-1:] + [0, REST_OFFSETS[0, 1], 0], frames, 0)


def test_a_held_standing_pose_is_never_frozen_and_the_feet_stay_planted():
    rot, root = _standing(300)
    assert _frozen_share(rot, root) == 1.0
    w = idle.idle_weight(300, [(0, 300)])
    out_rot, out_root = idle.enliven(rot, root, w, idle.seed_of("Eve"))
    assert _frozen_share(out_rot[15:-15], out_root[15:-15]) <= 0.05
    before, _ = forward_kinematics(rot, root)
    after, _ = forward_kinematics(out_rot, out_root)
    for foot in ("LeftFoot", "RightFoot", "LeftToeBase", "RightToeBase"):
        assert np.abs(after[:, JOINT_INDEX[foot]] - before[:, JOINT_INDEX[foot]]).max() < 0.003
    sway = np.ptp(out_root[:, [0, 2]], axis=0).max()
    assert 0.015 < sway < 0.06  # the weight goes from foot to foot: the hips travel a couple of centimetres


def test_frames_outside_the_idle_stretches_are_untouched_and_the_edges_do_not_pop():
    rot, root = _standing(200)
    w = idle.idle_weight(200, [(50, 150)])
    out_rot, out_root = idle.enliven(rot, root, w, 3)
    assert np.array_equal(out_rot[:50], rot[:50]) and np.array_equal(out_rot[150:], rot[150:])
    assert np.array_equal(out_root[:50], root[:50])
    _, g = forward_kinematics(out_rot, out_root)
    turn = np.degrees(2 * np.arccos(np.clip(np.abs(np.sum(g[1:] * g[:-1], -1)), 0, 1)))
    assert turn.max() < 2.0  # degrees per frame anywhere, the edges included (a pop is tens)


def test_the_same_character_idles_the_same_way_and_two_characters_differ():
    rot, root = _standing(120)
    w = idle.idle_weight(120, [(0, 120)])
    a = idle.enliven(rot, root, w, idle.seed_of("Tom"))[0]
    b = idle.enliven(rot, root, w, idle.seed_of("Tom"))[0]
    c = idle.enliven(rot, root, w, idle.seed_of("Eve"))[0]
    assert np.array_equal(a, b)
    assert not np.allclose(a, c)


def test_the_gaze_turns_the_head_toward_what_calls_for_attention():
    rot, root = _standing(150, yaw=0.0)  # facing +Z
    target = np.array([3.0, 1.6, 0.0])  # to the character's left (+X)
    gaze = np.full((150, 3), np.nan)
    gaze[40:] = target
    out_rot, out_root = idle.enliven(rot, root, idle.idle_weight(150, [(0, 150)]), 5, gaze)
    pos, g = forward_kinematics(out_rot, out_root)
    head = JOINT_INDEX["Head"]
    facing = quat.rotate(g[:, head], np.array([0.0, 0.0, 1.0]))
    to_target = target - pos[:, head]
    angle = np.degrees(np.arccos(np.sum(facing * to_target, 1) / np.linalg.norm(to_target, axis=1)))
    assert angle[90:130].max() < angle[30] - 30.0  # turned well toward it (the layer fades out after)


def test_a_seated_idle_breathes_and_looks_about_but_the_hips_stay_on_the_seat():
    rot, root = _sitting(240)
    out_rot, out_root = idle.enliven(rot, root, idle.idle_weight(240, [(0, 240)]), 11)
    assert np.array_equal(out_root, root)
    assert _frozen_share(out_rot[15:-15], out_root[15:-15]) <= 0.1
    assert np.allclose(out_rot[:, JOINT_INDEX["LeftUpLeg"]], rot[:, JOINT_INDEX["LeftUpLeg"]])


def test_idle_stretches_are_holds_and_long_still_runs_of_clips_without_a_hand_contact():
    rot, _ = _standing(120)
    segs = [
        Segment(index=0, action="wave", start_frame=0, end_frame=40),  # no contact: a still run counts
        Segment(index=1, action="hold", start_frame=40, end_frame=60),
        Segment(index=2, action="type", start_frame=60, end_frame=120),  # hands on keys: never
    ]
    spans = idle.idle_spans(segs, 120, rot)
    assert spans == [(1, 60)]


def test_a_busy_motion_is_returned_as_is():
    rot, root = _standing(90)
    busy = Motion(
        character="Eve",
        root_position=to_wire(root.astype(np.float32)),
        rotations=to_wire(rot.astype(np.float32)),
        segments=[Segment(index=0, action="drink", start_frame=0, end_frame=90)],
    )
    assert idle.enliven_motion(busy) is busy


def _holding(track_pos: np.ndarray | None = None) -> Motion:
    """A 90-frame hold with a cup whose grip is on the right hand (or at track_pos: put down there)."""
    rot, root = _standing(90)
    hand, _ = forward_kinematics(rot, root)
    at = hand[:, JOINT_INDEX["RightHand"]] if track_pos is None else track_pos
    return Motion(
        character="Eve",
        root_position=to_wire(root.astype(np.float32)),
        rotations=to_wire(rot.astype(np.float32)),
        segments=[Segment(index=0, action="hold", start_frame=0, end_frame=90)],
        props=[
            PropTrack(
                object_id="cup",
                joint="RightHand",
                start_frame=0,
                end_frame=90,
                position=to_wire(at.astype(np.float32)),
                rotation=to_wire(np.tile([0, 0, 0, 1], (90, 1)).astype(np.float32)),
            )
        ],
    )


def test_a_character_holding_a_prop_still_breathes_and_the_prop_stays_in_its_hand():
    held = _holding()
    out = idle.enliven_motion(held)
    rot, root = from_wire(out.rotations).astype(np.float64), from_wire(out.root_position).astype(np.float64)
    assert _frozen_share(rot[15:-15], root[15:-15]) <= 0.05  # never a frozen mannequin
    pos, _ = forward_kinematics(rot, root)
    cup = from_wire(out.props[0].position)
    assert np.abs(cup - pos[:, JOINT_INDEX["RightHand"]]).max() < 1e-4  # the cup moved with the hand
    for j in ("RightArm", "RightForeArm", "LeftArm", "RightShoulder"):  # the arms keep their hold
        assert np.array_equal(
            from_wire(out.rotations)[:, JOINT_INDEX[j]], from_wire(held.rotations)[:, JOINT_INDEX[j]]
        )


def test_a_prop_put_down_away_from_the_hand_does_not_stop_the_arms_or_follow_them():
    put = _holding(np.tile([3.0, 0.8, 0.0], (90, 1)))
    out = idle.enliven_motion(put)
    assert np.array_equal(from_wire(out.props[0].position), from_wire(put.props[0].position))
    arm = JOINT_INDEX["RightArm"]
    assert not np.array_equal(from_wire(out.rotations)[:, arm], from_wire(put.rotations)[:, arm])


def test_hands_solved_onto_another_character_are_left_where_the_solve_put_them():
    """The partner of a handshake holds still where the cast fit met the hands (breathing and weight shifts
    pulled them 2-3 cm apart: eval/social.py greetings hand_contact_cm 3.03 -> 0.37); before and after, the
    hold breathes again."""
    rot, root = _standing(150)
    hold = Motion(
        character="Ada",
        root_position=to_wire(root.astype(np.float32)),
        rotations=to_wire(rot.astype(np.float32)),
        segments=[Segment(index=0, action="hold", start_frame=0, end_frame=150)],
    )
    out = idle.enliven_motion(hold, touching=[(60, 90)])
    before, after = from_wire(hold.rotations), from_wire(out.rotations)
    pos0, _ = forward_kinematics(before.astype(np.float64), root)
    pos1, _ = forward_kinematics(after.astype(np.float64), from_wire(out.root_position).astype(np.float64))
    hand = JOINT_INDEX["RightHand"]
    assert np.abs(pos1[60:90, hand] - pos0[60:90, hand]).max() < 1e-3  # the met hand stays met
    assert np.abs(pos1[:40, hand] - pos0[:40, hand]).max() > 2e-3  # the hold breathes before it
    assert np.abs(pos1[110:, hand] - pos0[110:, hand]).max() > 2e-3  # and after it


def test_whoever_acts_draws_the_eyes_and_the_next_target_wins_just_before_the_action():
    rot, root = _standing(120)
    still = Motion(
        character="Eve",
        root_position=to_wire(root.astype(np.float32)),
        rotations=to_wire(rot.astype(np.float32)),
        segments=[
            Segment(index=0, action="hold", start_frame=0, end_frame=90),
            Segment(index=1, action="wave", start_frame=90, end_frame=120, action_index=0),
        ],
    )
    other_root = root + [2.0, 0.0, 0.0]
    tom = Motion(
        character="Tom",
        root_position=to_wire(other_root.astype(np.float32)),
        rotations=to_wire(rot.astype(np.float32)),
        segments=[
            Segment(index=0, action="hold", start_frame=0, end_frame=20),
            Segment(index=1, action="walk", start_frame=20, end_frame=120, action_index=0),
        ],
    )
    points = idle.attention("Eve", {"Eve": still, "Tom": tom}, {0: (0.0, 0.8, 5.0)})
    assert np.isnan(points[:20]).all()
    assert np.allclose(points[30, [0, 2]], other_root[30, [0, 2]])
    assert np.allclose(points[85], (0.0, 0.8, 5.0))  # the last 1.2 s before the wave: what it is aimed at


def test_blinks_close_the_eyes_every_few_seconds_and_leave_the_rest_of_the_face():
    names = ["smile", "eyes_closed"]
    face = np.zeros((600, 2), np.float32)
    face[:, 0] = 0.3
    out = idle.with_blinks(face, names, idle.seed_of("Eve"))
    assert np.array_equal(out[:, 0], face[:, 0])
    closed = out[:, 1] >= 0.99
    starts = np.flatnonzero(closed[1:] & ~closed[:-1])
    assert 3 <= len(starts) <= 12  # 20 s: a blink every 2-5.5 s
    assert np.diff(starts).max() <= int(6 * 30)
    assert idle.with_blinks(face, ["smile", "frown"], 1) is face


@pytest.mark.parametrize("frames", [0, 1, 2])
def test_tiny_motions_pass_through(frames: int):
    rot, root = _standing(max(frames, 1))
    rot, root = rot[:frames], root[:frames]
    out_rot, out_root = idle.enliven(rot, root, np.ones(frames), 1)
    assert out_rot.shape == rot.shape and out_root.shape == root.shape


def test_an_idle_stretch_moved_in_time_or_lengthened_keeps_its_frames_bit_for_bit():
    """Each stretch has its own clock: an edit earlier in the story that moves a hold by a few frames (or one
    that lengthens it) changes none of the hold's frames, so the editor is sent only what the edit changed."""
    rot, root = _standing(400)
    first = idle.enliven(rot, root, idle.idle_weight(400, [(40, 200), (260, 380)]), 7)
    moved = idle.enliven(rot, root, idle.idle_weight(400, [(40, 200), (253, 373)]), 7)
    longer = idle.enliven(rot, root, idle.idle_weight(400, [(40, 260), (260, 380)]), 7)
    for a, b in ((first, moved), (first, longer)):
        assert np.array_equal(a[0][40:180], b[0][40:180]) and np.array_equal(a[1][40:180], b[1][40:180])
    assert np.array_equal(first[0][260:380], moved[0][253:373])
    assert np.array_equal(first[1][260:380], moved[1][253:373])
    assert not np.array_equal(first[0][260:380], first[0][40:160])  # the layer still moves (not frozen)


def _held_then_acting(lead: int) -> Motion:
    """``lead`` frames of a drink, then a 4 s hold, a 1 s drink and a 3 s hold."""
    frames = lead + 120 + 30 + 90
    rot, root = _standing(frames)
    bounds = [(0, lead, "drink"), (lead, lead + 120, "hold"), (lead + 120, lead + 150, "drink")]
    bounds.append((lead + 150, frames, "hold"))
    return Motion(
        character="Eve",
        root_position=to_wire(root.astype(np.float32)),
        rotations=to_wire(rot.astype(np.float32)),
        segments=[
            Segment(index=i, action=a, start_frame=s, end_frame=e)
            for i, (s, e, a) in enumerate(bounds)
            if e > s
        ],
    )


def test_the_layer_of_a_stretch_moves_with_it_when_the_time_line_shifts():
    """An edit that makes an earlier action longer shifts the holds after it: each is laid in its own time,
    so it comes out the same, only later (and from the window cache: an edit costs the windows it touches)."""
    early, late = idle.enliven_motion(_held_then_acting(30)), idle.enliven_motion(_held_then_acting(75))
    a, b = from_wire(early.rotations), from_wire(late.rotations)
    assert np.array_equal(a[30:], b[75:])
    assert not np.array_equal(a[30:150], from_wire(_held_then_acting(30).rotations)[30:150])  # it did move
    laid = len(idle._WINDOWS)
    idle.enliven_motion(_held_then_acting(52))
    assert len(idle._WINDOWS) == laid  # both holds were laid before, at other frames


def test_whoever_speaks_draws_the_eyes_of_a_listener():
    rot, root = _standing(120)
    listener = Motion(
        character="Eve",
        root_position=to_wire(root.astype(np.float32)),
        rotations=to_wire(rot.astype(np.float32)),
        segments=[Segment(index=0, action="hold", start_frame=0, end_frame=120)],
    )
    speaker_root = root + [-2.5, 0.0, 1.0]
    speaker = Motion(
        character="Tom",
        root_position=to_wire(speaker_root.astype(np.float32)),
        rotations=to_wire(rot.astype(np.float32)),
        segments=[
            Segment(index=0, action="hold", start_frame=0, end_frame=40),
            Segment(index=1, action="talk", start_frame=40, end_frame=120, action_index=0),
        ],
    )
    points = idle.attention("Eve", {"Eve": listener, "Tom": speaker})
    assert np.isnan(points[:40]).all()
    assert np.allclose(points[40:, [0, 2]], speaker_root[40:, [0, 2]])  # at the speaker's head
    out = idle.enliven_motion(listener, points)
    pos, g = forward_kinematics(from_wire(out.rotations).astype(np.float64), root)
    head = JOINT_INDEX["Head"]
    facing = quat.rotate(g[:, head], np.array([0.0, 0.0, 1.0]))[:, [0, 2]]
    to_speaker = (speaker_root - pos[:, head])[:, [0, 2]]
    cos = np.sum(facing * to_speaker, 1) / np.linalg.norm(facing, axis=1) / np.linalg.norm(to_speaker, axis=1)
    assert np.degrees(np.arccos(cos[80:100])).max() < np.degrees(np.arccos(cos[20])) - 20.0  # turned to him
