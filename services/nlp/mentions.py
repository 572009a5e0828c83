"""Noun phrases of a parsed sentence -> object mentions and character mentions.

An object mention is a noun (with its compounds, adjectives, numbers and determiner) that names a
catalog category; a character mention is a name, a person noun or a personal pronoun.
"""

from __future__ import annotations

import functools
import re
from dataclasses import dataclass, field

from spacy.tokens import Token

from services.nlp import lexicon
from services.nlp.compounds import split_glued
from wana.assets import vocabulary

MODIFIER_DEPS = frozenset({"compound", "amod", "nmod:npmod", "flat", "nummod", "det", "nmod:poss", "advmod"})
QUANTITY_HEADS = {
    "couple": 2,
    "pair": 2,
    "lot": 3,
    "lots": 3,
    "number": 3,
    "set": 3,
    "group": 3,
    "bunch": 3,
    "stack": 3,
    "pile": 3,
    "row": 3,
    "few": 3,
    "piece": 1,
    "slice": 1,
}
DEFINITE_DETS = frozenset(
    {"the", "this", "that", "these", "those", "its", "his", "her", "their", "my", "your"}
)
NUMBER_RE = re.compile(r"^\d+$")
PLURALE_TANTUM = frozenset(
    {
        "headphones",
        "earphones",
        "drums",
        "gloves",
        "scissors",
        "pliers",
        "glasses",
        "jeans",
        "trousers",
        "binoculars",
        "dumbbells",
        "blinds",
        "curtains",
        "drapes",
    }
)


# Heads that name the thing their compound names ("drum kit", "tea set"): the compound's category.
COLLECTIVE_HEADS = frozenset({"kit", "set", "unit", "machine", "equipment", "gear", "system", "station"})
# Families whose things hold or show what follows "of" ("a bowl of popcorn", "a negative of a photo"):
# the "of" noun is their content, one object, never a second object nor an unknown word.
CONTENT_HOLDERS = frozenset(
    {
        "container",
        "drinkware",
        "tableware",
        "cookware",
        "bag",
        "food",
        "stationery",
        "artwork",
        "decoration",
        "medicine",
    }
)


@dataclass
class ObjectMention:
    """A noun phrase naming a catalog category (sentence-local character offsets)."""

    head: Token
    category: str
    word: str
    attributes: dict[str, str] = field(default_factory=dict)
    count: int = 1
    start: int = 0
    end: int = 0
    definite: bool = False


@dataclass
class CharacterMention:
    head: Token
    name: str  # "Eve", "man"; "" for a pronoun (resolved later)
    mention: str  # as written: "Eve", "He", "the old man"
    pronoun: str = ""  # "he" / "she" / "they" / "i" / "you" when a pronoun


@functools.lru_cache(maxsize=1)
def _exact_index() -> dict[str, str]:
    """Category names and synonyms (lower case, spaces) -> category; no attribute stripping."""
    index: dict[str, str] = {}
    for name, info in vocabulary.CATEGORIES.items():
        index.setdefault(name.replace("_", " "), name)
        for syn in info.synonyms:
            index.setdefault(syn, name)
    return index


def _singular(word: str) -> str:
    w = word.lower()
    if w.endswith("ies") and len(w) > 4:
        return w[:-3] + "y"
    if w.endswith(("ches", "shes", "sses", "xes")):
        return w[:-2]
    if w.endswith("ves") and len(w) > 4:
        return w[:-3] + "f"
    if w.endswith("s") and not w.endswith("ss") and len(w) > 3:
        return w[:-1]
    return w


def exact_category(words: list[str]) -> str | None:
    """Category whose name or synonym is exactly these words (last word may be plural)."""
    index = _exact_index()
    phrase = " ".join(w.lower() for w in words)
    if phrase in index:
        return index[phrase]
    if words:
        singular = " ".join([*(w.lower() for w in words[:-1]), _singular(words[-1])])
        return index.get(singular)
    return None


def _left_modifiers(head: Token) -> list[Token]:
    """Contiguous compound/adjective tokens right before the head, in order."""
    mods: list[Token] = []
    for child in reversed(list(head.lefts)):
        if child.dep_ in ("compound", "amod", "flat", "nmod:npmod") or (
            child.dep_ == "nummod" and not child.like_num and child.pos_ != "NUM"
        ):
            mods.insert(0, child)
            # "dark blue chair": the adverb/adjective modifying the adjective
            mods[0:0] = [g for g in child.lefts if g.dep_ in ("advmod", "amod", "compound")]
        elif child.dep_ in ("det", "nummod", "punct", "nmod:poss", "case"):
            continue
        else:
            break
    return mods


