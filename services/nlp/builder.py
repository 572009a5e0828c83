"""Accumulates one sentence's graph: object ids, relations, characters, diagnostics -> SentenceGraph."""

from __future__ import annotations

from dataclasses import dataclass, field

from spacy.tokens import Token

from proto.common import Span
from proto.ssg import (
    RELATIONS,
    ActionNode,
    CharacterNode,
    Command,
    Diagnostic,
    ObjectNode,
    RelationNode,
    SentenceGraph,
    SentenceKind,
    SocialNode,
)
from services.nlp.errors import diagnostic
from services.nlp.mentions import ObjectMention


@dataclass
class _Obj:
    id: str
    category: str
    word: str
    attributes: dict[str, str]
    count: int
    start: int
    end: int


@dataclass
class _Char:
    name: str
    mention: str
    pronoun: str
    actions: list[ActionNode] = field(default_factory=list)


class GraphBuilder:
    """Builds the SentenceGraph of one sentence; spans are shifted by ``offset`` into the document."""

    def __init__(self, text: str, offset: int) -> None:
        self.text = text
        self.offset = offset
        self.objects: list[_Obj] = []
        self._by_token: dict[int, str] = {}
        self.relations: list[RelationNode] = []
        self._relation_keys: set[tuple[str, str, str]] = set()
        self.characters: list[_Char] = []
        self.social: list[SocialNode] = []
        self.commands: list[Command] = []
        self.diagnostics: list[Diagnostic] = []
        self._diag_keys: set[tuple[str, int, int]] = set()
        self.room_type = ""

    def span(self, start: int, end: int) -> Span:
        return Span(self.offset + start, self.offset + end)

    def token_span(self, tok: Token) -> Span:
        return self.span(tok.idx, tok.idx + len(tok.text))

    # --- objects and relations ---------------------------------------------------------------------

    def object_id(self, mention: ObjectMention) -> str:
        """Id of the object a mention names; a new node unless the same token or a definite repeat."""
        if mention.head.i in self._by_token:
            return self._by_token[mention.head.i]
        same = [o for o in self.objects if o.category == mention.category]
        target: _Obj | None = None
        if same and mention.definite:
            target = same[0]
        if target is None:
            oid = mention.category if not same else f"{mention.category}#{len(same) + 1}"
            target = _Obj(
                oid,
                mention.category,
                mention.word,
                dict(mention.attributes),
                mention.count,
                mention.start,
                mention.end,
            )
            self.objects.append(target)
        else:
            for k, v in mention.attributes.items():
                target.attributes.setdefault(k, v)
        self._by_token[mention.head.i] = target.id
        return target.id

    def drop_object(self, object_id: str) -> None:
        """Forget an object a word seemed to name that is no thing ("takes a photo of the cake": the act)."""
        if any(object_id in (r.subject, r.object) for r in self.relations):
            return
        self.objects = [o for o in self.objects if o.id != object_id]
        self._by_token = {k: v for k, v in self._by_token.items() if v != object_id}

    def set_attribute(self, object_id: str, knob: str, value: str) -> None:
        for o in self.objects:
            if o.id == object_id:
                o.attributes[knob] = value

    def add_relation(
        self, subject: str, relation: str, anchor: str, start: int, end: int, *, each: bool = False
    ) -> None:
        if relation not in RELATIONS or subject == anchor:
            return
        key = (subject, relation, anchor)
        if key in self._relation_keys:
            return
        self._relation_keys.add(key)
        self.relations.append(
            RelationNode(
                subject=subject, relation=relation, object=anchor, span=self.span(start, end), each=each
            )
        )

    # --- characters -----------------------------------------------------------------------------------

    def character(self, name: str, mention: str, pronoun: str = "") -> _Char:
        key = name or mention.lower()
        for c in self.characters:
            if (c.name or c.mention.lower()) == key:
                return c
        c = _Char(name=name, mention=mention, pronoun=pronoun)
        self.characters.append(c)
        return c

    def add_social(self, kind: str, subjects: list[str], label: str, start: int, end: int) -> None:
        node = SocialNode(kind=kind, subjects=subjects, label=label, span=self.span(start, end))  # type: ignore[arg-type]
        if node not in self.social:
            self.social.append(node)

    def add_command(self, kind: str, value: str, start: int, end: int) -> None:
        """A command a sentence implies ("that night" -> weather night); one of each kind."""
        if not any(c.kind == kind for c in self.commands):
            self.commands.append(Command(kind=kind, value=value, span=self.span(start, end)))  # type: ignore[arg-type]

    # --- diagnostics -------------------------------------------------------------------------------------

    def diagnose(self, code: str, detail: str, start: int, end: int) -> None:
        """Add a diagnostic for sentence-local characters [start, end)."""
        key = (code, start, end)
        if key not in self._diag_keys:
            self._diag_keys.add(key)
            self.diagnostics.append(diagnostic(code, detail, self.offset + start, self.offset + end))

    def build(self, sentence_id: str, kind: SentenceKind) -> SentenceGraph:
        objects = [
            ObjectNode(
                id=o.id,
                category=o.category,
                word=o.word,
                attributes=dict(sorted(o.attributes.items())),
                count=o.count,
                span=self.span(o.start, o.end),
            )
            for o in self.objects
        ]
        characters = [
            CharacterNode(name=c.name, actions=list(c.actions), mention=c.mention) for c in self.characters
        ]
        return SentenceGraph(
            sentence_id=sentence_id,
            text=self.text,
            kind=kind,
            objects=objects,
            relations=list(self.relations),
            characters=characters,
            social=list(self.social),
            commands=list(self.commands),
            diagnostics=list(self.diagnostics),
            room_type=self.room_type,
        )
