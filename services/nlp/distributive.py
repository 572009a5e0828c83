"""Distributive scene phrases: "A chair is at each desk", "Each table has a lamp on it".

A relation written with "each"/"every" on its anchor (``RelationNode.each``) places one subject at every
copy of that anchor, so the subject gets as many copies as the anchor has ("two desks" and "a chair at
each desk" make two chairs). The count is set here, over the whole document, because the anchor's count
may come from another sentence; the layout then pairs copy k of the subject with copy k of the anchor.
"""

from __future__ import annotations

import msgspec

from proto.ssg import SentenceGraph


def each_copies(graphs: list[SentenceGraph]) -> list[SentenceGraph]:
    """The graphs with every subject of an "each" relation counted once per copy of its anchor."""
    counts: dict[str, int] = {}
    for g in graphs:
        for o in g.objects:
            counts.setdefault(o.id, o.count)
    out: list[SentenceGraph] = []
    for g in graphs:
        per_anchor = {r.subject: counts.get(r.object, 1) for r in g.relations if r.each}
        if not any(n > 1 for n in per_anchor.values()):
            out.append(g)
            continue
        objects = [
            msgspec.structs.replace(o, count=o.count * per_anchor[o.id]) if per_anchor.get(o.id, 1) > 1 else o
            for o in g.objects
        ]
        out.append(msgspec.structs.replace(g, objects=objects))
    return out


__all__ = ["each_copies"]
