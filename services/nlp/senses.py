"""Room-aware word senses: "the sink" in a bathroom is the bathroom sink, "her desk" is the teacher's
desk already standing there.

A bare word that several catalog kinds share ("sink", "desk", "chair") means, in order: a kind already
in the scene when the phrase is definite ("the sink", "her desk"), the kind it looks up to when that
fits the room, then a kind that fits the room type (``wana.assets.vocabulary.sense_in_context``). The
object keeps its node; its category and id change, and so do the relations and actions that name it.

A definite thing the scene lacks that a kind in it carries as a part is that kind: "Dad lights the
candles" after "A cake is on the table" is the cake's candles (the cake is made with them), not three
more candles placed around the room.
"""

from __future__ import annotations

import re

import msgspec

from proto.ssg import ActionNode, CharacterNode, ObjectNode, SentenceGraph
from wana.assets import vocabulary

# A kind -> the kinds that carry it as a part of their own mesh.
CARRIED_BY: dict[str, tuple[str, ...]] = {"candle": ("cake",)}
_DEFINITE = re.compile(r"\b(the|his|her|their|its|my|your|our|this|that|these|those)\s*$", re.IGNORECASE)


def _definite(graph: SentenceGraph, obj: ObjectNode, base: int) -> bool:
    local = max(0, obj.span.start - base)
    return bool(_DEFINITE.search(graph.text[:local])) or bool(
        re.match(r"(the|his|her|their|its|my|your|our|this|that)\b", graph.text[local:], re.IGNORECASE)
    )


def room_senses(graphs: list[SentenceGraph], offsets: list[int] | None = None) -> list[SentenceGraph]:
    """The graphs with every shared word read as the kind it means in this room (see module doc)."""
    room = next((g.room_type for g in graphs if g.room_type), "")
    present: list[str] = []
    renames: dict[str, str] = {}
    out: list[SentenceGraph] = []
    for gi, graph in enumerate(graphs):
        base = offsets[gi] if offsets is not None and gi < len(offsets) else 0
        objects: list[ObjectNode] = []
        changed = False
        for o in graph.objects:
            word = o.word.split()[-1] if o.word else ""
            if o.id in renames:
                new_cat = renames[o.id].split("#")[0]
            elif word and vocabulary.lookup(word) not in (None, o.category):
                new_cat = o.category  # "the teacher's desk": its words named the kind, not the bare "desk"
            else:
                seen = tuple(present) if _definite(graph, o, base) else ()
                new_cat = vocabulary.sense_in_context(word, o.category, room, seen) if word else o.category
                if o.category not in seen:
                    new_cat = next((c for c in CARRIED_BY.get(o.category, ()) if c in seen), new_cat)
            if new_cat != o.category and new_cat in vocabulary.CATEGORIES:
                suffix = o.id[len(o.category) :] if o.id.startswith(o.category) else ""
                renames.setdefault(o.id, new_cat + suffix)
                count = 1 if new_cat in CARRIED_BY.get(o.category, ()) else o.count
                o = msgspec.structs.replace(o, category=new_cat, id=renames[o.id], count=count)
                changed = True
            objects.append(o)
            if o.category not in present:
                present.append(o.category)
        if changed or any(_names(graph, renames)):
            graph = _renamed(graph, objects, renames)
        out.append(graph)
    return out


def _names(graph: SentenceGraph, renames: dict[str, str]) -> list[str]:
    ids = [r.subject for r in graph.relations] + [r.object for r in graph.relations]
    ids += [v for c in graph.characters for a in c.actions for v in (a.target, a.instrument, a.destination)]
    return [i for i in ids if i in renames]


def _renamed(graph: SentenceGraph, objects: list[ObjectNode], renames: dict[str, str]) -> SentenceGraph:
    def mv(a: ActionNode) -> ActionNode:
        return msgspec.structs.replace(
            a,
            target=renames.get(a.target, a.target),
            instrument=renames.get(a.instrument, a.instrument),
            destination=renames.get(a.destination, a.destination),
        )

    relations = [
        msgspec.structs.replace(
            r, subject=renames.get(r.subject, r.subject), object=renames.get(r.object, r.object)
        )
        for r in graph.relations
    ]
    characters: list[CharacterNode] = [
        msgspec.structs.replace(c, actions=[mv(a) for a in c.actions]) for c in graph.characters
    ]
    return msgspec.structs.replace(graph, objects=objects, relations=relations, characters=characters)
