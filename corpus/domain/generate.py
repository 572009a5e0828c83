"""Generate wana's domain treebank (CoNLL-U, UD English-EWT conventions) from templates with known trees.

The language wana's users write -- scene descriptions ending in ``$``, narrative and imperative action
sentences, social statements and short commands -- is rare in the web text of EWT. Each template
below builds its sentence token by token together with its dependency tree, so every tree is correct
by construction and follows EWT's analyses (copula not head, ``in front of`` as obl/nmod of ``front``,
``next to`` as two ``case`` dependents, existential ``there`` as ``expl``).

Usage:
    python corpus/domain/generate.py            # writes corpus/domain/domain-{train,test}.conllu

Deterministic: seed 20240611; 640 train and 160 test sentences.
"""

from __future__ import annotations

import argparse
import random
from dataclasses import dataclass, field
from pathlib import Path

SEED = 20240611
HERE = Path(__file__).resolve().parent

DEF = "Definite=Def|PronType=Art"
IND = "Definite=Ind|PronType=Art"
SG = "Number=Sing"
PL = "Number=Plur"
VBZ = "Mood=Ind|Number=Sing|Person=3|Tense=Pres|VerbForm=Fin"
VBP = "Mood=Ind|Number=Plur|Person=3|Tense=Pres|VerbForm=Fin"
VBD = "Mood=Ind|Number=Sing|Person=3|Tense=Past|VerbForm=Fin"
VB_IMP = "Mood=Imp|VerbForm=Fin"
VBG = "Tense=Pres|VerbForm=Part"
POS_DEG = "Degree=Pos"

