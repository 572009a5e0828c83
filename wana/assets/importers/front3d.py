"""3D-FRONT-style scene import: a house JSON with furniture references -> scene records.

Keys used (as in 3D-FRONT): ``furniture`` [{uid, jid, title, category?, size?/bbox?}], ``mesh``
[{type: "Floor", xyz: [...]}] for room extents, and ``scene.room`` [{type, instanceid, children:
[{ref, pos, rot (quaternion x, y, z, w), scale}]}]. A child whose ``ref`` is a furniture uid becomes a
placed object; its category comes from the furniture's category/title through the vocabulary. If
``model_dir/<jid>/raw_model.obj`` exists, that mesh is imported (registered as "front3d:<jid>");
otherwise the procedural catalog object of the category stands in, scaled to the furniture's size.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ObjectNode, RelationNode
from wana.assets.catalog import make_object
from wana.assets.importers.meshes import asset_from_mesh, load_mesh_file, resolve_category
from wana.assets.importers.registry import imported_object, register_imported
from wana.assets.relations import relation_holds
from wana.assets.scenedb import SceneRecord

ROOM_MAP = {
    "livingroom": "living_room",
    "livingdiningroom": "living_room",
    "diningroom": "dining_room",
    "bedroom": "bedroom",
    "masterbedroom": "bedroom",
    "secondbedroom": "bedroom",
    "kidsroom": "kids_room",
    "elderlyroom": "bedroom",
    "library": "library",
    "studyroom": "home_office",
    "kitchen": "kitchen",
    "bathroom": "bathroom",
    "secondbathroom": "bathroom",
    "masterbathroom": "bathroom",
    "hallway": "lobby",
    "lounge": "living_room",
    "storageroom": "garage",
    "office": "office",
}


def _yaw_from_quat(q: list[float]) -> float:
    x, y, z, w = (float(v) for v in q)
    return float(np.arctan2(2.0 * (w * y + x * z), 1.0 - 2.0 * (y * y + x * x)))


def import_front3d(
    json_path: str | Path, model_dir: str | Path | None = None
) -> tuple[list[SceneRecord], list[str]]:
    """Read one 3D-FRONT house file.

    Returns:
        (records, skipped): one SceneRecord per room with furniture, and reasons for skipped items.

    Raises:
        ValueError: when the file lacks ``scene.room``.
    """
    data = json.loads(Path(json_path).read_text())
    if "scene" not in data or "room" not in data["scene"]:
        raise ValueError(f"{json_path}: not a 3D-FRONT house (no scene.room)")
    furniture = {f["uid"]: f for f in data.get("furniture", [])}
    floors = {m.get("uid"): m for m in data.get("mesh", []) if "floor" in str(m.get("type", "")).lower()}
    records: list[SceneRecord] = []
    skipped: list[str] = []
    for room in data["scene"]["room"]:
        room_type = ROOM_MAP.get(str(room.get("type", "")).lower().replace("_", ""), "living_room")
        placed: list[tuple[dict, str, str, dict]] = []
        floor_pts = []
        for child in room.get("children", []):
            ref = child.get("ref")
            if ref in floors:
                floor_pts.append(np.asarray(floors[ref]["xyz"], float).reshape(-1, 3))
            elif ref in furniture:
                f = furniture[ref]
                cat = resolve_category(str(f.get("category", "")), str(f.get("title", "")))
                if cat is None:
                    skipped.append(f"{ref}: unknown furniture {f.get('category') or f.get('title')!r}")
                    continue
                placed.append((child, cat, f.get("jid", ref), f))
        if not placed:
            continue
        positions = np.array([c.get("pos", [0, 0, 0]) for c, *_ in placed], float)
        if floor_pts:
            pts = np.concatenate(floor_pts)
            lo, hi = pts.min(axis=0), pts.max(axis=0)
        else:
            lo, hi = positions.min(axis=0) - 1.0, positions.max(axis=0) + 1.0
        centre = (lo + hi) / 2.0
        objects: list[PlacedObject] = []
        nodes: list[ObjectNode] = []
        counts: dict[str, int] = {}
        for child, cat, jid, f in placed:
            counts[cat] = counts.get(cat, 0) + 1
            oid = cat if counts[cat] == 1 else f"{cat}#{counts[cat]}"
            name = cat
            scale = np.asarray(child.get("scale", [1, 1, 1]), float)
            mesh_path = Path(model_dir) / str(jid) / "raw_model.obj" if model_dir else None
            if mesh_path is not None and mesh_path.is_file():
                name = f"front3d:{jid}"
                if imported_object(name) is None:
                    register_imported(name, asset_from_mesh(load_mesh_file(mesh_path), cat))
            elif "size" in f or "bbox" in f:
                size = np.asarray(
                    f.get("size") or np.ptp(np.asarray(f["bbox"], float).reshape(-1, 3), axis=0), float
                )
                scale = scale * size / np.maximum(make_object(cat).dims, 1e-6)
            pos = np.asarray(child.get("pos", [0, 0, 0]), float) - [centre[0], 0.0, centre[2]]
            objects.append(
                PlacedObject(
                    id=oid,
                    category=name,
                    position=(float(pos[0]), float(pos[1]), float(pos[2])),
                    yaw=_yaw_from_quat(child.get("rot", [0, 0, 0, 1])),
                    scale=(float(scale[0]), float(scale[1]), float(scale[2])),
                    from_text=False,
                )
            )
            nodes.append(ObjectNode(id=oid, category=cat, word=str(f.get("title") or cat)))
        relations = [
            RelationNode(subject=a.id, relation="on", object=b.id)
            for a in objects
            for b in objects
            if a is not b and a.position[1] > 0.05 and relation_holds("on", a, b)
        ]
        width, depth = float(hi[0] - lo[0]), float(hi[2] - lo[2])
        scene = Scene(
            room=Room(room_type=room_type, width=max(width, 1.0), depth=max(depth, 1.0), height=2.8),
            objects=objects,
        )
        rid = str(room.get("instanceid", f"{room_type}-{len(records)}"))
        records.append(
            SceneRecord(
                id=f"front3d:{rid}", room_type=room_type, objects=nodes, relations=relations, scene=scene
            )
        )
    return records, skipped
