"""Character sentences -> characters with ordered actions, and social relations/emotions.

Per verb clause (the root, its conjuncts, adverbial clauses; "starts to dance" reads as "dance"):
subject -> character; obj / obl -> target, destination or instrument by the verb's kind and the
preposition; advmod -> manner or direction; "for 5 seconds" -> duration. "They are friends",
"Mary is Tom's boss", "Tom is angry" and "They are married" -> social nodes; "Tom apologizes to
Mary" -> an action plus a social emotion node (lexicon.is_social); two subjects of a reciprocal act
with no target ("Tom and Mary hug", "They quarrel", "... at each other") target each other.
Reading the verb's arguments is services.nlp.arguments.
"""

from __future__ import annotations

import msgspec
from spacy.tokens import Span as SpacySpan
from spacy.tokens import Token

from proto.ssg import ActionNode
from services.nlp import lexicon, verbs
from services.nlp.arguments import (
    STATE_PARTICLES,
    Argument,
    argument,
    arguments,
    case_of,
    character_of,
    event_action,
    event_phrase,
    object_words,
    unknown_capitalised_subject,
    verb_lemma,
)
from services.nlp.builder import GraphBuilder
from services.nlp.mentions import CharacterMention, character_mention, is_title, object_mention
from services.nlp.scene import SUBJECT_DEPS, _mention
from services.nlp.suggest import did_you_mean

PHOTO_WORDS = frozenset({"photo", "picture", "pic", "snapshot", "selfie", "photograph", "shot"})
DEFINITE = frozenset({"the", "this", "that", "his", "her", "their", "its", "my", "our", "your"})
CLAUSE_DEPS = frozenset({"ROOT", "conj", "advcl", "xcomp", "ccomp", "parataxis"})
LINKING_VERBS = frozenset(
    {"look", "feel", "seem", "become", "get", "appear", "grow", "turn", "remain", "stay"}
)


def _subject_tokens(verb: Token) -> list[Token]:
    glued = _glued_subject(verb)
    if glued is not None:
        return [glued]
    if verb.pos_ == "VERB" and not any(c.dep_ in SUBJECT_DEPS for c in verb.children):
        # "Ada/compound crosses her arms", "The hero/compound nods": who acts, hung on the verb
        lead = [
            c
            for c in verb.children
            if c.dep_ in ("compound", "flat", "nmod:desc", "dep", "amod")
            and c.i < verb.i
            and c.pos_ in ("PROPN", "NOUN", "ADJ")
        ]
        # "One afternoon/compound Priya/compound skips": the time before the name is no one
        who = [c for c in lead if character_mention(c) is not None or unknown_capitalised_subject(c)]
        if who:
            return _with_conj_people(who[0])
    v = verb
    climbed_from_conj = False
    for _ in range(6):
        subj = [c for c in v.children if c.dep_ in SUBJECT_DEPS and (not climbed_from_conj or c.i < verb.i)]
        if subj and (v.pos_ in ("VERB", "AUX") or v is verb or any(c.dep_ == "cop" for c in v.children)):
            subj = [_member_of(s) for s in subj]
            out: list[Token] = []
            for s in subj:  # "Peter and Kate walk": the parser may mark both as subjects
                out += [t for t in _with_conj_people(s) if t not in out]
            return out
        if v.dep_ in ("conj", "xcomp", "advcl", "parataxis") and v.head.i != v.i:
            climbed_from_conj = True
            v = v.head
            continue
        if (
            climbed_from_conj
            and v.dep_ in ("obj", "obl", "nmod", "advmod", "compound:prt")
            and v.head.i != v.i
        ):
            # "opens the door and leaves": "leaves" hangs under "door"; "jump out and shout": under "out"
            v = v.head
            continue
        break
    if climbed_from_conj and v is not verb and v.pos_ == "VERB":
        # "Sofia/compound stuffs the clothes ... and slams the lid", "Mom/NOUN/compound hugs Lily and walks
        # out": the name hung on the first verb
        lead = [
            c
            for c in v.children
            if c.dep_ in ("compound", "flat") and c.i < v.i and c.pos_ in ("PROPN", "NOUN", "ADJ")
        ]
        who = [c for c in lead if character_mention(c) is not None or unknown_capitalised_subject(c)]
        if who:
            return _with_conj_people(who[0])
    return []