# Objects: (singular, plural, compound modifier or "")
OBJECTS = [
    ("desk", "desks", ""),
    ("chair", "chairs", ""),
    ("table", "tables", ""),
    ("sofa", "sofas", ""),
    ("couch", "couches", ""),
    ("lamp", "lamps", ""),
    ("laptop", "laptops", ""),
    ("window", "windows", ""),
    ("door", "doors", ""),
    ("bookshelf", "bookshelves", ""),
    ("bed", "beds", ""),
    ("piano", "pianos", ""),
    ("guitar", "guitars", ""),
    ("microphone", "microphones", ""),
    ("painting", "paintings", ""),
    ("sculpture", "sculptures", ""),
    ("plant", "plants", ""),
    ("vase", "vases", ""),
    ("cup", "cups", ""),
    ("mug", "mugs", ""),
    ("phone", "phones", ""),
    ("television", "televisions", ""),
    ("tv", "tvs", ""),
    ("monitor", "monitors", ""),
    ("keyboard", "keyboards", ""),
    ("computer", "computers", ""),
    ("book", "books", ""),
    ("box", "boxes", ""),
    ("clock", "clocks", ""),
    ("mirror", "mirrors", ""),
    ("rug", "rugs", ""),
    ("cabinet", "cabinets", ""),
    ("stool", "stools", ""),
    ("bench", "benches", ""),
    ("whiteboard", "whiteboards", ""),
    ("blackboard", "blackboards", ""),
    ("hammer", "hammers", ""),
    ("workbench", "workbenches", ""),
    ("ladder", "ladders", ""),
    ("treadmill", "treadmills", ""),
    ("fridge", "fridges", ""),
    ("stove", "stoves", ""),
    ("sink", "sinks", ""),
    ("bottle", "bottles", ""),
    ("speaker", "speakers", ""),
    ("drum", "drums", ""),
    ("violin", "violins", ""),
    ("armchair", "armchairs", ""),
    ("table", "tables", "coffee"),
    ("bag", "bags", "boxing"),
    ("painting", "paintings", "oil"),
    ("chair", "chairs", "office"),
    ("lamp", "lamps", "floor"),
    ("table", "tables", "dining"),
    ("can", "cans", "soda"),
    ("machine", "machines", "coffee"),
    ("mat", "mats", "yoga"),
    ("stand", "stands", "music"),
    ("board", "boards", "cutting"),
    ("cabinet", "cabinets", "kitchen"),
]
ADJS = [
    "red",
    "blue",
    "green",
    "black",
    "white",
    "brown",
    "grey",
    "yellow",
    "small",
    "large",
    "big",
    "tall",
    "old",
    "modern",
    "wooden",
    "classic",
    "new",
    "messy",
    "empty",
    "round",
    "long",
    "comfortable",
]
NOUN_MODS = ["leather", "metal", "glass", "plastic", "stone"]  # material nouns as compound
ROOMS = [
    ("office", ""),
    ("kitchen", ""),
    ("bedroom", ""),
    ("classroom", ""),
    ("gym", ""),
    ("studio", ""),
    ("gallery", ""),
    ("library", ""),
    ("room", "living"),
    ("shop", "working"),
    ("room", "dining"),
    ("studio", "music"),
    ("room", "meeting"),
]
NAMES = [
    "Eve",
    "Tom",
    "Mary",
    "John",
    "Alice",
    "Bob",
    "Anna",
    "Peter",
    "Lucy",
    "Sam",
    "Kate",
    "David",
    "Emma",
    "Jack",
    "Lily",
    "Mike",
    "Sara",
    "Ben",
    "Nina",
    "Paul",
]
PRONOUNS = [
    ("He", "he", "Case=Nom|Gender=Masc|Number=Sing|Person=3|PronType=Prs"),
    ("She", "she", "Case=Nom|Gender=Fem|Number=Sing|Person=3|PronType=Prs"),
]
THEY = ("They", "they", "Case=Nom|Number=Plur|Person=3|PronType=Prs")
MANNERS = [
    "slowly",
    "quickly",
    "happily",
    "sadly",
    "angrily",
    "madly",
    "calmly",
    "carefully",
    "quietly",
    "loudly",
    "nervously",
    "proudly",
    "casually",
    "fast",
]
# Intransitive motion/posture verbs: (base, 3sg, past, gerund, preposition options)
MOTION = [
    ("walk", "walks", "walked", "walking", ["to", "towards", "toward"]),
    ("run", "runs", "ran", "running", ["to", "towards"]),
    ("go", "goes", "went", "going", ["to"]),
    ("jog", "jogs", "jogged", "jogging", ["to"]),
    ("move", "moves", "moved", "moving", ["to"]),
    ("sit", "sits", "sat", "sitting", ["on", "at"]),
    ("lie", "lies", "lay", "lying", ["on"]),
    ("stand", "stands", "stood", "standing", ["near", "behind", "by"]),
    ("lean", "leans", "leaned", "leaning", ["on", "against"]),
    ("type", "types", "typed", "typing", ["on"]),
    ("wave", "waves", "waved", "waving", ["at", "to"]),
    ("look", "looks", "looked", "looking", ["at"]),
    ("jump", "jumps", "jumped", "jumping", ["on", "over"]),
    ("dance", "dances", "danced", "dancing", ["with", "near"]),
    ("sing", "sings", "sang", "singing", ["with", "into"]),
    ("talk", "talks", "talked", "talking", ["to", "with"]),
    ("point", "points", "pointed", "pointing", ["at"]),
    ("climb", "climbs", "climbed", "climbing", ["on", "up"]),
]
# Transitive verbs: (base, 3sg, past, gerund)
TRANSITIVE = [
    ("play", "plays", "played", "playing"),
    ("drink", "drinks", "drank", "drinking"),
    ("read", "reads", "read", "reading"),
    ("open", "opens", "opened", "opening"),
    ("close", "closes", "closed", "closing"),
    ("push", "pushes", "pushed", "pushing"),
    ("punch", "punches", "punched", "punching"),
    ("kick", "kicks", "kicked", "kicking"),
    ("hit", "hits", "hit", "hitting"),
    ("use", "uses", "used", "using"),
    ("watch", "watches", "watched", "watching"),
    ("hold", "holds", "held", "holding"),
    ("grab", "grabs", "grabbed", "grabbing"),
    ("carry", "carries", "carried", "carrying"),
    ("clean", "cleans", "cleaned", "cleaning"),
    ("touch", "touches", "touched", "touching"),
    ("hug", "hugs", "hugged", "hugging"),
    ("greet", "greets", "greeted", "greeting"),
    ("call", "calls", "called", "calling"),
    ("approach", "approaches", "approached", "approaching"),
]
INTRANS_BARE = [
    ("sit", "sits"),
    ("stand", "stands"),
    ("sing", "sings"),
    ("dance", "dances"),
    ("wave", "waves"),
    ("laugh", "laughs"),
    ("cry", "cries"),
    ("clap", "claps"),
    ("jump", "jumps"),
    ("sleep", "sleeps"),
    ("wait", "waits"),
    ("kneel", "kneels"),
    ("bow", "bows"),
    ("nod", "nods"),
    ("stretch", "stretches"),
    ("sneeze", "sneezes"),
    ("shout", "shouts"),
    ("cheer", "cheers"),
    ("turn", "turns"),
    ("squat", "squats"),
]
PHRASAL = [
    ("pick", "picks", "up"),
    ("sit", "sits", "down"),
    ("stand", "stands", "up"),
    ("put", "puts", "down"),
    ("turn", "turns", "on"),
    ("turn", "turns", "off"),
    ("lie", "lies", "down"),
    ("walk", "walks", "in"),
    ("walk", "walks", "away"),
    ("look", "looks", "around"),
    ("get", "gets", "up"),
]
SOCIAL_NOUNS = [
    ("friends", "friend"),
    ("colleagues", "colleague"),
    ("enemies", "enemy"),
    ("siblings", "sibling"),
    ("strangers", "stranger"),
    ("partners", "partner"),
    ("neighbors", "neighbor"),
    ("rivals", "rival"),
]
ROLE_NOUNS = [
    "boss",
    "friend",
    "teacher",
    "sister",
    "brother",
    "mother",
    "father",
    "wife",
    "husband",
    "student",
    "coach",
    "manager",
    "colleague",
]
EMOTION_ADJS = [
    "angry",
    "happy",
    "sad",
    "nervous",
    "excited",
    "tired",
    "scared",
    "calm",
    "surprised",
    "bored",
]
SOCIAL_VERBS = [
    ("apologize", "apologizes", "to"),
    ("shout", "shouts", "at"),
    ("smile", "smiles", "at"),
    ("wave", "waves", "at"),
    ("talk", "talks", "to"),
    ("laugh", "laughs", "at"),
    ("yell", "yells", "at"),
]
REL_SIMPLE = [
    "on",
    "near",
    "behind",
    "under",
    "above",
    "in",
    "beside",
    "by",
    "below",
    "against",
    "inside",
    "around",
]
NUMBERS = [
    ("two", 2),
    ("three", 3),
    ("four", 4),
    ("five", 5),
    ("2", 2),
    ("3", 3),
    ("10", 10),
    ("5", 5),
    ("1.5", 1.5),
]


