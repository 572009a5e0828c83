"""Document-level resolution of names and pronouns across sentence graphs (cheap, pure).

Kept apart from the per-sentence parse so that editing one sentence re-parses only that sentence
and then re-runs this pass over all graphs (microseconds per sentence).

Rules, in document order:
- a name or person noun introduces (or repeats) a character; its spelling at first mention wins;
- "he"/"she" -> the most recent character of that gender (names and person nouns carry a gender when
  known; a character of unknown gender matches either);
- "they" -> the characters of the most recent sentence that had two or more, else the last two;
- a sentence without a subject ("Walk to the door.") -> the most recent acting character;
- "him"/"her"/"them" as targets -> as above, never the acting character itself;
- "it"/"this"/"that" as targets -> the most recent object mentioned;
- what cannot be resolved stays "" and gets a W105/W109 diagnostic.
"""

from __future__ import annotations

import re

import msgspec

from proto.common import Span
from proto.ssg import ActionNode, CharacterNode, Diagnostic, ObjectNode, SentenceGraph, SocialNode
from services.nlp import lexicon
from services.nlp.distributive import each_copies
from services.nlp.errors import diagnostic
from services.nlp.scene import PRONOUN_ANCHOR
from services.nlp.senses import room_senses

PRONOUN_WORDS = {
    "he": "he",
    "him": "he",
    "his": "he",
    "she": "she",
    "her": "she",
    "they": "they",
    "them": "they",
    "everyone": "all",
    "everybody": "all",
    "their": "they",
    "it": "it",
}


# Actions named by their own noun, whatever the pronoun turns out to be ("takes a photo of it": a photo)
OWN_NOUN_ACTIONS = frozenset({"take_photo"})


class _State:
    def __init__(self) -> None:
        self.characters: list[str] = []  # in order of last mention, most recent last
        self.spelling: dict[str, str] = {}
        self.gender: dict[str, str] = {}
        self.last_group: list[str] = []
        self.last_actor = ""
        self.last_object = ""
        self.object_categories: dict[str, str] = {}
        self.seat_of: dict[str, str] = {}  # character -> the object it last sat or lay on
        self.went_to: dict[str, str] = {}  # character -> the object its last action went to or used
        self.several: set[str] = set()  # object ids that stand for more than one ("eight chairs")
        self.multiword: dict[str, str] = {}  # last word of an object named in several words -> its id
        self.resolved_words: set[str] = set()  # words of this sentence that turned out to name an object
        self.passing_names: list[str] = []  # names said of no acting character ("Jen's phone", "named Rosa")
        self.last_sentence: list[str] = []  # the characters the previous sentence named
        self.described: dict[str, str] = {}  # "waitress" -> "Rosa" after "a waitress named Rosa"

    def mention(self, name: str, recent: bool = True) -> str:
        """Register a mention; ``recent=False`` (an object of a verb) keeps the subject the most recent."""
        key = name.lower()
        canonical = self.spelling.setdefault(key, name)
        if not recent:
            if canonical not in self.characters:
                self.characters.insert(0, canonical)
        else:
            if canonical in self.characters:
                self.characters.remove(canonical)
            self.characters.append(canonical)
        if key not in self.gender:
            words = [w.rstrip(".") for w in key.split()] or [""]
            first = words[0]
            if first in lexicon.TITLES and first not in lexicon.FEMALE_NOUNS | lexicon.MALE_NOUNS:
                first = words[-1]  # "Dr. Ada": the name says it
            if first in lexicon.FEMALE_NAMES or first in lexicon.FEMALE_NOUNS:
                self.gender[key] = "she"
            elif first in lexicon.MALE_NAMES or first in lexicon.MALE_NOUNS:
                self.gender[key] = "he"
            else:
                self.gender[key] = ""
        return canonical

    def pronoun(self, pron: str, exclude: str = "") -> list[str]:
        if pron == "it":  # "The bunny hops. It ...": only an animal is an "it" that acts
            return [c for c in self.characters if c != exclude and _is_animal(c)][-1:]
        if pron == "all":  # "Everyone raises their glasses": every character named so far
            return [c for c in self.characters if c != exclude]
        if pron == "they":
            group = [c for c in self.last_group if c != exclude]
            if len(group) >= 2 or (group and exclude):
                return group
            others = [c for c in self.characters if c != exclude]
            return others[-2:]
        # "The waiter hands Ada the menu. She reads it": of the last sentence's characters, one known
        # to be a she before one whose gender nothing says; else the most recent that may be one
        for c in reversed(self.characters):
            if c != exclude and c in self.last_sentence and self.gender.get(c.lower(), "") == pron:
                return [c]
        for c in reversed(self.characters):
            if c != exclude and self.gender.get(c.lower(), "") in ("", pron):
                return [c]
        return []


