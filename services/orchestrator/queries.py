"""Query nodes keyed by the content hash of their inputs, with early cutoff (salsa's backdating).

Vocabulary (salsa's): an *input* is a value set from outside (a sentence's text); a *query* is a derived
value computed by a function of inputs and other queries; its *memo* keeps the hash of the inputs it was
computed from and the hash of its result. A query re-runs only when its input hash changed; when the new
result hashes the same as the old one, downstream queries see an unchanged input and are reused.
Every query logs whether it ran or was reused, so tests can assert exactly what an edit recomputed.
"""

from __future__ import annotations

import hashlib
import threading
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any, Literal, TypeVar

import msgspec
import numpy as np

T = TypeVar("T")

_encoder = msgspec.msgpack.Encoder(enc_hook=lambda o: _enc_hook(o), order="deterministic")


def _enc_hook(obj: Any) -> Any:
    if isinstance(obj, np.ndarray):
        a = np.ascontiguousarray(obj)
        return [a.dtype.str, list(a.shape), a.tobytes()]
    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, (set, frozenset)):
        return sorted(obj)
    if hasattr(obj, "__dataclass_fields__"):
        return {k: getattr(obj, k) for k in obj.__dataclass_fields__}
    raise TypeError(f"cannot hash a {type(obj).__name__}")


def content_hash(value: Any) -> str:
    """A stable 128-bit hex digest of a value made of msgspec structs, dataclasses, arrays and builtins."""
    return hashlib.blake2b(_encoder.encode(value), digest_size=16).hexdigest()


@dataclass
class Memo:
    input_hash: str
    result_hash: str
    value: Any


@dataclass(frozen=True)
class LogEntry:
    revision: int
    key: str
    outcome: Literal["ran", "reused"]
    changed: bool  # for "ran": did the result differ from the previous one


@dataclass
class QueryEngine:
    """Memoises query results across revisions of one document."""

    revision: int = 0
    memos: dict[str, Memo] = field(default_factory=dict)
    log: list[LogEntry] = field(default_factory=list)
    _lock: threading.RLock = field(default_factory=threading.RLock)
    _start: int = 0  # where the current revision's entries begin in the log
    # a stage's own record of its last finished pass, by pass (stages/replay.py: the motion stage's
    # checkpoints); it only saves walking what the memos would answer, never decides a value
    traces: dict[str, Any] = field(default_factory=dict)

    def new_revision(self) -> int:
        self.revision += 1
        self._start = len(self.log)
        return self.revision

    def _entries(self, revision: int | None) -> list[LogEntry]:
        """The log entries of a revision (the current one without scanning the older revisions' entries)."""
        if revision is None or revision == self.revision:
            return [e for e in self.log[self._start :] if e.revision == self.revision]
        return [e for e in self.log if e.revision == revision]

    def fresh(self, key: str, inputs: Any) -> bool:
        """Whether `query(key, inputs, ...)` would reuse its memo (a stage batches the nodes that would not)."""
        with self._lock:
            memo = self.memos.get(key)
        return memo is not None and memo.input_hash == content_hash(inputs)

    def query(self, key: str, inputs: Any, compute: Callable[[], T]) -> T:
        """Return the memoised value of `key` for these inputs, computing it only when they changed."""
        input_hash = content_hash(inputs)
        memo, reused = self._memo_for(key, input_hash)
        if reused:
            return memo.value  # type: ignore[union-attr,no-any-return]
        value = compute()
        result_hash = content_hash(value)
        with self._lock:
            changed = memo is None or memo.result_hash != result_hash
            if not changed and memo is not None:
                value = memo.value  # backdate: keep the identical old value
            self.memos[key] = Memo(input_hash, result_hash, value)
            self.log.append(LogEntry(self.revision, key, "ran", changed))
        return value

    def _memo_for(self, key: str, input_hash: str) -> tuple[Memo | None, bool]:
        """The memo of ``key`` and whether it answers these inputs (then logged as reused)."""
        with self._lock:
            memo = self.memos.get(key)
            if memo is not None and memo.input_hash == input_hash:
                self.log.append(LogEntry(self.revision, key, "reused", False))
                return memo, True
        return memo, False

    def mark_reused(self, keys: Iterable[str]) -> None:
        """Log queries as reused without asking them: a stage that knows their inputs are the ones of their
        memos (a pass resumed from its checkpoint) logs what asking would have logged."""
        with self._lock:
            self.log.extend(LogEntry(self.revision, key, "reused", False) for key in keys)

    def query_unhashed(self, key: str, inputs: Any, compute: Callable[[], T]) -> T:
        """``query`` for a value too big to hash on every run (every character's whole motion): memoised by
        its input hash alone, logged like any query; it never backdates, so no node may key on its hash."""
        input_hash = content_hash(inputs)
        memo, reused = self._memo_for(key, input_hash)
        if reused:
            return memo.value  # type: ignore[union-attr,no-any-return]
        value = compute()
        with self._lock:
            self.memos[key] = Memo(input_hash, "", value)
            self.log.append(LogEntry(self.revision, key, "ran", True))
        return value

    def result_hash(self, key: str) -> str:
        return self.memos[key].result_hash

    def hash_of(self, key: str, value: object) -> str:
        """The content hash of a query's value: its memo's when the value is the memoised one (hashed once,
        when it was computed), else hashed now (a value that was not memoised, e.g. a failed parse)."""
        memo = self.memos.get(key)
        if memo is not None and memo.value is value and memo.result_hash:
            return memo.result_hash
        return content_hash(value)

    def ran(self, revision: int | None = None) -> list[str]:
        """Keys of the queries that ran at a revision (default: the current one), in order."""
        return [e.key for e in self._entries(revision) if e.outcome == "ran"]

    def reused(self, revision: int | None = None) -> list[str]:
        return [e.key for e in self._entries(revision) if e.outcome == "reused"]

    def forget(self, keep: Callable[[str], bool]) -> None:
        """Drop memos whose key fails `keep` (sentences that no longer exist)."""
        with self._lock:
            for key in [k for k in self.memos if not keep(k)]:
                del self.memos[key]

    def trim_log(self, keep_revisions: int = 50) -> None:
        floor = self.revision - keep_revisions
        if self.log and self.log[0].revision > floor:
            return  # nothing that old yet
        self.log = [e for e in self.log if e.revision > floor]
        self._start = next((i for i, e in enumerate(self.log) if e.revision == self.revision), len(self.log))