@dataclass
class Tok:
    form: str
    lemma: str
    upos: str
    xpos: str
    feats: str = "_"
    head: int = 0  # 1-based after finalisation, 0 = root
    deprel: str = "root"
    space_after: bool = True


@dataclass
class Sent:
    """A sentence under construction: tokens with 0-based heads (-1 = root)."""

    toks: list[Tok] = field(default_factory=list)
    heads: list[int] = field(default_factory=list)

    def add(self, form: str, lemma: str, upos: str, xpos: str, feats: str = "_") -> int:
        self.toks.append(Tok(form, lemma, upos, xpos, feats))
        self.heads.append(-1)
        return len(self.toks) - 1

    def attach(self, dep: int, head: int, rel: str) -> None:
        self.heads[dep] = head
        self.toks[dep].deprel = rel

    def conllu(self, sent_id: str) -> str:
        roots = [i for i, h in enumerate(self.heads) if h == -1]
        assert len(roots) == 1, (sent_id, [t.form for t in self.toks], roots)
        self.toks[roots[0]].deprel = "root"
        text = ""
        for t in self.toks:
            text += t.form + (" " if t.space_after else "")
        lines = [f"# sent_id = {sent_id}", f"# text = {text.strip()}"]
        for i, t in enumerate(self.toks):
            head = self.heads[i] + 1
            misc = "_" if t.space_after else "SpaceAfter=No"
            lines.append(
                "\t".join(
                    [str(i + 1), t.form, t.lemma, t.upos, t.xpos, t.feats, str(head), t.deprel, "_", misc]
                )
            )
        return "\n".join(lines) + "\n"


def cap(s: Sent) -> None:
    first = s.toks[0]
    if first.upos != "PROPN" and first.form[0].islower():
        first.form = first.form[0].upper() + first.form[1:]


def end(s: Sent, root: int, mark: str = ".") -> None:
    # A scene sentence's "$" reaches the parser as "." (services/nlp/parse.py swaps it, same offsets).
    mark = "." if mark == "$" else mark
    s.toks[-1].space_after = False
    p = s.add(mark, mark, "PUNCT", ".")
    s.attach(p, root, "punct")


def article(word: str, definite: bool) -> tuple[str, str, str]:
    if definite:
        return ("the", "the", DEF)
    return ("an" if word[0] in "aeiou" else "a", "a", IND)


