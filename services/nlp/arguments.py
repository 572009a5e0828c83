"""Arguments of a verb clause: objects and obliques as objects, characters, body parts or words.

``arguments(verb, builder)`` reads a verb's children into :class:`Argument`s (with the preposition
of an oblique), and a "for 5 seconds" duration; "it" is resolved within the sentence, "himself" is
skipped, "each other" becomes the reciprocal marker, "hands" of "shakes hands" a body part that names
the action. Event nouns of light verbs ("gives Mary a hug") are read by :func:`event_action`.
"""

from __future__ import annotations

from dataclasses import dataclass

from spacy.tokens import Token

from services.nlp import lexicon
from services.nlp.builder import GraphBuilder
from services.nlp.commands import NUMBER_WORDS, UNIT_SECONDS
from services.nlp.lemmatizer import rule_lemma
from services.nlp.mentions import (
    CharacterMention,
    character_mention,
    is_speech,
    is_title,
    is_unknown_object_word,
    object_mention,
)
from services.nlp.scene import _mention, relative_antecedent
from services.nlp.suggest import did_you_mean
from services.nlp.timephrase import time_light

TIME_UNITS = frozenset(UNIT_SECONDS)


@dataclass
class Argument:
    tok: Token
    prep: str
    object_id: str = ""
    character: str = ""  # a name, a pronoun as written, or "each other"
    word: str = ""
    body_part: bool = False  # "hands" of "shakes hands": names the action, is never its target


def verb_lemma(tok: Token) -> str:
    """Lemma of a verb; for a word the tagger took for a noun or adverb, its verb reading."""
    if tok.pos_ in ("VERB", "AUX"):
        return tok.lemma_.lower()
    return rule_lemma(tok.text, "VERB", lexicon.verb_words()).lower()


STATE_PARTICLES = frozenset({"asleep", "awake"})  # "falls asleep", "stays awake": read as particles


def duration_of(tok: Token) -> float | None:
    """Seconds of "for 5 seconds" / "2 minutes" / "a second" headed by the unit noun ``tok``."""
    unit = tok.lower_
    if unit not in TIME_UNITS:
        return None
    value: float | None = None
    for c in tok.children:
        if c.dep_ in ("nummod", "det", "amod") or c.like_num:
            try:
                value = float(c.text)
            except ValueError:
                value = NUMBER_WORDS.get(c.lower_, value)
    if value is None:
        value = 1.0 if unit in ("second", "minute", "hour", "sec", "min") else None
    return None if value is None else value * UNIT_SECONDS[unit]


GIVING_VERBS = frozenset({"give", "hand", "pass", "offer", "bring", "deliver"})  # "... the cup to Sam"


def character_of(tok: Token, builder: GraphBuilder) -> CharacterMention | None:
    cm = character_mention(tok)
    if cm is None and (tok.pos_ == "PROPN" or unknown_capitalised_subject(tok)):
        if object_mention(tok) is None and not is_title(tok):
            cm = CharacterMention(head=tok, name=tok.text, mention=tok.text)
    return cm


def unknown_capitalised_subject(tok: Token) -> bool:
    """ "Forrest/ADJ eats": a capitalised subject that is no English word the treebank knows: a name."""
    from services.nlp.compounds import _english_words

    lead = (
        tok.dep_ in ("amod", "compound") and tok.head.pos_ == "VERB" and tok.i < tok.head.i
    )  # "Forrest/amod sits"
    return (
        (tok.dep_ in ("nsubj", "nsubj:pass") or lead)
        and tok.pos_ in ("ADJ", "NOUN", "X")
        and tok.text[:1].isupper()
        and tok.text[1:].islower()
        and tok.is_alpha
        and len(tok.text) >= 3
        and tok.lower_ not in _english_words()
        and not lexicon.room_of(tok.lower_)
    )


_SALIENCE = {"obj": 0, "nsubj": 1, "nsubj:pass": 1, "obl": 2, "nmod": 3}


def _antecedent(pronoun: Token, builder: GraphBuilder) -> str:
    """Object id "it" refers to within its sentence: an earlier direct object, else subject, else the last."""
    candidates: list[tuple[int, int, str]] = []
    for tok in pronoun.sent:
        if tok.i >= pronoun.i:
            break
        oid = builder._by_token.get(tok.i)
        if oid is None:
            m = object_mention(tok) if tok.pos_ in ("NOUN", "PROPN") else None
            oid = builder.object_id(m) if m is not None else None
        if oid is not None:
            candidates.append((_SALIENCE.get(tok.dep_, 4), -tok.i, oid))
    return min(candidates)[2] if candidates else ""


