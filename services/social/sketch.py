"""A compact notation for social stories, for evaluation, tests and debugging without the NLP stage.

One sentence per ``;``-separated item, each made the way the NLP stage makes its graphs:
    "rel Mary Tom boss"      -> SocialNode(relation, [Mary, Tom], "boss")   (Mary is Tom's boss)
    "emo Tom angry"          -> SocialNode(emotion, [Tom], "angry")
    "act Tom criticize Mary" -> Tom's ActionNode(action "criticize", target "Mary") + the social-verb node
    "act Tom cry"            -> an untargeted action
    "both Tom Mary quarrel"  -> both characters do the action ("They quarrel")
"""

from __future__ import annotations

from proto.ssg import ActionNode, CharacterNode, SentenceGraph, SocialNode


def sketch_graphs(text: str) -> list[SentenceGraph]:
    """Sentence graphs of a sketch ("rel Tom Mary friends; act Tom hug Mary").

    Raises:
        ValueError: an item it cannot read.
    """
    graphs = []
    for n, item in enumerate(i.strip() for i in text.split(";")):
        if not item:
            continue
        words = item.split()
        kind, args = words[0], words[1:]
        sid = f"s{n}"
        if kind == "rel" and len(args) == 3:
            a, b, label = args
            g = SentenceGraph(
                sentence_id=sid,
                text=item,
                kind="action",
                characters=[CharacterNode(name=a), CharacterNode(name=b)],
                social=[SocialNode(kind="relation", subjects=[a, b], label=label)],
            )
        elif kind == "emo" and len(args) == 2:
            g = SentenceGraph(
                sentence_id=sid,
                text=item,
                kind="action",
                characters=[CharacterNode(name=args[0])],
                social=[SocialNode(kind="emotion", subjects=[args[0]], label=args[1])],
            )
        elif kind == "act" and len(args) in (2, 3):
            target = args[2] if len(args) == 3 else ""
            node = ActionNode(verb=args[1].split("_")[0], action=args[1], target=target)
            social = (
                [SocialNode(kind="emotion", subjects=[args[0], target], label=node.verb)] if target else []
            )
            g = SentenceGraph(
                sentence_id=sid,
                text=item,
                kind="action",
                characters=[CharacterNode(name=args[0], actions=[node])],
                social=social,
            )
        elif kind == "both" and len(args) == 3:
            node = ActionNode(verb=args[2], action=args[2])
            g = SentenceGraph(
                sentence_id=sid,
                text=item,
                kind="action",
                characters=[
                    CharacterNode(name=args[0], actions=[node]),
                    CharacterNode(name=args[1], actions=[node]),
                ],
            )
        else:
            raise ValueError(
                f"cannot read sketch item {item!r} (rel A B label | emo A label | act A action [B] | both A B action)"
            )
        graphs.append(g)
    return graphs