def _is_animal(name: str) -> bool:
    return name in lexicon.ANIMAL_NOUNS or name in lexicon.THING_ANIMALS


_PASSING_NAME = re.compile(r"\b(?:named|called) ([A-Z][a-z]+)\b|\b([A-Z][a-z]+)'s\b")


_DESCRIBED_NAME = (
    re.compile(r"\b([a-z]+) (?:named|called) ([A-Z][a-z]+)\b"),  # "a waitress named Rosa"
    re.compile(
        r"\b(?:[Hh]is|[Hh]er|[Tt]heir|[Mm]y|[Oo]ur|[Tt]he|[Aa]n?) ([a-z]+) ([A-Z][a-z]+)\b"
    ),  # "his grandson Eli"
    re.compile(r"\b([A-Z][a-z]+), (?:the|a|an|his|her|their) ([a-z]+),"),  # "Rosa, the waitress,"
)


def _described_names(text: str) -> dict[str, str]:
    """Person nouns a sentence gives a name ("a waitress named Rosa", "his grandson Eli", "Rosa, the
    waitress,") -> that name: a later "the waitress" is Rosa (services.nlp.repair makes Rosa the one who acts)."""
    out = {}
    for k, pattern in enumerate(_DESCRIBED_NAME):
        for m in pattern.finditer(text):
            noun, name = (m.group(2), m.group(1)) if k == 2 else (m.group(1), m.group(2))
            if noun in lexicon.PERSON_NOUNS and name.lower() not in lexicon.TITLES | lexicon.PRONOUNS.keys():
                out[noun] = name
    return out


def _names_in_passing(text: str) -> list[str]:
    """Names a sentence gives without making them act: "a girl named Rosa lived ...", "Jen's phone
    buzzes"; a later "she" with no other character to refer to is that one."""
    out = []
    for m in _PASSING_NAME.finditer(text):
        name = m.group(1) or m.group(2)
        lower = name.lower()
        if lower in lexicon.PRONOUNS or lower in lexicon.TITLES or lexicon.category_of(lower) is not None:
            continue
        out.append(name)
    return out


def _pronoun_of(mention: str) -> str:
    words = mention.lower().split()
    if len(words) >= 2 and words[0] == "the" and words[-1] in lexicon.COLLECTIVE_NOUNS:
        return "all"  # "The band bows": everyone on stage
    return PRONOUN_WORDS.get(mention.lower().strip(), "")


def _span_of(graph: SentenceGraph, word: str, offset: int | None, fallback: Span) -> Span:
    if offset is not None and word:
        m = re.search(rf"\b{re.escape(word)}\b", graph.text)
        if m:
            return Span(offset + m.start(), offset + m.end())
    return fallback


def _resolve_ref(
    value: str,
    state: _State,
    actor: str,
    graph: SentenceGraph,
    before: int = -1,
    group: tuple[str, ...] = (),
) -> str:
    """A target/destination that is a pronoun or a character name -> canonical name or object id.

    ``before``: document offset of the action; "it" means the last object mentioned before it.
    ``group``: the characters a plural subject stood for; "each other" is the one that is not ``actor``.
    """
    if not value:
        return value
    lower = value.lower()
    if lower in lexicon.RECIPROCAL_PHRASES:
        others = [n for n in group if n != actor]
        if len(others) == 1:
            return others[0]
        return "each other" if not others else ""  # "the children whisper to each other": among them
    if lower in lexicon.PART_NOUNS and state.last_object in state.object_categories:
        state.resolved_words.add(lower)
        return state.last_object  # "slams the lid": of the machine just filled
    if lower in ("everything", "all") and state.last_object:
        return state.last_object  # "folds everything": what was just handled (the clothes)
    if lower in state.multiword and value not in state.object_categories:
        state.resolved_words.add(lower)
        return state.multiword[lower]  # "into the machine" after "a washing machine"
    if lower in lexicon.OBJECT_PRONOUNS and lower != "them":
        ids = [o.id for o in graph.objects if before < 0 or o.span.end <= before]
        return ids[-1] if ids else (_thing_before(graph, state, before) or state.last_object)
    if lower == "them" and (thing := _thing_before(graph, state, before)):
        return thing  # "chops the onions and fries them"
    pron = _pronoun_of(lower)
    if pron == "all":
        return value  # "waves at everyone": at the room, not at one of them
    if pron:
        names = state.pronoun(pron, exclude=actor)
        return names[0] if names else (state.last_object if lower == "them" else "")
    if lower in state.spelling:
        return state.spelling[lower]
    return _titled_character(value, state)


