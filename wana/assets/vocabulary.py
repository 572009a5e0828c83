"""The object vocabulary: categories, synonyms, hypernyms, attribute words and room types.

Shared by the NLP stage (word -> category, word -> attribute knob), the retrieval stage
(category similarity for fallback matches) and the catalog (which knobs apply to a category).

    >>> lookup("couch")
    'sofa'
    >>> lookup("notebook computer")
    'laptop'
    >>> hypernyms("office_chair")
    ['chair', 'seat', 'furniture']
    >>> ATTRIBUTE_WORDS["red"], ATTRIBUTE_WORDS["wooden"], ATTRIBUTE_WORDS["messy"]
    ('colour', 'material', 'state')
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache

from wana.assets._category_table import ABSTRACT_PARENTS, CATEGORY_ROWS, ROOM_ROWS

KNOBS: tuple[str, ...] = ("size", "style", "colour", "material", "state")
_KNOB_LETTERS = {"S": "size", "T": "style", "C": "colour", "M": "material", "X": "state"}
MOUNTS = ("floor", "surface", "wall")


@dataclass(frozen=True)
class CategoryInfo:
    """One catalog category.

    Attributes:
        name: canonical snake_case name, e.g. "office_chair".
        parent: direct hypernym (a category or an abstract class), e.g. "chair".
        synonyms: lower-case words/phrases that mean this category ("couch" for sofa).
        rooms: room types the category typically appears in.
        knobs: attribute knobs that change its mesh, a subset of KNOBS.
        mount: "floor", "surface" (rests on a table/shelf) or "wall".
    """

    name: str
    parent: str
    synonyms: tuple[str, ...]
    rooms: tuple[str, ...]
    knobs: tuple[str, ...]
    mount: str


def _parse_rows() -> dict[str, CategoryInfo]:
    table: dict[str, CategoryInfo] = {}
    for line in CATEGORY_ROWS.strip().splitlines():
        name, parent, syn, rooms, knobs, mount = (f.strip() for f in line.split("|"))
        if name in table:
            raise ValueError(f"duplicate category {name!r}")
        table[name] = CategoryInfo(
            name=name,
            parent=parent,
            synonyms=tuple(s.strip().lower() for s in syn.split(",") if s.strip()),
            rooms=tuple(rooms.split()),
            knobs=tuple(_KNOB_LETTERS[c] for c in knobs),
            mount=mount,
        )
    return table


CATEGORIES: dict[str, CategoryInfo] = _parse_rows()

# Room types -> synonyms. Iterate or test membership like a set of names.
ROOM_TYPES: dict[str, tuple[str, ...]] = dict(ROOM_ROWS)

# Canonical values of each knob (what generators understand) and the words that map to them.
KNOB_VALUES: dict[str, tuple[str, ...]] = {
    "size": ("small", "medium", "large"),
    "style": ("modern", "classic", "old", "rustic", "minimalist", "industrial", "luxurious", "futuristic"),
    "colour": (
        "red",
        "orange",
        "yellow",
        "green",
        "blue",
        "purple",
        "pink",
        "brown",
        "black",
        "white",
        "grey",
        "beige",
        "teal",
        "navy",
    ),
    "material": ("wooden", "metal", "plastic", "leather", "fabric", "glass", "stone"),
    "state": ("organized", "messy", "empty"),
}

_VALUE_WORDS: dict[str, tuple[str, ...]] = {
    # size
    "small": ("small", "little", "tiny", "mini", "compact", "short", "narrow", "low", "petite"),
    "medium": ("medium", "regular", "normal", "average", "standard", "mid sized", "medium sized"),
    "large": (
        "large",
        "big",
        "huge",
        "giant",
        "enormous",
        "tall",
        "long",
        "wide",
        "high",
        "massive",
        "oversized",
    ),
    # style
    "modern": ("modern", "contemporary", "sleek", "new", "stylish", "modernist"),
    "classic": ("classic", "classical", "traditional", "elegant", "victorian", "baroque"),
    "old": ("old", "vintage", "antique", "ancient", "worn", "retro", "shabby", "aged", "old fashioned"),
    "rustic": ("rustic", "country", "farmhouse", "rough", "handmade", "cottage"),
    "minimalist": ("minimalist", "minimal", "simple", "plain", "basic", "scandinavian", "nordic"),
    "industrial": ("industrial", "loft", "heavy duty", "utilitarian", "sturdy"),
    "luxurious": ("luxurious", "luxury", "fancy", "expensive", "posh", "ornate", "royal", "lavish"),
    "futuristic": ("futuristic", "high tech", "hi tech", "space age", "cyber", "sci fi"),
    # colour
    "red": ("red", "crimson", "scarlet", "maroon", "burgundy", "cherry"),
    "orange": ("orange", "amber", "tangerine", "copper"),
    "yellow": ("yellow", "golden", "gold", "mustard", "lemon"),
    "green": ("green", "olive", "lime", "emerald", "mint"),
    "blue": ("blue", "azure", "cobalt", "sky blue", "light blue", "cyan"),
    "purple": ("purple", "violet", "lilac", "lavender", "magenta"),
    "pink": ("pink", "rose", "salmon", "fuchsia"),
    "brown": ("brown", "chocolate", "tan", "walnut", "mahogany", "chestnut"),
    "black": ("black", "dark", "ebony", "jet black"),
    "white": ("white", "ivory", "snow white", "cream", "light"),
    "grey": ("grey", "gray", "silver", "charcoal", "slate", "ash"),
    "beige": ("beige", "khaki", "sand", "taupe", "off white"),
    "teal": ("teal", "turquoise", "aqua", "aquamarine"),
    "navy": ("navy", "navy blue", "dark blue", "indigo", "midnight blue"),
    # material
    "wooden": (
        "wooden",
        "wood",
        "oak",
        "pine",
        "timber",
        "bamboo",
        "birch",
        "teak",
        "cherrywood",
        "walnut wood",
    ),
    "metal": ("metal", "metallic", "steel", "iron", "aluminium", "aluminum", "chrome", "brass", "stainless"),
    "plastic": ("plastic", "acrylic", "vinyl", "rubber", "polymer"),
    "leather": ("leather", "leathern", "suede"),
    "fabric": (
        "fabric",
        "cloth",
        "velvet",
        "cotton",
        "wool",
        "woolen",
        "linen",
        "upholstered",
        "padded",
        "soft",
    ),
    "glass": ("glass", "crystal", "transparent", "see through"),
    "stone": ("stone", "marble", "granite", "concrete", "ceramic", "porcelain", "clay", "terracotta"),
    # state
    "organized": (
        "organized",
        "organised",
        "tidy",
        "neat",
        "clean",
        "orderly",
        "arranged",
        "ordered",
        "full",
    ),
    "messy": (
        "messy",
        "untidy",
        "cluttered",
        "disorganized",
        "disorganised",
        "chaotic",
        "dirty",
        "scattered",
    ),
    "empty": ("empty", "bare", "cleared", "unused", "vacant"),
}

# word -> canonical value, and word -> knob ("red" -> "colour").
ATTRIBUTE_VALUE: dict[str, str] = {}
ATTRIBUTE_WORDS: dict[str, str] = {}
for _knob, _values in KNOB_VALUES.items():
    for _value in _values:
        for _word in _VALUE_WORDS[_value]:
            # First definition wins for words listed under two knobs ("light" stays colour).
            ATTRIBUTE_VALUE.setdefault(_word, _value)
            ATTRIBUTE_WORDS.setdefault(_word, _knob)


def normalize_attribute(word: str) -> tuple[str, str] | None:
    """Map an attribute word to ``(knob, canonical value)``, e.g. "tidy" -> ("state", "organized")."""
    w = _norm(word)
    if w in ATTRIBUTE_VALUE:
        return ATTRIBUTE_WORDS[w], ATTRIBUTE_VALUE[w]
    return None


def _norm(text: str) -> str:
    text = text.lower().replace("_", " ").replace("-", " ").replace("’", "'")
    text = re.sub(r"[^a-z0-9' ]+", " ", text)
    return re.sub(r"\s+", " ", text).strip()


def _build_index() -> dict[str, str]:
    index: dict[str, str] = {}
    for info in CATEGORIES.values():
        index[_norm(info.name)] = info.name
    for info in CATEGORIES.values():
        for syn in info.synonyms:
            index.setdefault(_norm(syn), info.name)
    return index


_INDEX: dict[str, str] = _build_index()
_ARTICLES = {
    "a",
    "an",
    "the",
    "some",
    "this",
    "that",
    "these",
    "those",
    "his",
    "her",
    "their",
    "my",
    "your",
    "its",
    "our",
    "one",
    "two",
    "three",
    "four",
    "five",
    "several",
    "many",
    "few",
    "of",
}


_LEADING_ARTICLE = re.compile(r"^(?:a|an|the|some|this|that|his|her|their|my|your|its|our) ")


def _singular(word: str) -> list[str]:
    out = [word]
    if word.endswith("ies") and len(word) > 4:
        out.append(word[:-3] + "y")
    if word.endswith("ves") and len(word) > 4:
        out += [word[:-3] + "f", word[:-3] + "fe"]
    if word.endswith("es") and len(word) > 3:
        out.append(word[:-2])
    if word.endswith("s") and not word.endswith("ss") and len(word) > 2:
        out.append(word[:-1])
    return out


def _lookup_exact(phrase: str) -> str | None:
    if phrase in _INDEX:
        return _INDEX[phrase]
    words = phrase.split(" ")
    for last in _singular(words[-1])[1:]:
        cand = " ".join([*words[:-1], last])
        if cand in _INDEX:
            return _INDEX[cand]
    joined = phrase.replace(" ", "")
    if joined != phrase and joined in _INDEX:
        return _INDEX[joined]
    return None


@lru_cache(maxsize=4096)
def lookup(word_or_phrase: str) -> str | None:
    """Category for a word or phrase, or None when unknown.

    Tries, in order: the whole phrase (synonyms included, plural forms folded), the phrase without
    leading articles and attribute words ("the big red couch" -> sofa), the longest known tail
    ("old wooden office chair" -> office_chair), and compounds written as one word that start with
    an attribute word ("modernchair" -> chair family).
    """
    phrase = _norm(word_or_phrase)
    if not phrase:
        return None
    whole = _lookup_exact(phrase) or _lookup_exact(_LEADING_ARTICLE.sub("", phrase))
    if whole is not None:  # "chest of drawers", "a box of chocolates"
        return whole
    if " of " in phrase:  # "a cup of coffee" -> cup, "a stack of paper" -> paper
        head, _, rest = phrase.partition(" of ")
        hit = (
            lookup(head)
            if head.split(" ")[-1] not in ("stack", "pile", "set", "pair", "piece", "plank")
            else None
        )
        return hit if hit is not None else lookup(rest)
    words = [w for w in phrase.split(" ") if w not in _ARTICLES] or phrase.split(" ")
    # Longest tail first so that "notebook computer" wins over "computer".
    for start in range(len(words)):
        tail = " ".join(words[start:])
        hit = _lookup_exact(tail)
        if hit is not None:
            return hit
    # "modernchair": attribute word glued to a category word.
    last = words[-1]
    for attr in sorted(ATTRIBUTE_WORDS, key=len, reverse=True):
        a = attr.replace(" ", "")
        if last.startswith(a) and len(last) > len(a) + 2:
            hit = _lookup_exact(last[len(a) :])
            if hit is not None:
                return hit
    return None


def lookup_room(word_or_phrase: str) -> str | None:
    """Room type for a word or phrase ("working shop" -> "workshop"), or None."""
    phrase = _norm(word_or_phrase)
    words = [w for w in phrase.split(" ") if w not in _ARTICLES]
    phrase = " ".join(words)
    for start in range(len(words)):
        tail = " ".join(words[start:])
        for cand in (tail, tail.rstrip("s")):
            if cand.replace(" ", "_") in ROOM_TYPES:
                return cand.replace(" ", "_")
            for room, syns in ROOM_TYPES.items():
                if cand in syns:
                    return room
    return None


def _parent(name: str) -> str:
    if name in CATEGORIES:
        return CATEGORIES[name].parent
    return ABSTRACT_PARENTS.get(name, "")


@lru_cache(maxsize=1024)
def _chain(category: str) -> tuple[str, ...]:
    chain: list[str] = []
    node = _parent(category)
    while node and node not in chain:
        chain.append(node)
        node = _parent(node)
    return tuple(chain)


def hypernyms(category: str) -> list[str]:
    """Hypernyms from the nearest up, e.g. office_chair -> ['chair', 'seat', 'furniture'].

    Raises:
        KeyError: for a name that is neither a category nor an abstract class.
    """
    if category not in CATEGORIES and category not in ABSTRACT_PARENTS:
        raise KeyError(f"unknown category {category!r}")
    return list(_chain(category))


def category_similarity(a: str, b: str) -> float:
    """Wu-Palmer similarity in the hypernym tree: 1 for the same category, lower with distance.

    office_chair~chair 0.86, office_chair~armchair 0.75, office_chair~sofa 0.57, chair~desk 0.33,
    unrelated trees 0. Unknown names give 0 (or 1 when equal).
    """
    if a == b:
        return 1.0
    if (a not in CATEGORIES and a not in ABSTRACT_PARENTS) or (
        b not in CATEGORIES and b not in ABSTRACT_PARENTS
    ):
        return 0.0
    pa = (a, *_chain(a))
    pb = (b, *_chain(b))
    common = next((n for n in pa if n in pb), None)
    if common is None:
        return 0.0
    depth = {n: len(pa) - i for i, n in enumerate(pa)} | {n: len(pb) - i for i, n in enumerate(pb)}
    return 2.0 * depth[common] / (len(pa) + len(pb))


def categories_in_room(room_type: str) -> list[str]:
    """Categories that typically appear in a room type, in table order."""
    return [c.name for c in CATEGORIES.values() if room_type in c.rooms]


def _check_table() -> None:
    for info in CATEGORIES.values():
        if info.parent not in CATEGORIES and info.parent not in ABSTRACT_PARENTS:
            raise ValueError(f"{info.name}: unknown parent {info.parent!r}")
        if info.mount not in MOUNTS:
            raise ValueError(f"{info.name}: bad mount {info.mount!r}")
        for room in info.rooms:
            if room not in ROOM_TYPES:
                raise ValueError(f"{info.name}: unknown room type {room!r}")


_check_table()


@lru_cache(maxsize=4096)
def senses(word: str) -> tuple[str, ...]:
    """Categories a bare word can name: those it is a synonym of and those whose name ends in it
    ("sink" -> kitchen_sink, bathroom_sink; "desk" -> desk, standing_desk, teacher_desk, ...)."""
    w = _norm(word)
    if not w:
        return ()
    forms = {w, *_singular(w)}
    out = [
        info.name
        for info in CATEGORIES.values()
        if info.name.split("_")[-1] in forms
        or _norm(info.name) in forms
        or any(s in forms for s in info.synonyms)
    ]
    return tuple(out)


def sense_in_context(word: str, category: str, room_type: str, present: tuple[str, ...] = ()) -> str:
    """The category a bare word means here: a kind already in the scene first, then the category as
    looked up when it fits the room, then the one kind that fits the room type; else ``category``.

    "the sink" in a bathroom is the bathroom sink; "her desk" where a teacher's desk stands is that desk.
    """
    options = senses(word)
    if category not in options or len(options) < 2:
        return category
    if category in present:
        return category
    for c in present:
        if c in options:
            return c
    if not room_type or room_type in CATEGORIES[category].rooms:
        return category
    fitting = [c for c in options if room_type in CATEGORIES[c].rooms]
    return fitting[0] if len(fitting) == 1 else category  # two that fit ("desk" in a classroom): as written
