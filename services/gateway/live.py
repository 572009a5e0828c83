"""Live documents: the WebSocket clients of each open document and its coalescing compute loop.

One `DocumentChannel` per open document. Edits are applied (and persisted: acknowledged) in the order a
client sends them; every edit marks the channel dirty. One compute loop per channel runs
`Session.compute` (on a snapshot, without the document lock) in a thread pool, off the event loop; edits that arrive while it runs are coalesced into
the next run, and results are pushed only when they belong to the newest version, so a fast typist never
waits for intermediate versions.

The animation goes out first, then the pipeline's diagnostics; the story checks (wana.fidelity) run after
that as their own task, dropped when a newer version arrives, and their verdicts follow as one more
diagnostics delta (services.gateway.diagdelta).
"""

from __future__ import annotations

import asyncio
import collections
import dataclasses
import logging
import secrets
import time
from concurrent.futures import Executor
from dataclasses import dataclass, field
from typing import Any

from starlette.concurrency import run_in_threadpool
from starlette.websockets import WebSocket, WebSocketState

from proto.common import ErrorCode
from services.gateway import animwire, messages, metrics
from services.gateway.delta import CharacterCache, EncodedAnimation, Holdings, encode_animation, encode_json
from services.gateway.diagdelta import DiagnosticsState
from services.orchestrator.document import BadEdit, Document, StaleEdit, TextChange
from services.orchestrator.pipeline import PipelineResult
from services.orchestrator.session import Orchestrator, Session

log = logging.getLogger(__name__)

PROGRESS_INTERVAL_S = 0.05  # at most one progress message per stage per interval (plus the last one)
EDIT_LOG_LENGTH = 1000  # recent edits kept per channel, so a stale client catches up by changes, not text


@dataclass(eq=False)
class Client:
    """One WebSocket connection; sends are serialised so messages never interleave.

    `holdings` are the hashes of the characters and objects of the last animation message this client was
    sent: it is updated under the send lock, so it always matches what the client has read in order.
    """

    ws: WebSocket
    lock: asyncio.Lock = field(default_factory=asyncio.Lock)
    client_id: str = field(default_factory=lambda: secrets.token_hex(4))  # names its caret for the others
    holdings: Holdings = field(default_factory=Holdings)
    binary: bool = (
        False  # animation messages as binary frames, characters patched (services.gateway.animwire)
    )
    diag_seq: int | None = None  # the diagnostics state (DiagnosticsState.seq) this client holds

    async def _send_text(self, text: str | bytes) -> bool:
        if self.ws.client_state != WebSocketState.CONNECTED:
            return False
        if self.binary and isinstance(text, str):
            text = animwire.compress_text(text)  # a large JSON message (diagnostics) as a WJZ1 frame
        try:
            if isinstance(text, bytes):
                await self.ws.send_bytes(text)
            else:
                await self.ws.send_text(text)
        except Exception:  # a closed socket: the receive loop will detach it
            return False
        return True

    async def send(self, message: dict[str, Any] | str) -> bool:
        """Send one message (a dict, or its JSON text when it was encoded once for many clients)."""
        text = message if isinstance(message, str) else encode_json(message)
        async with self.lock:
            return await self._send_text(text)

    async def send_animation(self, animation: EncodedAnimation) -> bool:
        """Send an animation message, with `unchanged` stubs for the entries this client holds."""
        async with self.lock:
            data: str | bytes
            if self.binary:
                data, holdings, _ = animation.binary_for(self.holdings)
            else:
                data, holdings, _ = animation.text_for(self.holdings)
            sent = await self._send_text(data)
            self.holdings = holdings if sent else Holdings()
            return sent

    async def send_diagnostics(self, state: DiagnosticsState, delta: tuple[int, str] | None) -> bool:
        """Send `state` as the delta (base seq, its text) when this client holds that base, else whole."""
        async with self.lock:
            if delta is not None and self.diag_seq == delta[0]:
                text = delta[1]
            else:
                text = encode_json(state.message(None))
            sent = await self._send_text(text)
            self.diag_seq = state.seq if sent else None
            return sent

    def forget_holdings(self) -> None:
        """The next animation (and diagnostics) message goes to this client in full (it asked to resume)."""
        self.holdings = Holdings()
        self.diag_seq = None