def _member_of(tok: Token) -> Token:
    """ "One of her teammates sits down": the teammate acts, not "one"."""
    if tok.lower_ not in ("one", "each", "either", "neither") or character_mention(tok) is not None:
        return tok
    for c in tok.children:
        if (
            c.dep_ == "nmod"
            and any(g.lower_ == "of" for g in c.children)
            and character_mention(c) is not None
        ):
            return c
    return tok


def _with_conj_people(tok: Token) -> list[Token]:
    out = [tok]
    for c in tok.children:
        if c.dep_ == "conj":
            out += _with_conj_people(c)
    return out


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
        if tok.dep_ not in CLAUSE_DEPS and not (tok.dep_ == "appos" and is_title(tok.head)):
            continue  # "Prof./ROOT Kim nods/appos": the verb the parser hung under a title
        if tok.pos_ != "VERB" and not _verb_by_position(tok):
            continue
        if tok.dep_ == "xcomp" and tok.head.lemma_.lower() not in lexicon.ASPECT_VERBS:
            continue
        if tok.dep_ == "ccomp" and _reports(tok.head):
            continue  # "announces that they qualified": what is said or thought, not done here
        if tok.tag_ == "VBN" and not lexicon.is_known_verb(verb_lemma(tok)):
            if not any(c.dep_ in ("aux", "aux:pass", *SUBJECT_DEPS) for c in tok.children):
                if tok.dep_ != "ROOT":
                    continue  # "exhausted but grinning": a state, not an action
            elif not any(c.dep_ in ("obj", "obl") for c in tok.children) and any(
                c.dep_ in ("aux", "aux:pass", "cop") and c.lemma_.lower() == "be" for c in tok.children
            ):
                continue  # "when he is done": a state
        if tok.lemma_.lower() in lexicon.ASPECT_VERBS and any(
            c.dep_ == "xcomp" and c.pos_ == "VERB" for c in tok.children
        ):
            continue  # "starts to dance": the action is "dance"
        if _relation_state(tok):
            continue  # "are married": a relation, handled by _social
        if tok.lemma_.lower() in LINKING_VERBS and any(
            c.dep_ == "xcomp" and c.pos_ == "ADJ" for c in tok.children
        ):
            continue  # "looks angry": an emotion, handled by _social
        verbs.append(tok)
    return verbs


def _reports(verb: Token) -> bool:
    """A verb of saying or thinking, whose clausal complement is content ("says that", "knows that")."""
    lemma = verb_lemma(verb)
    action = lexicon.action_for(lemma)
    return action in ("talk", "whisper", "shout", "think", "nod") or bool(verbs.not_animatable_reason(lemma))


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


# Clips that touch another person: a body part they name is that person's ("kisses her cheek").
PERSON_CONTACT = frozenset({"hold_hands", "shake_hands", "kiss_cheek", "comfort", "high_five"})


def _body_part_owner(args: list[Argument], builder: GraphBuilder) -> str:
    """The character whose body part an argument names ("his hand" -> him, "Mary's cheek" -> Mary), else ""."""
    for arg in args:
        if not arg.body_part:
            continue
        for c in arg.tok.children:
            if c.dep_ != "nmod:poss" and c.tag_ != "PRP$":
                continue
            if c.lower_ in ("his", "her", "their"):
                return {"his": "him", "her": "her", "their": "them"}[c.lower_]  # resolve() names them
            cm = character_of(c, builder)
            if cm is not None and cm.name:
                return cm.name
    return ""


