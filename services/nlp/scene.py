"""Scene sentences -> object nodes (category, attributes, count) and spatial relation nodes.

Relations are read off the dependency tree in the shapes UD English uses:
  "A laptop is on the desk"          desk <-nsubj- laptop, desk -case-> on, desk -cop-> is
  "There is a desk near a window"    is -nsubj-> desk, is|desk -obl|nmod-> window -case-> near
  "A chair is in front of the desk"  front -nsubj-> chair, front -case-> in, front -nmod-> desk -case-> of
  "The lamp is hanging above ..."    hanging -nsubj-> lamp, hanging -obl-> table -case-> above
  "Put a lamp on the desk"           put -obj-> lamp, put -obl-> desk -case-> on
  "The sofa faces the TV"            faces -nsubj-> sofa, faces -obj-> TV
  "a bed under which a box lies"     which -case-> under; the relative clause's noun is the anchor
  "a desk with a lamp"               desk -nmod-> lamp -case-> with: lamp on desk
Over 400 lines because each of these shapes needs its own reading of the tree, kept in one place.
"""

from __future__ import annotations

from spacy.tokens import Span as SpacySpan
from spacy.tokens import Token

from services.nlp import lexicon
from services.nlp.builder import GraphBuilder
from services.nlp.mentions import (
    ObjectMention,
    character_mention,
    is_unknown_object_word,
    object_mention,
    quantity_target,
)
from services.nlp.suggest import did_you_mean
from wana.assets import vocabulary

MULTIWORD_RELATIONS = {
    "next to": "next_to",
    "close to": "near",
    "near to": "near",
    "close by": "near",
    "across from": "facing",
    "opposite to": "facing",
    "opposite of": "facing",
    "in front of": "in_front_of",
    "on top of": "on",
    "in back of": "behind",
    "left of": "left_of",
    "right of": "right_of",
    "on to": "on",
    "up against": "next_to",
    "adjacent to": "next_to",
    "beside of": "next_to",
    "underneath of": "under",
    "inside of": "in",
}
PLACEMENT_VERBS = frozenset(
    {
        "put",
        "place",
        "add",
        "set",
        "position",
        "hang",
        "lay",
        "move",
        "stand",
        "lean",
        "mount",
        "install",
        "keep",
        "store",
        "stack",
        "arrange",
    }
)
ADJ_RELATION_HEADS = {
    "next": "next_to",
    "close": "near",
    "near": "near",
    "adjacent": "next_to",
    "opposite": "facing",
}
SUBJECT_DEPS = ("nsubj", "nsubj:pass")
# Placement verbs in the present tense the tagger can take for a plural noun ("a whiteboard hangs").
SCENE_VERB_FORMS = {
    "hangs": "hang",
    "stands": "stand",
    "lies": "lie",
    "sits": "sit",
    "rests": "rest",
    "leans": "lean",
    "faces": "face",
}


def _misread_verb(tok: Token) -> bool:
    """A placement verb tagged as a noun, its subject glued on as a compound ("whiteboard hangs")."""
    return (
        tok.pos_ in ("NOUN", "PROPN")
        and tok.lower_ in SCENE_VERB_FORMS
        and any(c.dep_ in ("compound", "amod") and c.i < tok.i and c.pos_ != "DET" for c in tok.children)
    )


def _subject_verb_noun(tok: Token) -> bool:
    """A placement verb tagged as a noun that the parser still gave its subject ("A punching bag/nsubj
    hangs/NOUN near the ring")."""
    return (
        tok.pos_ in ("NOUN", "PROPN")
        and tok.lower_ in SCENE_VERB_FORMS
        and any(c.dep_ in SUBJECT_DEPS and c.i < tok.i for c in tok.children)
    )


def _verb_lemma(tok: Token) -> str:
    if _misread_verb(tok) or _subject_verb_noun(tok):
        return SCENE_VERB_FORMS.get(tok.lower_, tok.lemma_.lower())
    return tok.lemma_.lower()


def _case_words(tok: Token) -> list[Token]:
    out: list[Token] = []
    for c in tok.children:
        if c.dep_ == "case" and c.i < tok.i:
            out.append(c)
            out += [f for f in c.children if f.dep_ == "fixed"]
    return sorted(out, key=lambda t: t.i)


