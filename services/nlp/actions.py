"""Character sentences -> characters with ordered actions, and social relations/emotions.

Per verb clause (the root, its conjuncts, adverbial clauses; "starts to dance" reads as "dance"):
subject -> character; obj / obl -> target, destination or instrument by the verb's kind and the
preposition; advmod -> manner or direction; "for 5 seconds" -> duration. "They are friends",
"Mary is Tom's boss" and "Tom is angry" -> social nodes; "Tom apologizes to Mary" -> an action plus
a social emotion node.
"""

from __future__ import annotations

from dataclasses import dataclass

from spacy.tokens import Span as SpacySpan
from spacy.tokens import Token

from proto.ssg import ActionNode
from services.nlp import lexicon
from services.nlp.builder import GraphBuilder
from services.nlp.commands import NUMBER_WORDS, UNIT_SECONDS
from services.nlp.lemmatizer import rule_lemma
from services.nlp.mentions import CharacterMention, character_mention, is_unknown_object_word, object_mention
from services.nlp.scene import SUBJECT_DEPS, _mention

CLAUSE_DEPS = frozenset({"ROOT", "conj", "advcl", "xcomp", "ccomp", "parataxis"})
TIME_UNITS = frozenset(UNIT_SECONDS)
LINKING_VERBS = frozenset(
    {"look", "feel", "seem", "become", "get", "appear", "grow", "turn", "remain", "stay"}
)


@dataclass
class _Argument:
    tok: Token
    prep: str
    object_id: str = ""
    character: str = ""
    word: str = ""


def _subject_tokens(verb: Token) -> list[Token]:
    glued = _glued_subject(verb)
    if glued is not None:
        return [glued]
    v = verb
    climbed_from_conj = False
    for _ in range(6):
        subj = [c for c in v.children if c.dep_ in SUBJECT_DEPS and (not climbed_from_conj or c.i < verb.i)]
        if subj and (v.pos_ in ("VERB", "AUX") or v is verb or any(c.dep_ == "cop" for c in v.children)):
            out: list[Token] = []
            for s in subj:  # "Peter and Kate walk": the parser may mark both as subjects
                out += [t for t in _with_conj_people(s) if t not in out]
            return out
        if v.dep_ in ("conj", "xcomp", "advcl") and v.head.i != v.i:
            climbed_from_conj = True
            v = v.head
            continue
        if climbed_from_conj and v.dep_ in ("obj", "obl", "nmod") and v.head.i != v.i:
            v = v.head  # "opens the door and leaves": "leaves" hangs under "door"
            continue
        break
    return []


def verb_lemma(tok: Token) -> str:
    """Lemma of a verb; for a word the tagger took for a noun or adverb, its verb reading."""
    if tok.pos_ in ("VERB", "AUX"):
        return tok.lemma_.lower()
    return rule_lemma(tok.text, "VERB").lower()


def _with_conj_people(tok: Token) -> list[Token]:
    out = [tok]
    for c in tok.children:
        if c.dep_ == "conj":
            out += _with_conj_people(c)
    return out


def _duration(tok: Token) -> float | None:
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


def _manner_and_direction(verb: Token) -> tuple[str, str]:
    manner, direction = "", ""
    for c in verb.children:
        lower = c.lower_
        if (
            c.dep_ in ("advmod", "compound:prt", "obl:unmarked", "obl", "xcomp", "obj")
            and lower in lexicon.DIRECTION_ADVERBS
        ):
            if not any(g.dep_ == "case" for g in c.children) or lower in ("left", "right"):
                direction = direction or lexicon.DIRECTION_ADVERBS[lower]
            continue
        if (
            c.dep_ in ("advmod", "obl", "obl:unmarked", "xcomp", "obj")
            and lower not in lexicon.MANNER_STOP
            and not any(g.dep_ == "case" for g in c.children)
        ):
            if (lower.endswith("ly") and len(lower) > 4 and lower not in ("only", "family", "early")) or (
                c.pos_ in ("ADV", "ADJ") and lower in ("fast", "hard", "slow", "quick", "loud", "well")
            ):
                manner = manner or lower
    return manner, direction


def _clause_verbs(sent: SpacySpan) -> list[Token]:
    verbs: list[Token] = []
    for tok in sent:
        if tok.dep_ not in CLAUSE_DEPS:
            continue
        if tok.pos_ != "VERB" and not _verb_by_position(tok):
            continue
        if tok.dep_ == "xcomp" and tok.head.lemma_.lower() not in lexicon.ASPECT_VERBS:
            continue
        if tok.lemma_.lower() in lexicon.ASPECT_VERBS and any(
            c.dep_ == "xcomp" and c.pos_ == "VERB" for c in tok.children
        ):
            continue  # "starts to dance": the action is "dance"
        if tok.lemma_.lower() in LINKING_VERBS and any(
            c.dep_ == "xcomp" and c.pos_ == "ADJ" for c in tok.children
        ):
            continue  # "looks angry": an emotion, handled by _social
        verbs.append(tok)
    return verbs


