"""The seeded scene grammar: room type + seed -> SSG (objects, relations) + placements.

Each room type has a list of rules (``scene_rules.RULES``). A rule places one kind of object by an
operation (against a wall, hung on a wall, in front of / beside / around / under / on / above an
anchor, in a corner, free on the floor), with a probability and a count. Every candidate placement
is accepted only if it stays inside the room, overlaps nothing (collision boxes) and every relation
the rule states holds geometrically; otherwise the next candidate is tried.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ObjectNode, RelationNode
from wana.assets import catalog, vocabulary
from wana.assets.relations import relation_holds
from wana.assets.scene_rules import ROOM_SIZES, RULES, Rule
from wana.assets.validate import WALL_TOL_M, aabbs_overlap, boxes_overlap, rests_on

WALLS = ("N", "S", "W", "E")
WALL_YAW = {"N": 0.0, "S": np.pi, "W": np.pi / 2, "E": -np.pi / 2}
EPS = 0.005


@dataclass
class GeneratedScene:
    room_type: str
    seed: int
    objects: list[ObjectNode]
    relations: list[RelationNode]
    scene: Scene


@dataclass
class _State:
    room: Room
    rng: np.random.Generator
    placed: list[PlacedObject] = field(default_factory=list)
    bounds: dict[str, np.ndarray] = field(default_factory=dict)
    boxes: dict[str, np.ndarray] = field(default_factory=dict)
    labels: dict[str, str] = field(default_factory=dict)
    relations: list[RelationNode] = field(default_factory=list)
    counts: dict[str, int] = field(default_factory=dict)

    def by_id(self, oid: str) -> PlacedObject:
        return next(p for p in self.placed if p.id == oid)


def _random_attributes(category: str, rng: np.random.Generator) -> dict[str, str]:
    out = {}
    probs = {"size": 0.2, "style": 0.4, "colour": 0.35, "material": 0.25, "state": 0.5}
    for knob, values in catalog.variant_space(category).items():
        if rng.random() < probs[knob]:
            out[knob] = str(values[int(rng.integers(len(values)))])
    return out


def _fits(st: _State, cand: PlacedObject) -> bool:
    room = st.room
    b = catalog.world_bounds(cand)
    lo = np.array([-room.width / 2, 0.0, -room.depth / 2])
    hi = np.array([room.width / 2, room.height, room.depth / 2])
    if np.any(b[0] < lo - 1e-6) or np.any(b[1] > hi + 1e-6):
        return False
    if cand.support and not rests_on(cand, st.by_id(cand.support)):
        return False
    if not cand.support and catalog.asset_for(cand).mount == "wall":
        gaps = np.concatenate([b[0] - lo, hi - b[1]])[[0, 2, 3, 5]]
        if gaps.min() > WALL_TOL_M:
            return False
    boxes = catalog.world_collision_boxes(cand)
    for other in st.placed:
        if other.id == cand.support or other.support == cand.id:
            continue
        if aabbs_overlap(b, st.bounds[other.id]) and boxes_overlap(boxes, st.boxes[other.id]):
            return False
    return True


def _wall_pose(st: _State, obj: catalog.AssetObject, wall: str, t: float, y: float = 0.0) -> tuple:
    w, d = obj.dims[0], obj.dims[2]
    room = st.room
    if wall in ("N", "S"):
        x = -room.width / 2 + w / 2 + t * max(room.width - w, 0.0)
        z = -room.depth / 2 + d / 2 + EPS if wall == "N" else room.depth / 2 - d / 2 - EPS
    else:
        z = -room.depth / 2 + w / 2 + t * max(room.depth - w, 0.0)
        x = -room.width / 2 + d / 2 + EPS if wall == "W" else room.width / 2 - d / 2 - EPS
    return (float(x), float(y), float(z)), WALL_YAW[wall]


def _local_to_world(anchor: PlacedObject, local: np.ndarray) -> tuple[float, float, float]:
    p = catalog.to_world(anchor, np.asarray(local, float))
    return float(p[0]), float(p[1]), float(p[2])


def _candidates(st: _State, rule: Rule, obj: catalog.AssetObject, anchor: PlacedObject | None):
    """Yield (position, yaw, support_id, relations[(rel, anchor_id)]) candidates for one object."""
    rng = st.rng
    op = rule.op
    for _ in range(14):
        if op in ("wall", "hang"):
            wall = rule.wall or WALLS[int(rng.integers(4))]
            y = 0.0 if op == "wall" else float(rng.uniform(*rule.height))
            pos, yaw = _wall_pose(st, obj, wall, float(rng.uniform(0.05, 0.95)), y)
            yield pos, yaw, "", []
        elif op == "corner":
            sx, sz = rng.choice([-1, 1]), rng.choice([-1, 1])
            r = max(obj.dims[0], obj.dims[2]) / 2 + 0.02
            pos = (sx * (st.room.width / 2 - r), 0.0, sz * (st.room.depth / 2 - r))
            yield pos, float(np.arctan2(-pos[0], -pos[2])), "", []
        elif op == "free":
            m = max(obj.dims[0], obj.dims[2]) / 2 + 0.3
            pos = (
                float(rng.uniform(-st.room.width / 2 + m, st.room.width / 2 - m)),
                0.0,
                float(rng.uniform(-st.room.depth / 2 + m, st.room.depth / 2 - m)),
            )
            yield pos, (float(rng.integers(4)) * np.pi / 2 if rule.yaw is None else rule.yaw), "", []
        elif op == "centre":
            pos = (float(rng.uniform(-0.3, 0.3)), 0.0, float(rng.uniform(-0.3, 0.3)))
            yield pos, (float(rng.integers(2)) * np.pi / 2 if rule.yaw is None else rule.yaw), "", []
        elif anchor is not None:
            a = catalog.asset_for(anchor)
            ad, aw, od, ow = a.dims[2], a.dims[0], obj.dims[2], obj.dims[0]
            if op == "front":
                gap = float(rng.uniform(*rule.gap))
                lateral = float(rng.uniform(-0.15, 0.15)) * aw
                local = np.array([lateral, 0.0, ad / 2 + gap + od / 2])
                yaw = anchor.yaw + (np.pi if rule.facing else 0.0)
                rels = [("in_front_of", anchor.id)] + ([("facing", anchor.id)] if rule.facing else [])
                yield _local_to_world(anchor, local), yaw, "", rels
            elif op == "beside":
                side = rule.side or ("left" if rng.random() < 0.5 else "right")
                sgn = 1.0 if side == "left" else -1.0
                gap = float(rng.uniform(*rule.gap))
                local = np.array([sgn * (aw / 2 + gap + ow / 2), 0.0, -ad / 2 + od / 2])
                rels = [("left_of" if side == "left" else "right_of", anchor.id)]
                if gap + 1e-9 <= 0.4:
                    rels.append(("next_to", anchor.id))
                yield _local_to_world(anchor, local), anchor.yaw, "", rels
            elif op == "around":
                quadrant = int(rng.integers(4))
                if quadrant < 2:
                    z = (ad / 2 + rule.gap[0] + od / 2) * (1 if quadrant == 0 else -1)
                    x = float(rng.uniform(-0.35, 0.35)) * max(aw - ow, 0.0)
                    local, yaw_local = np.array([x, 0.0, z]), (np.pi if quadrant == 0 else 0.0)
                else:
                    x = (aw / 2 + rule.gap[0] + od / 2) * (1 if quadrant == 2 else -1)
                    z = float(rng.uniform(-0.3, 0.3)) * max(ad - ow, 0.0)
                    local, yaw_local = np.array([x, 0.0, z]), (-np.pi / 2 if quadrant == 2 else np.pi / 2)
                yield _local_to_world(anchor, local), anchor.yaw + yaw_local, "", [("around", anchor.id)]
            elif op == "under":
                x = float(rng.uniform(-0.3, 0.3)) * max(aw - ow, 0.0)
                local = np.array([x, 0.0, float(rng.uniform(-0.2, 0.1)) * ad])
                yield _local_to_world(anchor, local), anchor.yaw, "", [("under", anchor.id)]
            elif op == "on":
                surfs = a.support_surfaces
                if not surfs:
                    return
                s = (
                    surfs[int(rng.integers(len(surfs)))]
                    if rule.any_surface
                    else max(surfs, key=lambda q: q.height)
                )
                half = np.array([ow / 2, od / 2])
                lo, hi = s.min_xz + half, s.max_xz - half
                if np.any(lo > hi):
                    continue
                xz = rng.uniform(lo, hi)
                local = np.array([xz[0], s.height, xz[1]])
                yield _local_to_world(anchor, local), anchor.yaw, anchor.id, [("on", anchor.id)]
            elif op == "above":
                top = a.dims[1]
                y = float(rng.uniform(*rule.height)) + top
                local = np.array([0.0, 0.0, -ad / 2 + od / 2])
                p = _local_to_world(anchor, local)
                yield (p[0], anchor.position[1] + y, p[2]), anchor.yaw, "", [("hanging_above", anchor.id)]


def _new_id(st: _State, category: str) -> str:
    k = st.counts.get(category, 0) + 1
    st.counts[category] = k
    return category if k == 1 else f"{category}#{k}"


def _apply(st: _State, rule: Rule) -> None:
    if rule.anchor.endswith("*"):
        for p in [q for q in st.placed if q.category == rule.anchor[:-1]]:
            _apply_once(st, rule, p)
        return
    _apply_once(st, rule, None)


def _apply_once(st: _State, rule: Rule, anchor: PlacedObject | None) -> None:
    rng = st.rng
    if rng.random() > rule.p:
        return
    if rule.anchor and anchor is None:
        if rule.anchor not in st.labels:
            return
        anchor = st.by_id(st.labels[rule.anchor])
    n = int(rng.integers(rule.n[0], rule.n[1] + 1))
    category = rule.category
    if "|" in category:
        options = category.split("|")
        category = options[int(rng.integers(len(options)))]
    for _ in range(n):
        attrs = _random_attributes(category, rng)
        seed = int(rng.integers(0, 4))
        obj = catalog.make_object(category, attrs, seed)
        oid = _new_id(st, category)
        for pos, yaw, support, rels in _candidates(st, rule, obj, anchor):
            if rule.op in ("front", "beside", "around", "under") and obj.mount != "wall":
                pos = (pos[0], 0.0, pos[2])  # anchors may be raised (a TV on a stand, a hung board)
            cand = PlacedObject(
                id=oid,
                category=category,
                attributes=obj.attributes,
                seed=seed,
                position=(round(float(pos[0]), 4), round(float(pos[1]), 4), round(float(pos[2]), 4)),
                yaw=round(float(np.arctan2(np.sin(yaw), np.cos(yaw))), 5),
                support=support,
            )
            if not _fits(st, cand):
                continue
            if not all(relation_holds(r, cand, st.by_id(aid)) for r, aid in rels):
                continue
            st.placed.append(cand)
            st.bounds[oid] = catalog.world_bounds(cand)
            st.boxes[oid] = catalog.world_collision_boxes(cand)
            st.labels.setdefault(rule.label or category, oid)
            st.relations.extend(RelationNode(subject=oid, relation=r, object=aid) for r, aid in rels)
            break
        else:
            st.counts[category] -= 1


def generate_scene(room_type: str, seed: int) -> GeneratedScene:
    """Generate one scene of a room type with a seed (same input -> same scene).

    Raises:
        KeyError: for a room type without rules.
    """
    if room_type not in RULES:
        raise KeyError(f"no scene rules for room type {room_type!r}; known: {sorted(RULES)}")
    rng = np.random.default_rng([seed, list(vocabulary.ROOM_TYPES).index(room_type)])
    (w0, w1), (d0, d1), hgt = ROOM_SIZES[room_type]
    room = Room(
        room_type=room_type,
        width=round(float(rng.uniform(w0, w1)), 2),
        depth=round(float(rng.uniform(d0, d1)), 2),
        height=hgt,
    )
    st = _State(room=room, rng=rng)
    for rule in RULES[room_type]:
        _apply(st, rule)
    _add_near_relations(st)
    nodes = [
        ObjectNode(
            id=p.id, category=p.category, word=p.category.replace("_", " "), attributes=dict(p.attributes)
        )
        for p in st.placed
    ]
    return GeneratedScene(
        room_type=room_type,
        seed=seed,
        objects=nodes,
        relations=st.relations,
        scene=Scene(room=room, objects=st.placed, seed=seed),
    )


def _add_near_relations(st: _State) -> None:
    """Floor objects without any relation get "near" their closest floor neighbour when it holds."""
    related = {r.subject for r in st.relations}
    for p in st.placed:
        if p.id in related or p.support:
            continue
        others = [o for o in st.placed if o.id != p.id and not o.support]
        if not others:
            continue
        c = (st.bounds[p.id][0] + st.bounds[p.id][1]) / 2
        best = min(
            others,
            key=lambda o: float(np.linalg.norm(((st.bounds[o.id][0] + st.bounds[o.id][1]) / 2 - c)[[0, 2]])),
        )
        if relation_holds("near", p, best):
            st.relations.append(RelationNode(subject=p.id, relation="near", object=best.id))