def _relation_noun(tok: Token, case: str) -> str | None:
    lemma = tok.lemma_.lower()
    rel = lexicon.RELATION_NOUNS.get(lemma)
    if rel is None:
        return None
    if lemma == "top" and case not in ("on", "at", "atop"):
        return None
    return rel


def relation_at(tok: Token) -> tuple[str, list[Token], Token, int] | None:
    """If ``tok`` heads a spatial phrase: (relation, anchor nouns, attachment token, phrase start char)."""
    cases = _case_words(tok)
    case = " ".join(c.lower_ for c in cases)
    start = cases[0].idx if cases else tok.idx
    # "in front of the desk", "to the left of the sofa", "on top of the shelf"
    rel = _relation_noun(tok, case)
    if rel is not None and cases:
        for child in tok.children:
            if child.dep_ in ("nmod", "obl") and any(c.lower_ == "of" for c in _case_words(child)):
                return rel, _with_conj(child), tok, start
        # "of the bed" attached beside "right" instead of under it
        for sib in tok.head.children:
            if (
                sib.i > tok.i
                and sib.dep_ in ("nmod", "obl")
                and any(c.lower_ == "of" for c in _case_words(sib))
            ):
                return rel, _with_conj(sib), tok, start
        return None
    # "next to the desk" (two case words) and other multiword prepositions
    if case in MULTIWORD_RELATIONS:
        return MULTIWORD_RELATIONS[case], _with_conj(tok), tok, start
    if case == "between":
        return "near", _with_conj(tok), tok, start
    if len(cases) == 1 and case in lexicon.RELATION_PREPS:
        # the preposition's head is "next"/"close" ("next to" parsed as ADV + obl)
        head = tok.head
        if case == "to" and head.lemma_.lower() in ADJ_RELATION_HEADS:
            return ADJ_RELATION_HEADS[head.lemma_.lower()], _with_conj(tok), head, head.idx
        return lexicon.RELATION_PREPS[case], _with_conj(tok), tok, start
    if case == "to" and tok.head.lemma_.lower() in ADJ_RELATION_HEADS and tok.head.pos_ in ("ADJ", "ADV"):
        head = tok.head
        return ADJ_RELATION_HEADS[head.lemma_.lower()], _with_conj(tok), head, head.idx
    return None


def _with_conj(tok: Token) -> list[Token]:
    out = [tok]
    for c in tok.children:
        if c.dep_ == "conj" and c.pos_ in ("NOUN", "PROPN", "X"):
            out += _with_conj(c)
    return out