# Verbs whose object is what gets made: the action happens at the instrument, not at the product.
MAKING_VERBS = frozenset({"make", "brew", "cook", "bake", "prepare", "fix"})
# Verbs whose object is a liquid poured into what the destination names ("pours tea into the mug").
POURING_VERBS = frozenset({"pour", "splash", "spill"})
BRINGING_VERBS = frozenset({"bring", "deliver"})  # "brings the cup to Sam": handed over on arrival
POURED_FROM = frozenset({"bottle", "kettle", "teapot", "jug", "pitcher"})  # vessels one pours out of
# Drinks the catalog reads as the vessel they come in ("drinks tea": a cup); poured, they are the liquid.
DRINK_WORDS = frozenset(
    {"tea", "coffee", "water", "juice", "milk", "wine", "beer", "espresso", "cocoa", "lemonade", "soda"}
)


# "gets out of bed", "climbs into the bathtub", "hops off the sofa": a verb of getting somewhere whose
# place is a bed, a tub or a seat says a change of posture, not a climb or a walk
POSTURE_MOVE_VERBS = frozenset(
    {"get", "climb", "clamber", "scramble", "roll", "crawl", "slide", "slip", "ease", "step"}
)
CLIMBING_VERBS = frozenset({"climb", "clamber", "scramble"})
OUT_OF_PREPS = frozenset({"out of", "off", "off of", "from", "out"})
INTO_PREPS = frozenset({"into", "in", "onto", "on", "on to", "in to"})
LYING_PLACES = frozenset({"bed", "bunk_bed", "bathtub", "hammock", "cot"})
SITTING_PLACES = frozenset({"seat", "chair", "sofa", "couch", "armchair", "bench", "stool", "office_chair"})


def _posture_move(lemma: str, primary: Argument | None, obj_words: tuple[str, ...]) -> str:
    """ "stand" for getting out of a bed, tub or seat; "lie_down" into a bed or tub; "sit" onto a seat;
    "" for anything else ("climbs onto the table" stays a climb)."""
    if lemma not in POSTURE_MOVE_VERBS or primary is None or not primary.object_id:
        return ""
    words = {w.lower().replace(" ", "_") for w in obj_words}
    if not words & (LYING_PLACES | SITTING_PLACES):
        return ""
    if primary.prep in OUT_OF_PREPS:
        return "stand"
    if primary.prep in INTO_PREPS and lemma not in CLIMBING_VERBS:  # "climbs into the bed" is shown climbing
        return "lie_down" if words & LYING_PLACES else "sit"
    return ""


