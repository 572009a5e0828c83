"""The editor messages built from orchestrator results: offsets, arrays, mesh URLs."""

from __future__ import annotations

import base64

import numpy as np
from scipy.spatial.transform import Rotation

from proto.common import Span
from proto.motion_data import Motion, Segment
from proto.scene import PlacedObject, Room, Scene
from proto.ssg import Command, Diagnostic
from services.gateway.messages import animation_message, diagnostics_message, mesh_url
from services.orchestrator.document import Document
from services.orchestrator.pipeline import PipelineResult, SentenceView
from wana.arrays import to_wire
from wana.domain import skeleton


def _f32(b64: str) -> np.ndarray:
    return np.frombuffer(base64.b64decode(b64), dtype="<f4")


def _walk(frames: int = 12) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(7)
    rotations = Rotation.from_rotvec(rng.normal(0, 0.3, (frames * skeleton.N_JOINTS, 3))).as_quat()
    root = np.stack([np.linspace(0, 1, frames), np.full(frames, 0.95), np.zeros(frames)], axis=1)
    return rotations.reshape(frames, skeleton.N_JOINTS, 4).astype(np.float32), root.astype(np.float32)


def test_animation_carries_each_characters_frames_exactly() -> None:
    rotations, root = _walk()
    motion = Motion(
        character="Eve",
        joint_names=list(skeleton.JOINT_NAMES),
        root_position=to_wire(root),
        rotations=to_wire(rotations),
        segments=[Segment(index=0, action="walk", start_frame=0, end_frame=12, sentence_id="s2")],
    )
    result = PipelineResult(doc_id="d", version=3, motions={"Eve": motion})
    msg = animation_message(result)
    (eve,) = msg["characters"]
    assert msg["version"] == 3 and msg["frames"] == 12 and eve["frames"] == 12
    np.testing.assert_array_equal(_f32(eve["rotations"]).reshape(12, skeleton.N_JOINTS, 4), rotations)
    np.testing.assert_array_equal(_f32(eve["root_position"]).reshape(12, 3), root)
    np.testing.assert_allclose(_f32(eve["offsets"]).reshape(-1, 3), skeleton.REST_OFFSETS, rtol=1e-6)
    assert eve["parents"] == [int(p) for p in skeleton.PARENTS]
    assert eve["segments"][0]["sentence_id"] == "s2"


def test_a_character_off_stage_carries_its_presence_and_one_always_on_stage_none() -> None:
    rotations, root = _walk(12)
    on = np.r_[np.zeros(4), np.ones(8)].astype(np.uint8)
    motion = Motion(character="Eve", root_position=to_wire(root), rotations=to_wire(rotations))
    (always,) = animation_message(PipelineResult(doc_id="d", version=1, motions={"Eve": motion}))[
        "characters"
    ]
    assert always["present"] is None
    entering = Motion(
        character="Eve", root_position=to_wire(root), rotations=to_wire(rotations), present=to_wire(on)
    )
    (eve,) = animation_message(PipelineResult(doc_id="d", version=1, motions={"Eve": entering}))["characters"]
    np.testing.assert_array_equal(_f32(eve["present"]), on)


def test_a_motion_in_another_joint_order_gets_matching_parents_and_offsets() -> None:
    names = list(reversed(skeleton.JOINT_NAMES))
    rotations, root = _walk(2)
    motion = Motion(
        character="Tom", joint_names=names, root_position=to_wire(root), rotations=to_wire(rotations)
    )
    (tom,) = animation_message(PipelineResult(doc_id="d", version=1, motions={"Tom": motion}))["characters"]
    for j, name in enumerate(names):
        p = tom["parents"][j]
        expected_parent = skeleton.PARENTS[skeleton.JOINT_INDEX[name]]
        assert (p < 0) == (expected_parent < 0)
        if p >= 0:
            assert names[p] == skeleton.JOINT_NAMES[expected_parent]
    offsets = _f32(tom["offsets"]).reshape(-1, 3)
    np.testing.assert_allclose(offsets[0], skeleton.REST_OFFSETS[skeleton.JOINT_INDEX[names[0]]], rtol=1e-6)


def test_objects_carry_placement_and_one_mesh_url_per_variant() -> None:
    desk = PlacedObject(
        id="desk",
        category="desk",
        attributes={"colour": "red"},
        seed=2,
        position=(1.0, 0.0, -0.5),
        yaw=0.5,
        scale=(1.0, 1.2, 1.0),
    )
    same_variant = PlacedObject(id="desk#2", category="desk", attributes={"colour": "red"}, seed=2)
    other = PlacedObject(id="desk#3", category="desk", attributes={"colour": "blue"}, seed=2)
    scene = Scene(
        room=Room(room_type="office", width=5, depth=4, height=2.7), objects=[desk, same_variant, other]
    )
    msg = animation_message(PipelineResult(doc_id="d", version=1, scene=scene))
    assert msg["room"] == {"room_type": "office", "width": 5, "depth": 4, "height": 2.7}
    first = msg["objects"][0]
    assert first["position"] == [1.0, 0.0, -0.5] and first["yaw"] == 0.5 and first["scale"] == [1.0, 1.2, 1.0]
    assert mesh_url(desk) == mesh_url(same_variant) != mesh_url(other)
    assert first["mesh_url"].startswith("/api/meshes/desk.glb?seed=2&attributes=")


def test_diagnostics_keep_document_offsets_sorted_by_position() -> None:
    doc = Document.from_text("d", "A desk$. Eve flies.")
    s1, s2 = doc.sentences
    result = PipelineResult(
        doc_id="d",
        version=0,
        sentences=[
            SentenceView(s1.id, s1.start, s1.end, s1.text, "scene"),
            SentenceView(s2.id, s2.start, s2.end, s2.text, "action"),
        ],
        diagnostics={
            s2.id: [Diagnostic(code="W201", message="unknown verb 'flies'", span=Span(13, 18))],
            s1.id: [Diagnostic(code="W101", message="x", span=Span(2, 6), severity="info")],
        },
        commands=[(s2.id, Command(kind="camera", value="left"))],
    )
    msg = diagnostics_message(result, doc)
    assert [d["code"] for d in msg["diagnostics"]] == ["W101", "W201"]
    assert doc.text[msg["diagnostics"][1]["start"] : msg["diagnostics"][1]["end"]] == "flies"
    assert [s["kind"] for s in msg["sentences"]] == ["scene", "action"]
    assert animation_message(result)["commands"][0]["value"] == "left"


def test_before_the_parser_answers_sentences_come_from_the_document() -> None:
    doc = Document.from_text("d", "A desk$. Eve walks.")
    msg = diagnostics_message(PipelineResult(doc_id="d", version=0, unavailable={"parse": "no"}), doc)
    assert [(s["start"], s["end"], s["kind"]) for s in msg["sentences"]] == [
        (0, 8, "unknown"),
        (9, 19, "unknown"),
    ]
    assert msg["unavailable"] == {"parse": "no"}