def _subjects_of(attach: Token) -> list[Token]:
    """Nouns a spatial phrase attached at ``attach`` is said of."""
    head = attach.head
    dep = attach.dep_  # spaCy labels the root "ROOT"
    if attach.lower_ in RELATIVE_PRONOUNS and head.dep_ == "acl:relcl" and head.i != attach.i:
        # "a window near which/obj a plant grows": what the relative clause says is near the window
        subj = [c for c in head.children if c.dep_ in SUBJECT_DEPS and c.i != attach.i]
        if subj:
            return _expand_subject(subj[0])
    if _misread_verb(head) and head.i != attach.i:
        compounds = [c for c in head.children if c.dep_ in ("compound", "amod") and c.i < head.i]
        return _expand_subject(compounds[-1])
    if _subject_verb_noun(head) and head.i != attach.i:
        return _expand_subject(next(c for c in head.children if c.dep_ in SUBJECT_DEPS))
    if dep in ("nmod", "acl", "amod") and head.pos_ in ("NOUN", "PROPN", "X", "NUM") and head.i != attach.i:
        if head.lemma_.lower() in lexicon.NON_OBJECT_NOUNS and object_mention(head) is None:
            return _subjects_of(head)  # "on the floor near the bed": what is on the floor is near the bed
        if _is_content(head):
            return _with_conj(head.head)  # "a cup of tea on the desk": the cup is on the desk
        q = quantity_target(head)
        return _with_conj(q[0] if q else head)
    if (
        dep == "ROOT"
        or any(c.dep_ == "cop" for c in attach.children)
        or (dep == "conj" and not any(c.dep_ in SUBJECT_DEPS for c in attach.children))
    ):
        pred = attach
        while True:
            subj = [c for c in pred.children if c.dep_ in SUBJECT_DEPS]
            if subj:
                return _expand_subject(subj[0])
            if pred.dep_ == "conj" and pred.head.i != pred.i:
                pred = pred.head
                continue
            break
        if dep == "ROOT":
            return []
    if dep in ("obl", "advmod", "obl:unmarked", "advcl", "xcomp") or head.pos_ in ("VERB", "AUX"):
        verb = head if dep != "ROOT" else attach
        while True:
            if any(c.dep_ == "expl" for c in verb.children) or verb.lemma_.lower() == "be":
                subj = [c for c in verb.children if c.dep_ in SUBJECT_DEPS]
                if subj:
                    return _expand_subject(subj[0])
            obj = [c for c in verb.children if c.dep_ == "obj"]
            if obj and (
                verb.lemma_.lower() in PLACEMENT_VERBS
                or verb.lemma_.lower() == "have"  # "the desk has a lamp on it": the lamp is on it
                or not any(c.dep_ in SUBJECT_DEPS for c in verb.children)
            ):
                return _expand_subject(obj[0])
            subj = [c for c in verb.children if c.dep_ in SUBJECT_DEPS]
            if subj:
                return _expand_subject(subj[0])
            if verb.dep_ in ("conj", "xcomp", "advcl") and verb.head.i != verb.i:
                verb = verb.head
                continue
            return []
    return []


def _expand_subject(tok: Token) -> list[Token]:
    q = quantity_target(tok)
    out = _with_conj(q[0] if q else tok)
    # "A soda can and a bowl are on the coffee table": the parser hangs "bowl" on the predicate as a second
    # subject (not a conjunct of "can"); a later subject of the same head joined by "and" is one more thing
    for c in tok.head.children if tok.head.i != tok.i else ():
        if c.i > tok.i and c.dep_ == tok.dep_ and any(g.dep_ == "cc" for g in c.children) and c not in out:
            out += _with_conj(c)
    return out


def _mention(tok: Token, builder: GraphBuilder, report_unknown: bool) -> str | None:
    q = quantity_target(tok)
    if q is not None:
        m = object_mention(q[0])
        if m is not None:
            m.count = max(m.count if m.count > 1 else 0, q[1])
            m.start = tok.idx if tok.i < q[0].i else m.start
            for c in tok.lefts:
                if c.dep_ == "det":
                    m.start = min(m.start, c.idx)
        if m is None:
            return None
        return builder.object_id(m)
    m = object_mention(tok)
    if m is None:
        if report_unknown and is_unknown_object_word(tok):
            builder.diagnose(
                "W101",
                f"'{tok.text}' is not in the object catalog{did_you_mean(tok.text, 'object')}",
                tok.idx,
                tok.idx + len(tok.text),
            )
        return None
    return builder.object_id(m)


def _is_content(tok: Token) -> bool:
    """The "of" complement a container holds ("flowers" in "a vase of flowers")."""
    if tok.dep_ != "nmod" or not any(c.dep_ == "case" and c.lower_ == "of" for c in tok.children):
        return False
    holder = object_mention(tok.head)
    return holder is not None and holder.attributes.get("content") == tok.lemma_.lower()


def _room(tok: Token) -> str | None:
    words = [c.lower_ for c in tok.lefts if c.dep_ in ("compound", "amod")] + [tok.lower_]
    for k in range(len(words)):
        room = lexicon.room_of(" ".join(words[k:]))
        if room and object_mention(tok) is None:
            return room
    return None


# Catalog things built on their own stand: "a microphone on a stand" is one microphone.
OWN_STAND = frozenset({"microphone", "guitar", "electric_guitar", "bass_guitar"})