def _count(head: Token) -> int:
    for child in head.children:
        if child.dep_ == "nummod" or (child.like_num and child.i < head.i):
            text = child.lower_
            if NUMBER_RE.match(text):
                return max(1, min(int(text), 100))
            if text in lexicon.COUNT_WORDS:
                return lexicon.COUNT_WORDS[text]
        if child.dep_ == "det" and child.lower_ in lexicon.COUNT_WORDS and child.lower_ != "some":
            return lexicon.COUNT_WORDS[child.lower_]
        if child.dep_ in ("det", "amod") and child.lower_ in ("another", "a", "an", "one", "single"):
            return 1
    plural = "Plur" in head.morph.get("Number", []) or head.tag_ in ("NNS", "NNPS")
    if plural and head.lower_ not in PLURALE_TANTUM:
        return lexicon.PLURAL_DEFAULT_COUNT
    return 1


def _attributes(mods: list[Token], attributes: dict[str, str]) -> None:
    i = 0
    while i < len(mods):
        if i + 1 < len(mods):
            pair = f"{mods[i].lower_} {mods[i + 1].lower_}"
            hit = lexicon.attribute_of(pair)
            if hit:
                attributes.setdefault(hit[0], hit[1])
                i += 2
                continue
        hit = lexicon.attribute_of(mods[i].lower_)
        if hit:
            attributes.setdefault(hit[0], hit[1])
        elif mods[i].pos_ in ("NOUN", "PROPN", "X") and mods[i].dep_ in ("compound", "flat"):
            attributes.setdefault("kind", mods[i].lower_)
        i += 1


def _glued_attributes(parts: list[str], attributes: dict[str, str]) -> None:
    for part in parts:
        hit = lexicon.attribute_of(part)
        if hit:
            attributes.setdefault(hit[0], hit[1])
        else:
            attributes.setdefault("kind", part)


def of_complement(head: Token) -> Token | None:
    """The noun after "of" that modifies ``head`` ("popcorn" of "a bowl of popcorn"), or None."""
    for child in head.rights:
        if child.dep_ in ("nmod", "obl") and child.pos_ in ("NOUN", "PROPN", "X", "ADJ"):
            if any(c.dep_ == "case" and c.lower_ == "of" for c in child.children):
                return child
    return None


_PICTURES = frozenset({"artwork", "stationery"})  # what shows a thing: "a photo of a cake" is one photo
_EDIBLE = frozenset({"drinkware", "tableware", "food"})  # content words that name a vessel's food or drink


def holder_families(holder: ObjectMention) -> list[str]:
    return lexicon.hypernyms(holder.category)


def holds_content(category: str) -> bool:
    """True for a category whose "of" phrase is what it holds or shows (see CONTENT_HOLDERS)."""
    return bool(CONTENT_HOLDERS.intersection(lexicon.hypernyms(category)))


def is_content(tok: Token) -> bool:
    """True when ``tok`` is what a container holds ("juice" of "a glass of juice")."""
    head = tok.head
    if head.i == tok.i or head.lower_ in QUANTITY_HEADS:
        return False
    content = of_complement(head)
    if content is None or content.i != tok.i:
        return False
    holder = object_mention(head)
    if holder is None or not holds_content(holder.category):
        return False
    own = lexicon.category_of(tok.lemma_) or lexicon.category_of(tok.text)
    if (
        own is None
        or own == holder.category
        or holds_content(own)
        and _PICTURES & set(holder_families(holder))
    ):
        return True  # "popcorn", "juice" (a glass's own word), "a negative of a photo"
    return bool(_EDIBLE.intersection(lexicon.hypernyms(own)))  # "a plate of sandwiches"; not "clothes"


