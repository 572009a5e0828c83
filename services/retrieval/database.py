"""The scene database as graphs: one networkx MultiDiGraph per scene, plus flat arrays to score fast.

A scene record (wana.assets.scenedb.SceneRecord, or anything with the same attributes: id, room_type,
objects, relations, scene) becomes a graph whose nodes are object ids (attribute ``node``: the
ObjectNode) and whose edges are relations (key and attribute ``relation``). Each relation is also
indexed read from the anchor's side ("A in front of B" as "B behind A") so that a query may state
it either way.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import Any, Protocol

import networkx as nx
import numpy as np

from proto.scene import Scene
from proto.ssg import RELATIONS, ObjectNode, RelationNode
from services.retrieval.similarity import INVERSE_RELATION

RELATION_INDEX = {name: i for i, name in enumerate(RELATIONS)}


class SceneRecordLike(Protocol):
    id: str
    room_type: str
    objects: list[ObjectNode]
    relations: list[RelationNode]
    scene: Scene


@dataclass(frozen=True)
class DbObject:
    scene: int  # index of the record in SceneGraphDB.records
    node: ObjectNode


class SceneGraphDB:
    """Scene records indexed for relation-first and object-first matching.

    Attributes:
        records: the scene records, in load order.
        graphs: one nx.MultiDiGraph per record.
        objects: every object of every record, flat (N_obj entries).
        obj_scene: (N_obj,) int record index of each object.
        obj_category: (N_obj,) int index into ``categories``.
        categories: distinct categories of the database.
        edge_subject, edge_anchor: (N_edge,) int flat object indices of each indexed relation.
        edge_relation: (N_edge,) int index into proto.ssg.RELATIONS.
        edge_scene: (N_edge,) int record index.
        scene_edges: per record, its edge indices.
        edge_order: (N_edge,) edge indices sorted by record (stable).
        edge_scenes: (S',) records that have edges; edge_starts: (S',) where each starts in edge_order.
    """

    def __init__(self, records: Sequence[SceneRecordLike]) -> None:
        self.records = list(records)
        self.graphs: list[nx.MultiDiGraph] = []
        self.objects: list[DbObject] = []
        self.object_index: dict[tuple[int, str], int] = {}
        subjects: list[int] = []
        anchors: list[int] = []
        relations: list[int] = []
        scenes: list[int] = []
        for s, record in enumerate(self.records):
            graph = nx.MultiDiGraph(scene_id=record.id, room_type=record.room_type)
            for node in record.objects:
                graph.add_node(node.id, node=node)
                self.object_index[(s, node.id)] = len(self.objects)
                self.objects.append(DbObject(scene=s, node=node))
            for rel in record.relations:
                if rel.subject not in graph or rel.object not in graph or rel.relation not in RELATION_INDEX:
                    continue
                graph.add_edge(rel.subject, rel.object, key=rel.relation, relation=rel.relation)
                a, b = self.object_index[(s, rel.subject)], self.object_index[(s, rel.object)]
                subjects.append(a)
                anchors.append(b)
                relations.append(RELATION_INDEX[rel.relation])
                scenes.append(s)
                inverse = INVERSE_RELATION.get(rel.relation)
                if inverse is not None:
                    subjects.append(b)
                    anchors.append(a)
                    relations.append(RELATION_INDEX[inverse])
                    scenes.append(s)
            self.graphs.append(graph)
        self.categories: list[str] = sorted({o.node.category for o in self.objects})
        cat_index = {c: i for i, c in enumerate(self.categories)}
        self.obj_scene = np.array([o.scene for o in self.objects], dtype=np.int64)
        self.obj_category = np.array([cat_index[o.node.category] for o in self.objects], dtype=np.int64)
        self.edge_subject = np.array(subjects, dtype=np.int64)
        self.edge_anchor = np.array(anchors, dtype=np.int64)
        self.edge_relation = np.array(relations, dtype=np.int64)
        self.edge_scene = np.array(scenes, dtype=np.int64)
        # Edge indices of each scene, for growing a matched subgraph inside one scene.
        order = np.argsort(self.edge_scene, kind="stable")
        bounds = np.searchsorted(self.edge_scene[order], np.arange(len(self.records) + 1))
        self.scene_edges: list[np.ndarray] = [
            order[bounds[i] : bounds[i + 1]] for i in range(len(self.records))
        ]
        # The same, for per-scene reductions over all edges at once: edges in scene order, and the
        # first position of each scene that has edges (edge_scenes) in that order.
        self.edge_order: np.ndarray = order
        self.edge_scenes: np.ndarray = np.flatnonzero(bounds[1:] > bounds[:-1])
        self.edge_starts: np.ndarray = bounds[:-1][self.edge_scenes]
        self.room_types: list[str] = [r.room_type for r in self.records]

    def __len__(self) -> int:
        return len(self.records)

    def scene_id(self, scene: int) -> str:
        return self.records[scene].id

    def relations_between(self, scene: int, subject: str, anchor: str) -> list[str]:
        """Relation words the record states from subject to anchor, either direction (read as subject->anchor)."""
        graph = self.graphs[scene]
        found: list[str] = []
        if graph.has_edge(subject, anchor):
            found.extend(graph[subject][anchor])
        if graph.has_edge(anchor, subject):
            found.extend(INVERSE_RELATION[k] for k in graph[anchor][subject] if k in INVERSE_RELATION)
        return found


@lru_cache(maxsize=1)
def default_db() -> SceneGraphDB:
    """The project's scene database (wana.assets.scenedb), loaded once per process."""
    from wana.assets.scenedb import load_scenedb

    records: Any = load_scenedb()
    return SceneGraphDB(records)
