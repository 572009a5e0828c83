"""Animation messages per client: entries a client holds travel as `unchanged` stubs, the rest in full."""

from __future__ import annotations

import base64
import json

import msgpack
import msgspec
import numpy as np
from scipy.spatial.transform import Rotation

from proto.motion_data import Motion, Segment
from proto.scene import PlacedObject, Room, Scene
from services.gateway.delta import CharacterCache, Holdings, encode_animation
from services.gateway.messages import animation_message
from services.orchestrator.pipeline import PipelineResult
from wana.arrays import to_wire
from wana.domain import skeleton


def _motion(name: str, frames: int, seed: int) -> tuple[Motion, np.ndarray]:
    rng = np.random.default_rng(seed)
    rotations = Rotation.from_rotvec(rng.normal(0, 0.3, (frames * skeleton.N_JOINTS, 3))).as_quat()
    rotations = rotations.reshape(frames, skeleton.N_JOINTS, 4).astype(np.float32)
    root = np.zeros((frames, 3), np.float32)
    root[:, 0] = np.linspace(0, 1, frames)
    motion = Motion(
        character=name,
        joint_names=list(skeleton.JOINT_NAMES),
        root_position=to_wire(root),
        rotations=to_wire(rotations),
        segments=[Segment(index=0, action="walk", start_frame=0, end_frame=frames, sentence_id="s1")],
    )
    return motion, rotations


def _scene(desk_x: float) -> Scene:
    desk = PlacedObject(id="desk", category="desk", position=(desk_x, 0.0, 0.0))
    chair = PlacedObject(id="chair", category="chair", position=(0.0, 0.0, 1.0))
    return Scene(room=Room(room_type="office", width=5.0, depth=4.0, height=2.8), objects=[desk, chair])


def _rotations(entry: dict, frames: int) -> np.ndarray:
    return np.frombuffer(base64.b64decode(entry["rotations"]), "<f4").reshape(frames, skeleton.N_JOINTS, 4)


def test_a_client_holding_nothing_gets_every_entry_in_full_with_its_arrays() -> None:
    eve, eve_rot = _motion("Eve", 10, 1)
    tom, tom_rot = _motion("Tom", 14, 2)
    result = PipelineResult(doc_id="d", version=1, scene=_scene(1.0), motions={"Tom": tom, "Eve": eve})
    text, holds, stubs = encode_animation(result, CharacterCache()).text_for(Holdings())
    msg = json.loads(text)
    assert stubs == 0 and msg["type"] == "animation" and msg["version"] == 1 and msg["frames"] == 14
    assert [c["name"] for c in msg["characters"]] == ["Eve", "Tom"]
    np.testing.assert_array_equal(_rotations(msg["characters"][0], 10), eve_rot)
    np.testing.assert_array_equal(_rotations(msg["characters"][1], 14), tom_rot)
    assert [o["id"] for o in msg["objects"]] == ["desk", "chair"] and msg["room"]["width"] == 5.0
    assert holds.characters == {c["hash"] for c in msg["characters"]} and len(holds.characters) == 2
    assert msgpack.unpackb(msgpack.packb(msg)) == msg  # plain builtins: any msgpack or JSON library reads it


def test_the_full_message_equals_the_one_the_rest_of_the_gateway_builds() -> None:
    eve, _ = _motion("Eve", 6, 3)
    result = PipelineResult(doc_id="d", version=4, scene=_scene(0.5), motions={"Eve": eve})
    assert encode_animation(result, CharacterCache()).full() == animation_message(result)


def test_entries_the_client_holds_are_sent_as_stubs_and_changed_ones_in_full() -> None:
    cache = CharacterCache()
    eve, _ = _motion("Eve", 10, 1)
    tom, tom_rot = _motion("Tom", 14, 2)
    first = encode_animation(
        PipelineResult(doc_id="d", version=1, scene=_scene(1.0), motions={"Eve": eve, "Tom": tom}), cache
    )
    _, held, _ = first.text_for(Holdings())
    eve2, eve2_rot = _motion("Eve", 12, 5)  # Eve's action changed; Tom is equal (a new, equal object)
    tom_again, _ = _motion("Tom", 14, 2)
    second = encode_animation(
        PipelineResult(doc_id="d", version=2, scene=_scene(2.0), motions={"Eve": eve2, "Tom": tom_again}),
        cache,
    )
    text, held2, stubs = second.text_for(held)
    msg = json.loads(text)
    eve_entry, tom_entry = msg["characters"]
    np.testing.assert_array_equal(_rotations(eve_entry, 12), eve2_rot)
    assert eve_entry["hash"] != json.loads(first.text_for(Holdings())[0])["characters"][0]["hash"]
    assert set(tom_entry) == {"name", "hash", "unchanged"} and tom_entry["unchanged"] is True
    assert tom_entry["name"] == "Tom" and tom_entry["hash"] in held.characters
    desk, chair = msg["objects"]
    assert desk["position"] == [2.0, 0.0, 0.0] and "unchanged" not in desk  # moved: sent in full
    assert set(chair) == {"id", "hash", "unchanged"}  # did not move: a stub
    assert stubs == 2 and msg["frames"] == 14
    assert held2.characters == {eve_entry["hash"], tom_entry["hash"]}
    # The stub stands for exactly the arrays the client already has.
    full_tom = second.full()["characters"][1]
    np.testing.assert_array_equal(_rotations(full_tom, 14), tom_rot)