def noun_phrase(
    s: Sent,
    rng: random.Random,
    plural: bool = False,
    definite: bool | None = None,
    number: tuple[str, float] | None = None,
    adjs: int | None = None,
) -> int:
    """Append a determiner/number, adjectives and a (compound) noun; returns the head noun index."""
    sg, pl, mod = rng.choice(OBJECTS)
    noun = pl if plural else sg
    definite = rng.random() < 0.5 if definite is None else definite
    n_adj = rng.choice([0, 0, 1, 1, 2]) if adjs is None else adjs
    adj_words = rng.sample(ADJS, n_adj)
    material = rng.choice(NOUN_MODS) if rng.random() < 0.12 else ""
    first_word = (adj_words + [material, mod, noun])[0] or material or mod or noun
    deps: list[tuple[int, str]] = []
    if number is not None:
        word = number[0]
        feats = "NumForm=Digit|NumType=Card" if word[0].isdigit() else "NumForm=Word|NumType=Card"
        deps.append((s.add(word, word, "NUM", "CD", feats), "nummod"))
    elif plural:
        if rng.random() < 0.3:
            deps.append((s.add("some", "some", "DET", "DT", "PronType=Ind"), "det"))
    else:
        form, lemma, feats = article(first_word, definite)
        deps.append((s.add(form, lemma, "DET", "DT", feats), "det"))
    for adj in adj_words:
        deps.append((s.add(adj, adj, "ADJ", "JJ", POS_DEG), "amod"))
    if material:
        deps.append((s.add(material, material, "NOUN", "NN", SG), "compound"))
    if mod:
        deps.append((s.add(mod, mod, "NOUN", "NN", SG), "compound"))
    head = s.add(noun, sg, "NOUN", "NNS" if plural else "NN", PL if plural else SG)
    for d, rel in deps:
        s.attach(d, head, rel)
    return head


def relation_phrase(s: Sent, rng: random.Random, anchor_head: int, as_root: bool) -> int:
    """Append a spatial PP; attaches its noun to anchor_head (obl/nmod) unless as_root. Returns the PP head."""
    kind = rng.choice(["simple"] * 6 + ["front", "next", "side", "top", "facing"])
    rel = "obl" if s.toks[anchor_head].upos in ("VERB", "AUX") else "nmod"
    if kind == "simple":
        p = rng.choice(REL_SIMPLE)
        c = s.add(p, p, "ADP", "IN")
        n = noun_phrase(s, rng, adjs=rng.choice([0, 0, 1]))
        s.attach(c, n, "case")
        head = n
    elif kind == "next":
        a = s.add("next", "next", "ADP", "IN")
        b = s.add("to", "to", "ADP", "IN")
        n = noun_phrase(s, rng, adjs=rng.choice([0, 0, 1]))
        s.attach(a, n, "case")
        s.attach(b, n, "case")
        head = n
    elif kind in ("front", "top"):
        a = s.add("in" if kind == "front" else "on", "in" if kind == "front" else "on", "ADP", "IN")
        f = s.add(kind, kind, "NOUN", "NN", SG)
        o = s.add("of", "of", "ADP", "IN")
        n = noun_phrase(s, rng, adjs=rng.choice([0, 0, 1]))
        s.attach(a, f, "case")
        s.attach(o, n, "case")
        s.attach(n, f, "nmod")
        head = f
    elif kind == "side":
        side = rng.choice(["left", "right"])
        a = s.add("to", "to", "ADP", "IN")
        d = s.add("the", "the", "DET", "DT", DEF)
        f = s.add(side, side, "NOUN", "NN", SG)
        o = s.add("of", "of", "ADP", "IN")
        n = noun_phrase(s, rng, adjs=0)
        s.attach(a, f, "case")
        s.attach(d, f, "det")
        s.attach(o, n, "case")
        s.attach(n, f, "nmod")
        head = f
    else:  # "facing the window" as a participle modifier
        v = s.add("facing", "face", "VERB", "VBG", VBG)
        n = noun_phrase(s, rng, adjs=0)
        s.attach(n, v, "obj")
        if not as_root:
            s.attach(v, anchor_head, "acl" if rel == "nmod" else "advcl")
        return v
    if not as_root:
        s.attach(head, anchor_head, rel)
    return head


def there_is(rng: random.Random) -> Sent:
    s = Sent()
    plural = rng.random() < 0.35
    lead = rng.random() < 0.35
    if lead:
        c = s.add("in", "in", "ADP", "IN")
        d = s.add("the", "the", "DET", "DT", DEF)
        room, mod = rng.choice(ROOMS)
        m = (
            s.add(mod, mod, "ADJ" if mod.endswith("ing") and mod != "meeting" else "NOUN", "NN", SG)
            if mod
            else None
        )
        r = s.add(room, room, "NOUN", "NN", SG)
        s.attach(c, r, "case")
        s.attach(d, r, "det")
        if m is not None:
            s.toks[m].upos, s.toks[m].xpos = ("NOUN", "NN")
            s.attach(m, r, "compound")
        comma = rng.random() < 0.4
        if comma:
            s.toks[-1].space_after = False
            pc = s.add(",", ",", "PUNCT", ",")
    ex = s.add("there", "there", "PRON", "EX")
    verb = s.add("are" if plural else "is", "be", "VERB", "VBP" if plural else "VBZ", VBP if plural else VBZ)
    s.attach(ex, verb, "expl")
    if lead:
        s.attach(r, verb, "obl")
        if comma:
            s.attach(pc, verb, "punct")
    num = rng.choice(NUMBERS[:4]) if plural and rng.random() < 0.7 else None
    n = noun_phrase(s, rng, plural=plural, definite=False, number=num)
    s.attach(n, verb, "nsubj")
    if rng.random() < 0.8:
        relation_phrase(s, rng, verb, as_root=False)
    end(s, verb, "$" if rng.random() < 0.6 else ".")
    cap(s)
    return s