def _action(verb: Token, builder: GraphBuilder) -> tuple[ActionNode, str]:
    """The ActionNode of a verb clause and the verb its social meaning is read from ("hug" of "gives
    Mary a hug"; the verb's lemma otherwise)."""
    lemma = verb_lemma(verb)
    particle = next(
        (c.lower_ for c in verb.children if c.dep_ == "compound:prt" or c.lower_ in STATE_PARTICLES), ""
    )
    manner, direction = _manner_and_direction(verb)
    if particle in lexicon.DIRECTION_ADVERBS and particle in ("left", "right", "around", "back"):
        direction = direction or lexicon.DIRECTION_ADVERBS[particle]
    objects, obliques, duration = arguments(verb, builder)
    target = instrument = destination = ""
    is_motion = lexicon.action_for(lemma, particle) in lexicon.LOCOMOTION_ACTIONS
    primary: Argument | None = None
    # A character is the target before a thing ("gives Mary a hug"); a thing or body part names the
    # action before a character ("shakes hands with Mary", "gives Mary a high five").
    for arg in sorted(objects, key=lambda a: not a.character):
        value = arg.object_id or arg.character or arg.word
        if is_motion and not arg.character and arg.object_id:
            destination = destination or value
        elif is_motion and arg.character:
            destination = destination or value
        elif not arg.body_part:
            target = target or value
    things = [a for a in objects if not a.character]
    primary = things[0] if things and len(things) < len(objects) else (objects[0] if objects else None)
    # "casts a spell at the troll": an act that is no thing in hand is aimed at who comes after "at"
    plain_target = any(
        a.word == target and a.word in lexicon.AIMED_ACTS and not (a.object_id or a.character)
        for a in objects
        if target
    )
    for arg in obliques:
        value = arg.object_id or arg.character or arg.word
        last = arg.prep.split()[-1] if arg.prep else ""
        if arg.body_part and any(a.body_part for a in objects):
            continue  # "buries his face in his hands": the face is what the act is about
        if last == "at" and plain_target and (arg.character or arg.object_id):
            target, plain_target = value, False
            continue
        if last in lexicon.INSTRUMENT_PREPS and arg.object_id:
            instrument = instrument or value
            if primary is None or primary.prep in ("",) and not primary.object_id and not primary.body_part:
                primary = primary or arg
        elif is_motion and (last in lexicon.DESTINATION_PREPS or last in lexicon.RELATION_PREPS or not last):
            destination = destination or value
        elif not target:
            target = value
            primary = primary or arg
        elif not destination and last in lexicon.DESTINATION_PREPS:
            destination = value
    if not target and not destination:
        target = next((a.word for a in objects if a.body_part), "")  # "washes his hands": as written
    if primary is None and instrument:
        primary = next(a for a in obliques if (a.object_id or a.word) == instrument)
    obj_words: tuple[str, ...] = ()
    prep = ""
    person = False
    if primary is not None:
        obj_words = object_words(primary, builder)
        if primary.word and not primary.object_id and not primary.body_part:
            obj_words = (event_phrase(primary.tok), *obj_words)
        prep = primary.prep.split()[-1] if primary.prep else ""
        person = bool(primary.character)
        if primary.body_part and any(c.lower_ == "their" for c in primary.tok.children):
            # "The students raise their hands": each raises one
            obj_words = tuple(w for w in obj_words if w == primary.tok.lemma_.lower()) or obj_words
    if instrument and primary is not None and (primary.object_id or primary.word) != instrument:
        inst_arg = next(a for a in obliques if (a.object_id or a.word) == instrument)
        action = lexicon.action_for(
            lemma, particle, obj_words, prep, direction, person
        ) or lexicon.action_for(
            lemma, particle, object_words(inst_arg, builder), inst_arg.prep.split()[-1], direction, False
        )
    else:
        action = lexicon.action_for(lemma, particle, obj_words, prep, direction, person)
    if action in PERSON_CONTACT and (not target or target in lexicon.BODY_PARTS):
        owner = _body_part_owner(objects + obliques, builder)
        target = owner or target  # "takes his hand": holding Marcus's hand, not a thing called hand
    if (
        primary is not None
        and target
        and target == primary.word
        and not (primary.object_id or primary.character or primary.body_part)
        and primary.word in lexicon.SAID_WORDS
    ):
        # "says goodbye (to Mia)": the word is the act's own, nothing it is aimed at
        target = next((a.character for a in obliques if a.character), "")
    if lemma in MAKING_VERBS and instrument:
        target = instrument  # "makes coffee with the coffee maker": the hands are at the machine
    if lemma in POURING_VERBS and destination and target:
        poured = next((a for a in objects if (a.object_id or a.word) == target), None)
        liquid = poured is not None and poured.tok.lemma_.lower() in DRINK_WORDS
        if liquid and target.split("#")[0] not in POURED_FROM:
            # "pours tea into the mug": the tea is no cup to fetch, the mug is what it pours into (as "pours
            # wine into the glasses" reads the wine as the glasses); a bottle or kettle named is poured from
            if destination.split("#")[0] == target.split("#")[0]:
                destination = target  # "pours tea into a cup": the tea took the id cup, the cup got cup#2
            target = destination
    if action == "take_photo" and primary is not None and primary.tok.lemma_.lower() in PHOTO_WORDS:
        of = next((g for g in primary.tok.children if g.dep_ == "nmod" and case_of(g) == "of"), None)
        definite = any(c.dep_ in ("det", "nmod:poss") and c.lower_ in DEFINITE for c in primary.tok.children)
        if of is None and definite and lemma == "take" and primary.object_id:
            action = "pick_up"  # "takes the photo from the table": that photo, into the hand
        else:
            # "takes a photo of the cake": the photo is the act (no photo frame to make); the cake its target
            if primary.object_id:
                builder.drop_object(primary.object_id)
            if of is not None and of.lower_ in lexicon.OBJECT_PRONOUNS:
                target = of.lower_  # "a picture of it": what "it" was before (resolve), not the picture
            else:
                pictured = argument(of, "of", builder, report_unknown=True) if of is not None else None
                target = (pictured.object_id or pictured.character or pictured.word) if pictured else ""
    if lemma in verbs.WITH_THING and primary is not None and primary.object_id and not person:
        action = verbs.WITH_THING[lemma]  # "balances three plates"
    if (
        action in ("lie_down", "sleep")
        and lemma in verbs.DOZE_VERBS
        and not destination
        and (not target or target in lexicon.BODY_PARTS)
    ):
        action = "look_down"  # "dozes off with his head against the window": asleep where he sits
    if any(c.lower_ in lexicon.REFLEXIVE_PRONOUNS and c.dep_ in ("obj", "iobj") for c in verb.children):
        action = verbs.VERB_ACTIONS.get(f"{lemma} oneself", action)  # "lowers himself into the chair"
    posture = _posture_move(lemma, primary, obj_words)
    if posture:
        action = posture  # "gets out of bed", "climbs into bed", "gets off the sofa"
        if posture == "stand":
            target = ""  # up from where one is: no walk to the bed first
    social_verb = lemma
    if (
        lemma in lexicon.LIGHT_VERBS
        and primary is not None
        and primary.word
        and not primary.body_part
        and primary.tok.lemma_.lower() not in lexicon.WORN_NOUNS  # "takes off his boot": no kick
    ):
        # "gives Mary a hug", "has a quarrel with Tom", "takes a bow": the event noun is the action,
        # the character (if any) its target
        from_event = event_action(primary.tok)
        if from_event:
            action = from_event
            social_verb = primary.word
            people = [a for a in objects + obliques if a.character]
            target = people[0].character if people else ""
    person_to = next((a.character for a in objects + obliques if a.character), "")
    # the thing: an object of the verb, or a bare noun the parser left as an oblique ("brings Sam a/obl cup")
    bare = [a for a in obliques if not a.prep]
    thing = next((a.object_id for a in objects + bare if a.object_id and not a.character), "")
    if lemma in BRINGING_VERBS and person_to and thing and person_to in (target, destination):
        # "brings the cup to Sam", "brings Sam a cup": the cup passes to Sam's hand, as "gives Sam the cup"
        # (the planner walks it there, services.motion.planning hand_over), not carried there and kept
        action, target, instrument, destination = "present", person_to, thing, ""
    if action == "present" and not instrument and any(a.character == target for a in objects if target):
        # "gives Tom a bowl": Tom is the target; the bowl is what changes hands (the planner takes it)
        instrument = thing
    first = verb.i
    last_tok = max([verb.i] + [a.tok.i for a in objects + obliques])
    doc = verb.doc
    end_tok = doc[last_tok]
    span_end = end_tok.idx + len(end_tok.text)
    if not action:
        shown = verb.text + (f" {particle}" if particle else "")
        reason = verbs.not_animatable_reason(f"{lemma} {particle}" if particle else lemma)
        reason = reason or verbs.not_animatable_reason(lemma)
        if not reason and any(a.tok.lower_ in lexicon.WORN_NOUNS for a in objects + obliques):
            reason = verbs.not_animatable_reason("put on")  # "puts on/ADP her coat"
        if reason:
            builder.diagnose(
                "W113", f"'{shown}' is {reason}, not a movement", verb.idx, verb.idx + len(verb.text)
            )
        else:
            builder.diagnose(
                "W102",
                f"'{shown}' is not an action in the motion library{did_you_mean(verb.text, 'action')}",
                verb.idx,
                verb.idx + len(verb.text),
            )
    node = ActionNode(
        verb=lemma + (f" {particle}" if particle else ""),
        action=action,
        manner=manner,
        target=target,
        instrument=instrument,
        destination=destination,
        duration_s=duration,
        span=builder.span(doc[first].idx, span_end),
    )
    return node, social_verb