def _glued_subject(tok: Token) -> Token | None:
    """ "Emma texts/NOUN on her phone": a name the parser made a compound of a verb it read as a noun."""
    if tok.pos_ not in ("NOUN", "PROPN") or not tok.lower_.endswith("s") or tok.dep_ != "ROOT":
        return None
    names = [c for c in tok.children if c.dep_ == "compound" and c.i < tok.i and c.pos_ == "PROPN"]
    return names[0] if names and character_mention(names[0]) is not None else None


def _verb_by_position(tok: Token) -> bool:
    """A root (or its conjunct) the tagger did not call a verb but that has a subject and no copula, and
    whose verb reading is an action: "Eve claps/ADV", "Peter and Lucy dance/NOUN"."""
    if tok.pos_ in ("VERB", "AUX", "PRON", "DET", "PUNCT", "ADP", "CCONJ", "NUM"):
        return False
    if any(c.dep_ in ("cop", "det", "case", "amod") for c in tok.children):
        return False
    if any(c.dep_ in SUBJECT_DEPS for c in tok.children):
        return True  # in UD a noun with a subject but no copula is a verb the tagger misread
    if _glued_subject(tok) is not None:
        return True
    return tok.dep_ == "conj" and tok.head.pos_ == "VERB" and lexicon.is_known_verb(verb_lemma(tok))


def _character_of(tok: Token, builder: GraphBuilder) -> CharacterMention | None:
    cm = character_mention(tok)
    if cm is None and tok.pos_ == "PROPN" and object_mention(tok) is None:
        cm = CharacterMention(head=tok, name=tok.text, mention=tok.text)
    return cm


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


def _argument(tok: Token, prep: str, builder: GraphBuilder, report_unknown: bool) -> _Argument:
    arg = _Argument(tok=tok, prep=prep)
    cm = _character_of(tok, builder)
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
            "W101", f"'{tok.text}' is not in the object catalog", tok.idx, tok.idx + len(tok.text)
        )
    return arg


def _object_words(arg: _Argument, builder: GraphBuilder) -> tuple[str, ...]:
    if arg.object_id:
        category = next(o.category for o in builder.objects if o.id == arg.object_id)
        return (category, *lexicon.hypernyms(category), arg.tok.lemma_.lower(), arg.tok.lower_)
    if arg.word:
        return (arg.word, arg.tok.lower_)
    return ()


def _action(verb: Token, builder: GraphBuilder) -> ActionNode:
    lemma = verb_lemma(verb)
    particle = next((c.lower_ for c in verb.children if c.dep_ == "compound:prt"), "")
    manner, direction = _manner_and_direction(verb)
    if particle in lexicon.DIRECTION_ADVERBS and particle in ("left", "right", "around", "back"):
        direction = direction or lexicon.DIRECTION_ADVERBS[particle]
    duration = 0.0
    objects: list[_Argument] = []
    obliques: list[_Argument] = []
    for c in verb.children:
        if c.pos_ == "ADV" and c.lower_.endswith("ly"):
            continue  # a manner the parser attached as an argument
        if c.lower_ in lexicon.DIRECTION_ADVERBS and not any(g.dep_ in ("det", "case") for g in c.children):
            continue  # "turns right": a direction, read by _manner_and_direction
        if c.dep_ in ("obj", "iobj", "dobj") or (c.dep_ == "advmod" and c.pos_ in ("NOUN", "PROPN")):
            objects.append(_argument(c, "", builder, report_unknown=True))
        elif c.dep_ in ("obl", "obl:unmarked", "obl:tmod", "obl:npmod", "nmod:tmod", "nmod"):
            seconds = _duration(c)
            if seconds is not None:
                duration = seconds
                continue
            if (
                c.lower_ in lexicon.DIRECTION_ADVERBS
                or c.pos_ in ("ADV", "ADP", "PART", "SCONJ", "ADJ")
                or (c.lower_.endswith("ly") and not any(g.dep_ == "case" for g in c.children))
            ):
                continue  # "walks in", "looks outside", "dances happily": no object
            cases = [g for g in c.children if g.dep_ == "case"]
            prep = " ".join(g.lower_ for g in cases)
            obliques.append(_argument(c, prep, builder, report_unknown=True))
            for conj in c.children:
                if conj.dep_ == "conj" and conj.pos_ in ("NOUN", "PROPN"):
                    obliques.append(_argument(conj, prep, builder, report_unknown=True))
    target = instrument = destination = ""
    is_motion = lexicon.action_for(lemma, particle) in lexicon.LOCOMOTION_ACTIONS
    primary: _Argument | None = None
    for arg in objects:
        value = arg.object_id or arg.character or arg.word
        if is_motion and not arg.character and arg.object_id:
            destination = destination or value
        elif is_motion and arg.character:
            destination = destination or value
        else:
            target = target or value
        primary = primary or arg
    for arg in obliques:
        value = arg.object_id or arg.character or arg.word
        last = arg.prep.split()[-1] if arg.prep else ""
        if last in lexicon.INSTRUMENT_PREPS and arg.object_id:
            instrument = instrument or value
            if primary is None or primary.prep in ("",) and not primary.object_id:
                primary = primary or arg
        elif is_motion and (last in lexicon.DESTINATION_PREPS or last in lexicon.RELATION_PREPS or not last):
            destination = destination or value
        elif not target:
            target = value
            primary = primary or arg
        elif not destination and last in lexicon.DESTINATION_PREPS:
            destination = value
    if primary is None and instrument:
        primary = next(a for a in obliques if (a.object_id or a.word) == instrument)
    obj_words: tuple[str, ...] = ()
    prep = ""
    person = False
    if primary is not None:
        obj_words = _object_words(primary, builder)
        prep = primary.prep.split()[-1] if primary.prep else ""
        person = bool(primary.character)
    if instrument and primary is not None and (primary.object_id or primary.word) != instrument:
        inst_arg = next(a for a in obliques if (a.object_id or a.word) == instrument)
        action = lexicon.action_for(
            lemma, particle, obj_words, prep, direction, person
        ) or lexicon.action_for(
            lemma, particle, _object_words(inst_arg, builder), inst_arg.prep.split()[-1], direction, False
        )
    else:
        action = lexicon.action_for(lemma, particle, obj_words, prep, direction, person)
    first = verb.i
    last_tok = max([verb.i] + [a.tok.i for a in objects + obliques])
    doc = verb.doc
    end_tok = doc[last_tok]
    span_end = end_tok.idx + len(end_tok.text)
    if not action:
        shown = verb.text + (f" {particle}" if particle else "")
        builder.diagnose(
            "W102", f"'{shown}' is not an action in the motion library", verb.idx, verb.idx + len(verb.text)
        )
    return ActionNode(
        verb=lemma + (f" {particle}" if particle else ""),
        action=action,
        manner=manner,
        target=target,
        instrument=instrument,
        destination=destination,
        duration_s=duration,
        span=builder.span(doc[first].idx, span_end),
    )


