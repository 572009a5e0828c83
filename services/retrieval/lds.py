"""The object-first baseline: LDS (Ma et al., "Language-Driven Synthesis of 3D Scenes from Scene
Databases", SIGGRAPH Asia 2018), as the Write-An-Animation paper compares against it.

Objects are matched first, one by one in document order, each to the database object most similar to
it (category through synonyms and hypernyms, attributes); among equally similar candidates the one
whose scene already holds most of the matched objects wins, so matches gather in few subscenes as
LDS's subscene retrieval does. Relations are not consulted while matching; they only count when the
result is scored (``services.retrieval.matching.matching_score``, shared with our method).
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence

import numpy as np

from proto.ssg import ObjectNode, RelationNode
from services.retrieval.database import SceneGraphDB
from services.retrieval.matching import Matching, NodeMatch, matching_score, node_similarity_matrix


def match_object_first(
    objects: Sequence[ObjectNode], relations: Sequence[RelationNode], db: SceneGraphDB
) -> Matching:
    """Match every query object as a single node, then score the relations that happen to agree.

    Args:
        objects: query object nodes (unique ids).
        relations: query relation nodes (used for scoring only).
        db: the scene database.

    Returns:
        A Matching with ``nodes`` filled (via "object"), no pieces, and the shared score.
    """
    objects = list(objects)
    node_sim = node_similarity_matrix(objects, db)
    result = Matching()
    scene_hits: Counter[int] = Counter()
    taken: set[int] = set()
    for q, obj in enumerate(objects):
        if node_sim.shape[1] == 0:
            break
        row = node_sim[q].copy()
        if taken:
            row[list(taken)] = -1.0  # one database object stands for one query object
        top = float(row.max())
        if top <= 0.0:
            continue
        (ties,) = np.nonzero(row >= top - 1e-12)
        k = max((int(t) for t in ties), key=lambda t: (scene_hits[int(db.obj_scene[t])], -t))
        scene = int(db.obj_scene[k])
        result.nodes[obj.id] = NodeMatch(obj.id, scene, k, top, "object")
        scene_hits[scene] += 1
        taken.add(k)
    result.relation_scores, result.score = matching_score(objects, relations, result.nodes, db)
    return result
