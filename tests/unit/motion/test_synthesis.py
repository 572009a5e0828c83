"""Planning, synthesis, IK, segment-wise recompute, handlers and the import CLI."""

from __future__ import annotations

import json

import msgspec
import numpy as np

from proto.common import Header
from proto.motion import SynthesizeRequest
from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.handlers import CONTRACT
from services.motion.ik import global_transforms, two_bone_ik
from services.motion.planning import plan_actions
from services.motion.synthesis import synthesise, synthesise_segment
from wana.arrays import from_wire
from wana.bus.service import call_in_process
from wana.domain.actions import get_clip, load_library
from wana.domain.skeleton import JOINT_INDEX

SCENE = Scene(
    room=Room(room_type="office", width=6, depth=6, height=3),
    objects=[
        PlacedObject(id="desk", category="desk", position=(1.0, 0.0, 0.3), yaw=0.0),
        PlacedObject(id="chair", category="office_chair", position=(1.0, 0.0, 1.05), yaw=np.pi),
    ],
)
EVE = CharacterNode(
    name="Eve",
    actions=[
        ActionNode(verb="walk", action="walk", destination="chair"),
        ActionNode(verb="sit", action="sit", target="chair"),
        ActionNode(verb="type", action="type", target="desk"),
        ActionNode(verb="wave", action="wave"),
    ],
)


def test_two_bone_ik_reaches_a_reachable_target():
    rot, off, _ = get_clip("wave").sample()
    root = off + [0, 0.95, 0]
    target = np.broadcast_to([-0.3, 1.2, 0.4], (len(rot), 3))
    out = two_bone_ik(rot, root, "RightHandMiddle1", target)
    pos, _ = global_transforms(out, root)
    assert np.linalg.norm(pos[:, JOINT_INDEX["RightHandMiddle1"]] - target, axis=1).max() < 0.01


def test_sitting_puts_the_hips_on_the_seat_and_typing_hands_on_the_desk():
    plan = plan_actions(EVE, SCENE, (-2.0, -2.0, 0.0))
    motion, pieces, states = synthesise(plan)
    pos, _ = global_transforms(
        from_wire(motion.rotations).astype(float), from_wire(motion.root_position).astype(float)
    )
    f0 = 0
    checked = 0
    for p in pieces:
        for joint, (frames, target) in p.contact_frames.items():
            if len(frames):
                d = np.linalg.norm(pos[f0 + frames, JOINT_INDEX[joint]] - target, axis=1)
                assert d.mean() < 0.03, (p.segment.action, joint, d.mean())
                checked += 1
        f0 += len(p.root)
    assert checked >= 3
    assert [s.posture for s in states][-2:] == ["sit", "sit"]


def test_recompute_from_a_segment_gives_the_same_frames_and_end_states():
    plan = plan_actions(EVE, SCENE, (-2.0, -2.0, 0.0))
    _, pieces, states = synthesise(plan)
    piece, end = synthesise_segment(plan, 2, states[1])
    assert end == states[2]
    assert np.array_equal(piece.rotations, pieces[2].rotations)
    assert hash(end) == hash(states[2])


def test_handler_returns_a_motion_and_reports_unknown_actions():
    ch = CharacterNode(
        name="Tom", actions=[ActionNode(verb="wave", action="wave"), ActionNode(verb="zork", action="zork")]
    )
    reply = call_in_process(CONTRACT, SynthesizeRequest(header=Header(), character=ch, scene=SCENE))
    assert reply.status == "ok" and any("zork" in d for d in reply.diagnostics)
    rot = from_wire(reply.motion.rotations)
    assert rot.shape[1:] == (24, 4) and rot.shape[0] == reply.motion.segments[-1].end_frame
    # one end state per segment: the wave, the 1 s wait for "zork", and any step the wave's arms need clear
    # of the desk beside Tom (services.motion.elbow_room)
    assert len(reply.end_states) == len(reply.motion.segments) >= 2
    assert [s.action for s in reply.motion.segments][-2:] == ["wave", "idle"]
    social = {name for name, clip in load_library().items() if "social" in clip.tags}
    assert {"hug", "shake_hands"} <= social
    msgspec.msgpack.decode(msgspec.msgpack.encode(reply), type=type(reply))


def test_motion_import_cli_adds_a_clip_without_retraining(tmp_path, monkeypatch):
    from services.motion import cli
    from wana.domain.actions import reload_library
    from wana.domain.bvh import write_bvh

    rot, off, _ = get_clip("clap").sample()
    write_bvh(tmp_path / "My Clap.bvh", off + [0, 0.95, 0], rot, scale=100.0)
    out = tmp_path / "lib"
    monkeypatch.setenv("WANA_ACTIONS_DIR", str(out))
    assert (
        cli.main(["import", str(tmp_path / "My Clap.bvh"), "--tags", "social,test", "--out", str(out)]) == 0
    )
    try:
        clip = reload_library()["my_clap"]
        assert clip.tags == ("social", "test") and abs(clip.duration_s - get_clip("clap").duration_s) < 0.05
        assert json.loads((out / "my_clap.json").read_text())["source"] == "imported"
        assert cli.main(["import", str(tmp_path / "missing.bvh")]) == 2
    finally:
        monkeypatch.delenv("WANA_ACTIONS_DIR")
        reload_library()