def copular_location(rng: random.Random) -> Sent:
    s = Sent()
    plural = rng.random() < 0.25
    num = rng.choice(NUMBERS[:4]) if plural and rng.random() < 0.5 else None
    subj = noun_phrase(s, rng, plural=plural, number=num)
    second = None
    if not plural and rng.random() < 0.15:
        cc = s.add("and", "and", "CCONJ", "CC")
        second = noun_phrase(s, rng, adjs=0)
        s.attach(cc, second, "cc")
        s.attach(second, subj, "conj")
        plural = True
    kind = rng.random()
    if kind < 0.15:  # "The lamp is hanging above the table."
        aux = s.add(
            "are" if plural else "is", "be", "AUX", "VBP" if plural else "VBZ", VBP if plural else VBZ
        )
        v = s.add(rng.choice(["hanging", "standing", "placed", "lying"]), "x", "VERB", "VBG", VBG)
        s.toks[v].lemma = {"hanging": "hang", "standing": "stand", "placed": "place", "lying": "lie"}[
            s.toks[v].form
        ]
        if s.toks[v].form == "placed":
            s.toks[v].xpos, s.toks[v].feats = "VBN", "Tense=Past|VerbForm=Part|Voice=Pass"
        s.attach(aux, v, "aux:pass" if s.toks[v].form == "placed" else "aux")
        s.attach(subj, v, "nsubj:pass" if s.toks[v].form == "placed" else "nsubj")
        relation_phrase(s, rng, v, as_root=False)
        root = v
    elif kind < 0.25:  # "The sofa faces the TV."
        v = s.add(
            "face" if plural else "faces", "face", "VERB", "VBP" if plural else "VBZ", VBP if plural else VBZ
        )
        o = noun_phrase(s, rng, adjs=0)
        s.attach(subj, v, "nsubj")
        s.attach(o, v, "obj")
        root = v
    else:
        cop = s.add(
            "are" if plural else "is", "be", "AUX", "VBP" if plural else "VBZ", VBP if plural else VBZ
        )
        root = relation_phrase(s, rng, -1, as_root=True)
        s.attach(cop, root, "cop")
        s.attach(subj, root, "nsubj")
        # cop must precede the predicate head's dependents: fine because cop was added before the PP
    end(s, root, "$" if rng.random() < 0.6 else ".")
    cap(s)
    return s


def attribute_sentence(rng: random.Random) -> Sent:
    s = Sent()
    subj = noun_phrase(s, rng, definite=True, adjs=0)
    cop = s.add("is", "be", "AUX", "VBZ", VBZ)
    a = rng.choice(ADJS)
    adj = s.add(a, a, "ADJ", "JJ", POS_DEG)
    s.attach(cop, adj, "cop")
    s.attach(subj, adj, "nsubj")
    if rng.random() < 0.4:
        cc = s.add("and", "and", "CCONJ", "CC")
        b = rng.choice([x for x in ADJS if x != a])
        adj2 = s.add(b, b, "ADJ", "JJ", POS_DEG)
        s.attach(cc, adj2, "cc")
        s.attach(adj2, adj, "conj")
    end(s, adj, "$" if rng.random() < 0.6 else ".")
    cap(s)
    return s


def has_sentence(rng: random.Random) -> Sent:
    s = Sent()
    if rng.random() < 0.5:
        d = s.add("the", "the", "DET", "DT", DEF)
        room, mod = rng.choice(ROOMS)
        m = s.add(mod, mod, "NOUN", "NN", SG) if mod else None
        subj = s.add(room, room, "NOUN", "NN", SG)
        s.attach(d, subj, "det")
        if m is not None:
            s.attach(m, subj, "compound")
    else:
        subj = s.add("it", "it", "PRON", "PRP", "Case=Nom|Gender=Neut|Number=Sing|Person=3|PronType=Prs")
    v = s.add("has", "have", "VERB", "VBZ", VBZ)
    s.attach(subj, v, "nsubj")
    o = noun_phrase(s, rng, definite=False)
    s.attach(o, v, "obj")
    if rng.random() < 0.5:
        cc = s.add("and", "and", "CCONJ", "CC")
        num = rng.choice(NUMBERS[:4])
        o2 = noun_phrase(s, rng, plural=True, number=num)
        s.attach(cc, o2, "cc")
        s.attach(o2, o, "conj")
    end(s, v, "$" if rng.random() < 0.6 else ".")
    cap(s)
    return s


