"""Per-document sessions: persisted edits, and the incremental pipeline run over them.

`Orchestrator` owns the session database and the backend that reaches the services; `Session` is one open
document. `Session.edit` is acknowledged once the edit is committed to SQLite; `Session.compute` brings the
derived values (parse, scene, motion, ...) up to date, re-running only the query nodes whose inputs changed.
"""

from __future__ import annotations

import dataclasses
import threading
import uuid
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from proto.render import CastMember
from services.orchestrator.backend import Backend
from services.orchestrator.budget import Budget
from services.orchestrator.document import Document, TextChange
from services.orchestrator.pipeline import Pipeline, PipelineResult
from services.orchestrator.queries import QueryEngine
from services.orchestrator.store import SessionStore

Progress = Callable[[str, int, int], None]  # (stage, done, total)


@dataclass(frozen=True)
class EditAck:
    doc_id: str
    version: int  # the version this edit produced
    changed: list[str]  # ids of sentences whose text changed


@dataclass
class Session:
    doc: Document
    store: SessionStore
    pipeline: Pipeline
    engine: QueryEngine = field(default_factory=QueryEngine)
    lock: threading.RLock = field(default_factory=threading.RLock)  # guards the document (edits)
    compute_lock: threading.Lock = field(default_factory=threading.Lock)  # one pipeline run at a time
    last: PipelineResult | None = None
    # the user's own characters for this document's exports (story name -> rig), as `wana animate --cast`;
    # kept in the session database with the document (set_cast / drop_cast write through)
    cast: dict[str, CastMember] = field(default_factory=dict)

    @property
    def doc_id(self) -> str:
        return self.doc.doc_id

    def set_cast(self, name: str, glb: bytes) -> None:
        """Play story character ``name`` with the user's rig (a GLB or VRM file), kept with the document."""
        with self.lock:
            self.store.put_cast(self.doc_id, name, glb)
            self.cast[name] = CastMember(name=name, glb=glb)

    def drop_cast(self, name: str) -> bool:
        """Play ``name`` with the built-in character again; False when it had no rig of its own."""
        with self.lock:
            kept = self.store.delete_cast(self.doc_id, name)
            return self.cast.pop(name, None) is not None or kept

    def edit(self, base_version: int, changes: list[TextChange]) -> EditAck:
        """Apply and persist an edit; raises StaleEdit / BadEdit without changing anything."""
        with self.lock:
            snapshot = (self.doc.text, self.doc.version, list(self.doc.sentences), self.doc.next_id)
            changed = self.doc.apply(base_version, changes)
            try:
                self.store.append_edit(self.doc_id, self.doc.version, changes, self.doc.text)
            except BaseException:
                self.doc.text, self.doc.version, self.doc.sentences, self.doc.next_id = snapshot
                raise
            return EditAck(self.doc_id, self.doc.version, changed)

    def compute(
        self, *, stages: tuple[str, ...] | None = None, progress: Progress | None = None
    ) -> PipelineResult:
        """Bring every derived value up to date for the current version.

        Runs on a snapshot of the document, so edits are acknowledged while a compute is running; the
        result names the version it was computed for.
        """
        with self.lock:
            doc = dataclasses.replace(self.doc, sentences=list(self.doc.sentences))
        with self.compute_lock:
            self.engine.new_revision()
            result = self.pipeline.run(doc, self.engine, stages=stages, progress=progress)
            live = {s.id for s in doc.sentences}
            self.engine.forget(lambda key: not key.startswith("parse:") or key.split(":", 1)[1] in live)
            self.engine.trim_log()
            self.last = result
            return result


class Orchestrator:
    """Opens sessions over one SQLite file and one backend."""

    def __init__(
        self, db_path: str | Path, backend: Backend, *, seed: int = 0, budget: Budget | None = None
    ) -> None:
        self.store = SessionStore(db_path)
        self.backend = backend
        self.seed = seed
        self.budget = budget or Budget()  # what one compute of one document may spend
        self._sessions: dict[str, Session] = {}
        self._lock = threading.Lock()

    def create(self, text: str = "", *, doc_id: str | None = None, title: str = "") -> Session:
        doc_id = doc_id or uuid.uuid4().hex[:12]
        self.store.create(doc_id, text, title)
        return self.open(doc_id)

    def open(self, doc_id: str) -> Session:
        """The live session of a document, rebuilt from the database when not in memory."""
        with self._lock:
            session = self._sessions.get(doc_id)
            if session is None:
                doc = self.store.load(doc_id)
                session = Session(
                    doc, self.store, Pipeline(self.backend, doc_id=doc_id, seed=self.seed, budget=self.budget)
                )
                session.cast = {n: CastMember(name=n, glb=g) for n, g in self.store.cast(doc_id).items()}
                self._sessions[doc_id] = session
            return session

    def list(self) -> list[dict[str, object]]:
        return self.store.list()

    def delete(self, doc_id: str) -> None:
        """Forget a document: its session and everything stored about it."""
        with self._lock:
            self._sessions.pop(doc_id, None)
            self.store.delete(doc_id)

    def close(self) -> None:
        self.store.close()