_TITLE_NOUNS = {
    "doctor": ("dr", "doctor"),
    "professor": ("prof", "professor"),
    "detective": ("det", "detective"),
}


def _titled_character(name: str, state: _State) -> str:
    """ "the nurse" after "Nurse Adaeze", "the coach" after "Coach Miller": the one character so titled."""
    if not name or not name.islower() or " " in name or name not in lexicon.PERSON_NOUNS | lexicon.TITLES:
        return name
    if name in state.described:
        return state.described[name]  # "the waitress" after "a waitress named Rosa"
    titles = _TITLE_NOUNS.get(name, (name,))
    hits = {c for c in state.characters if len(c.split()) > 1 and c.split()[0].lower().rstrip(".") in titles}
    return hits.pop() if len(hits) == 1 else name


def _same_thing(
    graph: SentenceGraph, named: dict[str, str], state: _State, offset: int | None
) -> SentenceGraph:
    """ "the can" after "a watering can": the object already named, not a new one of the word's own
    category (a soda can); only for a definite one-word mention."""
    renames: dict[str, str] = {}
    for o in graph.objects:
        earlier = named.get(o.word)
        if earlier is None or earlier == o.id or " " in o.word or o.id in state.object_categories:
            continue
        local = o.span.start - offset if offset is not None else graph.text.lower().find(o.word)
        words = (
            graph.text[: max(0, local)].lower().split()[-1:] + graph.text[max(0, local) :].lower().split()
        )[:3]
        if any(w in ("the", "his", "her", "their") for w in words[:2]):
            renames[o.id] = earlier
    if not renames:
        return graph

    def mv(a: ActionNode) -> ActionNode:
        return msgspec.structs.replace(
            a,
            target=renames.get(a.target, a.target),
            destination=renames.get(a.destination, a.destination),
            instrument=renames.get(a.instrument, a.instrument),
        )

    return msgspec.structs.replace(
        graph,
        objects=[o for o in graph.objects if o.id not in renames],
        characters=[msgspec.structs.replace(c, actions=[mv(a) for a in c.actions]) for c in graph.characters],
        relations=[
            msgspec.structs.replace(
                r, subject=renames.get(r.subject, r.subject), object=renames.get(r.object, r.object)
            )
            for r in graph.relations
        ],
    )


def _is_thing(value: str, state: _State) -> bool:
    """A target that is a thing: an object id, or a word no character, pronoun or body part is
    ("the drink" the catalog lacks: "it" in the next sentence may still mean it)."""
    if value in state.object_categories:
        return True
    lower = value.lower()
    return bool(value) and not (
        value[0].isupper()
        or lower in state.spelling
        or lower in lexicon.PRONOUNS
        or lower in lexicon.OBJECT_PRONOUNS
        or lower in lexicon.BODY_PARTS
        or lower in lexicon.RECIPROCAL_PHRASES
        or lower in lexicon.PERSON_NOUNS
    )


def _thing_before(graph: SentenceGraph, state: _State, before: int) -> str:
    """The last thing acted upon earlier in the same sentence, or "" ("fries them" after "the onions")."""
    things = [
        (a.span.start, a.target)
        for c in graph.characters
        for a in c.actions
        if (before < 0 or a.span.end <= before) and _is_thing(a.target, state)
    ]
    return max(things)[1] if things else ""