def place_imperative(rng: random.Random) -> Sent:
    s = Sent()
    verb = rng.choice(["put", "place", "add"])
    v = s.add(verb, verb, "VERB", "VB", VB_IMP)
    o = noun_phrase(s, rng)
    s.attach(o, v, "obj")
    relation_phrase(s, rng, v, as_root=False)
    end(s, v, "$" if rng.random() < 0.5 else ".")
    cap(s)
    return s


def subject(s: Sent, rng: random.Random, allow_they: bool = False) -> tuple[int, bool]:
    r = rng.random()
    if r < 0.25:
        form, lemma, feats = THEY if allow_they and rng.random() < 0.3 else rng.choice(PRONOUNS)
        return s.add(form, lemma, "PRON", "PRP", feats), form == "They"
    if r < 0.3:
        d = s.add("the", "the", "DET", "DT", DEF)
        n = s.add(rng.choice(["man", "woman", "boy", "girl", "teacher", "student"]), "x", "NOUN", "NN", SG)
        s.toks[n].lemma = s.toks[n].form
        s.attach(d, n, "det")
        return n, False
    name = rng.choice(NAMES)
    return s.add(name, name, "PROPN", "NNP", SG), False


def verb_token(s: Sent, rng: random.Random, forms: tuple, plural: bool, tense: str) -> tuple[int, int | None]:
    """Append (aux +) verb in the chosen tense; returns (verb index, aux index or None)."""
    base, third, past, ger = forms[0], forms[1], forms[2], forms[3]
    if tense == "prog":
        aux = s.add(
            "are" if plural else "is", "be", "AUX", "VBP" if plural else "VBZ", VBP if plural else VBZ
        )
        v = s.add(ger, base, "VERB", "VBG", VBG)
        s.attach(aux, v, "aux")
        return v, aux
    if tense == "past":
        return s.add(past, base, "VERB", "VBD", "Mood=Ind|Tense=Past|VerbForm=Fin"), None
    if plural:
        return s.add(base, base, "VERB", "VBP", VBP), None
    return s.add(third, base, "VERB", "VBZ", VBZ), None


def character_pp(s: Sent, rng: random.Random, verb: int, prep: str) -> None:
    c = s.add(prep, prep, "ADP", "IN")
    if prep in ("at", "to", "with") and rng.random() < 0.3:
        name = rng.choice(NAMES)
        n = s.add(name, name, "PROPN", "NNP", SG)
    else:
        n = noun_phrase(s, rng, definite=True if rng.random() < 0.8 else None, adjs=rng.choice([0, 0, 0, 1]))
    s.attach(c, n, "case")
    s.attach(n, verb, "obl")


def action_clause(s: Sent, rng: random.Random, plural: bool, tense: str) -> int:
    """Append a verb phrase (verb + args) and return the verb index."""
    kind = rng.random()
    pre_manner = tense != "prog" and rng.random() < 0.08
    if pre_manner:
        m = rng.choice(MANNERS[:-1])
        mi = s.add(m, m, "ADV", "RB", POS_DEG)
    if kind < 0.4:
        forms = rng.choice(MOTION)
        v, _ = verb_token(s, rng, forms, plural, tense)
        if rng.random() < 0.3:
            m = rng.choice(MANNERS)
            s.attach(s.add(m, m, "ADV", "RB", POS_DEG), v, "advmod")
        character_pp(s, rng, v, rng.choice(forms[4]))
    elif kind < 0.7:
        forms = rng.choice(TRANSITIVE)
        v, _ = verb_token(s, rng, forms, plural, tense)
        if forms[0] in ("hug", "greet", "call", "approach") and rng.random() < 0.6:
            name = rng.choice(NAMES)
            o = s.add(name, name, "PROPN", "NNP", SG)
        else:
            o = noun_phrase(s, rng, definite=True if rng.random() < 0.7 else None, adjs=rng.choice([0, 0, 1]))
        s.attach(o, v, "obj")
        if rng.random() < 0.25:
            character_pp(s, rng, v, "with")
    elif kind < 0.85:
        base, third = rng.choice(INTRANS_BARE)
        forms = (base, third, base + "ed", base + "ing")
        v = s.add(
            third if not plural else base,
            base,
            "VERB",
            "VBZ" if not plural else "VBP",
            VBZ if not plural else VBP,
        )
        if rng.random() < 0.5:
            m = rng.choice(MANNERS)
            s.attach(s.add(m, m, "ADV", "RB", POS_DEG), v, "advmod")
    else:
        base, third, prt = rng.choice(PHRASAL)
        v = s.add(
            third if not plural else base,
            base,
            "VERB",
            "VBZ" if not plural else "VBP",
            VBZ if not plural else VBP,
        )
        p = s.add(prt, prt, "ADP", "RP")
        s.attach(p, v, "compound:prt")
        if base in ("pick", "put", "turn"):
            o = noun_phrase(s, rng, definite=True, adjs=0)
            s.attach(o, v, "obj")
    if pre_manner:
        s.attach(mi, v, "advmod")
    if rng.random() < 0.15:
        f = s.add("for", "for", "ADP", "IN")
        word, val = rng.choice(NUMBERS[4:] + NUMBERS[:3])
        feats = "NumForm=Digit|NumType=Card" if word[0].isdigit() else "NumForm=Word|NumType=Card"
        nm = s.add(word, word, "NUM", "CD", feats)
        unit = "second" if val == 1 else "seconds"
        u = s.add(unit, "second", "NOUN", "NN" if val == 1 else "NNS", SG if val == 1 else PL)
        s.attach(f, u, "case")
        s.attach(nm, u, "nummod")
        s.attach(u, v, "obl")
    return v