def argument(tok: Token, prep: str, builder: GraphBuilder, report_unknown: bool) -> Argument:
    """What one noun of a verb names: a character, a body part, an object (its id) or a bare word."""
    tok = relative_antecedent(tok)  # "a table at which a sailor sits": at the table
    tok = partitive_noun(tok)  # "sits on one of the chairs": on a chair
    arg = Argument(tok=tok, prep=prep)
    if reciprocal_phrase(tok):
        arg.character = "each other"
        return arg
    if tok.lemma_.lower() in lexicon.BODY_PARTS or tok.lower_ in lexicon.BODY_PARTS:
        arg.word, arg.body_part = tok.lemma_.lower(), True
        return arg
    cm = character_of(tok, builder)
    if cm is not None and (cm.name or cm.pronoun in ("he", "she", "they")):
        arg.character = cm.name or cm.mention
        return arg
    if tok.lower_ in lexicon.OBJECT_PRONOUNS:
        antecedent = _antecedent(tok, builder)
        if antecedent:
            arg.object_id = antecedent
        else:
            arg.word = tok.lower_  # resolved against earlier sentences by resolve()
        return arg
    oid = _mention(tok, builder, report_unknown=False)
    if oid is not None:
        arg.object_id = oid
        return arg
    arg.word = tok.lemma_.lower()
    if report_unknown and is_unknown_object_word(tok):
        builder.diagnose(
            "W101",
            f"'{tok.text}' is not in the object catalog{did_you_mean(tok.text, 'object')}",
            tok.idx,
            tok.idx + len(tok.text),
        )
    return arg


PARTITIVE_WORDS = frozenset({"one", "each", "some", "any", "either", "neither", "both", "all", "another"})


def partitive_noun(tok: Token) -> Token:
    """The noun after "of" of "one of the chairs", "either of the stools" (``tok`` itself otherwise)."""
    if tok.lower_ not in PARTITIVE_WORDS:
        return tok
    for c in tok.children:
        if c.dep_ == "nmod" and c.pos_ in ("NOUN", "PROPN") and any(g.lower_ == "of" for g in c.children):
            return c
    return tok


def reciprocal_phrase(tok: Token) -> bool:
    """ "each other" / "one another" headed by ``tok``."""
    words = [tok.lower_, *(c.lower_ for c in tok.children if c.dep_ in ("fixed", "amod", "det", "nummod"))]
    if len(words) < 2:
        return False
    # "each other" is headed by "each" (fixed "other") or by "other" (det "each")
    return f"{words[0]} {words[1]}" in lexicon.RECIPROCAL_PHRASES or f"{words[1]} {words[0]}" in (
        lexicon.RECIPROCAL_PHRASES
    )


def event_phrase(tok: Token) -> str:
    """The noun phrase of an event noun without its determiner: "a high five" -> "high_five"."""
    mods = [c.lower_ for c in tok.children if c.dep_ in ("amod", "compound") and c.i < tok.i]
    return "_".join([*mods, tok.lemma_.lower()])


def object_words(arg: Argument, builder: GraphBuilder) -> tuple[str, ...]:
    if arg.object_id:
        category = next(o.category for o in builder.objects if o.id == arg.object_id)
        return (category, *lexicon.hypernyms(category), arg.tok.lemma_.lower(), arg.tok.lower_)
    if arg.word:
        return (arg.word, arg.tok.lower_)
    return ()


