"""Binary animation frames for the live WebSocket (`?wire=binary`): quantised characters, patched per run.

A JSON animation message carries each character as base64 of float32 arrays: about 400 bytes a frame,
every frame, whenever any of the character's frames changed. An edit of one sentence changes few frames,
but the story's time line moves every later frame by the edited sentence's change of length, and moods
and glances change others a little. So the editor is sent animation messages as one binary frame:

    b"WAN2" | zlib( u32 little-endian header length | header JSON (UTF-8) | zero padding to 8 | blobs )

The header is the animation message with `blobs`: [offset, bytes, dtype, shape] in the blob section
(each at a multiple of 8; dtype "i16", "u32" or "u8"). A character entry carries `ops` and three blobs
(from its `blob_base`): residual rotations (int16, quaternion component x `QUAT_SCALE`), residual root
positions (the bits of float32, as uint32) and residual presence (uint8). Each op [n, src, residual]
copies n held frames from src (src -1: zeros) and, when residual is 1, adds the next n residual rows
(wrapping integer sums). An entry with `patch` (the held version's hash) is rebuilt from that version;
without it, from zeros (every frame). Rows are compared after quantisation, so a client that applies a
patch holds exactly what a full entry would have given it (`Quantised`).

Each blob of R rows and C columns of B-byte integers is stored filtered (`"filter": "delta-planes"`), so
that deflate finds the runs a smooth motion makes: row r minus row r - 1 (wrapping; row 0 as it is),
then column by column (each column's R values together), then byte plane by byte plane (the low bytes of
every value, then the next bytes): byte b of column c, row r is at b * C * R + c * R + r. A residual of a
new piece of motion changes a little from frame to frame, so its deltas are small numbers whose high
bytes are mostly zero or 255. (In a 3-character document this halves the bytes of a one-word edit.)

Large JSON messages to a binary client (the diagnostics deltas after an edit) travel as
b"WJZ1" | zlib(JSON text) (`compress_text`).
"""

from __future__ import annotations

import struct
import zlib
from dataclasses import dataclass
from typing import Any

import msgspec
import numpy as np

MAGIC = b"WAN2"
TEXT_MAGIC = b"WJZ1"  # a zlib-compressed JSON message
COMPRESS_TEXT_MIN = 1024  # JSON messages from this many bytes on are worth compressing
QUAT_SCALE = 32767.0  # an int16 unit of a quaternion component: about 0.0035 degrees
_DTYPES: dict[str, np.dtype[Any]] = {"i16": np.dtype("<i2"), "u32": np.dtype("<u4"), "u8": np.dtype("u1")}
_NAMES = {v: k for k, v in _DTYPES.items()}
_json = msgspec.json.Encoder()


@dataclass(frozen=True)
class Quantised:
    """One character's frames as the live client holds them (what a patch is computed against)."""

    rotations: np.ndarray  # (T, J * 4) int16, component x QUAT_SCALE
    root: np.ndarray  # (T, 3) float32 metres
    present: np.ndarray | None  # (T,) uint8, None: always on stage

    @classmethod
    def of(cls, rotations: np.ndarray, root: np.ndarray, present: np.ndarray | None) -> Quantised:
        """Quantise (T, J, 4) rotations, (T, 3) root positions and (T,) presence."""
        rot = np.asarray(rotations, dtype=np.float64).reshape(len(rotations), -1)
        q = np.clip(np.rint(rot * QUAT_SCALE), -32767, 32767).astype("<i2")
        pres = None if present is None else (np.asarray(present) > 0.5).astype("u1")
        return cls(q, np.ascontiguousarray(root, dtype="<f4").reshape(len(root), 3), pres)

    @property
    def frames(self) -> int:
        return len(self.rotations)


def _row_table(q: Quantised) -> np.ndarray:
    """(T, row bytes) uint8: each frame's rotation, root and presence bytes side by side."""
    pres = q.present if q.present is not None else np.ones(q.frames, "u1")
    return np.concatenate([q.rotations.view("u1"), q.root.view("u1"), pres[:, None]], axis=1)