def _social(sent: SpacySpan, builder: GraphBuilder) -> bool:
    """Copular social sentences. Returns True when the sentence was one."""
    found = False
    for tok in sent:
        is_pred = any(c.dep_ == "cop" for c in tok.children) or (
            tok.dep_ == "xcomp" and tok.head.lemma_.lower() in LINKING_VERBS and tok.pos_ == "ADJ"
        )
        if not is_pred:
            continue
        subj_holder = tok if any(c.dep_ in SUBJECT_DEPS for c in tok.children) else tok.head
        subjects = _subject_tokens(subj_holder)
        chars = [c for c in (_character_of(s, builder) for s in subjects) if c is not None]
        if not chars:
            continue
        names = [c.name or c.mention.lower() for c in chars]
        for c in chars:
            builder.character(c.name, c.mention, c.pronoun)
        lower = tok.lower_
        start = min(s.idx for s in subjects)
        end = tok.idx + len(tok.text)
        if tok.pos_ == "ADJ" or lower in lexicon.EMOTION_WORDS:
            builder.add_social("emotion", names, lower, start, end)
            found = True
        elif tok.lemma_.lower() in lexicon.SOCIAL_RELATION_WORDS or lower in lexicon.SOCIAL_RELATION_WORDS:
            poss = [c for c in tok.children if c.dep_ == "nmod:poss"]
            others = [_character_of(p, builder) for p in poss]
            extra = [o.name or o.mention.lower() for o in others if o is not None]
            for o in others:
                if o is not None:
                    builder.character(o.name, o.mention, o.pronoun)
            builder.add_social("relation", names + extra, lower, start, end)
            found = True
    return found


def extract_actions(sent: SpacySpan, builder: GraphBuilder) -> int:
    """Add the characters, actions and social nodes of a character sentence; returns the action count."""
    social = _social(sent, builder)
    count = 0
    for verb in _clause_verbs(sent):
        subjects = _subject_tokens(verb)
        chars = [c for c in (_character_of(s, builder) for s in subjects) if c is not None]
        if subjects and not chars:
            continue  # an object does something ("the lamp hangs"): not a character action
        action = _action(verb, builder)
        if not chars:
            chars = [CharacterMention(head=verb, name="", mention="")]  # imperative: the current character
        for cm in chars:
            node = builder.character(cm.name, cm.mention, cm.pronoun)
            node.actions.append(action)
            target = action.target
            target_is_person = bool(target) and (target[0].isupper() or target.lower() in lexicon.PRONOUNS)
            if verb_lemma(verb) in lexicon.SOCIAL_VERBS and target_is_person:
                builder.add_social(
                    "emotion",
                    [cm.name or cm.mention.lower(), target],
                    verb_lemma(verb),
                    action.span.start - builder.offset,
                    action.span.end - builder.offset,
                )
        count += 1
    if count == 0 and not social:
        verbless = not any(t.pos_ in ("VERB", "AUX") for t in sent)
        if verbless:
            builder.diagnose("W103", f"'{sent.text}'", sent.start_char, sent.end_char)
    return count