class DocumentChannel:
    """The live state of one document: its clients, its latest results, its compute loop."""

    def __init__(self, session: Session, executor: Executor, title: str = "") -> None:
        self.session = session
        self.executor = executor
        self.title = title
        self.clients: set[Client] = set()
        self.latest: EncodedAnimation | None = None  # the newest version's animation
        self.diag: DiagnosticsState | None = None  # the diagnostics last sent to every client
        self._diag_lock = asyncio.Lock()  # one diagnostics state goes out at a time, in order
        self._judging: asyncio.Task[None] | None = None  # the story checks of self.diag's version
        self._characters = CharacterCache()  # used by one compute at a time (the compute loop's)
        self._dirty = False
        self._task: asyncio.Task[None] | None = None
        self._progress_sent: dict[str, float] = {}
        # version -> its changes (base offsets of version - 1), newest last: a client whose edit was stale
        # gets the edits it missed as they were made, so it rebases its own (CodeMirror collab) exactly.
        self.edit_log: collections.OrderedDict[int, list[dict[str, Any]]] = collections.OrderedDict()

    @property
    def version(self) -> int:
        return self.session.doc.version

    # -- clients -------------------------------------------------------------------------------------
    async def attach(self, client: Client, known_version: int | None = None) -> None:
        """Send the current text (the client rebases onto it), then the newest results or start a compute.

        The client is treated as holding nothing: its next animation message is sent in full.
        """
        client.forget_holdings()
        state = await run_in_threadpool(self._state)
        state["resumed_from"] = known_version
        await client.send(state)  # first, before any broadcast can reach this client
        self.clients.add(client)
        if self.version != state["version"]:  # an edit landed while the state was on its way
            state = await run_in_threadpool(self._state)
            state["resumed_from"] = known_version
            await client.send(state)
        if self.latest is not None and self.latest.head["version"] == self.version:
            await client.send_animation(self.latest)
            async with self._diag_lock:
                if self.diag is not None and self.diag.version == self.latest.head["version"]:
                    await client.send_diagnostics(self.diag, None)
        else:
            self.request_compute()

    def detach(self, client: Client) -> None:
        self.clients.discard(client)

    async def relay_presence(self, client: Client, version: int, anchor: int, head: int | None) -> None:
        """Tell the other clients where this client's selection is (head None: it left)."""
        message: dict[str, Any] = {"type": "presence", "client": client.client_id, "version": version}
        if head is None:
            message["gone"] = True
        else:
            message.update(anchor=anchor, head=head)
        await self.broadcast(message, exclude=client)

    async def broadcast(self, message: dict[str, Any], *, exclude: Client | None = None) -> None:
        """Send one message to every client (but `exclude`), encoded once."""
        targets = [c for c in list(self.clients) if c is not exclude]
        if targets:
            text = encode_json(message)
            await asyncio.gather(*(c.send(text) for c in targets))

    async def broadcast_animation(self, animation: EncodedAnimation) -> None:
        """Send an animation to every client, each with stubs for the entries it holds."""
        targets = list(self.clients)
        if targets:
            await asyncio.gather(*(c.send_animation(animation) for c in targets))

    async def broadcast_diagnostics(self, state: DiagnosticsState) -> None:
        """Make `state` the channel's diagnostics and send it: as a delta to the clients that hold the
        previous one (encoded once), whole to the others. Call with `_diag_lock` held."""
        base = self.diag
        delta = None if base is None else (base.seq, encode_json(state.message(base)))
        self.diag = state
        targets = list(self.clients)
        if targets:
            await asyncio.gather(*(c.send_diagnostics(state, delta) for c in targets))

    def _state(self) -> dict[str, Any]:
        with self.session.lock:
            return messages.state_message(self.session.doc, title=self.title)

    # -- edits ---------------------------------------------------------------------------------------
    async def edit(
        self, base_version: int, changes: list[TextChange], *, origin: Client | None = None
    ) -> dict[str, Any]:
        """Apply one edit; returns the message for its sender (ack, stale or error) and tells the others."""
        arrived = time.perf_counter()
        try:
            ack = await run_in_threadpool(self.session.edit, base_version, changes)
        except StaleEdit as exc:
            state = await run_in_threadpool(self._state)
            return {
                "type": "stale",
                "base_version": exc.base_version,
                "current_version": state["version"],
                "text": state["text"],
                "updates": self.missed_edits(exc.base_version, state["version"]),
            }
        except BadEdit as exc:
            return {"type": "error", "code": ErrorCode.INVALID_INPUT, "message": str(exc)}
        changes_json = [{"start": c.start, "end": c.end, "text": c.text} for c in changes]
        self.edit_log[ack.version] = changes_json
        while len(self.edit_log) > EDIT_LOG_LENGTH:
            self.edit_log.popitem(last=False)
        await self.broadcast(
            {
                "type": "remote_edit",
                "base_version": ack.version - 1,
                "version": ack.version,
                "changes": changes_json,
            },
            exclude=origin,
        )
        self.request_compute()
        metrics.EDIT_ACK_SECONDS.observe(time.perf_counter() - arrived)
        return {"type": "ack", "version": ack.version, "changed": list(ack.changed)}

    def missed_edits(self, since: int, until: int) -> list[dict[str, Any]] | None:
        """The edits after version `since` up to `until` as `remote_edit`-like entries, or None when the
        log no longer holds them all (the client then rebases onto the stale reply's text)."""
        wanted = range(since + 1, until + 1)
        if since > until or any(v not in self.edit_log for v in wanted):
            return None
        return [{"base_version": v - 1, "version": v, "changes": self.edit_log[v]} for v in wanted]

    # -- computing -----------------------------------------------------------------------------------
    def request_compute(self) -> None:
        """Mark the document dirty; start the compute loop unless one is running (it will pick this up).

        The story checks of an older version are dropped: their verdicts would be outdated on arrival."""
        self._dirty = True
        self._drop_judging()
        if self._task is None:
            self._task = asyncio.get_running_loop().create_task(self._compute_loop())

    async def wait_idle(self) -> None:
        """Wait until no compute (nor story check) is pending (tests and benchmarks)."""
        while self._task is not None or self._judging is not None:
            task = self._task or self._judging
            assert task is not None
            await asyncio.wait({task})  # a dropped story check ends cancelled: that is idle too

    def _drop_judging(self) -> None:
        if self._judging is not None:
            self._judging.cancel()
            self._judging = None

    async def _compute_loop(self) -> None:
        loop = asyncio.get_running_loop()
        try:
            while self._dirty:
                self._dirty = False
                started = time.perf_counter()
                try:
                    result, doc, anim = await loop.run_in_executor(self.executor, self._compute, loop)
                except Exception as exc:
                    metrics.COMPUTE_FAILURES.inc()
                    log.exception("compute of %s failed", self.session.doc_id)
                    await self.broadcast(
                        {
                            "type": "error",
                            "code": ErrorCode.HANDLER_FAILED,
                            "message": f"computing the animation failed: {type(exc).__name__}: {exc}",
                        }
                    )
                    continue
                if result.version != self.version:
                    self._dirty = True  # an edit landed meanwhile: only the newest version is pushed
                    continue
                anim.head["stats"]["total_ms"] = round((time.perf_counter() - started) * 1000.0, 2)
                self.latest = anim
                self._drop_judging()
                await self.broadcast_animation(anim)  # the preview first: it does not wait for diagnostics
                async with self._diag_lock:
                    await self.broadcast_diagnostics(self._pipeline_state(result, doc))
                if not self._dirty:
                    self._judging = loop.create_task(self._judge(result, self.diag))
        finally:
            self._task = None

    def _pipeline_state(self, result: PipelineResult, doc: Document) -> DiagnosticsState:
        """The new version's pipeline diagnostics, the last verdicts kept until its own are judged."""
        sentences = messages.sentence_list(result, doc)
        unavailable = dict(result.unavailable)
        entries = messages.pipeline_entries(result)
        if self.diag is None:
            return DiagnosticsState(result.version, sentences, unavailable, entries, {}, True)
        return self.diag.carried_into(result.version, sentences, unavailable, entries)

    async def _judge(self, result: PipelineResult, pipeline: DiagnosticsState | None) -> None:
        """Run the story checks of `result` in the compute pool and send their verdicts, unless a newer
        version came meanwhile (this task is then cancelled, or finds the channel moved on)."""
        try:
            judged = await asyncio.get_running_loop().run_in_executor(
                self.executor, messages.story_verdicts, result
            )
            warnings, verdicts = messages.verdict_entries(result, judged)
            async with self._diag_lock:
                if pipeline is None or self.diag is not pipeline or self._dirty:
                    return
                entries = messages.pipeline_entries(result)
                for sid, items in warnings.items():
                    entries.setdefault(sid, []).extend(items)
                state = DiagnosticsState(
                    pipeline.version, pipeline.sentences, pipeline.unavailable, entries, verdicts, False
                )
                await self.broadcast_diagnostics(state)
        except asyncio.CancelledError:
            raise
        except Exception:
            metrics.COMPUTE_FAILURES.inc()
            log.exception("story checks of %s failed", self.session.doc_id)
        finally:
            if self._judging is asyncio.current_task():
                self._judging = None

    def _compute(self, loop: asyncio.AbstractEventLoop) -> tuple[PipelineResult, Document, EncodedAnimation]:
        """Runs in the compute pool: bring the session up to date and build (and encode) the animation."""
        version = self.version
        self._progress_sent.clear()

        def progress(stage: str, done: int, total: int) -> None:
            now = time.perf_counter()
            last = self._progress_sent.get(stage)
            if done < total and last is not None and now - last < PROGRESS_INTERVAL_S:
                return
            self._progress_sent[stage] = now
            message = {"type": "progress", "version": version, "stage": stage, "done": done, "total": total}
            asyncio.run_coroutine_threadsafe(self.broadcast(message), loop)

        started = time.perf_counter()
        # Session.compute works on its own snapshot of the document, so the document lock is not held
        # while it runs: edits are acknowledged and REST reads answered during a long compute.
        result = self.session.compute(progress=progress)
        compute_ms = (time.perf_counter() - started) * 1000.0
        metrics.COMPUTE_SECONDS.observe(compute_ms / 1000.0)
        with self.session.lock:  # a consistent copy of the sentences, for as long as that takes
            doc = dataclasses.replace(self.session.doc, sentences=list(self.session.doc.sentences))
        anim = encode_animation(result, self._characters, compute_ms=compute_ms)
        return result, doc, anim


class LiveHub:
    """The channels of every document that has live clients or pending work."""

    def __init__(self, orchestrator: Orchestrator, executor: Executor) -> None:
        self.orchestrator = orchestrator
        self.executor = executor
        self.channels: dict[str, DocumentChannel] = {}

    def channel(self, doc_id: str) -> DocumentChannel:
        """The document's channel (raises store.DocumentNotFound for an unknown id)."""
        channel = self.channels.get(doc_id)
        if channel is None:
            session = self.orchestrator.open(doc_id)
            title = next((str(d["title"]) for d in self.orchestrator.list() if d["doc_id"] == doc_id), "")
            channel = DocumentChannel(session, self.executor, title)
            self.channels[doc_id] = channel
        return channel

    async def drop(self, doc_id: str, *, code: int = 4404, reason: str = "document deleted") -> None:
        """Close every client of a document and forget its channel."""
        channel = self.channels.pop(doc_id, None)
        if channel is None:
            return
        for client in list(channel.clients):
            try:
                await client.ws.close(code=code, reason=reason)
            except Exception:
                pass
        channel.clients.clear()
