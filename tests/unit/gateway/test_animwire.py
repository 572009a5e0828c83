"""Binary animation frames: quantised characters, patched per run of frames against what a client holds.

The patch of a motion moved in time copies the held frames; a small change of a few joints travels as a
residual that compresses to little; the editor's JavaScript (editor/src/animwire.js, run by node) rebuilds
exactly the frames the gateway meant.
"""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from services.gateway import animwire
from services.gateway.delta import CharacterCache, Holdings, encode_animation
from services.orchestrator.pipeline import PipelineResult
from tests.unit.gateway.test_delta import _motion

REPO = Path(__file__).resolve().parents[3]
J = 24


def _frames(n: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """(n, J, 4) smoothly varying rotations and (n, 3) roots."""
    t = np.linspace(0, 4, n)[:, None]
    rng = np.random.default_rng(seed)
    rotvec = 0.3 * np.sin(t[..., None] * rng.uniform(0.5, 2, (J, 3)) + rng.uniform(0, 6, (J, 3)))
    rot = Rotation.from_rotvec(rotvec.reshape(-1, 3)).as_quat().reshape(n, J, 4)
    root = np.concatenate([t, np.full_like(t, 0.9), -t], axis=1)
    return rot, root


def _entry(name: str, digest: str, q: animwire.Quantised) -> dict:
    return {"name": name, "hash": digest, "fps": 30, "frames": q.frames, "segments": [], "joints": ["Hips"]}


def _roundtrip(old: animwire.Quantised | None, new: animwire.Quantised) -> tuple[bytes, animwire.Quantised]:
    base = None if old is None else ("h0", old)
    data = animwire.pack(
        {"type": "animation", "version": 2},
        [],
        [animwire.character_entry(_entry("Eve", "h1", new), new, base)],
    )
    header, blobs = animwire.unpack(data)
    return data, animwire.entry_frames(header["characters"][0], blobs, old)


def _same(a: animwire.Quantised, b: animwire.Quantised) -> bool:
    pa = a.present if a.present is not None else np.ones(a.frames, "u1")
    pb = b.present if b.present is not None else np.ones(b.frames, "u1")
    return (
        np.array_equal(a.rotations, b.rotations)
        and np.array_equal(a.root.view("u4"), b.root.view("u4"))
        and np.array_equal(pa, pb)
    )


def test_a_full_entry_rebuilds_its_quantised_frames_exactly_and_within_a_hundredth_of_a_degree() -> None:
    rot, root = _frames(300, 1)
    present = (np.arange(300) > 20).astype(np.float32)
    q = animwire.Quantised.of(rot, root, present)
    _, back = _roundtrip(None, q)
    assert _same(back, q)
    restored = back.rotations.reshape(300, J, 4) / animwire.QUAT_SCALE
    angle = 2 * np.degrees(
        np.arccos(np.clip(np.abs(np.sum(restored * rot, -1)) / np.linalg.norm(restored, axis=-1), 0, 1))
    )
    assert angle.max() < 0.01


def test_frames_moved_in_time_are_copied_and_a_new_piece_travels_alone() -> None:
    rot, root = _frames(400, 2)
    old = animwire.Quantised.of(rot[:300], root[:300], None)
    piece, piece_root = _frames(30, 9)  # an edited action: 30 new frames, everything after it 20 frames later
    new = animwire.Quantised.of(
        np.concatenate([rot[:100], piece, rot[110:300]]),
        np.concatenate([root[:100], piece_root, root[110:300]]),
        None,
    )
    data, back = _roundtrip(old, new)
    assert _same(back, new)
    full, _ = _roundtrip(None, new)
    alone, _ = _roundtrip(None, animwire.Quantised.of(piece, piece_root, None))
    assert len(data) < 0.3 * len(full), (len(data), len(full))
    assert len(data) < 1.3 * len(alone), (len(data), len(alone))  # the piece's own bytes and the ops
    header, _ = animwire.unpack(data)
    ops = header["characters"][0]["ops"]
    assert [op for op in ops if op[2] == 0] == [[100, 0, 0], [190, 110, 0]]


def test_a_small_change_of_a_few_joints_everywhere_is_a_residual_that_compresses_to_little() -> None:
    rot, root = _frames(600, 3)
    old = animwire.Quantised.of(rot, root, None)
    moody = rot.copy()
    nod = Rotation.from_rotvec([0.01, 0, 0])
    for j in (1, 2, 3):  # the spine a little more upright all along (a mood)
        moody[:, j] = (Rotation.from_quat(moody[:, j]) * nod).as_quat()
    new = animwire.Quantised.of(moody, root, None)
    data, back = _roundtrip(old, new)
    assert _same(back, new)
    full, _ = _roundtrip(None, new)
    assert len(data) < 0.5 * len(full), (len(data), len(full))


def test_the_gateway_sends_a_patch_to_a_client_holding_the_previous_version_and_a_stub_to_one_holding_this() -> (
    None
):
    cache = CharacterCache()
    eve, _ = _motion("Eve", 120, 1)
    first = encode_animation(PipelineResult(doc_id="d", version=1, motions={"Eve": eve}), cache)
    data1, held1, _ = first.binary_for(Holdings())
    eve2, _ = _motion("Eve", 130, 1)  # the same frames and ten more
    second = encode_animation(PipelineResult(doc_id="d", version=2, motions={"Eve": eve2}), cache)
    data2, held2, stubs = second.binary_for(held1)
    header1, blobs1 = animwire.unpack(data1)
    header2, blobs2 = animwire.unpack(data2)
    assert stubs == 0 and header2["characters"][0]["patch"] == header1["characters"][0]["hash"]
    held = animwire.entry_frames(header1["characters"][0], blobs1, None)
    rebuilt = animwire.entry_frames(header2["characters"][0], blobs2, held)
    assert _same(rebuilt, second.binary[0].frames)
    assert len(data2) < len(second.binary_for(Holdings())[0]) / 3
    again, _, stubs = second.binary_for(held2)
    assert stubs == 1 and animwire.unpack(again)[0]["characters"][0]["unchanged"] is True


NODE_CHECK = """
import { readFileSync } from "node:fs";
import { decodeFrame, rebuild } from "./editor/src/animwire.js";
const load = (p) => { const b = readFileSync(p); return b.buffer.slice(b.byteOffset, b.byteOffset + b.length); };
const first = await decodeFrame(load(process.argv[1]));
const held = rebuild(first.characters[0], null);
const second = await decodeFrame(load(process.argv[2]));
const now = rebuild(second.characters[0], held);
console.log(JSON.stringify({ rot: Array.from(now._q.rot), root: Array.from(now.root_position), pres: now.present && Array.from(now.present), frames: now.frames }));
"""


def test_the_editor_rebuilds_the_same_frames_from_a_patch(tmp_path: Path) -> None:
    node = shutil.which("node")
    if node is None:
        pytest.skip("needs node (the editor's JavaScript)")
    rot, root = _frames(200, 4)
    present = (np.arange(200) > 10).astype(np.float32)
    old = animwire.Quantised.of(rot[:150], root[:150], present[:150])
    new = animwire.Quantised.of(
        np.concatenate([rot[:50], rot[60:200]]),
        np.concatenate([root[:50], root[60:200]]) + 0.001,
        np.concatenate([present[:50], present[60:200]]),
    )
    first = animwire.pack(
        {"type": "animation"}, [], [animwire.character_entry(_entry("Eve", "h0", old), old)]
    )
    second = animwire.pack(
        {"type": "animation"}, [], [animwire.character_entry(_entry("Eve", "h1", new), new, ("h0", old))]
    )
    (tmp_path / "1.bin").write_bytes(first)
    (tmp_path / "2.bin").write_bytes(second)
    out = subprocess.run(
        [node, "--input-type=module", "-e", NODE_CHECK, str(tmp_path / "1.bin"), str(tmp_path / "2.bin")],
        cwd=REPO,
        capture_output=True,
        text=True,
        timeout=60,
        check=True,
    )
    got = json.loads(out.stdout)
    assert got["frames"] == new.frames
    assert np.array_equal(np.asarray(got["rot"], np.int16), new.rotations.ravel())
    assert np.array_equal(np.asarray(got["root"], np.float32), new.root.ravel())
    assert np.array_equal(np.asarray(got["pres"], np.float32), new.present.astype(np.float32))


def test_the_blob_filter_is_lossless_for_every_dtype_and_shape() -> None:
    rng = np.random.default_rng(5)
    for blob in (
        rng.integers(-32768, 32767, (37, 96), dtype=np.int64).astype("<i2"),
        rng.integers(0, 2**32 - 1, (11, 3), dtype=np.uint64).astype("<u4"),
        rng.integers(0, 255, 19).astype("u1"),
        np.zeros((0, 96), "<i2"),
    ):
        back = animwire._unfilter(animwire._filter(blob), blob.dtype, list(blob.shape))
        assert back.dtype == blob.dtype and np.array_equal(back, blob)


def test_a_new_piece_of_smooth_motion_costs_less_filtered_than_its_plain_bytes_deflated() -> None:
    import zlib

    rot, root = _frames(400, 6)
    new = animwire.Quantised.of(rot, root, None)
    data, back = _roundtrip(None, new)
    assert _same(back, new)
    plain = zlib.compress(new.rotations.tobytes() + new.root.tobytes(), 9)
    assert len(data) < 0.6 * len(plain), (len(data), len(plain))


def test_large_json_messages_travel_compressed_and_small_ones_as_text() -> None:
    small = json.dumps({"type": "ack", "version": 3})
    assert animwire.compress_text(small) == small
    big = json.dumps(
        {
            "type": "diagnostics",
            "verdicts": [{"reason": f"Eve walks (frames {i}-{i + 80})"} for i in range(200)],
        }
    )
    packed = animwire.compress_text(big)
    assert isinstance(packed, bytes) and len(packed) < len(big) / 4
    assert animwire.decompress_text(packed) == big


NODE_TEXT = """
import { readFileSync } from "node:fs";
import { decodeMessage } from "./editor/src/animwire.js";
const b = readFileSync(process.argv[1]);
console.log(JSON.stringify(await decodeMessage(b.buffer.slice(b.byteOffset, b.byteOffset + b.length))));
"""


def test_the_editor_reads_a_compressed_json_message(tmp_path: Path) -> None:
    node = shutil.which("node")
    if node is None:
        pytest.skip("needs node (the editor's JavaScript)")
    message = {
        "type": "diagnostics",
        "verdicts": [{"reason": f"Ann sits (frames {i}-{i + 9})"} for i in range(99)],
    }
    packed = animwire.compress_text(json.dumps(message))
    assert isinstance(packed, bytes)
    (tmp_path / "m.bin").write_bytes(packed)
    out = subprocess.run(
        [node, "--input-type=module", "-e", NODE_TEXT, str(tmp_path / "m.bin")],
        cwd=REPO,
        capture_output=True,
        text=True,
        timeout=60,
        check=True,
    )
    assert json.loads(out.stdout) == message
