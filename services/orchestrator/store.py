"""Sessions persisted in SQLite (WAL): a document's text, every acknowledged edit and its cast.

An edit is acknowledged only after its transaction commits, so it survives a crash of any process.
On open, the document is rebuilt from the latest snapshot plus the edits after it.
"""

from __future__ import annotations

import builtins
import json
import sqlite3
import threading
import time
from pathlib import Path

from services.orchestrator.document import Document, TextChange

_SCHEMA = """
CREATE TABLE IF NOT EXISTS documents (
    doc_id TEXT PRIMARY KEY,
    title TEXT NOT NULL DEFAULT '',
    created REAL NOT NULL,
    updated REAL NOT NULL,
    version INTEGER NOT NULL,
    snapshot_version INTEGER NOT NULL,
    snapshot_text TEXT NOT NULL
);
CREATE TABLE IF NOT EXISTS edits (
    doc_id TEXT NOT NULL REFERENCES documents(doc_id) ON DELETE CASCADE,
    version INTEGER NOT NULL,          -- the version this edit produced
    changes TEXT NOT NULL,             -- JSON list of {start, end, text} in base-version offsets
    created REAL NOT NULL,
    PRIMARY KEY (doc_id, version)
);
CREATE TABLE IF NOT EXISTS cast_members (
    doc_id TEXT NOT NULL REFERENCES documents(doc_id) ON DELETE CASCADE,
    name TEXT NOT NULL,                -- the story character the file plays
    glb BLOB NOT NULL,                 -- the user's rig as uploaded (GLB or VRM)
    created REAL NOT NULL,
    PRIMARY KEY (doc_id, name)
);
"""

SNAPSHOT_EVERY = 100  # edits between snapshots


class DocumentNotFound(KeyError):
    pass


class SessionStore:
    """Thread-safe access to the session database file."""

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._conn = sqlite3.connect(str(self.path), check_same_thread=False, isolation_level=None)
        self._conn.execute("PRAGMA journal_mode=WAL")
        self._conn.execute("PRAGMA synchronous=FULL")
        self._conn.execute("PRAGMA foreign_keys=ON")
        self._conn.executescript(_SCHEMA)
        self._lock = threading.Lock()

    def close(self) -> None:
        with self._lock:
            self._conn.close()

    def create(self, doc_id: str, text: str = "", title: str = "") -> None:
        now = time.time()
        with self._lock:
            try:
                self._conn.execute(
                    "INSERT INTO documents VALUES (?, ?, ?, ?, 0, 0, ?)", (doc_id, title, now, now, text)
                )
            except sqlite3.IntegrityError as exc:
                raise ValueError(f"document {doc_id!r} already exists") from exc

    def list(self) -> list[dict[str, object]]:
        with self._lock:
            rows = self._conn.execute(
                "SELECT doc_id, title, version, created, updated FROM documents ORDER BY updated DESC"
            ).fetchall()
        return [dict(zip(("doc_id", "title", "version", "created", "updated"), r, strict=True)) for r in rows]

    def append_edit(
        self, doc_id: str, version: int, changes: builtins.list[TextChange], text_after: str
    ) -> None:
        """Record the edit that produced `version`; commits before returning (the acknowledgement)."""
        payload = json.dumps([{"start": c.start, "end": c.end, "text": c.text} for c in changes])
        now = time.time()
        with self._lock:
            self._conn.execute("BEGIN IMMEDIATE")
            try:
                self._conn.execute("INSERT INTO edits VALUES (?, ?, ?, ?)", (doc_id, version, payload, now))
                snap = version % SNAPSHOT_EVERY == 0
                if snap:
                    self._conn.execute(
                        "UPDATE documents SET version=?, updated=?, snapshot_version=?, snapshot_text=? "
                        "WHERE doc_id=?",
                        (version, now, version, text_after, doc_id),
                    )
                    self._conn.execute("DELETE FROM edits WHERE doc_id=? AND version<=?", (doc_id, version))
                else:
                    self._conn.execute(
                        "UPDATE documents SET version=?, updated=? WHERE doc_id=?", (version, now, doc_id)
                    )
                self._conn.execute("COMMIT")
            except BaseException:
                self._conn.execute("ROLLBACK")
                raise

    def load(self, doc_id: str) -> Document:
        """Rebuild the document: snapshot plus the edits after it."""
        with self._lock:
            row = self._conn.execute(
                "SELECT snapshot_version, snapshot_text FROM documents WHERE doc_id=?", (doc_id,)
            ).fetchone()
            if row is None:
                raise DocumentNotFound(doc_id)
            edits = self._conn.execute(
                "SELECT version, changes FROM edits WHERE doc_id=? AND version>? ORDER BY version",
                (doc_id, row[0]),
            ).fetchall()
        doc = Document.from_text(doc_id, row[1], version=row[0])
        for version, payload in edits:
            changes = [TextChange(**c) for c in json.loads(payload)]
            doc.apply(version - 1, changes)
        return doc

    def rename(self, doc_id: str, title: str) -> None:
        """Set a document's title (raises DocumentNotFound for an unknown id)."""
        with self._lock:
            cur = self._conn.execute("UPDATE documents SET title=? WHERE doc_id=?", (title, doc_id))
            if cur.rowcount == 0:
                raise DocumentNotFound(doc_id)

    def put_cast(self, doc_id: str, name: str, glb: bytes) -> None:
        """Keep the user's character file for a story character (replacing one kept before)."""
        with self._lock:
            self._conn.execute(
                "INSERT OR REPLACE INTO cast_members VALUES (?, ?, ?, ?)", (doc_id, name, glb, time.time())
            )

    def delete_cast(self, doc_id: str, name: str) -> bool:
        """Forget a story character's file; False when none was kept."""
        with self._lock:
            cur = self._conn.execute("DELETE FROM cast_members WHERE doc_id=? AND name=?", (doc_id, name))
            return cur.rowcount > 0

    def cast(self, doc_id: str) -> dict[str, bytes]:
        """The document's kept character files: story name -> file bytes."""
        with self._lock:
            rows = self._conn.execute(
                "SELECT name, glb FROM cast_members WHERE doc_id=? ORDER BY name", (doc_id,)
            ).fetchall()
        return {str(name): bytes(glb) for name, glb in rows}

    def delete(self, doc_id: str) -> None:
        with self._lock:
            self._conn.execute("DELETE FROM documents WHERE doc_id=?", (doc_id,))
