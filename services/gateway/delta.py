"""Animation messages that send each client only what changed since the last animation it received.

Every character (and object) entry of an animation message carries a content hash. The gateway remembers,
per WebSocket client, the hashes of the entries in the last animation message it sent there (`Holdings`);
an entry whose hash the client holds travels as a stub `{"name", "hash", "unchanged": true}` (objects:
`{"id", "hash", "unchanged": true}`), and the client fills it in from what it kept. A new or reconnecting
client holds nothing and gets every entry in full; so does a client that sends `resume`.

Entries are encoded to JSON once per compute, in the compute thread (`EncodedAnimation`), and a
character whose Motion hashes the same as in the previous compute reuses its encoded text
(`CharacterCache`); on the event loop, a client's message is only a join of pre-encoded strings.
"""

from __future__ import annotations

import base64
from dataclasses import dataclass, field
from typing import Any

import msgspec
import numpy as np

from proto.motion_data import Motion
from services.gateway import animwire, messages
from services.orchestrator.pipeline import PipelineResult

_json = msgspec.json.Encoder()


def encode_json(message: Any) -> str:
    """Compact JSON text of a message made of builtins (NaN and infinities become null)."""
    return _json.encode(message).decode("utf-8")


@dataclass(frozen=True)
class EncodedEntry:
    """One character or object entry, encoded both ways."""

    key: str  # the character's name or the object's id
    hash: str  # content hash: equal hash, equal entry
    full: str  # JSON of the whole entry
    stub: str  # JSON of {"name"|"id", "hash", "unchanged": true}


@dataclass
class BinaryCharacter:
    """One character for binary frames: its quantised frames, and a patch against its previous version."""

    meta: dict[str, Any]  # the entry's fields but its arrays
    frames: animwire.Quantised
    patch: animwire.BinaryEntry | None = None  # against the previous version's hash (`patch.meta["patch"]`)
    _full: animwire.BinaryEntry | None = None

    def full(self) -> animwire.BinaryEntry:
        """Every frame (built once, when a client that holds no earlier version asks)."""
        if self._full is None:
            self._full = animwire.character_entry(self.meta, self.frames)
        return self._full


def encode_entry(entry: dict[str, Any], key_field: str) -> EncodedEntry:
    """Encode an entry (it must carry `hash` and `key_field`) in full and as an `unchanged` stub."""
    key, digest = str(entry[key_field]), str(entry["hash"])
    stub = {key_field: key, "hash": digest, "unchanged": True}
    return EncodedEntry(key=key, hash=digest, full=encode_json(entry), stub=encode_json(stub))


@dataclass(frozen=True)
class Holdings:
    """What one client holds: the hashes of the entries of the last animation message it was sent."""

    characters: frozenset[str] = frozenset()
    objects: frozenset[str] = frozenset()


@dataclass
class CharacterCache:
    """Per document: each character's encoded entry, reused while `messages.motion_hash` stays the same.

    Building a character's entry (base64 of its arrays, JSON) costs milliseconds per thousand frames;
    hashing its Motion costs less, and an unchanged character then costs nothing more.
    """

    _by_name: dict[str, tuple[str, EncodedEntry, int, int, BinaryCharacter]] = field(default_factory=dict)
    binary: list[BinaryCharacter] = field(default_factory=list)  # of the last `entries`, in the same order

    def entries(self, motions: dict[str, Motion]) -> tuple[list[EncodedEntry], list[dict[str, int]]]:
        """Encoded entries of the characters sorted by name, and each one's `fps` and `frames`.

        A character that changed also gets its binary patch against its previous version (`binary`).

        Raises:
            ValueError: a motion whose arrays disagree in shape.
        """
        encoded: list[EncodedEntry] = []
        timing: list[dict[str, int]] = []
        binary: list[BinaryCharacter] = []
        kept: dict[str, tuple[str, EncodedEntry, int, int, BinaryCharacter]] = {}
        for name, motion in sorted(motions.items()):
            digest = messages.motion_hash(motion)
            cached = self._by_name.get(name)
            if cached is None or cached[0] != digest:
                entry = messages.character_entry(motion, digest)
                bin_char = _binary_character(entry, cached[4] if cached else None)
                cached = (
                    digest,
                    encode_entry(entry, "name"),
                    int(entry["fps"]),
                    int(entry["frames"]),
                    bin_char,
                )
            kept[name] = cached
            encoded.append(cached[1])
            timing.append({"fps": cached[2], "frames": cached[3]})
            binary.append(cached[4])
        self._by_name = kept  # characters no longer in the document are forgotten
        self.binary = binary
        return encoded, timing


def _f32(b64: str) -> np.ndarray:
    return np.frombuffer(base64.b64decode(b64), "<f4")