def object_mention(head: Token) -> ObjectMention | None:
    """The object a noun token names, with its attributes and count, or None."""
    if is_speech(head):
        return None
    if head.dep_ in ("nmod", "obl") and is_content(head):
        return None  # "juice" in "a glass of juice" is the glass's content
    if head.pos_ in ("VERB", "AUX") and any(c.dep_ in ("nsubj", "nsubj:pass") for c in head.children):
        return None  # "a whiteboard stands near the door": a verb with its subject, not a stand
    if (
        head.lower_.endswith("s")
        and head.lower_[:-1] in lexicon.SCENE_VERBS
        and any(c.dep_ in ("compound", "amod") and c.i < head.i for c in head.children)
    ):
        return None  # "on which a clock stands", tagged a plural noun with its subject glued on
    if head.text[:1].isupper() and (head.lower_ in lexicon.FEMALE_NAMES or head.lower_ in lexicon.MALE_NAMES):
        return None  # "Mike" is a person here, not a microphone
    if (
        head.lower_ in lexicon.PERSON_NOUNS or head.lemma_.lower() in lexicon.PERSON_NOUNS
    ) and not named_thing(head):
        return None
    if (
        head.pos_ not in ("NOUN", "PROPN", "X", "ADJ", "VERB", "NUM")
        or head.lower_ in lexicon.OBJECT_PRONOUNS
    ):
        return None
    if head.lower_ in lexicon.NON_OBJECT_NOUNS or head.lemma_.lower() in lexicon.NON_OBJECT_NOUNS:
        return None
    if lexicon.room_of(head.lower_) and exact_category([head.lower_]) is None:
        return None
    mods = _left_modifiers(head)
    verb = head.head
    if head.dep_ == "compound" and verb.i == head.i + 1 and verb.lower_[:-1] in lexicon.SCENE_VERBS:
        # "A large white whiteboard/compound hangs/NOUN": the adjectives hung on the misread verb
        mods = [c for c in verb.lefts if c.dep_ == "amod" and c.pos_ == "ADJ" and c.i < head.i] + mods
    words = [t.text for t in mods] + [head.text]
    category = None
    used = len(words)
    for k in range(len(words)):  # longest exact phrase ending at the head
        category = exact_category(words[k:])
        if category is not None:
            used = k
            break
    attributes: dict[str, str] = {}
    word = " ".join(words[used:]) if category else head.text
    if category is None:
        parts = split_glued(head.text)
        if parts:
            category = exact_category(parts) or exact_category(parts[-1:])
            if category is not None:
                if exact_category(parts) is None:
                    _glued_attributes(parts[:-1], attributes)
                used = len(words) - 1
                word = head.text
    if category is None:
        category = lexicon.category_of(head.lemma_) or lexicon.category_of(head.text)
        used = len(words) - 1
    for poss in (c for c in head.lefts if c.dep_ == "nmod:poss" and c.pos_ == "NOUN"):
        # "a teacher's desk": the catalog's teacher_desk, not a desk that belongs to a teacher
        owned = exact_category([f"{poss.text}'s", *words[used if category else len(words) - 1 :]])
        if owned is not None:
            category, used = owned, len(words) - 1
    if category is None and head.lemma_.lower() in COLLECTIVE_HEADS and len(words) > 1:
        # "the drum kit", "a tea set": the thing the compound names
        for k in range(len(words) - 1):
            category = exact_category(words[k:-1])
            if category is not None:
                used = k
                word = " ".join(words[k:])
                break
    content = of_complement(head)
    if content is not None and head.lower_ not in QUANTITY_HEADS:
        # "a box of chocolates" is a category of its own; "a bowl of popcorn" a bowl holding popcorn
        whole = exact_category([*words[used if category else len(words) - 1 :], "of", content.text])
        if whole is not None:
            category, word = whole, f"{head.text} of {content.text}"
    if category is None:
        return None
    category = lexicon.VERB_SENSES.get((category, _governing_verb(head)), category)
    _attributes(mods[:used], attributes)
    # Attribute words the category's own synonym swallowed ("wooden table" is a synonym of table).
    for m in mods[used:]:
        hit = lexicon.attribute_of(m.lower_)
        if hit:
            attributes.setdefault(hit[0], hit[1])
    if parts := (split_glued(head.text) if category and exact_category([head.text]) is None else None):
        for part in parts[:-1]:
            hit = lexicon.attribute_of(part)
            if hit:
                attributes.setdefault(hit[0], hit[1])
    if content is not None and holds_content(category) and not word.endswith(f" of {content.text}"):
        attributes.setdefault("content", content.lemma_.lower())
    # Predicative attributes come from the caller; only the phrase's own words are used here.
    definite = any(c.dep_ in ("det", "nmod:poss") and c.lower_ in DEFINITE_DETS for c in head.children)
    start_tok = min([head.i] + [c.i for c in head.lefts if c.dep_ in MODIFIER_DEPS or c in mods])
    doc = head.doc
    count = _count(head)
    return ObjectMention(
        head=head,
        category=category,
        word=word.lower().replace("_", " "),  # "trash_can" as the parser read it
        attributes=attributes,
        count=count,
        start=doc[start_tok].idx,
        end=head.idx + len(head.text),
        definite=definite,
    )