def resolve(graphs: list[SentenceGraph], offsets: list[int] | None = None) -> list[SentenceGraph]:
    """Resolve names and pronouns across a document's sentence graphs (in document order).

    Args:
        graphs: the per-sentence graphs, in document order.
        offsets: document offset of each sentence, for exact spans of pronoun diagnostics
            (without it, a diagnostic points at the sentence's first action).

    Returns:
        New graphs; character names canonical, "they" expanded into one node per character.
    """
    graphs = each_copies(distinct_objects(room_senses(graphs, offsets), offsets))
    state = _State()
    out: list[SentenceGraph] = []
    multiword = state.multiword  # "can" -> the watering can
    for gi, graph in enumerate(graphs):
        offset = offsets[gi] if offsets is not None and gi < len(offsets) else None
        if graph.kind == "action":
            graph = _same_thing(graph, multiword, state, offset)
        for o in graph.objects:
            words = o.word.split()
            if len(words) >= 2:
                multiword.setdefault(words[-1], o.id)
            state.object_categories.setdefault(o.id, o.category)
            if o.count > 1:
                state.several.add(o.id)
        diagnostics: list[Diagnostic] = list(graph.diagnostics)
        state.passing_names.extend(_names_in_passing(graph.text))
        state.described.update(_described_names(graph.text))
        sentence_names: list[str] = []
        merged: dict[str, list[ActionNode]] = {}
        mentions: dict[str, str] = {}
        unresolved: list[CharacterNode] = []
        for char in graph.characters:
            first_span = char.actions[0].span if char.actions else Span(0, 0)
            if char.name:
                names = [state.mention(_titled_character(char.name, state))]
            elif char.mention:
                pron = _pronoun_of(char.mention)
                names = state.pronoun(pron) if pron else []
                if not names and pron in ("he", "she") and state.passing_names:
                    names = [state.passing_names[-1]]  # "Jen's phone buzzes. She ...": Jen
                if len(names) == 1 and pron in ("he", "she") and not state.gender.get(names[0].lower()):
                    # "Marcus ... He sits": Marcus is a he from now on, so a later "she" is Dana
                    state.gender[names[0].lower()] = pron
                if not names and pron == "it":
                    continue  # "It rolls away": a thing, not a character
                if not names:
                    diagnostics.append(
                        diagnostic(
                            "W105",
                            f"'{char.mention}'",
                            *_astuple(_span_of(graph, char.mention, offset, first_span)),
                        )
                    )
                    unresolved.append(char)
                    continue
                names = [state.mention(n) for n in names]
            else:
                names = [state.last_actor] if state.last_actor else []
                if not names:
                    diagnostics.append(
                        diagnostic(
                            "W109",
                            "say who does it, e.g. 'Eve walks to the door'",
                            first_span.start,
                            first_span.end,
                        )
                    )
                    unresolved.append(char)
                    continue
            for name in names:
                actions = [_resolve_action(a, state, name, graph, tuple(names)) for a in char.actions]
                merged.setdefault(name, []).extend(actions)
                mentions.setdefault(name, char.mention or name)
                if name not in sentence_names:
                    sentence_names.append(name)
                object_ids = {o.id for o in graph.objects}
                for a in actions:
                    for ref in (a.target, a.destination):
                        if ref and ref not in object_ids and ref[0].isupper():
                            ref = state.mention(ref, recent=False)
                            if ref not in sentence_names:
                                sentence_names.append(ref)
        social: list[SocialNode] = []
        for node in graph.social:
            subjects: list[str] = []
            for s in node.subjects:
                pron = _pronoun_of(s)
                resolved = (
                    state.pronoun(pron, exclude=subjects[0] if subjects and pron != "they" else "")
                    if pron
                    else [state.mention(s) if s.lower() not in state.spelling else state.spelling[s.lower()]]
                )
                if not resolved:
                    diagnostics.append(diagnostic("W105", f"'{s}'", node.span.start, node.span.end))
                for r in resolved:
                    if r not in subjects:
                        subjects.append(r)
            if len(node.subjects) >= 2 and len(subjects) < 2:
                continue  # "takes his hand" with no "him" to be found: no act between two characters
            for r in subjects:
                if r not in sentence_names:
                    sentence_names.append(r)
            social.append(msgspec.structs.replace(node, subjects=subjects))
        if state.resolved_words:  # "the lid", "the machine": no unknown object after all
            diagnostics = [
                d
                for d in diagnostics
                if not (
                    d.code == "W101"
                    and any(f"'{w}' is not in" in d.message.lower() for w in state.resolved_words)
                )
            ]
            state.resolved_words = set()
        named = [a.span for acts in merged.values() for a in acts if a.action]
        diagnostics = [
            d
            for d in diagnostics
            if not (d.code == "W102" and any(s.start <= d.span.start and d.span.end <= s.end for s in named))
        ]
        characters = [CharacterNode(name=n, actions=merged[n], mention=mentions[n]) for n in merged]
        characters += [c for c in unresolved]
        for c in characters:
            if c.name and c.actions:
                state.last_actor = c.name
        if len(sentence_names) >= 2:
            state.last_group = sentence_names
        state.last_sentence = sentence_names or state.last_sentence
        # what was last acted upon: a thing targeted (in the catalog or not), else a catalog destination
        targets = [
            a.target if _is_thing(a.target, state) else a.destination
            for c in characters
            for a in c.actions
            if _is_thing(a.target, state) or a.destination in state.object_categories
        ]
        if targets:
            state.last_object = targets[-1]  # "it" in the next sentence: what was last acted upon
        elif graph.objects:
            state.last_object = graph.objects[-1].id
        out.append(
            msgspec.structs.replace(graph, characters=characters, social=social, diagnostics=diagnostics)
        )
    return out


