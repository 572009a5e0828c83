"""Two-person actions solved on both bodies (PairRequest, services/motion/pairs.py): real synthesis, the
contacts measured on each character's own skeleton with the story checks' body model."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import msgspec
import numpy as np
import pytest

from proto.common import Header
from proto.motion import PairedAction, PairRequest, SynthesizeRequest
from proto.motion_data import Motion, Segment
from proto.scene import Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.motion.handlers import CONTRACT
from wana.arrays import from_wire, to_wire
from wana.bus.service import call_in_process
from wana.domain import quat
from wana.domain.skeleton import JOINT_INDEX
from wana.fidelity.bodies import body_of

EMPTY = Scene(room=Room(room_type="living_room", width=8, depth=8, height=3), objects=[])
EVE = (1.0, 1.0)
TOM = (-1.0, -1.0, 0.0)
CONTACT_M = 0.03  # the target: hands within 3 cm at the contact frames


def _social_eval():
    path = Path(__file__).resolve().parents[3] / "eval" / "social.py"
    spec = importlib.util.spec_from_file_location("social_eval", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules.setdefault("social_eval", module)
    spec.loader.exec_module(module)
    return module


def _synth(name: str, actions: list[ActionNode], start, others=None) -> Motion:  # noqa: ANN001
    req = SynthesizeRequest(
        header=Header(),
        character=CharacterNode(name=name, actions=actions),
        scene=EMPTY,
        start=start,
        others=others or {},
    )
    reply = call_in_process(CONTRACT, req)
    assert reply.status == "ok"
    return reply.motion


def _hold_to(motion: Motion, frames: int, lead: int = 0) -> Motion:
    """The motion on a story time line of ``frames``: ``lead`` frames holding its first pose, then it, then its
    last pose held (as the orchestrator's timeline does)."""
    root, rot = from_wire(motion.root_position), from_wire(motion.rotations)
    n = len(root)
    tail = frames - lead - n
    root = np.concatenate([np.repeat(root[:1], lead, 0), root, np.repeat(root[-1:], tail, 0)])
    rot = np.concatenate([np.repeat(rot[:1], lead, 0), rot, np.repeat(rot[-1:], tail, 0)])
    segments = [
        msgspec.structs.replace(s, start_frame=s.start_frame + lead, end_frame=s.end_frame + lead)
        for s in motion.segments
    ]
    if tail:
        segments.append(Segment(index=len(segments), action="hold", start_frame=lead + n, end_frame=frames))
    return msgspec.structs.replace(
        motion,
        root_position=to_wire(root.astype(np.float32)),
        rotations=to_wire(rot.astype(np.float32)),
        foot_contact=to_wire(np.ones((frames, 2), np.uint8)),
        segments=segments,
    )


def _pair(action: str, partner_actions: list[ActionNode] | None = None, eve_yaw: float = 2.5):
    """Tom does ``action`` to Eve (who stands facing away, ``eve_yaw``); both motions on one time line."""
    tom = _synth("Tom", [ActionNode(verb=action, action=action, target="Eve")], TOM, {"Eve": EVE})
    eve = _synth("Eve", partner_actions or [ActionNode(verb="stand", action="idle")], (*EVE, eve_yaw))
    frames = max(tom.root_position.shape[0], eve.root_position.shape[0]) + 10
    return {"Tom": _hold_to(tom, frames), "Eve": _hold_to(eve, frames)}


def _solve(motions: dict[str, Motion], action: str, partner: str = "Eve"):
    req = PairRequest(
        header=Header(),
        motions=motions,
        pairs=[PairedAction(actor="Tom", action_index=0, action=action, partner=partner)],
        give_way=False,
    )
    reply = call_in_process(CONTRACT, req)
    assert reply.status == "ok"
    return reply


def _gaps(motions: dict[str, Motion], action: str) -> list[float]:
    ev = _social_eval()
    bodies = {n: body_of(m) for n, m in motions.items()}
    on = {n: np.ones(b.frames, bool) for n, b in bodies.items()}
    seg = next(s for s in motions["Tom"].segments if s.action == action)
    gaps = ev.hand_gaps("Tom", seg, bodies, on)
    assert gaps
    return gaps


@pytest.fixture(scope="module")
def hug():
    motions = _pair("hug")
    return motions, _solve(motions, "hug")


def test_a_hug_is_returned_with_all_four_hands_on_the_other_back(hug):
    before, reply = hug
    assert max(_gaps(before, "hug")) > 0.15  # alone, Tom hugs the air and Eve stands passive
    after = reply.motions
    assert max(_gaps(after, "hug")) <= CONTACT_M  # Tom's hands on Eve and Eve's (she hugs back) on Tom
    assert reply.contacts and reply.contacts[0].gap_m <= CONTACT_M
    assert reply.contacts[0].partner == "Eve" and reply.contacts[0].action == "hug"


def test_the_hugged_partner_turns_to_face_the_actor(hug):
    before, reply = hug
    seg = next(s for s in before["Tom"].segments if s.action == "hug")
    f = (seg.start_frame + seg.end_frame) // 2

    def facing_error(motions: dict[str, Motion]) -> float:
        eve, tom = (from_wire(motions[n].root_position)[f] for n in ("Eve", "Tom"))
        want = np.arctan2(tom[0] - eve[0], tom[2] - eve[2])
        have = float(quat.yaw_of(from_wire(motions["Eve"].rotations)[f, 0].astype(np.float64)))
        return abs(float(np.angle(np.exp(1j * (want - have)))))

    assert facing_error(before) > 1.0
    assert facing_error(reply.motions) < 0.15


def test_outside_the_clip_the_partner_is_untouched(hug):
    before, reply = hug
    seg = next(s for s in before["Tom"].segments if s.action == "hug")
    early = max(0, seg.start_frame - 20)
    a, b = (from_wire(m["Eve"].rotations)[:early] for m in (before, reply.motions))
    assert np.allclose(a, b, atol=1e-6)


def test_a_handshake_has_both_right_hands_meeting():
    motions = _pair("shake_hands")
    assert max(_gaps(motions, "shake_hands")) > 0.1
    reply = _solve(motions, "shake_hands")
    assert max(_gaps(reply.motions, "shake_hands")) <= CONTACT_M


def test_a_high_five_meets_within_both_reaches():
    motions = _pair("high_five")
    reply = _solve(motions, "high_five")
    assert max(_gaps(reply.motions, "high_five")) <= CONTACT_M


def test_the_partner_is_the_nearest_character_when_the_text_names_none():
    motions = _pair("shake_hands")
    reply = _solve(motions, "shake_hands", partner="")
    assert reply.contacts[0].partner == "Eve"
    assert max(_gaps(reply.motions, "shake_hands")) <= CONTACT_M


def test_a_partner_out_of_reach_is_left_alone_with_a_note():
    tom = _synth("Tom", [ActionNode(verb="hug", action="hug")], TOM)  # nobody to walk up to
    eve = _synth("Eve", [ActionNode(verb="stand", action="idle")], (3.0, 3.0, 0.0))
    frames = max(tom.root_position.shape[0], eve.root_position.shape[0])
    motions = {"Tom": _hold_to(tom, frames), "Eve": _hold_to(eve, frames)}
    reply = _solve(motions, "hug")
    assert not reply.contacts
    assert any("too far" in d for d in reply.diagnostics)
    assert reply.motions["Eve"] == motions["Eve"]


def test_two_doing_one_hug_start_it_on_the_same_frame():
    tom = _synth("Tom", [ActionNode(verb="hug", action="hug", target="Eve")], TOM, {"Eve": EVE})
    eve = _synth("Eve", [ActionNode(verb="hug", action="hug", target="Tom")], (*EVE, 3.9))
    frames = max(tom.root_position.shape[0], eve.root_position.shape[0]) + 30
    motions = {"Tom": _hold_to(tom, frames), "Eve": _hold_to(eve, frames)}
    starts = {n: next(s.start_frame for s in m.segments if s.action == "hug") for n, m in motions.items()}
    assert starts["Tom"] != starts["Eve"]  # Tom walks up first: alone, Eve would hug the air before he comes
    req = PairRequest(
        header=Header(),
        motions=motions,
        pairs=[
            PairedAction(actor="Tom", action_index=0, action="hug", partner="Eve"),
            PairedAction(actor="Eve", action_index=0, action="hug", partner="Tom"),
        ],
        give_way=False,
    )
    reply = call_in_process(CONTRACT, req)
    after = {
        n: next(s.start_frame for s in m.segments if s.action == "hug") for n, m in reply.motions.items()
    }
    assert after["Tom"] == after["Eve"]
    assert {m.root_position.shape[0] for m in reply.motions.values()} == {frames}
    assert max(_gaps(reply.motions, "hug")) <= CONTACT_M


def test_a_high_five_from_far_away_waits_for_the_one_who_walks_up():
    """Tom walks 4 m before his high five; Eve's alone would be over before he arrives (no overlap in time),
    yet the two clips are one sentence's action and start together."""
    tom = _synth(
        "Tom",
        [ActionNode(verb="high-five", action="high_five", target="Eve")],
        (-2.0, -2.0, 0.0),
        {"Eve": EVE},
    )
    eve = _synth("Eve", [ActionNode(verb="high-five", action="high_five", target="Tom")], (*EVE, 3.9))
    frames = max(tom.root_position.shape[0], eve.root_position.shape[0]) + 30
    motions = {
        n: msgspec.structs.replace(
            _hold_to(m, frames),
            segments=[
                msgspec.structs.replace(s, sentence_id="s1" if s.action_index == 0 else "")
                for s in _hold_to(m, frames).segments
            ],
        )
        for n, m in (("Tom", tom), ("Eve", eve))
    }
    spans = {n: next(s for s in m.segments if s.action == "high_five") for n, m in motions.items()}
    assert spans["Eve"].end_frame < spans["Tom"].start_frame
    req = PairRequest(
        header=Header(),
        motions=motions,
        pairs=[
            PairedAction(actor="Tom", action_index=0, action="high_five", partner="Eve"),
            PairedAction(actor="Eve", action_index=0, action="high_five", partner="Tom"),
        ],
        give_way=False,
    )
    reply = call_in_process(CONTRACT, req)
    after = {
        n: next(s.start_frame for s in m.segments if s.action == "high_five")
        for n, m in reply.motions.items()
    }
    assert after["Tom"] == after["Eve"]
    assert max(_gaps(reply.motions, "high_five")) <= CONTACT_M


def _seated_eve(action: str, tom=(1.0, 3.0, np.pi)) -> dict[str, Motion]:  # noqa: ANN001
    """Eve sits on a chair; Tom walks up to her from ``tom`` (x, z, yaw) and does ``action`` to her (both on
    one time line)."""
    from proto.scene import PlacedObject

    scene = Scene(
        room=EMPTY.room,
        objects=[PlacedObject(id="chair", category="chair", position=(1.0, 0.0, 1.0), yaw=0.0)],
    )

    def synth(name: str, actions: list[ActionNode], start, others=None) -> Motion:  # noqa: ANN001
        req = SynthesizeRequest(
            header=Header(),
            character=CharacterNode(name=name, actions=actions),
            scene=scene,
            start=start,
            others=others or {},
        )
        reply = call_in_process(CONTRACT, req)
        assert reply.status == "ok"
        return reply.motion

    eve = synth("Eve", [ActionNode(verb="sit", action="sit", target="chair")], (1.0, 1.4, 0.0))
    seat = from_wire(eve.root_position)[-1]
    assert seat[1] < 0.7  # seated
    tom = synth(
        "Tom",
        [ActionNode(verb=action, action=action, target="Eve")],
        tom,
        {"Eve": (seat[0], seat[2])},
    )
    lead = eve.root_position.shape[0]
    frames = lead + tom.root_position.shape[0] + 10
    return {"Tom": _hold_to(tom, frames, lead), "Eve": _hold_to(eve, frames)}


def test_a_hand_on_a_seated_partners_shoulder_reaches_it_bending_down():
    """Eve sits on a chair; Tom walks up and comforts her: her shoulder is 0.5 m lower than his, out of his
    standing arm's reach, so he bends down to put his hand on it."""
    motions = _seated_eve("comfort")
    reply = _solve(motions, "comfort")
    assert max(_gaps(reply.motions, "comfort")) <= CONTACT_M


def test_a_seated_partner_answers_a_handshake_late_without_whipping_her_hand():
    """Eve, seated, answers Tom's handshake after a long delay: her hand still rises at a human speed (no
    jump the speed guard would drop, leaving Tom's hand in the air), her hips stay square to the seat and
    her chest turns to him; the two right hands meet."""
    from services.motion.pairs import HANDS_MAX_MS, _fastest_hand, _Side, offsets_of

    motions = _seated_eve("shake_hands", tom=(3.0, 1.2, -np.pi / 2))  # he comes to her left side
    req = PairRequest(
        header=Header(),
        motions=motions,
        pairs=[PairedAction(actor="Tom", action_index=0, action="shake_hands", partner="Eve", delay_s=1.5)],
        give_way=False,
    )
    reply = call_in_process(CONTRACT, req)
    assert max(_gaps(reply.motions, "shake_hands")) <= CONTACT_M
    before, after = (from_wire(m["Eve"].rotations).astype(np.float64) for m in (motions, reply.motions))
    root = from_wire(motions["Eve"].root_position).astype(np.float64)
    assert np.allclose(quat.yaw_of(before[:, 0]), quat.yaw_of(after[:, 0]), atol=1e-4)  # hips kept
    eve = _Side("Eve", after, root, offsets_of("Eve"))
    assert _fastest_hand(eve) <= HANDS_MAX_MS
    seg = next(s for s in reply.motions["Tom"].segments if s.action == "shake_hands")
    mid = (seg.start_frame + seg.end_frame) // 2
    spine = JOINT_INDEX["Spine"]
    assert (
        abs(float(quat.yaw_of(after[mid : mid + 1, spine])[0] - quat.yaw_of(before[mid : mid + 1, spine])[0]))
        > 0.05
    )


def test_a_seated_partner_comforted_from_the_side_keeps_still():
    """A hand put on Eve's shoulder asks nothing of her: she does not turn to Tom (her shoulder would move out
    of his reach while he bends to it)."""
    motions = _seated_eve("comfort", tom=(3.0, 1.2, -np.pi / 2))
    reply = _solve(motions, "comfort")
    assert max(_gaps(reply.motions, "comfort")) <= CONTACT_M
    before, after = (from_wire(m["Eve"].rotations) for m in (motions, reply.motions))
    assert np.allclose(before, after, atol=1e-6)


def test_a_seated_partner_hugged_from_the_side_has_both_hands_on_her_turned_back():
    """Eve, seated, turns her chest to Tom, who comes from her side: both his hands go on her back as it is
    turned (well behind the plane of her shoulders), not to where her hips' heading puts it (her flank)."""
    from services.motion.pairs import _window

    motions = _seated_eve("hug", tom=(3.0, 1.2, -np.pi / 2))
    reply = _solve(motions, "hug")
    tom, eve = (body_of(reply.motions[n]) for n in ("Tom", "Eve"))
    w0, w1 = _window(next(s for s in reply.motions["Tom"].segments if s.action == "hug"), "hug")
    across = eve.joint("LeftShoulder")[w0:w1] - eve.joint("RightShoulder")[w0:w1]
    forward = np.cross(across, eve.joint("Neck")[w0:w1] - eve.joint("Hips")[w0:w1])
    forward /= np.linalg.norm(forward, axis=1, keepdims=True)
    for hand in ("LeftHand", "RightHand"):
        ahead = np.einsum("ij,ij->i", tom.joint(hand)[w0:w1] - eve.joint("Spine2")[w0:w1], forward)
        assert float(ahead.max()) <= -0.05  # on her back, not beside her