def test_a_character_whose_motion_hashes_the_same_reuses_its_encoded_entry() -> None:
    cache = CharacterCache()
    eve, _ = _motion("Eve", 8, 1)
    (first,), _ = cache.entries({"Eve": eve})
    (again,), timing = cache.entries({"Eve": _motion("Eve", 8, 1)[0]})
    (changed,), _ = cache.entries({"Eve": _motion("Eve", 8, 9)[0]})
    assert again is first and timing == [{"fps": 30, "frames": 8}]
    assert changed.hash != first.hash and changed.full != first.full


def test_only_the_last_message_counts_as_held() -> None:
    cache = CharacterCache()
    walk, _ = _motion("Eve", 8, 1)
    run, _ = _motion("Eve", 8, 2)
    held = Holdings()
    for version, motion in enumerate([walk, run, walk]):
        anim = encode_animation(PipelineResult(doc_id="d", version=version, motions={"Eve": motion}), cache)
        text, held, stubs = anim.text_for(held)
        assert stubs == 0 and "rotations" in json.loads(text)["characters"][0]


def test_a_character_whose_face_alone_changed_is_still_sent_as_unchanged() -> None:
    cache = CharacterCache()
    eve, _ = _motion("Eve", 8, 1)
    smiling = msgspec.structs.replace(eve, expression=to_wire(np.full((8, 4), 0.5, np.float32)))
    first = encode_animation(PipelineResult(doc_id="d", version=1, motions={"Eve": eve}), cache)
    _, held, _ = first.text_for(Holdings())
    second = encode_animation(PipelineResult(doc_id="d", version=2, motions={"Eve": smiling}), cache)
    text, _, stubs = second.text_for(held)
    assert stubs == 1 and json.loads(text)["characters"][0]["unchanged"] is True
    moved = msgspec.structs.replace(eve, root_position=to_wire(np.ones((8, 3), np.float32)))
    third = encode_animation(PipelineResult(doc_id="d", version=3, motions={"Eve": moved}), cache)
    assert third.text_for(held)[2] == 0


def _padded(motion: Motion, hold: int) -> Motion:
    """The motion with its last pose held for ``hold`` more frames, as the orchestrator pads it."""
    from wana.arrays import from_wire

    rot, root = from_wire(motion.rotations), from_wire(motion.root_position)
    frames = len(rot)
    return msgspec.structs.replace(
        motion,
        rotations=to_wire(np.concatenate([rot, np.repeat(rot[-1:], hold, 0)])),
        root_position=to_wire(np.concatenate([root, np.repeat(root[-1:], hold, 0)])),
        segments=[
            *motion.segments,
            Segment(index=1, action="hold", start_frame=frames, end_frame=frames + hold),
        ],
    )


def test_a_longer_held_end_is_the_same_entry_and_the_story_keeps_its_length() -> None:
    from services.gateway.messages import character_entry, motion_hash

    tom, rotations = _motion("Tom", 30, seed=4)
    short, long = _padded(tom, 10), _padded(tom, 90)
    assert motion_hash(short) == motion_hash(long)
    entry = character_entry(long)
    assert entry["frames"] == 31  # the motion, then its last pose once: the editor holds it from there
    np.testing.assert_array_equal(_rotations(entry, 31)[:30], rotations)
    assert entry["segments"][-1] == {
        **entry["segments"][-1],
        "action": "hold",
        "start_frame": 30,
        "end_frame": 31,
    }
    result = PipelineResult(doc_id="d", version=1, motions={"Tom": long})
    assert animation_message(result)["frames"] == 120
    moved = _padded(_motion("Tom", 30, seed=5)[0], 90)
    assert motion_hash(moved) != motion_hash(long)