def _built_in_stands(sent: SpacySpan) -> set[int]:
    """Token indices of a bare "stand" that the thing on it already has ("a guitar on a stand")."""
    out: set[int] = set()
    for tok in sent:
        if tok.lemma_.lower() != "stand" or tok.pos_ not in ("NOUN", "PROPN"):
            continue
        m = object_mention(tok)
        if m is None or m.word != "stand":
            continue
        found = relation_at(tok)
        if found is None or found[0] != "on":
            continue
        subjects = [object_mention(s) for s in _subjects_of(found[2])]
        if subjects and all(s is not None and s.category in OWN_STAND for s in subjects):
            out.add(tok.i)
    return out


def extract_scene(sent: SpacySpan, builder: GraphBuilder) -> None:
    """Add the objects, attributes, relations and room type a scene sentence states."""
    built_in = _built_in_stands(sent)
    # Objects, in text order, so that ids follow the order of first mention.
    for tok in sent:
        if tok.i in built_in:
            continue
        if tok.pos_ in ("NOUN", "PROPN", "X", "ADJ", "NUM") or tok.dep_ in (
            "nsubj",
            "obj",
            "obl",
            "nmod",
            "ROOT",
        ):
            glued_subject = (
                tok.dep_ in ("compound", "amod") and _misread_verb(tok.head) and object_mention(tok)
            )
            if (
                tok.dep_ in ("compound", "amod", "flat", "det")
                and tok.head.pos_ in ("NOUN", "PROPN")
                and not (glued_subject)
            ):
                continue
            if (
                tok.pos_ in ("ADJ", "NUM")
                and tok.dep_ not in ("nsubj", "obj", "obl", "nmod", "ROOT", "conj")
                and not (glued_subject)
            ):
                continue
            room = _room(tok)
            if room:
                builder.room_type = builder.room_type or room
                continue
            if character_mention(tok) is not None and tok.pos_ in ("PROPN", "PRON"):
                continue
            if tok.dep_ in (
                "nsubj",
                "nsubj:pass",
                "obj",
                "obl",
                "nmod",
                "ROOT",
                "conj",
                "appos",
                "nmod:npmod",
            ):
                _mention(tok, builder, report_unknown=tok.pos_ in ("NOUN", "X") and not _misread_verb(tok))
            else:
                _mention(tok, builder, report_unknown=False)
    # Predicative attributes: "The chair is red (and old)."
    for tok in sent:
        if tok.pos_ == "ADJ" and any(c.dep_ == "cop" for c in tok.children):
            subjects = [c for c in tok.children if c.dep_ in SUBJECT_DEPS]
            adjs = [tok] + [c for c in tok.children if c.dep_ == "conj" and c.pos_ == "ADJ"]
            for s in subjects[:1] and _expand_subject(subjects[0]):
                oid = builder._by_token.get(s.i)
                for a in adjs:
                    hit = lexicon.attribute_of(a.lower_)
                    if oid and hit:
                        builder.set_attribute(oid, hit[0], hit[1])
    # Relations.
    for tok in sent:
        found = relation_at(tok)
        if found is None:
            continue
        relation, anchors, attach, start = found
        subjects = _subjects_of(attach)
        verb = attach.head if attach.dep_ in ("obl", "advmod") or _misread_verb(attach.head) else attach
        if _verb_lemma(verb) == "hang" and relation == "above":
            relation = "hanging_above"
        for anchor in anchors:
            anchor = relative_antecedent(anchor)  # "a bed under which a box lies": under the bed
            anchor = _holder_of_it(anchor)  # "Each desk has a computer on it": on each desk
            if anchor.i in built_in:
                continue
            anchor_room = _room(anchor)
            if anchor_room:
                builder.room_type = builder.room_type or anchor_room
                continue
            anchor_id = _mention(anchor, builder, report_unknown=False)
            if anchor_id is None and anchor.lower_ == "it" and anchor.pos_ == "PRON":
                anchor_id = PRONOUN_ANCHOR  # "another chair next to it": resolve() names the thing
            if anchor_id is None:
                continue
            for s in subjects:
                sid = _mention(s, builder, report_unknown=False)
                if sid is not None:  # the span covers both ends ("under which a box": box and bed)
                    end = max(anchor.idx + len(anchor.text), s.idx + len(s.text))
                    builder.add_relation(
                        sid, relation, anchor_id, min(start, s.idx, anchor.idx), end, each=_each(anchor)
                    )
    _with_relations(sent, builder)
    _room_parts(sent, builder)
    # Verbs that are relations: "The sofa faces the TV", "a chair facing the window".
    for tok in sent:
        rel = lexicon.RELATION_VERBS.get(tok.lemma_.lower())
        # "The desks in the office face/NOUN/ROOT the door": the verb the tagger read as a noun
        misread_root = tok.dep_ == "ROOT" and any(c.dep_ in SUBJECT_DEPS for c in tok.children)
        if rel is None or (tok.pos_ not in ("VERB", "AUX") and not misread_root):
            continue
        objs = [c for c in tok.children if c.dep_ == "obj"]
        if not objs:
            continue
        if tok.dep_ in ("acl", "amod") and tok.head.pos_ in ("NOUN", "PROPN"):
            subjects = _with_conj(tok.head)
        elif tok.dep_ == "advcl" and any(c.dep_ == "expl" for c in tok.head.children):
            # "There is a table facing the door": the table faces it
            subj = [c for c in tok.head.children if c.dep_ in SUBJECT_DEPS]
            subjects = _expand_subject(subj[0]) if subj else []
        else:
            subj = [relative_antecedent(c) for c in tok.children if c.dep_ in SUBJECT_DEPS]
            subjects = _expand_subject(subj[0]) if subj else []
        for anchor in _with_conj(objs[0]):
            anchor_id = _mention(anchor, builder, report_unknown=False)
            if anchor_id is None:
                continue
            for s in subjects:
                sid = _mention(s, builder, report_unknown=False)
                if sid is not None:
                    builder.add_relation(
                        sid,
                        rel,
                        anchor_id,
                        min(tok.idx, s.idx),
                        anchor.idx + len(anchor.text),
                        each=_each(anchor),
                    )


