"""Relation-first SSG matching: the paper's Algorithm 1 (Zhang et al., Write-An-Animation, PG 2021).

The query SSG's relation nodes are matched against the scene database first. Each round picks, over
all scenes, the largest-scoring subgraph of still-unmatched query relations that one scene contains
with consistent object correspondences (a query object maps to one scene object and back); that
subgraph goes into the matching map and its relations leave the pending set. Objects that no matched
relation covers are then matched as single nodes. Every match carries a score.

The score of a whole matching (used for ours and for the LDS baseline alike, see ``matching_score``):
mean over the query's nodes (objects and relations) of each node's agreement: an object node scores
its similarity to the database object it matched; a relation node scores the relation agreement when
its two objects matched objects of the same scene that the scene relates, else 0.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from proto.ssg import ObjectNode, RelationNode
from services.retrieval.database import RELATION_INDEX, SceneGraphDB
from services.retrieval.similarity import (
    attribute_agreement,
    category_similarity,
    relation_similarity,
    relation_table,
)

MIN_EDGE_SCORE = 0.3  # a query relation and a database relation agree at least this much to match
SCENES_TRIED = 12  # scenes grown per round, best upper bound first
ATTRIBUTE_WEIGHT = 0.25

_REL_NAMES, _REL_TABLE = relation_table()
REL_SIM = np.array(_REL_TABLE, dtype=np.float64)  # (K, K)


@dataclass(frozen=True)
class NodeMatch:
    """One entry of the matching map."""

    object_id: str  # query ObjectNode.id
    scene: int  # record index in the database
    db_object: int  # flat object index in the database
    score: float  # node similarity in [0, 1]
    via: Literal["relation", "object"]


@dataclass(frozen=True)
class SubgraphMatch:
    """A piece of the query matched inside one scene (a matched subgraph of Algorithm 1)."""

    scene: int
    mapping: dict[str, int]  # query object id -> flat database object index
    relations: tuple[int, ...]  # indices into the query's relation list
    score: float  # sum of the edge scores of its relations


@dataclass
class Matching:
    """Result of matching a query SSG: the matching map, the pieces, the score."""

    nodes: dict[str, NodeMatch] = field(default_factory=dict)
    pieces: list[SubgraphMatch] = field(default_factory=list)
    relation_scores: list[float] = field(default_factory=list)  # per query relation, in [0, 1]
    score: float = 0.0


def _valid_relations(objects: Sequence[ObjectNode], relations: Sequence[RelationNode]) -> list[int]:
    ids = {o.id for o in objects}
    return [
        i
        for i, r in enumerate(relations)
        if r.subject in ids and r.object in ids and r.subject != r.object and r.relation in RELATION_INDEX
    ]


def node_similarity_matrix(objects: Sequence[ObjectNode], db: SceneGraphDB) -> np.ndarray:
    """Similarity of every query object to every database object.

    Returns:
        (Q, N_obj) float64 in [0, 1].
    """
    cats = sorted({o.category for o in objects})
    cat_sim = np.array([[category_similarity(a, b) for b in db.categories] for a in cats], dtype=np.float64)
    row = {c: i for i, c in enumerate(cats)}
    sim = (
        cat_sim[[row[o.category] for o in objects]][:, db.obj_category]
        if len(db.objects)
        else np.zeros((len(objects), 0))
    )
    for q, obj in enumerate(objects):
        if not obj.attributes:
            continue
        (candidates,) = np.nonzero(sim[q] > 0.0)
        factors = np.array(
            [attribute_agreement(obj.attributes, db.objects[k].node.attributes) for k in candidates],
            dtype=np.float64,
        )
        sim[q, candidates] *= 1.0 - ATTRIBUTE_WEIGHT + ATTRIBUTE_WEIGHT * factors
    return sim


def _edge_scores(
    q_subject: np.ndarray,
    q_anchor: np.ndarray,
    q_relation: np.ndarray,
    node_sim: np.ndarray,
    db: SceneGraphDB,
) -> np.ndarray:
    """(R, N_edge) agreement of each query relation with each indexed database relation."""
    rel = REL_SIM[q_relation][:, db.edge_relation]
    subject = node_sim[q_subject][:, db.edge_subject]
    anchor = node_sim[q_anchor][:, db.edge_anchor]
    nodes = 0.5 * (subject + anchor)
    both = (subject > 0) & (anchor > 0)
    return rel * nodes * both


def _grow_in_scene(
    scene: int,
    pending: list[int],
    edge_scores: np.ndarray,
    q_subject: np.ndarray,
    q_anchor: np.ndarray,
    db: SceneGraphDB,
) -> tuple[dict[int, int], list[int], float]:
    """Greedily grow the best consistent matched subgraph of the pending relations inside one scene.

    Returns:
        (query object row -> database object, matched pending relation rows, summed edge score).
    """
    edges = db.scene_edges[scene]
    if len(edges) == 0:
        return {}, [], 0.0
    block = edge_scores[np.asarray(pending, dtype=np.int64)][:, edges]  # (P, E_s)
    # Pairs in decreasing score (ties in flat order, as a stable sort of the whole block gives them),
    # only those scoring at least MIN_EDGE_SCORE: the rest would never be taken.
    values = block.ravel()
    (strong,) = np.nonzero(values >= MIN_EDGE_SCORE)
    strong = strong[np.argsort(-values[strong], kind="stable")]
    rows, cols = np.divmod(strong, block.shape[1])
    subjects = db.edge_subject[edges[cols]].tolist()
    anchors = db.edge_anchor[edges[cols]].tolist()
    mapping: dict[int, int] = {}
    used: set[int] = set()
    matched: list[int] = []
    total = 0.0
    done: set[int] = set()
    for p, s, ds, da in zip(rows.tolist(), values[strong].tolist(), subjects, anchors, strict=True):
        if p in done:
            continue
        r = pending[p]
        qs, qa = int(q_subject[r]), int(q_anchor[r])
        # One-to-one correspondence: a query object keeps its database object, and back.
        if (qs in mapping and mapping[qs] != ds) or (qa in mapping and mapping[qa] != da):
            continue
        if (qs not in mapping and ds in used) or (qa not in mapping and da in used):
            continue
        if ds == da:
            continue
        mapping[qs] = ds
        mapping[qa] = da
        used.update((ds, da))
        matched.append(r)
        done.add(p)
        total += s
    return mapping, matched, total


def scene_bounds(scores: np.ndarray, db: SceneGraphDB) -> np.ndarray:
    """Per scene, the sum over query relations of each one's best edge score in that scene.

    Args:
        scores: (P, N_edge) edge scores (>= 0) of the pending query relations.

    Returns:
        (S,) upper bound of what growing a subgraph in each scene can score (0 for a scene without
        relations).
    """
    per_scene = np.zeros((len(db), scores.shape[0]))  # (S, P)
    if len(db.edge_starts):
        best = np.maximum.reduceat(scores[:, db.edge_order], db.edge_starts, axis=1)  # (P, S')
        per_scene[db.edge_scenes] = np.maximum(best.T, 0.0)
    return per_scene.sum(axis=1)


def match_relation_first(
    objects: Sequence[ObjectNode], relations: Sequence[RelationNode], db: SceneGraphDB
) -> Matching:
    """Algorithm 1: match relation nodes first, keep matched subgraphs, then match leftover objects.

    Args:
        objects: query object nodes (unique ids).
        relations: query relation nodes; ones naming unknown objects or relation words are ignored.
        db: the scene database.

    Returns:
        The matching map (one entry per query object that anything in the database resembles), the
        matched subgraphs, per-relation scores and the overall score.
    """
    objects = list(objects)
    row = {o.id: i for i, o in enumerate(objects)}
    valid = _valid_relations(objects, relations)
    node_sim = node_similarity_matrix(objects, db)
    q_subject = np.array([row[relations[i].subject] for i in valid], dtype=np.int64)
    q_anchor = np.array([row[relations[i].object] for i in valid], dtype=np.int64)
    q_relation = np.array([RELATION_INDEX[relations[i].relation] for i in valid], dtype=np.int64)
    result = Matching()
    if valid and len(db.edge_scene):
        scores = _edge_scores(q_subject, q_anchor, q_relation, node_sim, db)  # (R, N_edge)
        pending = list(range(len(valid)))
        while pending:
            # Upper bound per scene: each pending relation's best edge there; grow the most promising.
            bound = scene_bounds(scores[pending], db)
            order = np.argsort(-bound, kind="stable")[:SCENES_TRIED]
            best: tuple[float, int, dict[int, int], list[int]] | None = None
            for scene in order:
                if bound[scene] < MIN_EDGE_SCORE:
                    break
                mapping, matched, total = _grow_in_scene(int(scene), pending, scores, q_subject, q_anchor, db)
                if matched and (best is None or total > best[0] + 1e-12):
                    best = (total, int(scene), mapping, matched)
            if best is None:
                break
            total, scene, mapping, matched = best
            piece_map = {objects[q].id: d for q, d in mapping.items()}
            result.pieces.append(
                SubgraphMatch(
                    scene=scene, mapping=piece_map, relations=tuple(valid[r] for r in matched), score=total
                )
            )
            for q, d in mapping.items():
                oid = objects[q].id
                if oid not in result.nodes:  # an earlier (better) piece keeps its correspondence
                    result.nodes[oid] = NodeMatch(oid, scene, d, float(node_sim[q, d]), "relation")
            pending = [p for p in pending if p not in set(matched)]
    _match_single_nodes(objects, node_sim, db, result)
    result.relation_scores, result.score = matching_score(objects, relations, result.nodes, db, result.pieces)
    return result


def _match_single_nodes(
    objects: Sequence[ObjectNode], node_sim: np.ndarray, db: SceneGraphDB, result: Matching
) -> None:
    """Match each object the relation pass left out as a single node (best similarity).

    Ties go to a scene the matching map already uses, then to the earlier database object.
    """
    used_scenes = {m.scene for m in result.nodes.values()}
    taken = {m.db_object for m in result.nodes.values()}
    for q, obj in enumerate(objects):
        if obj.id in result.nodes or node_sim.shape[1] == 0:
            continue
        row = node_sim[q].copy()
        if taken:
            row[list(taken)] = -1.0  # one database object stands for one query object
        top = float(row.max())
        if top <= 0.0:
            continue
        (ties,) = np.nonzero(row >= top - 1e-12)
        preferred = [int(k) for k in ties if int(db.obj_scene[k]) in used_scenes]
        k = preferred[0] if preferred else int(ties[0])
        result.nodes[obj.id] = NodeMatch(obj.id, int(db.obj_scene[k]), k, top, "object")
        used_scenes.add(int(db.obj_scene[k]))
        taken.add(k)


def matching_score(
    objects: Sequence[ObjectNode],
    relations: Sequence[RelationNode],
    nodes: dict[str, NodeMatch],
    db: SceneGraphDB,
    pieces: Sequence[SubgraphMatch] = (),
) -> tuple[list[float], float]:
    """Score a matching, the same way for every matching method.

    A relation node scores the agreement of the database relation between the two database objects
    the method assigned to its ends for that relation: the matched subgraph that holds it when there
    is one (composition merges the pieces, so each piece's correspondence stands), else the matching
    map. Ends in different scenes, or a scene that does not relate them, score 0.

    Returns:
        (per-relation scores in request order, overall score in [0, 1]): the mean over object nodes of
        their match similarity and over relation nodes of their agreement.
    """
    valid = set(_valid_relations(objects, relations))
    in_piece: dict[int, SubgraphMatch] = {}
    for piece in pieces:
        for i in piece.relations:
            in_piece.setdefault(i, piece)
    rel_scores: list[float] = []
    for i, rel in enumerate(relations):
        s = 0.0
        if i in valid:
            found = in_piece.get(i)
            if found is not None:
                ends: tuple[int, int, int] | None = (
                    found.scene,
                    found.mapping[rel.subject],
                    found.mapping[rel.object],
                )
            else:
                a, b = nodes.get(rel.subject), nodes.get(rel.object)
                ends = (a.scene, a.db_object, b.db_object) if a and b and a.scene == b.scene else None
            if ends is not None and ends[1] != ends[2]:
                scene, ds, da = ends
                stated = db.relations_between(scene, db.objects[ds].node.id, db.objects[da].node.id)
                s = max((relation_similarity(rel.relation, w) for w in stated), default=0.0)
        rel_scores.append(s)
    node_total = sum(nodes[o.id].score for o in objects if o.id in nodes)
    n = len(objects) + len(valid)
    score = (node_total + sum(rel_scores[i] for i in valid)) / n if n else 0.0
    return rel_scores, score
