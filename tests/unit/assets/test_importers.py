"""Importers read small files the tests write: OBJ+annotation, ShapeNetSem CSV+OBJ, 3D-FRONT JSON."""

from __future__ import annotations

import json

import numpy as np
import pytest
import trimesh

from wana.assets import catalog
from wana.assets.importers.front3d import import_front3d
from wana.assets.importers.meshes import import_mesh
from wana.assets.importers.registry import clear_imported, imported_object
from wana.assets.importers.shapenetsem import import_shapenetsem, read_metadata

Z_UP_CM = np.array(
    [[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1.0]]
)  # Y-up metres -> Z-up, front -Y


def _write_zup_cm(category: str, path):
    mesh = catalog.make_object(category).mesh.copy()
    mesh.apply_transform(Z_UP_CM)
    mesh.apply_scale(100.0)
    mesh.export(path)
    return catalog.make_object(category)


@pytest.fixture(autouse=True)
def _clean_registry():
    clear_imported()
    yield
    clear_imported()


def test_obj_with_annotation_comes_back_in_the_object_frame(tmp_path):
    original = _write_zup_cm("chair", tmp_path / "thing.obj")
    (tmp_path / "thing.json").write_text(
        json.dumps({"category": "side chair", "up": [0, 0, 1], "front": [0, -1, 0], "unit": 0.01})
    )
    obj = import_mesh(tmp_path / "thing.obj")
    assert obj.category == "chair"
    assert np.allclose(obj.dims, original.dims, atol=1e-4)
    assert abs(obj.mesh.bounds[0, 1]) < 1e-9
    sit = obj.contact_points["sit"]
    assert sit.joint == "Hips" and np.allclose(
        sit.position, original.contact_points["sit"].position, atol=0.01
    )
    assert len(obj.collision_boxes) > 10
    lo, hi = obj.mesh.bounds
    assert np.all(obj.collision_boxes[:, 0] >= lo - 1e-9) and np.all(obj.collision_boxes[:, 1] <= hi + 1e-9)


def test_glb_without_annotation_uses_the_file_name_and_default_contacts(tmp_path):
    mesh = trimesh.creation.box((0.4, 0.9, 0.4))
    mesh.apply_translation((3.0, 0.45, -1.0))
    path = tmp_path / "boxing-bag.glb"
    path.write_bytes(trimesh.Scene(mesh).export(file_type="glb"))
    obj = import_mesh(path)
    assert obj.category == "boxing_bag"
    assert "punch" in obj.contact_points
    assert np.allclose(obj.mesh.bounds[0], [-0.2, 0.0, -0.2], atol=1e-6)
    unknown = tmp_path / "zorgle.obj"
    mesh.export(unknown)
    assert set(import_mesh(unknown).contact_points) == {"touch"}
    with pytest.raises(FileNotFoundError):
        import_mesh(tmp_path / "missing.obj")


def test_shapenetsem_metadata_and_models(tmp_path):
    models = tmp_path / "models"
    models.mkdir()
    desk = _write_zup_cm("desk", models / "abc123.obj")
    rows = [
        "fullId,category,wnsynset,wnlemmas,up,front,unit,name,tags",
        'wss.abc123,"Desk,OfficeDesk",n1,"desk",0\\,0\\,1,0\\,-1\\,0,0.01,my desk,',
        "wss.zzz999,Spaceship,n2,spaceship,0\\,0\\,1,0\\,-1\\,0,0.01,ship,",
        'wss.nofile,"Chair",n3,chair,0\\,0\\,1,0\\,-1\\,0,0.01,chair,',
    ]
    csv_path = tmp_path / "metadata.csv"
    csv_path.write_text("\n".join(rows) + "\n")
    entries = read_metadata(csv_path)
    assert [e.category for e in entries] == ["desk", None, "chair"]
    objects, skipped = import_shapenetsem(csv_path, models)
    assert len(objects) == 1 and len(skipped) == 2
    assert np.allclose(objects[0].dims, desk.dims, atol=1e-4)
    assert imported_object("shapenet:abc123") is objects[0]
    assert objects[0].support_surfaces and abs(objects[0].support_surfaces[0].height - 0.75) < 0.02


def test_front3d_house_becomes_scene_records(tmp_path):
    model_dir = tmp_path / "3D-FUTURE-model"
    (model_dir / "jid-sofa").mkdir(parents=True)
    _write_zup_cm("sofa", tmp_path / "tmp.obj")
    sofa_mesh = catalog.make_object("sofa").mesh.copy()
    sofa_mesh.export(model_dir / "jid-sofa" / "raw_model.obj")
    house = {
        "uid": "house-1",
        "furniture": [
            {
                "uid": "f1",
                "jid": "jid-sofa",
                "title": "three-seat sofa",
                "category": "Three-seat / Multi-seat Sofa",
            },
            {"uid": "f2", "jid": "jid-table", "title": "coffee table", "size": [1.2, 0.45, 0.6]},
            {"uid": "f3", "jid": "jid-x", "title": "air purifier"},
        ],
        "mesh": [{"uid": "m1", "type": "Floor", "xyz": [10, 0, 10, 15, 0, 10, 15, 0, 14, 10, 0, 14]}],
        "scene": {
            "room": [
                {
                    "type": "LivingRoom",
                    "instanceid": "LivingRoom-7",
                    "children": [
                        {"ref": "m1", "pos": [0, 0, 0], "rot": [0, 0, 0, 1], "scale": [1, 1, 1]},
                        {"ref": "f1", "pos": [12.5, 0, 10.6], "rot": [0, 0, 0, 1], "scale": [1, 1, 1]},
                        {
                            "ref": "f2",
                            "pos": [12.5, 0, 12.0],
                            "rot": [0, 0.7071068, 0, 0.7071068],
                            "scale": [1, 1, 1],
                        },
                        {"ref": "f3", "pos": [14, 0, 13], "rot": [0, 0, 0, 1], "scale": [1, 1, 1]},
                    ],
                }
            ]
        },
    }
    path = tmp_path / "house.json"
    path.write_text(json.dumps(house))
    records, skipped = import_front3d(path, model_dir)
    assert len(records) == 1 and len(skipped) == 1
    rec = records[0]
    assert rec.room_type == "living_room"
    assert (rec.scene.room.width, rec.scene.room.depth) == (5.0, 4.0)
    by_id = {o.id: o for o in rec.scene.objects}
    assert [n.category for n in rec.objects] == ["sofa", "coffee_table"]
    assert by_id["sofa"].category == "front3d:jid-sofa" and imported_object("front3d:jid-sofa") is not None
    assert np.allclose(by_id["coffee_table"].position, (0.0, 0.0, 0.0), atol=1e-9)
    assert abs(by_id["coffee_table"].yaw - np.pi / 2) < 1e-6
    bounds = catalog.world_bounds(by_id["coffee_table"])
    assert np.allclose(bounds[1] - bounds[0], [0.6, 0.45, 1.2], atol=1e-3)  # scaled to size, then turned
    assert len(catalog.world_collision_boxes(by_id["sofa"])) > 10
    with pytest.raises(ValueError, match="3D-FRONT"):
        bad = tmp_path / "bad.json"
        bad.write_text("{}")
        import_front3d(bad)