def ops_between(old: Quantised | None, new: Quantised) -> tuple[list[list[int]], Quantised]:
    """[n, src, residual] runs that rebuild `new` from `old`, covering new's frames in order, and the residuals.

    A run copies the held frames src, src + 1, ... (src -1: from zeros); with residual 1 it adds the next n
    rows of the residuals to them (wrapping integer sums: int16 rotations, the root's float32 bits as
    uint32, uint8 presence). A new frame equal to a held one continues the current copy or starts one from
    the first held frame equal to it (a frame moved in time by an edit earlier in the story); any other
    frame is a residual against the closest held frame at one of the offsets the copies found (a frame
    a mood or a glance changed a little), which compresses to a few bytes. `old` None: all from zeros.
    """
    new_rows = [r.tobytes() for r in _row_table(new)]
    old_rows = [r.tobytes() for r in _row_table(old)] if old is not None else []
    where: dict[bytes, int] = {}
    for i, r in enumerate(old_rows):
        where.setdefault(r, i)
    src = np.full(new.frames, -1)  # the held frame each new frame is built on (-1: zeros)
    exact = np.zeros(new.frames, bool)
    for f, row in enumerate(new_rows):
        nxt = src[f - 1] + 1 if f and exact[f - 1] else -1
        if 0 <= nxt < len(old_rows) and old_rows[nxt] == row:
            src[f], exact[f] = nxt, True
        elif row in where:
            src[f], exact[f] = where[row], True
    if old is not None and not exact.all():
        src[~exact] = _nearest_sources(old, new, src, exact)
    ops: list[list[int]] = []
    for f in range(new.frames):
        residual = 0 if exact[f] else 1
        last = ops[-1] if ops else None
        if last is not None and last[2] == residual and (last[1] < 0) == (src[f] < 0):
            if src[f] < 0 or last[1] + last[0] == src[f]:
                last[0] += 1
                continue
        ops.append([1, int(src[f]), residual])
    rows = np.flatnonzero(~exact)
    return ops, _residuals(old, new, rows, src[rows])


HYSTERESIS = 0.8  # a residual frame changes its source only for one that leaves at most this share


def _nearest_sources(old: Quantised, new: Quantised, src: np.ndarray, exact: np.ndarray) -> np.ndarray:
    """For each inexact new frame, the held frame closest to it among a few offsets in time: none, the
    story's change of length, and those of the exact copies (the offsets an edit moved frames by)."""
    frames = np.flatnonzero(~exact)
    shifts = {0, old.frames - new.frames, *(src[exact] - np.flatnonzero(exact)).tolist()}
    cand = sorted(shifts)[:32]
    target = new.rotations[frames].astype(np.int32)
    cost = np.empty((len(cand) + 1, len(frames)))
    cost[0] = np.abs(target).sum(axis=1)  # from zeros
    for k, d in enumerate(cand, start=1):
        idx = frames + d
        ok = (idx >= 0) & (idx < old.frames)
        held = old.rotations[np.clip(idx, 0, max(old.frames - 1, 0))].astype(np.int32)
        cost[k] = np.where(ok, np.abs(target - held).sum(axis=1), np.inf)
    best = np.argmin(cost, axis=0).tolist()
    columns, at = cost.T.tolist(), frames.tolist()
    choice = list(best)
    for i in range(1, len(at)):  # keep the previous frame's offset unless another is clearly closer
        prev = choice[i - 1]
        if at[i] == at[i - 1] + 1 and columns[i][best[i]] > HYSTERESIS * columns[i][prev]:
            choice[i] = prev
    offsets = np.asarray([0, *cand])
    out = frames + offsets[np.asarray(choice, dtype=int)]
    return np.where(np.asarray(choice) == 0, -1, out)


