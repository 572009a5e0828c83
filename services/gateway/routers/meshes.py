"""Object meshes as GLB, one URL per variant, cacheable forever (a variant's mesh never changes)."""

from __future__ import annotations

from fastapi import APIRouter, Query, Response
from starlette.concurrency import run_in_threadpool

from proto.common import ErrorCode
from services.gateway.deps import MeshesDep, error
from services.gateway.meshes import MeshUnavailable, UnknownObject, parse_attributes

router = APIRouter(prefix="/api/meshes", tags=["meshes"])


@router.get(
    "/{category}.glb",
    summary="The mesh of one catalog object variant as binary glTF",
    responses={
        200: {"content": {"model/gltf-binary": {}}},
        404: {"description": "unknown category"},
        503: {"description": "the asset catalog is not available yet"},
    },
    response_class=Response,
)
async def object_mesh(
    category: str,
    meshes: MeshesDep,
    seed: int = 0,
    attributes: str = Query("", max_length=2000, description="JSON object of attribute -> value"),
) -> Response:
    try:
        attrs = parse_attributes(attributes)
        data = await run_in_threadpool(meshes.glb, category, attrs, seed)
    except UnknownObject as exc:
        raise error(404, ErrorCode.INVALID_INPUT, str(exc)) from None
    except MeshUnavailable as exc:
        raise error(503, ErrorCode.UNAVAILABLE, str(exc)) from None
    return Response(data, media_type="model/gltf-binary", headers={"Cache-Control": "public, max-age=86400"})