def _holder_of_it(tok: Token) -> Token:
    """The subject of "has" that "it" points back to ("A desk has a lamp on it" -> desk); else the token."""
    if tok.lower_ != "it" or tok.pos_ != "PRON":
        return tok
    head = tok.head
    for _ in range(3):
        if head.lemma_.lower() == "have":
            holders = [c for c in head.children if c.dep_ in SUBJECT_DEPS and c.pos_ in ("NOUN", "PROPN")]
            return holders[0] if holders else tok
        if head.head.i == head.i:
            break
        head = head.head
    return tok


def _each(anchor: Token) -> bool:
    """True for an anchor written "each desk" / "every table": the thing stands at every one of them."""
    return any(c.dep_ == "det" and c.lower_ in ("each", "every") for c in anchor.children)


# Parts of a room a thing is placed by ("in the corner", "at the back of the room") -> the part's name.
ROOM_PARTS = {
    "corner": "corner",
    "middle": "middle",
    "center": "middle",
    "centre": "middle",
    "back": "back",
    "rear": "back",
    "front": "front",
    "side": "side",
    "end": "end",
}


def room_part(tok: Token) -> str:
    """The part of the room ``tok`` names as a place ("in the corner", "in the middle of the room"), else
    "" ("at the back of the sofa" is a relation to the sofa, not a part of the room)."""
    part = ROOM_PARTS.get(tok.lemma_.lower(), "")
    if not part or not _case_words(tok) or tok.pos_ not in ("NOUN", "ADV", "ADJ"):
        return ""
    of = [
        c for c in tok.children if c.dep_ in ("nmod", "obl") and any(x.lower_ == "of" for x in _case_words(c))
    ]
    if of and not (_room(of[0]) or of[0].lemma_.lower() in ("room", "space", "hall")):
        return ""
    return part