def _residuals(old: Quantised | None, new: Quantised, rows: np.ndarray, src: np.ndarray) -> Quantised:
    """new's frames `rows` minus old's frames `src` (-1: zeros), wrapping."""
    width = new.rotations.shape[1]
    have = src >= 0
    b_rot = np.zeros((len(rows), width), "<i2")
    b_root = np.zeros((len(rows), 3), "<u4")
    b_pres = np.zeros(len(rows), "u1")
    if old is not None and np.any(have):
        b_rot[have] = old.rotations[src[have]]
        b_root[have] = old.root.view("<u4")[src[have]]
        old_pres = old.present if old.present is not None else np.ones(old.frames, "u1")
        b_pres[have] = old_pres[src[have]]
    with np.errstate(over="ignore"):
        rot = (new.rotations[rows].astype("<i2") - b_rot).astype("<i2")
        root = (new.root.view("<u4")[rows] - b_root).astype("<u4")
        new_pres = new.present if new.present is not None else np.ones(new.frames, "u1")
        pres = (new_pres[rows] - b_pres).astype("u1")
    return Quantised(rot, root.view("<f4"), pres)


def apply_ops(
    old: Quantised | None, ops: list[list[int]], residual: Quantised, has_present: bool
) -> Quantised:
    """Rebuild the new frames from the held ones (what the editor does; here for tests and tools)."""
    width = residual.rotations.shape[1] if old is None else old.rotations.shape[1]
    frames = sum(n for n, _, _ in ops)
    rot = np.zeros((frames, width), "<i2")
    root = np.zeros((frames, 3), "<u4")
    pres = np.zeros(frames, "u1")
    old_pres = (
        None if old is None else (old.present if old.present is not None else np.ones(old.frames, "u1"))
    )
    res_pres = residual.present if residual.present is not None else np.zeros(residual.frames, "u1")
    at = k = 0
    with np.errstate(over="ignore"):
        for n, src, add in ops:
            if src >= 0 and old is not None and old_pres is not None:  # (old_pres: set with old)
                rot[at : at + n] = old.rotations[src : src + n]
                root[at : at + n] = old.root.view("<u4")[src : src + n]
                pres[at : at + n] = old_pres[src : src + n]
            if add:
                rot[at : at + n] += residual.rotations[k : k + n]
                root[at : at + n] += residual.root.view("<u4")[k : k + n]
                pres[at : at + n] += res_pres[k : k + n]
                k += n
            at += n
    return Quantised(rot, root.view("<f4"), pres if has_present else None)


@dataclass(frozen=True)
class BinaryEntry:
    """One entry's header fields, its arrays referenced as {"blob": i} (i local to the entry), and them."""

    meta: dict[str, Any]
    blobs: tuple[np.ndarray, ...] = ()


def character_entry(
    entry: dict[str, Any], new: Quantised, base: tuple[str, Quantised] | None = None
) -> BinaryEntry:
    """A character entry (messages.character_entry's fields) rebuilt by `ops` from the held version `base`
    (its hash and frames; joints, parents and offsets are then the held ones) or, base None, from zeros."""
    ops, res = ops_between(base[1] if base else None, new)
    keep = ("name", "hash", "fps", "frames", "segments")
    meta = {k: v for k, v in entry.items() if k not in ("rotations", "root_position", "present")}
    if base is not None:
        meta = {k: entry[k] for k in keep} | {"patch": base[0]}
    meta |= {
        "ops": ops,
        "scale": QUAT_SCALE,
        "has_present": new.present is not None,
        "rotations": {"blob": 0},
        "root_position": {"blob": 1},
        "present": {"blob": 2},
    }
    return BinaryEntry(meta, (res.rotations, res.root.view("<u4"), np.asarray(res.present, "u1")))


def stub_entry(name: str, digest: str) -> BinaryEntry:
    return BinaryEntry({"name": name, "hash": digest, "unchanged": True})


def _filter(a: np.ndarray) -> bytes:
    """A blob's bytes, filtered as the module docstring says (delta over rows, columns, byte planes)."""
    rows = a.reshape(len(a), int(np.prod(a.shape[1:])))  # (R, C); a 1-D blob is one column
    d = rows.copy()
    with np.errstate(over="ignore"):
        d[1:] = rows[1:] - rows[:-1]  # wrapping in the blob's own integer type
    size = a.dtype.itemsize
    planes = np.ascontiguousarray(d.T).view("u1").reshape(d.shape[1], d.shape[0], size)
    return np.ascontiguousarray(planes.transpose(2, 0, 1)).tobytes()


