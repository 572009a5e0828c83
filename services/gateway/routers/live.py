"""The document WebSocket: text diffs in; ack, stale, diagnostics, progress and animation out."""

from __future__ import annotations

import msgspec
from fastapi import APIRouter, WebSocket, WebSocketDisconnect

from proto.common import ErrorCode
from services.gateway.live import Client, LiveHub
from services.gateway.protocol import Edit, Ping, Presence, Resume, decoder
from services.gateway.security import origin_ok, server_port, token_ok
from services.gateway.settings import Settings
from services.orchestrator.document import TextChange
from services.orchestrator.store import DocumentNotFound

router = APIRouter(tags=["live"])

CLOSE_POLICY = 1008  # RFC 6455 policy violation: token or origin refused
CLOSE_NOT_FOUND = 4404


@router.websocket("/api/documents/{doc_id}/live")
async def live(websocket: WebSocket, doc_id: str, version: int | None = None, wire: str = "json") -> None:
    """One editor connection to one document. `?version=N` resumes from the last version the client saw;
    `?wire=binary` asks for animation messages as binary frames (services.gateway.animwire)."""
    settings: Settings = websocket.app.state.settings
    hub: LiveHub = websocket.app.state.hub
    if not token_ok(settings.token, websocket.headers, websocket.cookies):
        await websocket.close(code=CLOSE_POLICY, reason="missing or wrong token")
        return
    if not origin_ok(websocket.headers, settings.allowed_origins, server_port(websocket.scope)):
        await websocket.close(code=CLOSE_POLICY, reason="origin not allowed")
        return
    await websocket.accept()
    try:
        channel = hub.channel(doc_id)
    except DocumentNotFound:
        await websocket.send_json(
            {"type": "error", "code": ErrorCode.INVALID_INPUT, "message": f"no document {doc_id!r}"}
        )
        await websocket.close(code=CLOSE_NOT_FOUND, reason="no such document")
        return
    client = Client(websocket, binary=wire == "binary")
    await channel.attach(client, version)
    try:
        while True:
            raw = await websocket.receive()
            if raw["type"] == "websocket.disconnect":
                break
            text = raw.get("text")
            if text is None:
                text = (raw.get("bytes") or b"").decode("utf-8", errors="replace")
            if len(text.encode("utf-8")) > settings.max_message_bytes:
                await client.send(
                    {
                        "type": "error",
                        "code": ErrorCode.TOO_LARGE,
                        "message": f"message larger than {settings.max_message_bytes} bytes",
                    }
                )
                continue
            try:
                message = decoder.decode(text)
            except (msgspec.DecodeError, ValueError) as exc:  # ValueError: e.g. text that is not UTF-8
                await client.send(
                    {"type": "error", "code": ErrorCode.MALFORMED, "message": f"bad message: {exc}"}
                )
                continue
            if hub.channels.get(doc_id) is not channel:  # deleted meanwhile
                break
            match message:
                case Edit():
                    if len(message.changes) > settings.max_changes:
                        await client.send(
                            {
                                "type": "error",
                                "code": ErrorCode.INVALID_INPUT,
                                "client_seq": message.client_seq,
                                "message": f"an edit may carry at most {settings.max_changes} changes",
                            }
                        )
                        continue
                    changes = [TextChange(start=c.start, end=c.end, text=c.text) for c in message.changes]
                    reply = await channel.edit(message.base_version, changes, origin=client)
                    reply["client_seq"] = message.client_seq
                    await client.send(reply)
                case Resume():
                    await channel.attach(client, message.version)
                case Ping():
                    await client.send({"type": "pong", "nonce": message.nonce, "version": channel.version})
                case Presence():
                    await channel.relay_presence(client, message.version, message.anchor, message.head)
    except WebSocketDisconnect:
        pass
    finally:
        channel.detach(client)
        await channel.relay_presence(client, channel.version, 0, None)