_NEW_OBJECT = re.compile(r"\b(also|another|second|third|fourth|more|extra|additional|other)\b")
_INDEFINITE = re.compile(r"^(a|an|another|one|some|two|three|four|five|\d+)\b")


def _sentence_offset(graph: SentenceGraph) -> int:
    """Document offset of a graph's sentence when the caller gave none (the orchestrator's resolve):
    where the first object's span, as long as it is, names that object in the sentence text."""
    o = graph.objects[0]
    length = o.span.end - o.span.start
    text, word = graph.text.lower(), o.word.lower()
    for m in re.finditer(re.escape(word), text) if word else ():
        for start in range(max(0, m.end() - length), m.start() + 1):
            if start + length >= m.end() and text[start : start + length].rstrip().endswith(word):
                return o.span.start - start
    return o.span.start


def distinct_objects(graphs: list[SentenceGraph], offsets: list[int] | None = None) -> list[SentenceGraph]:
    """One object node per object across the scene sentences.

    "The desk" of a later scene sentence is the desk already there: its node is dropped (its new
    attributes go to the first node), so the scene has each object once and nobody is told it
    "appears twice". "A lamp" when a lamp is already there, or "also"/"another"/"a second" before
    it, is a new object with a new id ("lamp#2"), in its relations too.
    """
    first: dict[str, tuple[int, int]] = {}  # object id -> (graph index, object index) of its node
    used: set[str] = set()
    out = list(graphs)
    extra_attributes: dict[str, dict[str, str]] = {}
    topic = ""  # the first thing the last scene sentence named: what a later "next to it" is next to
    for gi, graph in enumerate(graphs):
        if graph.kind != "scene" or not graph.objects:
            continue
        base = offsets[gi] if offsets is not None and gi < len(offsets) else _sentence_offset(graph)
        renames: dict[str, str] = {}
        kept: list[ObjectNode] = []
        for o in graph.objects:
            if o.id not in used:
                used.add(o.id)
                first[o.id] = (gi, len(kept))
                kept.append(o)
                continue
            local = max(0, o.span.start - base)
            phrase = graph.text[local : max(local, o.span.end - base)].lower()
            before = " ".join(graph.text[:local].lower().split()[-1:])  # "also" right before "a lamp"
            if _INDEFINITE.match(phrase) or _NEW_OBJECT.search(before + " " + phrase):
                k = 2
                while f"{o.category}#{k}" in used:
                    k += 1
                new_id = f"{o.category}#{k}"
                used.add(new_id)
                renames[o.id] = new_id
                first[new_id] = (gi, len(kept))
                kept.append(msgspec.structs.replace(o, id=new_id))
            else:  # a repeat of an object already in the scene
                extra_attributes.setdefault(o.id, {}).update(o.attributes)
        if renames or len(kept) != len(graph.objects):
            relations = [
                msgspec.structs.replace(
                    r, subject=renames.get(r.subject, r.subject), object=renames.get(r.object, r.object)
                )
                for r in graph.relations
            ]
            out[gi] = msgspec.structs.replace(graph, objects=kept, relations=relations)
        done = out[gi]
        if any(r.object == PRONOUN_ANCHOR for r in done.relations):
            out[gi] = msgspec.structs.replace(
                done,
                relations=[
                    msgspec.structs.replace(r, object=topic) if r.object == PRONOUN_ANCHOR else r
                    for r in done.relations
                    if r.object != PRONOUN_ANCHOR or (topic and topic != r.subject)
                ],
            )
        topic = done.objects[0].id if done.objects else topic
    for oid, attributes in extra_attributes.items():
        gi, oi = first[oid]
        objects = list(out[gi].objects)
        merged = {**attributes, **objects[oi].attributes}
        if merged != objects[oi].attributes:
            objects[oi] = msgspec.structs.replace(objects[oi], attributes=dict(sorted(merged.items())))
            out[gi] = msgspec.structs.replace(out[gi], objects=objects)
    return out