def _room_parts(sent: SpacySpan, builder: GraphBuilder) -> None:
    """Say which things the text places by a part of the room: the layout places a thing relative to other
    things only, so "in the corner" is read but not honoured (an info diagnostic names it)."""
    for tok in sent:
        part = room_part(tok)
        if not part:
            continue
        ids = [builder._by_token.get(s.i) for s in _subjects_of(tok)]
        names = [i for i in ids if i]
        if not names:
            continue
        start_tok = _case_words(tok)[0].i
        start = sent.doc[start_tok].idx
        phrase = [
            c for c in tok.subtree if not c.is_punct and c.dep_ not in SUBJECT_DEPS and c.i >= start_tok
        ]
        end = max([tok.idx + len(tok.text)] + [c.idx + len(c.text) for c in phrase])
        builder.diagnose(
            "I114",
            f"{', '.join(names)} '{sent.doc.text[start:end]}' ({part} of the room): the layout places it "
            "relative to the other things only",
            start,
            end,
        )


RELATIVE_PRONOUNS = frozenset({"which", "that", "whom", "where"})


# The anchor of a relation to "it" ("There is another chair next to it$"): the thing an earlier scene
# sentence named, which services.nlp.resolve.distinct_objects puts in its place (or drops the relation).
PRONOUN_ANCHOR = "it"


def relative_antecedent(tok: Token) -> Token:
    """The noun a relative pronoun stands for ("which" in "a bed under which a box lies" -> bed)."""
    if tok.lower_ not in RELATIVE_PRONOUNS or tok.pos_ not in ("PRON", "DET", "ADV", "SCONJ"):
        return tok
    clause = tok.head
    for _ in range(4):
        if clause.dep_ == "acl:relcl" and clause.head.i != clause.i:
            return clause.head
        if clause.head.i == clause.i:
            break
        clause = clause.head
    return tok


def _with_relations(sent: SpacySpan, builder: GraphBuilder) -> None:
    """ "a desk with a lamp" -> lamp on desk; "three desks with chairs" -> chair next_to desk: a thing
    that stands on surfaces is on its holder, anything else stands beside it."""
    for tok in sent:
        full_of = (  # "a shelf full of books": the books are on the shelf, as with "with"
            tok.dep_ in ("obl", "nmod")
            and tok.head.lemma_.lower() == "full"
            and tok.head.dep_ == "amod"
            and any(c.dep_ == "case" and c.lower_ == "of" for c in tok.children)
        )
        if not full_of and not any(c.dep_ == "case" and c.lower_ == "with" for c in tok.children):
            continue
        if full_of:
            holders = [tok.head.head]
        elif tok.dep_ == "nmod" and tok.head.pos_ in ("NOUN", "PROPN"):
            holders = [tok.head]
        elif tok.dep_ == "obl" and any(c.dep_ == "expl" for c in tok.head.children):
            holders = [c for c in tok.head.children if c.dep_ in SUBJECT_DEPS]
        else:
            continue
        for holder in holders[:1]:
            hid = _mention(holder, builder, report_unknown=False)
            if hid is None:
                continue
            for thing in _with_conj(tok):
                tid = _mention(thing, builder, report_unknown=False)
                if tid is None:
                    continue
                category = next(o.category for o in builder.objects if o.id == tid)
                info = vocabulary.CATEGORIES.get(category)
                relation = "on" if info is not None and info.mount == "surface" else "next_to"
                builder.add_relation(
                    tid,
                    relation,
                    hid,
                    min(holder.idx, thing.idx),
                    max(holder.idx, thing.idx) + len(thing.text),
                    each=_each(holder),
                )


def is_scene_like(sent: SpacySpan) -> bool:
    """True for a sentence without "$" that still describes the scene ("There is a desk.")."""
    root = sent.root
    if any(c.dep_ == "expl" for c in root.children):
        return True
    if not any(t.pos_ in ("VERB", "AUX") for t in sent):
        # "A king-size bed, a minibar, heavy curtains.": a screenplay's set, a list of things
        nouns = [t for t in sent if t.pos_ in ("NOUN", "PROPN") and t.dep_ != "compound"]  # not "king"-size
        if nouns and root.pos_ == "NOUN" and not any(character_mention(t) is not None for t in nouns):
            return any(object_mention(t) is not None for t in nouns)
    subj = [c for c in root.children if c.dep_ in SUBJECT_DEPS]
    if subj:
        m: ObjectMention | None = object_mention(subj[0])
        return m is not None and character_mention(subj[0]) is None
    return False
