import os
import signal
import subprocess
import sys
import textwrap

import pytest

from services.orchestrator.document import TextChange
from services.orchestrator.store import DocumentNotFound, SessionStore


def test_edits_replay_to_the_same_document(tmp_path):
    store = SessionStore(tmp_path / "s.db")
    store.create("d", "Eve sits. Tom waves.")
    doc = store.load("d")
    for text in ["Ann", "Bob", "Cid"]:
        changes = [TextChange(start=0, end=3, text=text)]
        doc.apply(doc.version, changes)
        store.append_edit("d", doc.version, changes, doc.text)
    again = SessionStore(tmp_path / "s.db").load("d")
    assert again.text == "Cid sits. Tom waves." and again.version == 3
    assert [s.id for s in again.sentences] == [s.id for s in doc.sentences]


def test_loading_an_unknown_document_raises(tmp_path):
    with pytest.raises(DocumentNotFound):
        SessionStore(tmp_path / "s.db").load("nope")


def test_an_acknowledged_edit_survives_kill_9(tmp_path):
    db = tmp_path / "s.db"
    script = textwrap.dedent(
        f"""
        import os, sys, time
        from services.orchestrator.store import SessionStore
        from services.orchestrator.document import TextChange
        store = SessionStore({str(db)!r})
        store.create("d", "Eve sits.")
        doc = store.load("d")
        ch = [TextChange(start=4, end=8, text="types")]
        doc.apply(0, ch)
        store.append_edit("d", doc.version, ch, doc.text)
        print("ACK", flush=True)
        time.sleep(60)
        """
    )
    env = dict(os.environ, PYTHONPATH=os.getcwd())
    proc = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True, env=env)
    try:
        assert proc.stdout is not None and proc.stdout.readline().strip() == "ACK"
    finally:
        proc.send_signal(signal.SIGKILL)
        proc.wait()
    doc = SessionStore(db).load("d")
    assert doc.text == "Eve types." and doc.version == 1


def test_a_documents_cast_is_kept_with_it_and_goes_when_it_is_deleted(tmp_path):
    from services.orchestrator.session import Orchestrator

    db = tmp_path / "s.db"
    first = Orchestrator(db, backend=None)  # type: ignore[arg-type]  (no compute here)
    session = first.create("Eve walks to the desk.", doc_id="d")
    session.set_cast("Eve", b"glTF-eve")
    session.set_cast("Tom", b"glTF-tom")
    assert session.drop_cast("Tom") and not session.drop_cast("Tom")
    first.close()
    again = Orchestrator(db, backend=None).open("d")  # type: ignore[arg-type]  (a restarted gateway)
    assert {n: m.glb for n, m in again.cast.items()} == {"Eve": b"glTF-eve"}
    store = SessionStore(db)
    store.delete("d")
    assert store.cast("d") == {}