def arguments(verb: Token, builder: GraphBuilder) -> tuple[list[Argument], list[Argument], float]:
    """The verb's objects and obliques (with their preposition) and a "for 5 seconds" duration."""
    duration = 0.0
    objects: list[Argument] = []
    obliques: list[Argument] = []
    by_position = verb.pos_ not in ("VERB", "AUX")
    light = verb_lemma(verb) in lexicon.LIGHT_VERBS
    dressing = _dressing(verb)
    for c in verb.children:
        if (
            dressing
            and c.dep_ in ("obj", "obl")
            and c.lower_ in lexicon.WORN_NOUNS
            and not any(g.dep_ == "compound" for g in c.children)  # "the boxing gloves": a catalog thing
        ):
            # "puts on his glasses": what he wears, not a glass to put in the room
            objects.append(Argument(tok=c, prep=case_of(c), word=c.lemma_.lower()))
            continue
        if c.pos_ == "ADV" and c.lower_.endswith("ly"):
            continue  # a manner the parser attached as an argument
        if c.dep_ != "nsubj" and duration_of(c) is None and (lit := time_light(c)) is not None:
            if lit:  # "that night": the light of the scene, as the "night" command would set it
                builder.add_command("weather", lit, c.idx, c.idx + len(c.text))
            continue  # "the next morning", "after a while": when, not what
        if c.lower_ in lexicon.DIRECTION_ADVERBS and not any(g.dep_ in ("det", "case") for g in c.children):
            continue  # "turns right": a direction, read by _manner_and_direction
        if c.lower_ in lexicon.REFLEXIVE_PRONOUNS:
            continue  # "introduces himself to Mary": the subject, not a target
        if c.lower_ in STATE_PARTICLES:
            continue  # "falls asleep": part of the verb (see actions._action)
        if is_speech(c) or any(is_speech(g) for g in c.children if g.dep_ in ("compound", "amod")):
            # 'says "Sorry." to Ada': the words said are the caption, not a target; "to Ada" may hang
            # under them
            obliques += [
                argument(g, case_of(g), builder, report_unknown=True)
                for g in c.children
                if g.dep_ in ("nmod", "obl", "compound") and any(h.dep_ == "case" for h in g.children)
            ]
            continue
        if (
            c.dep_ in ("obj", "iobj", "dobj")
            or (c.dep_ == "advmod" and c.pos_ in ("NOUN", "PROPN"))
            # "hugs Forrest/ADJ/advmod": a capitalised name after the verb, tagged as an adverb
            or (c.dep_ == "advmod" and c.i > verb.i and c.text[:1].isupper() and character_of(c, builder))
            or (by_position and c.dep_ in ("vocative", "appos") and c.i > verb.i)  # "Tom thanks/NOUN Mary"
        ):
            event = light and not character_of(c, builder) and bool(event_action(c))
            arg = argument(c, "", builder, report_unknown=not event)  # "a hug" is no unknown object
            objects.append(arg)
            if arg.body_part or event:  # "shakes hands with Mary": "with Mary" may hang under "hands"
                obliques += [
                    argument(g, case_of(g), builder, report_unknown=True)
                    for g in c.children
                    if g.dep_ in ("nmod", "obl") and any(h.dep_ == "case" for h in g.children)
                ]
            elif verb_lemma(verb) in GIVING_VERBS:  # "hands the hammer to Sam": "to Sam" may hang under
                obliques += [  # "hammer"; Sam is whom it goes to
                    argument(g, case_of(g), builder, report_unknown=True)
                    for g in c.children
                    if g.dep_ == "nmod" and case_of(g) == "to" and character_of(g, builder) is not None
                ]
        elif c.dep_ in ("obl", "obl:unmarked", "obl:tmod", "obl:npmod", "nmod:tmod", "nmod"):
            seconds = duration_of(c)
            if seconds is not None:
                duration = seconds
                continue
            if (
                c.lower_ in lexicon.DIRECTION_ADVERBS
                or (c.pos_ in ("ADV", "ADP", "PART", "SCONJ", "ADJ") and not reciprocal_phrase(c))
                or (c.lower_.endswith("ly") and not any(g.dep_ == "case" for g in c.children))
            ):
                continue  # "walks in", "looks outside", "dances happily": no object
            prep = case_of(c)
            of = _relation_noun_object(c)
            if of is not None:  # "stands in front of the mirror": at the mirror, not at a "front"
                c = of  # with its own preposition: "walks to the front of the desk" goes to the desk
            obliques.append(argument(c, prep, builder, report_unknown=True))
            for conj in c.children:
                if conj.dep_ == "conj" and conj.pos_ in ("NOUN", "PROPN"):
                    obliques.append(argument(conj, prep, builder, report_unknown=True))
    return objects, obliques, duration


def _relation_noun_object(tok: Token) -> Token | None:
    """The thing of "in front of the mirror", "at the back of the room", "on top of the shelf": the noun
    after "of" under a relational noun (lexicon.RELATION_NOUNS) that has a preposition of its own."""
    relational = tok.lower_ in lexicon.RELATION_NOUNS or tok.lower_ in lexicon.END_NOUNS
    if not relational or not any(g.dep_ == "case" for g in tok.children):
        return None
    return next(
        (
            g
            for g in tok.children
            if g.dep_ == "nmod" and g.pos_ in ("NOUN", "PROPN") and case_of(g) == "of" and g.i > tok.i
        ),
        None,
    )


def _dressing(verb: Token) -> bool:
    """ "puts on", "takes off", "slips on/ADP", "wears": a verb of dressing, whose object is worn."""
    from services.nlp import verbs

    lemma = verb_lemma(verb)
    particles = [c.lower_ for c in verb.children if c.dep_ == "compound:prt"]
    particles += [g.lower_ for c in verb.children if c.dep_ == "obl" for g in c.children if g.dep_ == "case"]
    return verbs.not_animatable_reason(lemma) == verbs.not_animatable_reason("put on") != "" or any(
        verbs.not_animatable_reason(f"{lemma} {p}") == verbs.not_animatable_reason("put on")
        for p in particles
    )


def event_action(tok: Token) -> str:
    """The action an event noun names ("hug", "a high five", "a quarrel"), or ""."""
    if tok.pos_ not in ("NOUN", "NUM", "PROPN", "X") or object_mention(tok) is not None:
        return ""
    return lexicon.action_for(event_phrase(tok).replace("_", " ")) or lexicon.action_for(tok.lemma_.lower())


def case_of(tok: Token) -> str:
    return " ".join(g.lower_ for g in tok.children if g.dep_ == "case")