def _governing_verb(head: Token) -> str:
    """Lemma of the verb whose object or oblique ``head`` is ("punch" of "punches the bag"), or ""."""
    if head.dep_ in ("obj", "obl", "iobj") and head.head.pos_ == "VERB":
        return head.head.lemma_.lower()
    return ""


def quantity_target(head: Token) -> tuple[Token, int] | None:
    """For "a couple of chairs" / "a stack of books": (the noun after "of", its count)."""
    if head.lower_ not in QUANTITY_HEADS:
        return None
    for child in head.children:
        if child.dep_ == "nmod" and any(c.lower_ == "of" for c in child.children if c.dep_ == "case"):
            return child, QUANTITY_HEADS[head.lower_]
    return None


def is_unknown_object_word(head: Token) -> bool:
    """A common noun in an object slot that names no category, person, room or place (W101)."""
    if head.pos_ not in ("NOUN", "X") or head.lower_ in lexicon.OBJECT_PRONOUNS or is_speech(head):
        return False
    if head.dep_ in ("nmod", "obl") and is_content(head):
        return False
    prev = head.doc[head.i - 1] if head.i > 0 else None
    if prev is not None and exact_category([prev.text, head.text]) is not None:
        return False  # "kit" of "drum kit", however the parser hung the two words: the pair names the thing
    lemma = head.lemma_.lower()
    if (
        lemma in lexicon.PERSON_NOUNS
        or lemma in lexicon.NON_OBJECT_NOUNS
        or head.lower_ in lexicon.NON_OBJECT_NOUNS
    ):
        return False
    if lemma in lexicon.RELATION_NOUNS or lemma in lexicon.SOCIAL_RELATION_WORDS or lemma in QUANTITY_HEADS:
        return False
    if lexicon.room_of(head.lower_) or lexicon.room_of(lemma):
        return False
    if head.tag_ == "NNS" and head.lower_.endswith("s") and head.lower_[:-1] in lexicon.SCENE_VERBS:
        return False  # "a lamp glows", "the fridge hums": the verb of a scene sentence, not a thing
    if (
        head.dep_ == "ROOT"
        and lemma in lexicon.RELATION_VERBS
        and any(c.dep_ == "obj" for c in head.children)
    ):
        return False  # "The desks face/NOUN the door": the relation verb of a plural subject
    return object_mention(head) is None


def is_speech(tok: Token) -> bool:
    """The stand-in of quoted speech (services.nlp.parse masks what characters say)."""
    text = tok.text
    return (text.startswith("hello") and set(text[5:]) <= {"-"}) or (
        text.startswith("hi") and set(text[2:]) <= {"-"}
    )


def is_title(tok: Token) -> bool:
    """A capitalised title right before a capitalised name ("Dr." of "Dr. Jones", "Uncle" of "Uncle
    Bob"): part of that name, never a character, verb or sentence of its own."""
    if not tok.text[:1].isupper() or tok.lower_.rstrip(".") not in lexicon.TITLES:
        return False
    doc = tok.doc
    nxt = doc[tok.i + 1] if tok.i + 1 < len(doc) else None
    if nxt is None or not nxt.text[:1].isupper() or not nxt.is_alpha:
        return False
    return is_title(nxt) or exact_category([nxt.lower_]) is None


def title_start(tok: Token) -> int:
    """Index of the first title token written right before ``tok`` ("Dr." in "Dr. Jones"), or tok.i."""
    i = tok.i
    while i > 0 and is_title(tok.doc[i - 1]):
        i -= 1
    return i


