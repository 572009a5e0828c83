"""One router per resource: documents, exports, meshes, the live WebSocket."""