def _astuple(span: Span) -> tuple[int, int]:
    return span.start, span.end


SEAT_ACTIONS = frozenset({"sit", "lie_down", "sleep"})
SHARED_SEATS = frozenset({"sofa", "loveseat", "bench"})  # seats for two or more the text may share
BEDS = frozenset({"bed", "bunk_bed", "crib", "sofa_bed"})  # what one sleeps in
DOZING = frozenset({"fall asleep", "doze off", "doze", "drift off", "nap", "nod off", "snooze"})


def _resolve_action(
    action: ActionNode, state: _State, actor: str, graph: SentenceGraph, group: tuple[str, ...] = ()
) -> ActionNode:
    action = _resolve_refs(action, state, actor, graph, group)
    if action.verb == "listen" and action.action == "look_at" and not action.target:
        # "Ms Lee listens": to whoever acted last before her (the one talking to her)
        speaker = next((c for c in reversed(state.characters) if c != actor), "")
        action = msgspec.structs.replace(action, target=speaker) if speaker else action
    if action.action == "climb" and state.object_categories.get(action.target, "") in BEDS:
        state.seat_of[actor] = action.target  # "climbs into the bed": in it from now on
    if action.action == "look_down" and action.verb in DOZING and not action.target:
        bed = state.seat_of.get(actor, "")
        if state.object_categories.get(bed, "") in BEDS:  # "He falls asleep" in the bed he got into
            action = msgspec.structs.replace(action, action="sleep", target=bed)
    if action.action in SEAT_ACTIONS and not action.target and not action.destination:
        went = state.went_to.get(actor, "")
        if went not in state.several and _is_seat_for(state.object_categories.get(went, ""), action.action):
            # "walks to the sofa and sits down": on the sofa (so "next to her" finds her seat, and two
            # sent to one sofa are seated apart); "walks to a chair" of eight: left unnamed, the motion
            # service sits down on the nearest, the one the walk reached
            action = msgspec.structs.replace(action, target=went)
    went = action.destination or action.target
    state.went_to[actor] = went if went in state.object_categories else ""
    if action.action in SEAT_ACTIONS:
        if action.target in state.object_categories:
            state.seat_of[actor] = action.target
        elif action.target and (action.target[0].isupper() or action.target.lower() in state.spelling):
            # "sits next to Omar": a body is nothing to sit on. On the sofa or bench Omar shares, beside him
            # (the destination: the slot next to his), else on a free seat the motion service picks (it
            # walking up to Omar first ends on air)
            seat = state.seat_of.get(action.target, "")
            shared = seat if state.object_categories.get(seat, "") in SHARED_SEATS else ""
            beside = action.target if shared else ""
            action = msgspec.structs.replace(action, target=shared, destination=beside)
    return action


def _is_seat_for(category: str, action: str) -> bool:
    """Whether an object of ``category`` is what a sit (a lie or a sleep) with nothing named happens on."""
    if not category:
        return False
    kinds = {category, *lexicon.hypernyms(category)}
    if action == "sit":
        return "seat" in kinds
    return bool(kinds & (BEDS | {"bed"})) or category in SHARED_SEATS - {"bench"}


def _resolve_refs(
    action: ActionNode, state: _State, actor: str, graph: SentenceGraph, group: tuple[str, ...] = ()
) -> ActionNode:
    target = _resolve_ref(action.target, state, actor, graph, action.span.start, group)
    destination = _resolve_ref(action.destination, state, actor, graph, action.span.start)
    if target == action.target and destination == action.destination:
        return action
    name = action.action
    if target != action.target and target in state.object_categories and name not in OWN_NOUN_ACTIONS:
        # "She plays it": the verb's action depends on what "it" turned out to be.
        category = state.object_categories[target]
        verb, _, particle = action.verb.partition(" ")
        name = lexicon.action_for(verb, particle, (category, *lexicon.hypernyms(category))) or name
    return msgspec.structs.replace(action, target=target, destination=destination, action=name)