def _unfilter(data: bytes, dtype: np.dtype[Any], shape: list[int]) -> np.ndarray:
    """The blob `_filter` stored as `data`."""
    n_rows = shape[0] if shape else 0
    n_cols = int(np.prod(shape[1:])) if len(shape) > 1 else 1
    size = dtype.itemsize
    planes = np.frombuffer(data, "u1").reshape(size, n_cols, n_rows)
    d = np.ascontiguousarray(planes.transpose(1, 2, 0)).view(dtype).reshape(n_cols, n_rows).T
    with np.errstate(over="ignore"):
        rows = np.cumsum(d, axis=0, dtype=dtype) if n_rows else d
    return np.ascontiguousarray(rows).reshape(shape)


def pack(head: dict[str, Any], objects: list[str], characters: list[BinaryEntry]) -> bytes:
    """One binary animation frame: the message head, objects (their JSON texts) and character entries.

    Header and filtered blobs are compressed together (zlib): the residuals are mostly zeros and small
    deltas, and the header's segments and stubs are text.
    """
    blobs: list[np.ndarray] = []
    metas = []
    for c in characters:
        metas.append({**c.meta, "blob_base": len(blobs)} if c.blobs else c.meta)
        blobs.extend(c.blobs)
    table, offset, raw = [], 0, bytearray()
    for b in blobs:
        data = _filter(np.ascontiguousarray(b))
        table.append([offset, len(data), _NAMES[b.dtype], list(b.shape)])
        raw += data + b"\0" * (-len(data) % 8)
        offset = len(raw)
    head_json = _json.encode({**head, "characters": metas, "blobs": table, "filter": "delta-planes"}).decode(
        "utf-8"
    )
    text = f'{head_json[:-1]},"objects":[{",".join(objects)}]}}'.encode()
    pad = -(4 + len(text)) % 8
    body = struct.pack("<I", len(text)) + text + b"\0" * pad + bytes(raw)
    return MAGIC + zlib.compress(body, 6)


def unpack(data: bytes) -> tuple[dict[str, Any], list[np.ndarray]]:
    """The header and blobs of a binary animation frame (the Python reading, for tests and tools).

    Raises:
        ValueError: not a binary animation frame.
    """
    if data[:4] != MAGIC:
        raise ValueError("not a wana binary animation frame")
    body = zlib.decompress(data[4:])
    (length,) = struct.unpack("<I", body[:4])
    header: dict[str, Any] = msgspec.json.decode(body[4 : 4 + length])
    section = body[4 + length + (-(4 + length) % 8) :]
    blobs = []
    for offset, nbytes, dtype, shape in header["blobs"]:
        blobs.append(_unfilter(section[offset : offset + nbytes], _DTYPES[dtype], shape))
    return header, blobs


def compress_text(text: str) -> str | bytes:
    """A JSON message for a binary client: as it is when short, else b"WJZ1" | zlib(its UTF-8)."""
    raw = text.encode("utf-8")
    if len(raw) < COMPRESS_TEXT_MIN:
        return text
    return TEXT_MAGIC + zlib.compress(raw, 6)


def decompress_text(data: bytes) -> str:
    """The JSON text of a b"WJZ1" frame (`compress_text`).

    Raises:
        ValueError: not such a frame.
    """
    if data[:4] != TEXT_MAGIC:
        raise ValueError("not a compressed JSON frame")
    return zlib.decompress(data[4:]).decode("utf-8")


def entry_frames(entry: dict[str, Any], blobs: list[np.ndarray], held: Quantised | None) -> Quantised:
    """The frames a full or patch entry of an unpacked frame stands for (`held`: the patch's base)."""
    first = int(entry.get("blob_base", 0))
    rot, root, pres = blobs[first : first + 3]
    residual = Quantised(rot, root.view("<f4"), pres)
    return apply_ops(held if entry.get("patch") else None, entry["ops"], residual, bool(entry["has_present"]))
