"""The gesture clips move like an animator's, not a mannequin's (issue 23)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from tools.authoring.author_actions import all_specs, spec_to_dict
from tools.authoring.clip_sheets import held_straight_arms, sample, sheet
from wana.domain import quat
from wana.domain.actions import ACTIONS_DIR, clip_from_dict, get_clip, load_library
from wana.domain.skeleton import JOINT_INDEX, forward_kinematics


def _pos(name: str) -> np.ndarray:
    return sample(get_clip(name))[0]


def test_no_clip_of_the_library_holds_a_straight_raised_arm():
    held = {name: held_straight_arms(_pos(name)) for name in sorted(load_library())}
    assert {n: f for n, f in held.items() if f} == {}


def test_the_review_flags_a_held_straight_arm():
    still = np.repeat(_pos("idle")[:1], 30, 0)
    arm = still.copy()  # the right arm held straight out to the side for a second
    sh = arm[:, JOINT_INDEX["RightArm"]]
    arm[:, JOINT_INDEX["RightForeArm"]] = sh + [-0.28, 0, 0]
    arm[:, JOINT_INDEX["RightHand"]] = sh + [-0.53, 0, 0]
    assert held_straight_arms(still) == []
    assert held_straight_arms(arm) == [("Right", 0.0, 1.0)]


def test_the_wave_is_at_shoulder_height_with_the_forearm_swinging():
    pos = _pos("wave")
    sh, el, wr = (pos[:, JOINT_INDEX[j]] for j in ("RightArm", "RightForeArm", "RightHand"))
    head = pos[:, JOINT_INDEX["Head"]]
    swing = slice(int(0.9 * 30), int(2.1 * 30))
    assert np.abs(el[swing, 1] - sh[swing, 1]).max() < 0.1  # the elbow at shoulder height
    assert (wr[swing, 1] < head[swing, 1] + 0.2).all()  # the hand about head height, not above it
    assert (wr[swing, 1] > sh[swing, 1] + 0.15).all()
    assert np.ptp(wr[swing, 0]) > 0.15  # the forearm swings side to side
    # Anticipation: before it rises, the hand first moves against the way it is going.
    way = wr[int(0.7 * 30)] - wr[0]
    assert ((wr[1:6] - wr[0]) @ way).min() < -0.002


def test_the_wave_s_hand_trails_its_forearm():
    pos = _pos("wave")
    fore = pos[:, JOINT_INDEX["RightHand"], 0] - pos[:, JOINT_INDEX["RightForeArm"], 0]
    hand = pos[:, JOINT_INDEX["RightHandMiddle1"], 0] - pos[:, JOINT_INDEX["RightHand"], 0]
    swing = slice(int(0.9 * 30), int(2.1 * 30))
    lags = range(0, 8)
    best = max(lags, key=lambda k: np.corrcoef(fore[swing], np.roll(hand, -k)[swing])[0, 1])
    assert best >= 1  # the hand's swing peaks frames after the forearm's (overlapping action)


@pytest.mark.parametrize(("name", "turn"), [("point", -1), ("point_right", -1), ("point_left", 1)])
def test_pointing_turns_the_chest_and_keeps_the_elbow_soft(name: str, turn: int):
    clip = get_clip(name)
    rot, offs, _ = clip.sample()
    pos, grot = forward_kinematics(rot, offs + [0, 0.95, 0])
    mid = len(rot) // 2
    chest = quat.rotate(grot[mid, JOINT_INDEX["Spine2"]], np.array([0.0, 0.0, 1.0]))
    yaw = np.degrees(np.arctan2(chest[0], chest[2]))
    assert turn * yaw > 8.0
    side = "Left" if name == "point_left" else "Right"
    upper = pos[mid, JOINT_INDEX[f"{side}ForeArm"]] - pos[mid, JOINT_INDEX[f"{side}Arm"]]
    fore = pos[mid, JOINT_INDEX[f"{side}Hand"]] - pos[mid, JOINT_INDEX[f"{side}ForeArm"]]
    bend = np.degrees(np.arccos(upper @ fore / np.linalg.norm(upper) / np.linalg.norm(fore)))
    assert 12.0 < bend < 45.0


def test_the_shrug_lifts_the_shoulders_and_the_laugh_bounces_them():
    shrug = _pos("shrug")[:, JOINT_INDEX["LeftArm"], 1]
    assert shrug.max() - shrug[0] > 0.02
    laugh = _pos("laugh")[:, JOINT_INDEX["LeftArm"], 1]
    peaks = np.flatnonzero((laugh[1:-1] > laugh[:-2]) & (laugh[1:-1] > laugh[2:]))
    assert len(peaks) >= 4


def test_the_nod_lifts_the_chin_before_it_drops():
    rot, _, _ = get_clip("nod").sample()
    pitch = np.array([quat.to_euler("YXZ", q)[1] for q in rot[:, JOINT_INDEX["Neck"]]])
    first_down = int(np.argmax(pitch > 3.0))
    assert pitch[:first_down].min() < -0.5  # anticipation: up first
    assert pitch.max() > 5.0


def test_a_sheet_is_drawn_for_a_clip():
    img, flags = sheet(get_clip("wave"), tiles=4)
    assert img.width == 4 * 150 and flags == []


@pytest.mark.slow
def test_the_committed_clips_are_what_the_authoring_script_writes():
    """The same clip, key for key, and the same motion sampled frame by frame (within the files' 0.1 degree):
    not the same Euler digits, which differ across machines where an angle lands on -180 or 180 (one turn)."""
    for spec in all_specs():
        committed = json.loads((ACTIONS_DIR / f"{spec.name}.json").read_text())
        written = json.loads(json.dumps(spec_to_dict(spec)))
        assert {k: v for k, v in written.items() if k != "keys"} == {
            k: v for k, v in committed.items() if k != "keys"
        }, spec.name
        strip = [
            [{k: v for k, v in key.items() if k != "pose"} for key in d["keys"]] for d in (written, committed)
        ]
        assert strip[0] == strip[1], spec.name
        rot_w, root_w, yaw_w = clip_from_dict(written).sample()
        rot_c, root_c, yaw_c = clip_from_dict(committed).sample()
        dot = np.abs(np.einsum("...i,...i->...", rot_w, rot_c))
        assert np.degrees(2 * np.arccos(np.minimum(dot, 1.0))).max() < 0.3, spec.name
        assert np.allclose(root_w, root_c, atol=1e-6) and np.allclose(yaw_w, yaw_c, atol=1e-6), spec.name
