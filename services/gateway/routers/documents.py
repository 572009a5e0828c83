"""REST for whole documents: create, list, get, replace the text, delete."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter, Response
from pydantic import BaseModel, Field
from starlette.concurrency import run_in_threadpool

from proto.common import ErrorCode
from services.gateway.deps import HubDep, OrchestratorDep, error
from services.gateway.exports import FORMATS
from services.orchestrator.document import MAX_DOCUMENT_CHARS, BadEdit, StaleEdit, TextChange
from services.orchestrator.store import DocumentNotFound

router = APIRouter(prefix="/api/documents", tags=["documents"])

DOC_ID_PATTERN = r"^[A-Za-z0-9_-]{1,64}$"


class DocumentCreate(BaseModel):
    text: str = Field("", max_length=MAX_DOCUMENT_CHARS, description="initial text")
    title: str = Field("", max_length=200)
    doc_id: str | None = Field(
        None, pattern=DOC_ID_PATTERN, description="chosen id; a random one when absent"
    )


class DocumentRename(BaseModel):
    title: str = Field(..., max_length=200, description="the new title")


class TextReplace(BaseModel):
    text: str = Field(..., max_length=MAX_DOCUMENT_CHARS, description="the whole new text")
    base_version: int | None = Field(None, description="fail with 409 unless the document is at this version")


class SentenceOut(BaseModel):
    id: str
    start: int = Field(description="document offset (Unicode code points), inclusive")
    end: int = Field(description="document offset, exclusive")
    kind: str = Field(description="scene | action | command | empty | unknown (not parsed yet)")


class DocumentSummary(BaseModel):
    doc_id: str
    title: str
    version: int
    created: float = Field(description="seconds since the epoch")
    updated: float


class DocumentOut(BaseModel):
    doc_id: str
    title: str
    version: int
    text: str
    sentences: list[SentenceOut]
    live: str = Field(description="path of the document's WebSocket")
    exports: dict[str, str] = Field(description="format -> download path (mp4, glb, bvh)")


def _story_text(text: str, title: str = "") -> str:
    """A Fountain screenplay (a ``.fountain`` title, or a scene heading in the text) becomes the story it
    tells (wana.screenplay), as `wana animate` reads it; any other text is kept as written."""
    from wana.screenplay import looks_like_fountain, to_story

    if text and looks_like_fountain(text, title):
        try:
            return to_story(text)
        except ImportError:  # screenplain missing: the text as written, its sentences say what fails
            return text
    return text


def _title(orch: Any, doc_id: str) -> str:
    return next((str(d["title"]) for d in orch.list() if d["doc_id"] == doc_id), "")


def _out(orch: Any, doc_id: str) -> DocumentOut:
    try:
        session = orch.open(doc_id)
    except DocumentNotFound:
        raise error(404, ErrorCode.INVALID_INPUT, f"no document {doc_id!r}") from None
    with session.lock:
        doc = session.doc
        sentences = [SentenceOut(id=s.id, start=s.start, end=s.end, kind="unknown") for s in doc.sentences]
        if session.last is not None and session.last.version == doc.version and session.last.sentences:
            sentences = [
                SentenceOut(id=s.id, start=s.start, end=s.end, kind=s.kind) for s in session.last.sentences
            ]
        text, version = doc.text, doc.version
    return DocumentOut(
        doc_id=doc_id,
        title=_title(orch, doc_id),
        version=version,
        text=text,
        sentences=sentences,
        live=f"/api/documents/{doc_id}/live",
        exports={fmt: f"/api/documents/{doc_id}/export/{fmt}" for fmt in FORMATS},
    )


@router.post("", status_code=201, response_model=DocumentOut, summary="Create a document")
async def create_document(body: DocumentCreate, orch: OrchestratorDep) -> DocumentOut:
    try:
        text = _story_text(body.text, body.title)
        session = await run_in_threadpool(orch.create, text, doc_id=body.doc_id, title=body.title)
    except ValueError as exc:
        raise error(409, ErrorCode.INVALID_INPUT, str(exc)) from None
    return await run_in_threadpool(_out, orch, session.doc_id)


@router.get("", response_model=list[DocumentSummary], summary="List documents, most recently edited first")
async def list_documents(orch: OrchestratorDep) -> list[DocumentSummary]:
    rows = await run_in_threadpool(orch.list)
    return [DocumentSummary(**r) for r in rows]  # type: ignore[arg-type]


@router.get("/{doc_id}", response_model=DocumentOut, summary="The text, version, sentences and export links")
async def get_document(doc_id: str, orch: OrchestratorDep) -> DocumentOut:
    return await run_in_threadpool(_out, orch, doc_id)


@router.put(
    "/{doc_id}/text",
    response_model=DocumentOut,
    summary="Replace the whole text (one acknowledged edit)",
    responses={409: {"description": "base_version is not the current version"}},
)
async def replace_text(doc_id: str, body: TextReplace, orch: OrchestratorDep, hub: HubDep) -> DocumentOut:
    try:
        channel = hub.channel(doc_id)
    except DocumentNotFound:
        raise error(404, ErrorCode.INVALID_INPUT, f"no document {doc_id!r}") from None
    current = channel.session.doc
    base = current.version if body.base_version is None else body.base_version
    change = TextChange(start=0, end=len(current.text), text=_story_text(body.text, _title(orch, doc_id)))
    try:
        reply = await channel.edit(base, [change])
    except (StaleEdit, BadEdit) as exc:  # pragma: no cover - channel.edit turns these into replies
        raise error(409, ErrorCode.STALE, str(exc)) from None
    if reply["type"] == "stale":
        raise error(
            409, ErrorCode.STALE, f"the document is at version {reply['current_version']}, not {base}"
        )
    if reply["type"] == "error":
        raise error(422, reply["code"], reply["message"])
    return await run_in_threadpool(_out, orch, doc_id)


@router.patch("/{doc_id}", response_model=DocumentOut, summary="Rename a document")
async def rename_document(
    doc_id: str, body: DocumentRename, orch: OrchestratorDep, hub: HubDep
) -> DocumentOut:
    try:
        await run_in_threadpool(orch.store.rename, doc_id, body.title.strip())
    except DocumentNotFound:
        raise error(404, ErrorCode.INVALID_INPUT, f"no document {doc_id!r}") from None
    channel = hub.channels.get(doc_id)
    if channel is not None:
        channel.title = body.title.strip()
    return await run_in_threadpool(_out, orch, doc_id)


@router.delete("/{doc_id}", status_code=204, summary="Delete a document and close its live connections")
async def delete_document(doc_id: str, orch: OrchestratorDep, hub: HubDep) -> Response:
    rows = await run_in_threadpool(orch.list)
    if not any(r["doc_id"] == doc_id for r in rows):
        raise error(404, ErrorCode.INVALID_INPUT, f"no document {doc_id!r}")
    await hub.drop(doc_id)
    delete = getattr(orch, "delete", None)
    if delete is not None:
        await run_in_threadpool(delete, doc_id)
    else:  # older orchestrator without Orchestrator.delete
        await run_in_threadpool(orch.store.delete, doc_id)
        orch._sessions.pop(doc_id, None)  # noqa: SLF001
    return Response(status_code=204)