def action_sentence(rng: random.Random) -> Sent:
    s = Sent()
    then = rng.random() < 0.15
    if then:
        t = s.add(rng.choice(["then", "now", "suddenly", "finally"]), "x", "ADV", "RB")
        s.toks[t].lemma = s.toks[t].form
        if rng.random() < 0.3:
            s.toks[-1].space_after = False
            s.add(",", ",", "PUNCT", ",")
    subj, plural = subject(s, rng, allow_they=True)
    tense = rng.choice(["pres"] * 6 + ["prog", "past"])
    v = action_clause(s, rng, plural, tense)
    s.attach(subj, v, "nsubj")
    if then:
        s.attach(t, v, "advmod")
        if s.toks[t + 1].form == ",":
            s.attach(t + 1, v, "punct")
    if rng.random() < 0.3:
        cc = s.add("and", "and", "CCONJ", "CC")
        v2 = action_clause(s, rng, plural, tense)
        s.attach(cc, v2, "cc")
        s.attach(v2, v, "conj")
    end(s, v, rng.choice([".", ".", ".", "!"]))
    cap(s)
    return s


def imperative_action(rng: random.Random) -> Sent:
    s = Sent()
    kind = rng.random()
    if kind < 0.5:
        forms = rng.choice(MOTION)
        v = s.add(forms[0], forms[0], "VERB", "VB", VB_IMP)
        if rng.random() < 0.3:
            m = rng.choice(MANNERS)
            s.attach(s.add(m, m, "ADV", "RB", POS_DEG), v, "advmod")
        character_pp(s, rng, v, rng.choice(forms[4]))
    else:
        forms = rng.choice(TRANSITIVE)
        v = s.add(forms[0], forms[0], "VERB", "VB", VB_IMP)
        o = noun_phrase(s, rng, definite=True, adjs=0)
        s.attach(o, v, "obj")
    end(s, v, rng.choice([".", "!"]))
    cap(s)
    return s