def _relation_state(tok: Token) -> str:
    """Relation label of a participle that states a relation ("are married" -> "couple"), or ""."""
    label = lexicon.RELATION_STATES.get(tok.lower_, "")
    if label and any(c.dep_ in ("aux", "aux:pass", "cop") and c.lemma_.lower() == "be" for c in tok.children):
        return label
    return ""


def _social(sent: SpacySpan, builder: GraphBuilder) -> bool:
    """Copular social sentences. Returns True when the sentence was one."""
    found = False
    for tok in sent:
        is_pred = any(c.dep_ == "cop" for c in tok.children) or (
            tok.dep_ == "xcomp" and tok.head.lemma_.lower() in LINKING_VERBS and tok.pos_ == "ADJ"
        )
        state = _relation_state(tok)
        if not is_pred and not state:
            continue
        subj_holder = tok if any(c.dep_ in SUBJECT_DEPS for c in tok.children) else tok.head
        subjects = _subject_tokens(subj_holder)
        chars = [c for c in (character_of(s, builder) for s in subjects) if c is not None]
        if not chars:
            continue
        names = [c.name or c.mention.lower() for c in chars]
        for c in chars:
            builder.character(c.name, c.mention, c.pronoun)
        lower = tok.lower_
        start = min(s.idx for s in subjects)
        end = tok.idx + len(tok.text)
        if state:  # "Tom and Mary are married", "Tom is married to Mary"
            others = [character_of(c, builder) for c in tok.children if c.dep_ in ("obj", "obl", "nmod")]
            extra = [o.name or o.mention.lower() for o in others if o is not None]
            for o in others:
                if o is not None:
                    builder.character(o.name, o.mention, o.pronoun)
            builder.add_social("relation", names + [e for e in extra if e not in names], state, start, end)
            found = True
        elif tok.pos_ == "ADJ" or lower in lexicon.EMOTION_WORDS:
            builder.add_social("emotion", names, lower, start, end)
            found = True
        elif tok.lemma_.lower() in lexicon.SOCIAL_RELATION_WORDS or lower in lexicon.SOCIAL_RELATION_WORDS:
            # "Mary is Tom's boss", "Mary is the boss of Tom": Tom is the second subject
            poss = [c for c in tok.children if c.dep_ == "nmod:poss"] + [
                c for c in tok.children if c.dep_ == "nmod" and case_of(c) == "of"
            ]
            others = [character_of(p, builder) for p in poss]
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
        chars = [c for c in (character_of(s, builder) for s in subjects) if c is not None]
        chars = _distinct_names(chars)  # "Mr" and "Smith" both read as the subject "Mr Smith"
        if subjects and not chars:
            if not _animal_it(subjects, verb):
                arguments(verb, builder)  # "It rolls under the sofa": no action, but the sofa is in the story
                continue  # an object does something ("the lamp hangs"): not a character action
            # "The bunny hops. It picks up a carrot": resolve() names the animal, or drops the action
            chars = [CharacterMention(head=subjects[0], name="", mention=subjects[0].text, pronoun="it")]
        action, social_verb = _action(verb, builder)
        if not action.action and verbs.not_animatable_reason(verb_lemma(verb)):
            for cm in chars:  # "she hums", "he remembers": W113 says why; who it is still counts
                builder.character(cm.name, cm.mention, cm.pronoun)
            continue
        if not chars:
            chars = [CharacterMention(head=verb, name="", mention="")]  # imperative: the current character
        _add_action(chars, action, social_verb, builder)
        count += 1
    for tok in sent:
        if tok.dep_ == "acl:relcl" and tok.pos_ == "VERB":
            # "The girl who sits near the window", "the book that lies on the desk": in the story
            arguments(tok, builder)
    if count == 0 and not social:
        verbless = not any(t.pos_ in ("VERB", "AUX") for t in sent)
        things = [t for t in sent if t.pos_ == "NOUN" and object_mention(t) is not None] if verbless else []
        for t in things:  # "the clock strikes/NOUN twelve": no character acts, the clock is still there
            _mention(t, builder, report_unknown=False)
        if verbless and not things:
            hint = did_you_mean(sent.text.strip(" .!?$"), "command")
            builder.diagnose("W103", f"'{sent.text}'{hint}", sent.start_char, sent.end_char)
    return count