def _binary_character(entry: dict[str, Any], previous: BinaryCharacter | None) -> BinaryCharacter:
    """The binary form of a character entry, patched against its previous version when there is one."""
    frames, joints = int(entry["frames"]), len(entry["joints"])
    present = entry.get("present")
    q = animwire.Quantised.of(
        _f32(entry["rotations"]).reshape(frames, joints, 4),
        _f32(entry["root_position"]).reshape(frames, 3),
        None if present is None else _f32(present),
    )
    meta = {k: v for k, v in entry.items() if k not in ("rotations", "root_position", "present")}
    out = BinaryCharacter(meta, q)
    if previous is not None and previous.frames.rotations.shape[1:] == q.rotations.shape[1:]:
        out.patch = animwire.character_entry(meta, q, (str(previous.meta["hash"]), previous.frames))
    return out


@dataclass
class EncodedAnimation:
    """One version's animation message, pre-encoded; `text_for` makes the text one client is sent."""

    head: dict[str, Any]  # messages.animation_head: every field but `objects` and `characters`
    objects: list[EncodedEntry]
    characters: list[EncodedEntry]
    binary: list[BinaryCharacter] = field(default_factory=list)  # the characters' binary forms, same order
    _packed: dict[tuple[str, ...], bytes] = field(
        default_factory=dict
    )  # frames by what each entry is sent as

    @property
    def version(self) -> int:
        return int(self.head["version"])

    def text_for(self, held: Holdings) -> tuple[str, Holdings, int]:
        """The JSON text for a client holding `held`.

        Returns:
            (text, what the client holds once it has read it, how many entries were sent as stubs).
        """
        stubs = 0
        parts: dict[str, list[str]] = {"objects": [], "characters": []}
        for name, entries, hashes in (
            ("objects", self.objects, held.objects),
            ("characters", self.characters, held.characters),
        ):
            for e in entries:
                if e.hash in hashes:
                    parts[name].append(e.stub)
                    stubs += 1
                else:
                    parts[name].append(e.full)
        head = encode_json(self.head)
        text = (
            f'{head[:-1]},"objects":[{",".join(parts["objects"])}],'
            f'"characters":[{",".join(parts["characters"])}]}}'
        )
        holds = Holdings(
            characters=frozenset(e.hash for e in self.characters),
            objects=frozenset(e.hash for e in self.objects),
        )
        return text, holds, stubs

    def binary_for(self, held: Holdings) -> tuple[bytes, Holdings, int]:
        """The binary frame for a client holding `held` (services.gateway.animwire): stubs for what it holds,
        patches against the previous version where it holds that, else every frame.

        Returns:
            (frame, what the client holds once it has read it, how many entries were sent as stubs).
        """
        kinds = [("stub" if e.hash in held.objects else "full") for e in self.objects]
        for e, b in zip(self.characters, self.binary, strict=True):
            if e.hash in held.characters:
                kinds.append("stub")
            elif b.patch is not None and b.patch.meta["patch"] in held.characters:
                kinds.append("patch")
            else:
                kinds.append("full")
        holds = Holdings(
            characters=frozenset(e.hash for e in self.characters),
            objects=frozenset(e.hash for e in self.objects),
        )
        key = tuple(kinds)
        if key not in self._packed:  # clients that hold the same get the same frame: packed once
            n = len(self.objects)
            objects = [
                e.stub if k == "stub" else e.full for e, k in zip(self.objects, kinds[:n], strict=True)
            ]
            characters = []
            for e, b, k in zip(self.characters, self.binary, kinds[n:], strict=True):
                if k == "stub":
                    characters.append(animwire.stub_entry(e.key, e.hash))
                elif k == "patch" and b.patch is not None:
                    characters.append(b.patch)
                else:
                    characters.append(b.full())
            self._packed[key] = animwire.pack(self.head, objects, characters)
        return self._packed[key], holds, key.count("stub")

    def full(self) -> dict[str, Any]:
        """The whole message as a dict, every entry in full (decoded again: for tests and tools)."""
        text, _, _ = self.text_for(Holdings())
        message: dict[str, Any] = msgspec.json.decode(text)
        return message


def encode_animation(
    result: PipelineResult, cache: CharacterCache, *, compute_ms: float = 0.0
) -> EncodedAnimation:
    """Build and encode one version's animation message (run it off the event loop).

    Args:
        result: the pipeline's result.
        cache: the document's character cache (updated: it then holds this version's characters).
        compute_ms: how long the compute took (reported in `stats`).
    """
    characters, timing = cache.entries(result.motions)
    objects = (
        [encode_entry(messages.object_entry(o), "id") for o in result.scene.objects]
        if result.scene is not None
        else []
    )
    head = messages.animation_head(result, timing, compute_ms=compute_ms)
    return EncodedAnimation(head=head, objects=objects, characters=characters, binary=list(cache.binary))
