"""Checks of a scene sentence: the objects it names are in the room, with their count, and its relations hold.

The relation geometry is the project's own predicate (wana.assets.relations, on world bounds and support
surfaces), the same one retrieval keeps true, so a relation that retrieval could not keep shows here.
"""

from __future__ import annotations

import numpy as np

from proto.fidelity import Check
from proto.ssg import SentenceGraph
from wana.assets import vocabulary
from wana.assets.catalog import world_bounds
from wana.assets.relations import AROUND_M, NEAR_M, NEXT_TO_M, anchor_copy, footprint_gap, relation_holds
from wana.fidelity.world import World, display

RELATION_WORDS = {
    "on": "on",
    "near": "near",
    "in_front_of": "in front of",
    "behind": "behind",
    "left_of": "left of",
    "right_of": "right of",
    "under": "under",
    "above": "above",
    "next_to": "next to",
    "facing": "facing",
    "in": "in",
    "around": "around",
    "hanging_above": "hanging above",
}


def plural(name: str) -> str:
    if name.endswith(("s", "sh", "ch", "x")):
        return name + "es"
    return name[:-1] + "ies" if name.endswith("y") and name[-2:-1] not in "aeiou" else name + "s"


def _family(category: str) -> str:
    info = vocabulary.CATEGORIES.get(category)
    return info.parent if info is not None and info.parent else category


def object_checks(graph: SentenceGraph, world: World) -> list[Check]:
    """One `object_exists` check per object the sentence names (count and category included)."""
    checks = []
    for node in graph.objects:
        name = display(node.category)
        placed = world.copies(node.id)
        if not placed:
            checks.append(
                Check(
                    name="object_exists", ok=False, essential=True, reason=f"there is no {name} in the room"
                )
            )
            continue
        wrong = [
            p for p in placed if p.category != node.category and _family(p.category) != _family(node.category)
        ]
        if len(placed) < node.count:
            checks.append(
                Check(
                    name="object_exists",
                    ok=False,
                    reason=f"only {len(placed)} of the {node.count} {plural(name)} are in the room",
                )
            )
        elif wrong:
            checks.append(
                Check(
                    name="object_exists",
                    ok=False,
                    reason=f"the room has a {display(wrong[0].category)} where the text asks for a {name}",
                )
            )
        else:
            many = f"{node.count} {plural(name)} are" if node.count > 1 else f"the {name} is"
            checks.append(Check(name="object_exists", ok=True, reason=f"{many} in the room"))
    return checks


# How much further apart than the composer's own thresholds two objects may be and still look "near" /
# "next to" one another: judged on contact sheets (a stool 0.45 m from a drum kit reads as next to it).
PERCEIVED_SLACK_M = 0.1
_DISTANCE_LIMITS = {"near": NEAR_M, "next_to": NEXT_TO_M, "around": AROUND_M}


ON_SHARE = 0.5  # of the subject's footprint over the anchor's top: it reads as on it (a wrench at the edge)
ON_HEIGHT_M = 0.03


def _looks_on(subject, anchor) -> bool:  # noqa: ANN001 - PlacedObjects
    """Resting at the anchor's top height with at least half its footprint over the anchor: a viewer sees it
    on top even when its origin overhangs the support rectangle's edge (the predicate tests the origin)."""
    bs, ba = world_bounds(subject), world_bounds(anchor)
    if abs(float(subject.position[1]) - float(ba[1, 1])) > ON_HEIGHT_M:
        return False
    lo, hi = np.maximum(bs[0, [0, 2]], ba[0, [0, 2]]), np.minimum(bs[1, [0, 2]], ba[1, [0, 2]])
    over = float(np.prod(np.maximum(hi - lo, 0.0)))
    area = float(np.prod(np.maximum(bs[1, [0, 2]] - bs[0, [0, 2]], 1e-6)))
    return over / area >= ON_SHARE


def _looks_true(relation: str, subject, anchor) -> bool:  # noqa: ANN001 - PlacedObjects
    """The relation as a viewer judges it: the geometric predicate, with a little slack on distances."""
    if relation_holds(relation, subject, anchor):
        return True
    if relation == "on":
        return _looks_on(subject, anchor)
    limit = _DISTANCE_LIMITS.get(relation)
    if limit is None or relation == "around":
        return False
    return footprint_gap(subject, anchor) <= limit + PERCEIVED_SLACK_M


def _why_not(relation: str, subject, anchor) -> str:  # noqa: ANN001 - PlacedObjects
    if relation == "on":
        top = float(world_bounds(anchor)[1, 1])
        base = float(subject.position[1])
        if abs(base - top) > 0.03:
            where = "above" if base > top else "below"
            return f"its base is {abs(base - top):.2f} m {where} the top of the {display(anchor.id)}"
        return f"it is beside the {display(anchor.id)}, not over it"
    gap = footprint_gap(subject, anchor)
    if relation in ("near", "next_to", "around"):
        return f"they are {gap:.2f} m apart"
    d = np.subtract(subject.position, anchor.position)
    return f"it stands {float(np.hypot(d[0], d[2])):.1f} m from the {display(anchor.id)} in another direction"


def relation_checks(graph: SentenceGraph, world: World) -> list[Check]:
    """One `relation_holds` check per stated relation, between every copy of the subject and the anchor."""
    checks = []
    for rel in graph.relations:
        words = RELATION_WORDS.get(rel.relation, rel.relation.replace("_", " "))
        subjects, anchors = world.copies(rel.subject), world.copies(rel.object) or world.find(rel.object)
        said = f"the {display(rel.subject)} {words} the {display(rel.object)}"
        if not subjects or not anchors:
            missing = display(rel.subject) if not subjects else display(rel.object)
            checks.append(
                Check(name="relation_holds", ok=False, reason=f"{said}: there is no {missing} to place")
            )
            continue
        # "a chair at each desk": chair k at desk k; otherwise every copy at the (first) anchor
        by_id = {a.id: a for a in anchors}
        pairs = [(s, by_id.get(anchor_copy(s.id, rel, len(anchors)), anchors[0])) for s in subjects]
        failing = [(s, a) for s, a in pairs if not _looks_true(rel.relation, s, a)]
        if failing:
            subject, anchor = failing[0]
            checks.append(
                Check(
                    name="relation_holds",
                    ok=False,
                    reason=f"the {display(subject.id)} is not {words} the {display(anchor.id)}: "
                    + _why_not(rel.relation, subject, anchor),
                )
            )
        else:
            checks.append(Check(name="relation_holds", ok=True, reason=f"{said} holds"))
    return checks


__all__ = ["RELATION_WORDS", "object_checks", "relation_checks"]