def extract_relative_actions(sent: SpacySpan, builder: GraphBuilder) -> int:
    """The acts of characters a scene sentence names in a relative clause ("a table at which an old
    sailor sits", "a sofa on which Tom sleeps"); returns their count."""
    count = 0
    for verb in sent:
        if verb.dep_ != "acl:relcl" or verb.pos_ != "VERB":
            continue
        subjects = _subject_tokens(verb)
        chars = _distinct_names([c for c in (character_of(s, builder) for s in subjects) if c is not None])
        if not chars:
            continue  # "a bed under which a box lies": the scene reader's relation
        action, social_verb = _action(verb, builder)
        if action.action:
            _add_action(chars, action, social_verb, builder)
            count += 1
    return count


def _animal_it(subjects: list[Token], verb: Token) -> bool:
    """ "It" as the subject of a verb only an agent does ("picks up", "nibbles"): maybe an animal."""
    if len(subjects) != 1 or subjects[0].lower_ != "it" or subjects[0].pos_ != "PRON":
        return False
    lemma = verb_lemma(verb)
    if lemma in lexicon.SCENE_VERBS or lemma in lexicon.RELATION_VERBS or lemma in verbs.DOZE_VERBS:
        return False  # "It hangs on the wall", "it falls": things do that too
    particle = next((c.lower_ for c in verb.children if c.dep_ == "compound:prt"), "")
    return bool(lexicon.action_for(lemma, particle))


