"""The room: its kind (named by the text or voted by the matches), its size, and its context objects.

Size starts from the median room of that kind in the scene database and grows in half-metre steps
until the floor area is at least FLOOR_SHARE times what the objects standing on the floor cover.
Context objects ("an organized working shop" gets a workshop's usual things) come from the
best-matched database scene of that kind: its objects that the text did not ask for, with their
relations to each other and to matched text objects.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from proto.ssg import ObjectNode, RelationNode
from services.retrieval.database import SceneGraphDB
from services.retrieval.geometry import Footprint, extents
from services.retrieval.matching import Matching
from wana.assets import vocabulary

DEFAULT_SIZE = (5.0, 4.0, 2.8)  # width x, depth z, height y (metres)
FLOOR_SHARE = 2.6  # floor area / area the floor-standing objects cover
MAX_CONTEXT = 6


def normalize_room_type(room_type: str, db: SceneGraphDB) -> str:
    """A room word of the text as a vocabulary room type ("working shop" -> "workshop")."""
    word = room_type.strip().lower()
    if not word:
        return ""
    found = vocabulary.lookup_room(word)
    if found:
        return found
    snake = word.replace(" ", "_")
    return snake if snake in db.room_types else snake


def vote_room_type(matching: Matching, db: SceneGraphDB) -> str:
    """The room kind of the scenes the query matched, weighted by match scores ("" when none)."""
    votes: dict[str, float] = defaultdict(float)
    for m in matching.nodes.values():
        votes[db.room_types[m.scene]] += m.score
    if not votes:
        return ""
    return max(sorted(votes), key=lambda k: votes[k])


def base_size(room_type: str, db: SceneGraphDB) -> tuple[float, float, float]:
    """Median width, depth, height of the database's rooms of this kind (DEFAULT_SIZE when none)."""
    rooms = [r.scene.room for r in db.records if r.room_type == room_type]
    if not rooms:
        return DEFAULT_SIZE
    w = float(np.median([r.width for r in rooms]))
    d = float(np.median([r.depth for r in rooms]))
    h = float(np.median([r.height for r in rooms]))
    return w, d, max(h, 2.4)


def fit_size(
    size: tuple[float, float, float], floor_footprints: Sequence[Footprint], tallest: float
) -> tuple[float, float, float]:
    """Grow a room (half-metre steps) until the floor-standing objects have room around them."""
    area = 0.0
    for fp in floor_footprints:
        e = extents(fp, 0.0)
        area += float((e[1, 0] - e[0, 0]) * (e[1, 2] - e[0, 2]))
    w, d, h = size
    while w * d < FLOOR_SHARE * area:
        w, d = w + 0.5, d + 0.5
    return w, d, max(h, tallest + 0.3)


@dataclass(frozen=True)
class ContextPick:
    objects: list[ObjectNode]  # ids already prefixed with "ctx_"
    relations: list[RelationNode]  # among context objects, or to text object ids
    scene_id: str


def context_objects(
    room_type: str, matching: Matching, db: SceneGraphDB, query: Sequence[ObjectNode]
) -> ContextPick | None:
    """Usual objects of a room kind from the best-matched database scene of that kind."""
    scenes = [i for i, r in enumerate(db.records) if r.room_type == room_type]
    if not scenes:
        return None
    weight: dict[int, float] = defaultdict(float)
    for m in matching.nodes.values():
        weight[m.scene] += m.score
    for piece in matching.pieces:
        weight[piece.scene] += piece.score
    scene = max(scenes, key=lambda s: (weight.get(s, 0.0), -s))
    record = db.records[scene]
    matched = {db.objects[m.db_object].node.id: qid for qid, m in matching.nodes.items() if m.scene == scene}
    for piece in matching.pieces:
        if piece.scene == scene:
            for qid, k in piece.mapping.items():
                matched.setdefault(db.objects[k].node.id, qid)
    asked = {o.category for o in query}
    candidates = [n for n in record.objects if n.id not in matched and n.category not in asked]
    support = {r.subject: r.object for r in record.relations if r.relation in ("on", "in")}
    chosen: list[ObjectNode] = []
    chosen_ids: set[str] = set()
    # Supports first, so that what rests on something finds it: a monitor comes with its desk or not at all.
    for node in sorted(candidates, key=lambda n: n.id in support):
        anchor = support.get(node.id)
        if anchor is not None and anchor not in matched and anchor not in chosen_ids:
            continue
        if len(chosen) < MAX_CONTEXT:
            chosen.append(node)
            chosen_ids.add(node.id)
    ids = {n.id: f"ctx_{n.id}" for n in chosen}
    relations = []
    for r in record.relations:
        s = ids.get(r.subject)
        o = ids.get(r.object) or matched.get(r.object)
        if s and o:
            relations.append(RelationNode(subject=s, relation=r.relation, object=o))
    objects = [
        ObjectNode(id=ids[n.id], category=n.category, word=n.word, attributes=dict(n.attributes))
        for n in chosen
    ]
    return ContextPick(objects=objects, relations=relations, scene_id=record.id)
