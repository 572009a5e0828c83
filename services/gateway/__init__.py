"""The front door: a FastAPI gateway between the web editor and the orchestrator.

CONTRACT (HTTP + WebSocket, not the bus; see services/gateway/README.md and openapi.json):
- REST  /api/documents ...           create, list, get, replace text, delete, export links
- WS    /api/documents/{doc_id}/live  edit diffs in; ack, stale, diagnostics, progress, animation out
- GET   /api/meshes/{category}.glb    one catalog object variant as GLB (fetched once per variant)
- GET   /                             the built editor (editor/dist)

Start it with `wana serve` (services.gateway.app.main) or build the app in-process with
`services.gateway.app.create_app(settings, orchestrator=None)`.
"""