def _titled_name(tok: Token) -> CharacterMention | None:
    """ "Dr. Jones" as one character, whichever of its tokens the parser made the head; None for a title
    that only modifies its name ("Aunt" beside "May": the name's token carries the character)."""
    doc = tok.doc
    first = title_start(tok)
    name_tok = tok
    while is_title(name_tok):
        name_tok = doc[name_tok.i + 1]
    if name_tok.i != tok.i and name_tok.head.i != tok.i:
        return None
    last = name_tok.i
    while last + 1 < len(doc) and doc[last + 1].dep_ == "flat" and doc[last + 1].text[:1].isupper():
        last += 1
    name = doc[first : last + 1].text
    return CharacterMention(head=tok, name=name, mention=name)


def named_thing(tok: Token) -> bool:
    """A person or animal noun that is a catalog thing with the word before it ("teddy bear")."""
    return any(
        c.dep_ in ("compound", "amod") and lexicon.category_of(f"{c.lower_} {tok.lower_}") is not None
        for c in tok.lefts
    )


def acting_thing_animal(tok: Token) -> bool:
    """ "The mouse/nsubj creeps": an animal whose word is also a catalog thing, as the subject of a verb
    with an action (the computer mouse never creeps)."""
    if tok.lemma_.lower() not in lexicon.THING_ANIMALS or not tok.dep_.startswith("nsubj"):
        return False
    head = tok.head
    if any(c.dep_ == "compound" for c in tok.lefts):
        return False  # "the computer mouse"
    return head.pos_ == "VERB" and lexicon.is_known_verb(head.lemma_.lower())


def _the_group(tok: Token) -> bool:
    """ "the band", "the whole team": a collective noun said of the group on stage (not "a band")."""
    return any(c.dep_ == "det" and c.lower_ == "the" for c in tok.lefts) and not any(
        c.dep_ in ("compound", "nmod:poss") for c in tok.lefts
    )


def character_mention(tok: Token) -> CharacterMention | None:
    """A character named by a token: a proper name, a person noun or a personal pronoun."""
    lower = tok.lower_
    if is_title(tok) or title_start(tok) < tok.i:
        return _titled_name(tok)
    if tok.pos_ == "PRON" or lower in lexicon.PRONOUNS:
        pron = lexicon.PRONOUNS.get(lower)
        if pron is None:
            return None
        return CharacterMention(head=tok, name="", mention=tok.text, pronoun=pron)
    if lower in lexicon.COLLECTIVE_NOUNS and tok.dep_.startswith("nsubj") and _the_group(tok):
        start = min([tok.i] + [c.i for c in tok.lefts if c.dep_ in ("det", "amod")])
        return CharacterMention(head=tok, name="", mention=tok.doc[start : tok.i + 1].text, pronoun="all")
    if (tok.lemma_.lower() in lexicon.PERSON_NOUNS or lower in lexicon.PERSON_NOUNS) and not named_thing(tok):
        start = min([tok.i] + [c.i for c in tok.lefts if c.dep_ in ("det", "amod", "compound")])
        return CharacterMention(head=tok, name=tok.lemma_.lower(), mention=tok.doc[start : tok.i + 1].text)
    if acting_thing_animal(tok):
        start = min([tok.i] + [c.i for c in tok.lefts if c.dep_ in ("det", "amod", "compound")])
        return CharacterMention(head=tok, name=tok.lemma_.lower(), mention=tok.doc[start : tok.i + 1].text)
    known_name = tok.text[:1].isupper() and (lower in lexicon.FEMALE_NAMES or lower in lexicon.MALE_NAMES)
    if (
        known_name
        or tok.pos_ == "PROPN"
        or (tok.text[:1].isupper() and tok.i > 0 and tok.pos_ in ("NOUN", "X", "ADJ"))
    ):
        if not known_name and (exact_category([lower]) is not None or lexicon.room_of(lower)):
            return None
        parts = [c for c in tok.lefts if c.dep_ in ("compound", "flat") and c.pos_ == "PROPN"] + [tok]
        # what the character says ('to Marcus "We need to talk"') is never part of the name
        parts += [c for c in tok.rights if c.dep_ == "flat" and c.pos_ == "PROPN" and not is_speech(c)]
        name = " ".join(p.text for p in sorted(parts, key=lambda t: t.i))
        return CharacterMention(head=tok, name=name, mention=name)
    return None