def social_sentence(rng: random.Random) -> Sent:
    s = Sent()
    kind = rng.random()
    if kind < 0.3:  # They are friends. / Tom and Mary are colleagues.
        if rng.random() < 0.5:
            form, lemma, feats = THEY
            subj = s.add(form, lemma, "PRON", "PRP", feats)
        else:
            a, b = rng.sample(NAMES, 2)
            subj = s.add(a, a, "PROPN", "NNP", SG)
            cc = s.add("and", "and", "CCONJ", "CC")
            n2 = s.add(b, b, "PROPN", "NNP", SG)
            s.attach(cc, n2, "cc")
            s.attach(n2, subj, "conj")
        cop = s.add("are", "be", "AUX", "VBP", VBP)
        pl, sg = rng.choice(SOCIAL_NOUNS)
        n = s.add(pl, sg, "NOUN", "NNS", PL)
        s.attach(cop, n, "cop")
        s.attach(subj, n, "nsubj")
        root = n
    elif kind < 0.55:  # Mary is Tom's boss.
        a, b = rng.sample(NAMES, 2)
        subj = s.add(a, a, "PROPN", "NNP", SG)
        cop = s.add("is", "be", "AUX", "VBZ", VBZ)
        s.toks[-1].space_after = True
        poss = s.add(b, b, "PROPN", "NNP", SG)
        s.toks[poss].space_after = False
        ps = s.add("'s", "'s", "PART", "POS")
        role = rng.choice(ROLE_NOUNS)
        n = s.add(role, role, "NOUN", "NN", SG)
        s.attach(ps, poss, "case")
        s.attach(poss, n, "nmod:poss")
        s.attach(cop, n, "cop")
        s.attach(subj, n, "nsubj")
        root = n
    elif kind < 0.75:  # Tom is angry.
        subj, plural = subject(s, rng, allow_they=True)
        cop = s.add(
            "are" if plural else "is", "be", "AUX", "VBP" if plural else "VBZ", VBP if plural else VBZ
        )
        e = rng.choice(EMOTION_ADJS)
        adj = s.add(e, e, "ADJ", "JJ", POS_DEG)
        s.attach(cop, adj, "cop")
        s.attach(subj, adj, "nsubj")
        root = adj
    else:  # Tom apologizes to Mary.
        subj, _ = subject(s, rng)
        base, third, prep = rng.choice(SOCIAL_VERBS)
        v = s.add(third, base, "VERB", "VBZ", VBZ)
        s.attach(subj, v, "nsubj")
        c = s.add(prep, prep, "ADP", "IN")
        name = rng.choice(NAMES)
        o = s.add(name, name, "PROPN", "NNP", SG)
        s.attach(c, o, "case")
        s.attach(o, v, "obl")
        root = v
    end(s, root)
    cap(s)
    return s


def command_sentence(rng: random.Random) -> Sent:
    s = Sent()
    kind = rng.random()
    if kind < 0.5:  # Wait 2 seconds. / Wait for 3 seconds.
        v = s.add("wait", "wait", "VERB", "VB", VB_IMP)
        f = s.add("for", "for", "ADP", "IN") if rng.random() < 0.4 else None
        word, val = rng.choice(NUMBERS)
        feats = "NumForm=Digit|NumType=Card" if word[0].isdigit() else "NumForm=Word|NumType=Card"
        nm = s.add(word, word, "NUM", "CD", feats)
        unit = "second" if val == 1 else "seconds"
        u = s.add(unit, "second", "NOUN", "NN" if val == 1 else "NNS", SG if val == 1 else PL)
        s.attach(nm, u, "nummod")
        if f is not None:
            s.attach(f, u, "case")
            s.attach(u, v, "obl")
        else:
            s.attach(u, v, "obl:unmarked")
        root = v
    else:  # Move the camera to the left. / Zoom in.
        v = s.add("move", "move", "VERB", "VB", VB_IMP)
        d = s.add("the", "the", "DET", "DT", DEF)
        c = s.add("camera", "camera", "NOUN", "NN", SG)
        s.attach(d, c, "det")
        s.attach(c, v, "obj")
        side = rng.choice(["left", "right", "front", "back"])
        t = s.add("to", "to", "ADP", "IN")
        d2 = s.add("the", "the", "DET", "DT", DEF)
        n = s.add(side, side, "NOUN", "NN", SG)
        s.attach(t, n, "case")
        s.attach(d2, n, "det")
        s.attach(n, v, "obl")
        root = v
    end(s, root)
    cap(s)
    return s


GENERATORS = [
    (there_is, 14),
    (copular_location, 16),
    (attribute_sentence, 5),
    (has_sentence, 4),
    (place_imperative, 4),
    (action_sentence, 34),
    (imperative_action, 8),
    (social_sentence, 10),
    (command_sentence, 5),
]


def generate(n: int, rng: random.Random, prefix: str) -> list[str]:
    funcs = [f for f, w in GENERATORS for _ in range(w)]
    out, seen = [], set()
    while len(out) < n:
        s = rng.choice(funcs)(rng)
        text = " ".join(t.form for t in s.toks)
        if text in seen:
            continue
        seen.add(text)
        out.append(s.conllu(f"{prefix}-{len(out) + 1:04d}"))
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", type=Path, default=HERE, help="output folder (default: corpus/domain)")
    ap.add_argument("--train", type=int, default=640, help="number of training sentences")
    ap.add_argument("--test", type=int, default=160, help="number of test sentences")
    args = ap.parse_args(argv)
    rng = random.Random(SEED)
    train = generate(args.train, rng, "wana-train")
    test = generate(args.test, rng, "wana-test")
    train_texts = {t.split("\n")[1] for t in train}
    test = [t for t in test if t.split("\n")[1] not in train_texts]
    for name, sents in (("domain-train.conllu", train), ("domain-test.conllu", test)):
        (args.out / name).write_text("\n".join(sents) + "\n", encoding="utf-8")
        print(f"wrote {len(sents)} sentences to {args.out / name}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