def _distinct_names(chars: list[CharacterMention]) -> list[CharacterMention]:
    out: list[CharacterMention] = []
    for c in chars:
        if not c.name or all(o.name != c.name for o in out):
            out.append(c)
    return out


def _is_plural(cm: CharacterMention) -> bool:
    if cm.pronoun == "they" or (not cm.name and cm.head.tag_ in ("NNS", "NNPS")):
        return True
    return cm.name in lexicon.PERSON_NOUNS and cm.head.lower_ != cm.name  # "the children" (name "child")


def _add_action(
    chars: list[CharacterMention], action: ActionNode, social_verb: str, builder: GraphBuilder
) -> None:
    """Give ``action`` to each subject; a social act aimed at a character also becomes a SocialNode.

    Two or more subjects of a reciprocal act with no target ("Tom and Mary hug", "They quarrel",
    "... wave at each other") act on each other: with two named subjects each one's target is the
    other; "They" keeps the target "each other" for resolve() to fill in.
    """
    names = [cm.name or cm.mention.lower() for cm in chars]
    start, end = action.span.start - builder.offset, action.span.end - builder.offset
    reciprocal = action.target in lexicon.RECIPROCAL_PHRASES or (
        (not action.target or action.target in lexicon.BODY_PARTS)  # "Tom and Mary shake hands"
        and bool(action.action)
        and (len(chars) >= 2 or any(_is_plural(c) for c in chars))
        and lexicon.is_reciprocal(social_verb, action.action)
    )
    social = lexicon.is_social(social_verb, action.action)
    label = lexicon.social_label(social_verb, action.action)
    for cm, name in zip(chars, names, strict=True):
        node = builder.character(cm.name, cm.mention, cm.pronoun)
        if reciprocal:
            others = [n for n in names if n != name]
            target = others[0] if len(others) == 1 and cm.name else ("each other" if _is_plural(cm) else "")
            node.actions.append(msgspec.structs.replace(action, target=target))
            continue
        node.actions.append(action)
        target = action.target
        target_is_person = bool(target) and (
            target[0].isupper() or target.lower() in lexicon.PRONOUNS or target in lexicon.PERSON_NOUNS
        )
        if social and target_is_person:
            builder.add_social("emotion", [name, target], label, start, end)
    if reciprocal and social:
        builder.add_social("emotion", names, label, start, end)
