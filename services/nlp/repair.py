"""Repairs of parser errors on character sentences, made on the parsed Doc before extraction.

The pipeline is trained mostly on web text, where verbs such as "quarrel", "high-five" or "shake
hands" after a coordinated subject are rare; it then reads the verb as a noun and hangs the whole
sentence under the first name ("Tom/ROOT and Mary quarrel/conj"). And a progressive of a rare verb
comes out as a copula with an adjective ("Tom is/cop comforting/ADJ Mary"). Both are repaired only
when the word's verb reading names an action of the motion library, so that real adjectives ("Tom
is charming") and real nouns stay as parsed.

    repair_character_sentence(sent) -> bool   True when the tree of ``sent`` was changed
"""

from __future__ import annotations

from spacy.tokens import Span as SpacySpan
from spacy.tokens import Token

from services.nlp import lexicon
from services.nlp.lemmatizer import verb_lemma_candidates
from services.nlp.mentions import exact_category, is_title

_NOT_VERBS = frozenset({"PUNCT", "CCONJ", "DET", "ADP", "PRON", "PART", "SCONJ", "AUX", "SYM"})


def action_reading(word: str) -> str:
    """The lemma of ``word`` read as a verb when that verb names an action ("quarrel", "shake"), else ""."""
    for lemma in verb_lemma_candidates(word):
        if lemma in lexicon.SOCIAL_VERBS or lemma in lexicon.RECIPROCAL_VERBS or lexicon.is_known_verb(lemma):
            return lemma
        if lemma in lexicon.verb_words() and lemma not in lexicon.VERB_OVERRIDES:
            return lemma  # "shake" of "shake hands": a verb the library knows with its object
    return ""


def _is_person(tok: Token) -> bool:
    lower = tok.lower_
    if lower in lexicon.PRONOUNS and tok.pos_ == "PRON":
        return True
    if tok.pos_ == "PROPN" and lower[:1].isalpha() and tok.text[:1].isupper():
        return not action_reading(lower)  # "High-five Mary": not a name
    if tok.text[:1].isupper() and (lower in lexicon.FEMALE_NAMES or lower in lexicon.MALE_NAMES):
        return True  # "Ada/NOUN thanks her"
    if (
        lower in lexicon.COLLECTIVE_NOUNS
        and tok.i > tok.sent.start
        and tok.doc[tok.i - 1].lower_ in ("the", "whole")
    ):
        return True  # "The whole team cheers/NOUN": the group on stage
    if lower in lexicon.THING_ANIMALS and tok.i + 1 < tok.sent.end:
        return bool(action_reading(tok.doc[tok.i + 1].lower_))  # "The mouse creeps/NOUN"
    return tok.lemma_.lower() in lexicon.PERSON_NOUNS or lower in lexicon.PERSON_NOUNS


def _unknown_name(tok: Token) -> bool:
    """A capitalised first word that names nothing the system knows, right before a word with a verb
    reading: a name the tagger never saw ("Puck/ADJ leaps", "Lear/NOUN stumbles"), also after a title
    ("Officer Diaz/ADJ knocks")."""
    titled = tok.i == tok.sent.start + 1 and tok.doc[tok.i - 1].lower_.rstrip(".") in lexicon.TITLES
    if (tok.i != tok.sent.start and not titled) or not tok.text[:1].isupper() or not tok.is_alpha:
        return False
    if tok.pos_ not in ("NOUN", "PROPN", "ADJ", "X") or tok.i + 1 >= tok.sent.end:
        return False
    lower = tok.lower_
    if exact_category([lower]) is not None or lexicon.room_of(lower) or action_reading(lower):
        return False
    nxt = tok.doc[tok.i + 1]
    return nxt.lower_.endswith("s") and bool(action_reading(nxt.lower_))


def _lead_in_end(sent: SpacySpan) -> int:
    """Index after a leading time or linking phrase and its comma ("In the evening, ", "Then, "), else
    the sentence start."""
    from services.nlp.timephrase import time_light

    for tok in sent[:7]:
        if tok.text == ",":
            lead = sent.doc[sent.start : tok.i]
            if lead and (
                any(time_light(t) is not None for t in lead) or all(t.pos_ in ("ADV", "SCONJ") for t in lead)
            ):
                return tok.i + 1
            break
    return _bare_time_end(sent)


def _bare_time_end(sent: SpacySpan) -> int:
    """Index after a leading time phrase with no comma ("One morning Rosa skips", "That night he
    sleeps"): a time word or two before a time noun, then a person; else the sentence start."""
    from services.nlp.timephrase import TIME_MODIFIERS, TIME_NOUNS

    words = sent[:4]
    if not words or words[0].lower_ not in TIME_MODIFIERS | {"the"}:
        return sent.start
    for tok in words[1:]:
        if tok.lower_ in TIME_NOUNS and tok.i + 1 < sent.end:
            nxt = sent.doc[tok.i + 1]
            return tok.i + 1 if nxt.text[:1].isupper() or nxt.lower_ in lexicon.PRONOUNS else sent.start
        if tok.lower_ not in TIME_MODIFIERS:
            break
    return sent.start


def _subject_group(sent: SpacySpan) -> list[Token]:
    """Leading tokens that name who acts: "Tom and Mary", "The man and the woman", "They"."""
    group: list[Token] = []
    for tok in sent.doc[_lead_in_end(sent) : sent.end]:
        if (
            _is_person(tok)
            or _unknown_name(tok)
            or (group and tok.pos_ in ("CCONJ", "PUNCT") and tok.text in ("and", ",", "&"))
        ):
            group.append(tok)
        elif tok.pos_ == "DET" and tok.lower_ in ("the", "a", "an", "both"):
            group.append(tok)
        elif group and tok.pos_ == "ADJ" and group[-1].pos_ in ("DET", "ADJ"):
            group.append(tok)  # "The old man hobbles/NOUN"
        else:
            break
    while group and not (_is_person(group[-1]) or _unknown_name(group[-1])):
        group.pop()
    return group


def _repair_verbless(sent: SpacySpan) -> bool:
    """ "Tom and Mary quarrel/NOUN." -> quarrel/VERB the root with Tom as subject and what follows as
    its arguments; only when the sentence has no verb and the word after the subject names an action."""
    group = _subject_group(sent)
    if not group or group[-1].i + 1 >= sent.end:
        return False
    verb = sent.doc[group[-1].i + 1]
    appositive: list[Token] = []
    for k, tok in enumerate(group[:-1]):  # "Vincent, the barber, sweeps/NOUN": "the barber" is Vincent
        if tok.text == "," and group[k + 1].pos_ == "DET":
            appositive = group[k:]
            group = group[:k]
            break
    if appositive and verb.text == ",":
        appositive.append(verb)
        verb = sent.doc[verb.i + 1]
    elif verb.text == ",":  # "Her apprentice, a lanky teenager named Hugo, stumbles/NOUN in"
        close = next((t for t in sent.doc[verb.i + 1 : min(sent.end, verb.i + 10)] if t.text == ","), None)
        if close is not None and close.i + 1 < sent.end:
            appositive = list(sent.doc[verb.i : close.i + 1])
            verb = sent.doc[close.i + 1]
    root_is_noun = sent.root.pos_ in ("NOUN", "PROPN", "ADJ")
    misread = verb.pos_ == "NOUN" and verb.tag_ == "NNS" and root_is_noun  # "Ada kneads/NNS dough/ROOT"
    # "Max high-fives/VERB/flat Tom/list": a verb the parser hung under the name as part of it
    loose = (
        verb.pos_ == "VERB"
        and verb.dep_ in ("flat", "list", "compound", "dep")
        and verb.head.i in {t.i for t in group}
    )
    if (
        any(t.pos_ in ("VERB", "AUX") for t in sent)
        and not (verb.i == sent.root.i and verb.pos_ == "NOUN")
        and not misread
        and not loose
    ):
        return False  # a verb elsewhere is the root; but "The hero sprints/NOUN/ROOT ... and kicks" is not
    if verb.pos_ in _NOT_VERBS or verb.is_punct:
        return False
    lemma = action_reading(verb.lower_)
    if not lemma:
        return False
    old_root = sent.root
    people = [t for t in group if _is_person(t) or _unknown_name(t)]
    for t in people:
        if _unknown_name(t):
            t.pos_ = "PROPN"  # the name it is
    # "Her apprentice": the noun is who acts, the possessive hangs under it
    subject = next((t for t in people if t.tag_ != "PRP$" and t.dep_ != "nmod:poss"), people[0])
    in_group = {t.i for t in group}
    after = range(verb.i + 1, sent.end)
    verb.pos_ = "VERB"
    verb.lemma_ = lemma
    verb.head = verb
    verb.dep_ = "ROOT"
    subject.head = verb
    subject.dep_ = "nsubj"
    for tok in group:
        if tok is subject or tok.head.i in in_group:
            continue
        tok.head = subject
        tok.dep_ = "conj" if _is_person(tok) else ("cc" if tok.pos_ == "CCONJ" else tok.dep_)
    lead = range(sent.start, group[0].i)  # "In the evening ,": when, under the verb
    for i in lead:
        tok = sent.doc[i]
        if tok.head.i not in lead or tok.head.i == tok.i:
            tok.head = verb
            tok.dep_ = (
                "punct"
                if tok.is_punct
                else ("obl" if any(c.dep_ == "case" for c in tok.children) else "advmod")
            )
    for tok in appositive:
        if tok.head.i not in {t.i for t in appositive} or tok.head.i == tok.i:
            tok.head, tok.dep_ = subject, ("punct" if tok.is_punct else "appos")
    has_object = False
    first_object = verb
    for i in after:
        tok = sent.doc[i]
        if tok.head.i in after and tok.head.i != tok.i:
            continue  # inside an argument ("with" under "Mary"): keep
        tok.head = verb
        if tok.is_punct:
            tok.dep_ = "punct"
        elif any(c.dep_ == "case" for c in tok.children):
            tok.dep_ = "obl"
        elif tok.pos_ in ("NOUN", "PROPN", "PRON", "NUM") and not has_object:
            tok.dep_ = "obj"
            has_object = True
            first_object = tok
        elif tok.pos_ in ("NOUN", "PROPN") and tok.dep_ != "conj" and first_object.dep_ == "obj":
            first_object.dep_, tok.dep_ = "iobj", "obj"  # "hands the baby a bottle": to whom, then what
        elif tok.pos_ == "ADV":
            tok.dep_ = "advmod"
    _giving_order(sent, verb)
    if old_root.i != verb.i and old_root.i in after:  # what hung under the noun the parser made the root
        for tok in list(old_root.children):
            if tok.dep_ in ("advcl", "parataxis") or (tok.dep_ == "conj" and tok.pos_ == "VERB"):
                tok.head = verb
            elif tok.dep_ == "nmod" and any(c.dep_ == "case" for c in tok.children) and tok.i > old_root.i:
                tok.head, tok.dep_ = verb, "obl"
    return True


def _giving_order(sent: SpacySpan, verb: Token) -> None:
    """ "hands Omar the cup", "hands Ada/VERB the menu": a person right after the repaired verb and then
    a noun phrase are to whom (iobj) and what (obj), whatever the parser hung under what."""
    doc = sent.doc
    if verb.i + 2 >= sent.end:
        return
    person, det = doc[verb.i + 1], doc[verb.i + 2]
    if not _is_person(person) or person.lower_ in (
        "you",
        "me",
        "us",
        "i",
    ):  # "hands you a hammer": no character
        return
    if det.pos_ != "DET" or det.lower_ not in ("the", "a", "an", "his", "her", "their", "some"):
        return
    noun = next((t for t in doc[det.i + 1 : sent.end] if t.pos_ in ("NOUN", "PROPN")), None)
    if noun is None or any(t.is_punct for t in doc[det.i : noun.i]):
        return
    if person.pos_ not in ("PROPN", "NOUN", "PRON"):
        person.pos_ = "PROPN"  # "Ada/VERB": the name it is
    person.head, person.dep_ = verb, "iobj"
    noun.head, noun.dep_ = verb, "obj"
    det.head, det.dep_ = noun, "det"
    for t in doc[det.i + 1 : noun.i]:
        t.head, t.dep_ = noun, ("amod" if t.pos_ == "ADJ" else "compound")


def _repair_progressive(sent: SpacySpan) -> bool:
    """ "Tom is comforting/ADJ Mary" -> comforting/VERB with "is" as its auxiliary."""
    changed = False
    for tok in sent:
        if tok.pos_ != "ADJ" or not tok.lower_.endswith("ing") or tok.lower_ in lexicon.EMOTION_WORDS:
            continue
        cops = [c for c in tok.children if c.dep_ == "cop" and c.lemma_.lower() == "be"]
        if not cops:
            continue
        lemma = action_reading(tok.lower_)
        if not lemma:
            continue
        tok.pos_ = "VERB"
        tok.lemma_ = lemma
        for c in cops:
            c.dep_ = "aux"
        changed = True
    return changed


_STATE_ACTIONS = {"asleep": "sleep", "seated": "sit"}  # a state said with "is" that is an action's pose


def _repair_state(sent: SpacySpan) -> bool:
    """ "Nina is asleep/ADJ in the bed", "Tom is seated/ADJ at the desk" -> sleep/VERB, sit/VERB with "is"
    as its auxiliary: the character is shown in that pose (where it is, from the obliques)."""
    changed = False
    for tok in sent:
        lemma = _STATE_ACTIONS.get(tok.lower_)
        cops = [c for c in tok.children if c.dep_ in ("cop", "aux:pass") and c.lemma_.lower() == "be"]
        if lemma is None or not cops or not any(c.dep_ in ("nsubj", "nsubj:pass") for c in tok.children):
            continue
        tok.pos_, tok.tag_, tok.lemma_ = "VERB", "VBG", lemma
        for c in cops:
            c.dep_ = "aux"
        for c in tok.children:
            if c.dep_ == "nsubj:pass":
                c.dep_ = "nsubj"
        changed = True
    return changed


def _repair_participle_argument(sent: SpacySpan) -> bool:
    """ "Luis came in, yawning/VERB/obl": a verb's -ing form after a comma hung as its argument -> a clause of
    its own (advcl, as "walks in, smiling" is parsed), so it is a second action, never the walk's target."""
    changed = False
    for tok in sent:
        if (
            tok.pos_ == "VERB"
            and tok.lower_.endswith("ing")
            and tok.dep_ in ("obl", "obj", "nmod")
            and tok.i > sent.start
            and sent.doc[tok.i - 1].text == ","
            and not any(c.dep_ == "case" for c in tok.children)
        ):
            tok.dep_ = "advcl"
            changed = True
    return changed


def _prepositions_as_obliques(verb: Token) -> None:
    """A noun read as a verb kept its prepositional phrases as noun modifiers ("to the door"/nmod): under a
    verb they are obliques (obl), where the argument reader looks for destinations and targets."""
    for c in verb.children:
        if c.dep_ == "nmod" and any(g.dep_ == "case" for g in c.children):
            c.dep_ = "obl"


def _repair_conjoined_verb(sent: SpacySpan) -> bool:
    """ "He stops and stares/NOUN/obj at his hands" -> stares/VERB a conjunct of "stops"."""
    changed = False
    for tok in sent:
        if tok.dep_ != "obj" or tok.pos_ != "NOUN" or tok.head.pos_ != "VERB" or not tok.lower_.endswith("s"):
            continue
        if not any(c.dep_ == "cc" and c.i < tok.i for c in tok.children):
            continue
        if any(c.dep_ == "det" for c in tok.children):
            continue  # "and the cups": a noun
        lemma = action_reading(tok.lower_)
        if not lemma:
            continue
        tok.pos_ = "VERB"
        tok.lemma_ = lemma
        tok.dep_ = "conj"
        _prepositions_as_obliques(tok)
        changed = True
    return changed


def _repair_verb_as_subject(sent: SpacySpan) -> bool:
    """ "The teacher/compound sighs/NOUN/nsubj and shakes/ROOT her head" -> sighs/VERB the root with
    the teacher as subject and "shakes" its conjunct."""
    for tok in sent:
        head = tok.head
        if tok.dep_ != "nsubj" or tok.pos_ != "NOUN" or head.pos_ != "VERB" or not tok.lower_.endswith("s"):
            continue
        people = [c for c in tok.children if c.dep_ == "compound" and c.i < tok.i and _is_person(c)]
        if not people or not any(c.dep_ == "cc" and tok.i < c.i < head.i for c in head.children):
            continue
        lemma = action_reading(tok.lower_)
        if not lemma:
            continue
        tok.pos_, tok.lemma_ = "VERB", lemma
        tok.dep_, tok.head = head.dep_, (tok if head.dep_ == "ROOT" else head.head)
        head.dep_, head.head = "conj", tok
        people[0].dep_, people[0].head = "nsubj", tok
        return True
    return False


def _repair_clause_as_subject(sent: SpacySpan) -> bool:
    """ "Nurse Adaeze strides/nsubj in briskly, checks/ROOT the chart": a verb with a person as its own
    subject that the parser made the subject of the next verb -> the first clause, the next its conjunct."""
    for tok in sent:
        head = tok.head
        if tok.dep_ != "nsubj" or tok.pos_ != "VERB" or head.pos_ != "VERB" or head.i <= tok.i:
            continue
        people = [c for c in tok.children if c.dep_ in ("nsubj", "nsubj:pass") and c.i < tok.i]
        if not people or not (_is_person(people[0]) or people[0].lower_ in lexicon.PERSON_NOUNS):
            continue
        tok.dep_, tok.head = head.dep_, (tok if head.dep_ == "ROOT" else head.head)
        head.dep_, head.head = "conj", tok
        return True
    return False


def _repair_pronoun_relative_clause(sent: SpacySpan) -> bool:
    """ "Jamal's string snaps/NOUN, he swears/acl:relcl, and everybody bursts out laughing": a clause
    with a personal pronoun for subject is no relative clause -> a clause of its own (parataxis)."""
    changed = False
    for tok in sent:
        if tok.dep_ != "acl:relcl" or tok.pos_ != "VERB":
            continue
        subj = [c for c in tok.children if c.dep_ in ("nsubj", "nsubj:pass")]
        if not subj or subj[0].lower_ not in ("he", "she", "they", "i", "we", "you"):
            continue
        if not any(t.lower_ == "," for t in sent.doc[tok.head.i : subj[0].i]):
            continue  # "the man he saw": a relative clause without "that"
        tok.dep_ = "parataxis"
        changed = True
    return changed


def _clause_verb(tok: Token) -> Token | None:
    """The verb a noun hangs under, through objects, obliques and compounds ("bench" of "sits on a bench")."""
    for _ in range(4):
        if tok.pos_ == "VERB":
            return tok
        if (
            tok.dep_ not in ("obj", "obl", "nmod", "compound", "conj", "nmod:unmarked", "amod")
            or tok.head.i == tok.i
        ):
            return None
        tok = tok.head
    return None


def _repair_noun_conjunct_verb(sent: SpacySpan) -> bool:
    """ "sits on a bench and drinks/NNS water", "draws his sword and charges/NNS": a verb the parser
    coordinated with the noun before it -> a conjunct of the clause's verb, taking what follows as its
    arguments. Only for a bare plural-looking word right after "and" whose verb reading is an action."""
    changed = False
    for tok in sent:
        if (
            tok.dep_ != "conj"
            or tok.pos_ not in ("NOUN", "VERB")
            or tok.head.pos_ not in ("NOUN", "PROPN", "ADJ")
        ):
            continue
        before = tok.doc[tok.i - 1].lower_ if tok.i > 0 else ""
        if before in ("and", "then"):
            if not tok.lower_.endswith("s"):
                continue
        elif before == ",":  # "a backpack, hesitates, then", "the door, beaming,": never a catalog noun
            if (
                not (tok.lower_.endswith("s") or tok.tag_ == "VBG")
                or exact_category([tok.lower_]) is not None
            ):
                continue
        else:
            continue
        if any(c.dep_ in ("det", "nmod:poss", "amod", "nummod") for c in tok.children):
            continue  # "and the cups", "and two drinks": a noun
        noun = tok.head
        verb = _clause_verb(noun)
        lemma = action_reading(tok.lower_)
        if verb is None or not lemma:
            continue
        participle = tok.tag_ == "VBG"
        tok.pos_, tok.tag_, tok.lemma_ = "VERB", ("VBG" if participle else "VBZ"), lemma
        tok.head, tok.dep_ = verb, ("advcl" if participle else "conj")
        if noun.dep_ == "compound" and noun.head.i > tok.i:  # "bench/compound and drinks water"
            after = noun.head
            noun.head = verb
            noun.dep_ = "obl" if any(c.dep_ == "case" for c in noun.children) else "obj"
            after.head, after.dep_ = tok, "obj"
        for t in sent.doc[tok.i + 1 : sent.end]:
            if t.head.i < tok.i and not t.is_punct and t.dep_ in ("obj", "obl", "nmod", "advmod", "compound"):
                t.head = tok
                if t.dep_ == "compound":
                    t.dep_ = "obj"
                elif t.dep_ == "nmod":
                    t.dep_ = "obl"
        _prepositions_as_obliques(tok)
        changed = True
    return changed


def _repair_verb_conjunct_noun(sent: SpacySpan) -> bool:
    """ "Dad comes in and lights/NOUN/conj the candles/obj": a verb the parser read as a noun coordinated
    with the verb before it, its object hung under that verb -> a verb, the object after it its own.
    Only for a bare plural-looking word right after "and"/"then" whose verb reading is an action."""
    changed = False
    for tok in sent:
        verb = tok.head
        if tok.dep_ != "conj" or tok.pos_ != "NOUN" or verb.pos_ != "VERB" or not tok.lower_.endswith("s"):
            continue
        if tok.i == 0 or tok.doc[tok.i - 1].lower_ not in ("and", "then"):
            continue
        if any(c.dep_ in ("det", "nmod:poss", "amod", "nummod", "compound") for c in tok.children):
            continue  # "and the lights", "and two drinks": a noun
        moved = [t for t in verb.children if t.i > tok.i and t.dep_ in ("obj", "obl", "iobj")]
        lemma = action_reading(tok.lower_)
        if not moved or not lemma:
            continue  # "takes a cup and saucers": nothing after it to be a verb's argument
        tok.pos_, tok.tag_, tok.lemma_ = "VERB", "VBZ", lemma
        for t in moved:
            t.head = tok
        changed = True
    return changed


def _repair_adverb_subject(sent: SpacySpan) -> bool:
    """ "Marcus/compound sarcastically/nsubj says": a manner adverb the parser made the subject, the
    name hung under it -> the name is the subject and the adverb the verb's manner."""
    changed = False
    for adverb in sent:
        if adverb.dep_ != "nsubj" or not adverb.lower_.endswith("ly") or adverb.pos_ not in ("ADV", "ADJ"):
            continue
        people = [c for c in adverb.lefts if c.dep_ in ("compound", "amod", "nmod") and _is_person(c)]
        if not people:
            continue
        verb = adverb.head
        person = people[-1]
        person.head, person.dep_ = verb, "nsubj"
        adverb.dep_, adverb.pos_ = "advmod", "ADV"
        changed = True
    return changed


def _repair_adverb_name(sent: SpacySpan) -> bool:
    """ "The next morning, Willy/ADV sits", "looks at Willy/ADV": a capitalised word inside the sentence
    that the tagger read as an adverb by its "-ly" (Willy, Molly, Billy) is a name; before a verb with no
    subject it is that verb's subject."""
    changed = False
    for tok in sent:
        if tok.i == sent.start or tok.pos_ not in ("ADV", "ADJ") or not tok.is_alpha:
            continue
        if not (tok.text[:1].isupper() and tok.text[1:].islower() and tok.lower_.endswith("ly")):
            continue
        if sent.doc[tok.i - 1].text in ('"', "'", ":", "(") or tok.lower_ in lexicon.MANNER_STOP:
            continue
        tok.pos_, tok.tag_ = "PROPN", "NNP"
        verb = tok.head
        if (
            tok.dep_ == "advmod"
            and verb.pos_ == "VERB"
            and tok.i < verb.i
            and not any(c.dep_.startswith("nsubj") for c in verb.children)
        ):
            tok.dep_ = "nsubj"
        changed = True
    return changed


def _repair_name_as_verb(sent: SpacySpan) -> bool:
    """ "Marcus hands/NOUN Dana/VERB the tablet": a capitalised word that is no verb and no thing, after
    a verb the tagger read as a noun, is a name (the one it is handed to); retagged, the verbless repair reads "hands" as the verb."""
    changed = False
    for tok in sent:
        if tok.i == sent.start or tok.pos_ != "VERB" or not tok.text[:1].isupper():
            continue
        known = tok.lower_ in lexicon.FEMALE_NAMES or tok.lower_ in lexicon.MALE_NAMES
        if not known and (action_reading(tok.lower_) or exact_category([tok.lower_]) is not None):
            continue  # a capitalised verb or thing ("Wave", "Sofa") is no name
        before = sent.doc[tok.i - 1]
        if before.pos_ != "NOUN" or not action_reading(before.lower_):
            continue
        tok.pos_, tok.tag_ = "PROPN", "NNP"
        for child in list(tok.children):
            child.head = child  # what the name seemed to govern: the verb's, re-hung by the repair
        changed = True
    return changed


_RELATIVE_PRONOUNS = frozenset({"who", "that", "whom"})


def _repair_subject_relative_clause(sent: SpacySpan) -> bool:
    """ "The man who wears a hat walks/ccomp to the door", "The teacher who is standing by the board
    points/NOUN at the map": the parser ends the relative clause too late and makes the person the root,
    so the sentence has no action. The first word after the relative clause's verb whose verb reading is
    an action and that the clause cannot take (a bare present after its last noun) becomes the root with
    the person as subject; the relative clause stays on the person, what follows is the new verb's."""
    person = sent.root
    if not _is_person(person) or person.pos_ not in ("NOUN", "PROPN"):
        return False
    clause = next(
        (
            c
            for c in person.children
            if c.dep_ == "acl:relcl" and any(g.lower_ in _RELATIVE_PRONOUNS for g in c.children if g.i < c.i)
        ),
        None,
    )
    if clause is None:
        return False
    verb = None
    for tok in sent.doc[clause.i + 2 : sent.end]:
        prev = sent.doc[tok.i - 1]
        if prev.pos_ not in ("NOUN", "PROPN", "ADV") or tok.pos_ in _NOT_VERBS:
            continue
        if (
            tok.tag_ in ("VBZ", "NNS", "VBD")
            and tok.lower_.endswith(("s", "ed"))
            and action_reading(tok.lower_)
        ):
            verb = tok
            break
    if verb is None:
        return False
    inside = range(clause.i + 1, verb.i)
    after = range(verb.i + 1, sent.end)
    lemma = action_reading(verb.lower_)
    verb.pos_, verb.tag_, verb.lemma_ = "VERB", "VBZ", lemma
    verb.head, verb.dep_ = verb, "ROOT"
    person.head, person.dep_ = verb, "nsubj"
    for i in inside:  # "by the board": the relative clause's, not under the new verb
        tok = sent.doc[i]
        if tok.head.i == verb.i or tok.head.i in after or tok.head.i == tok.i:
            tok.head = clause
            tok.dep_ = "obl" if any(c.dep_ == "case" for c in tok.children) else "obj"
    has_object = False
    for i in after:
        tok = sent.doc[i]
        if tok.head.i in after and tok.head.i != tok.i:
            continue  # inside an argument: keep
        tok.head = verb
        if tok.is_punct:
            tok.dep_ = "punct"
        elif any(c.dep_ == "case" for c in tok.children):
            tok.dep_ = "obl"
        elif tok.pos_ in ("NOUN", "PROPN", "PRON", "NUM") and not has_object:
            tok.dep_, has_object = "obj", True
        elif tok.pos_ == "ADV":
            tok.dep_ = "advmod"
    for tok in list(person.children):  # the final stop the person held
        if tok.is_punct and tok.i > verb.i:
            tok.head, tok.dep_ = verb, "punct"
    return True


def _repair_determined_adverb(sent: SpacySpan) -> bool:
    """ "skips to the well/ADV": a word with a determiner and a preposition of its own is a noun, never
    an adverb (the tagger reads "well", "back", "down" as adverbs whatever comes before them)."""
    changed = False
    for tok in sent:
        if tok.pos_ != "ADV" or tok.dep_ not in ("obl", "obj", "nmod"):
            continue
        kids = {c.dep_ for c in tok.children if c.i < tok.i}
        if "det" in kids and "case" in kids:
            tok.pos_, tok.tag_ = "NOUN", "NN"
            changed = True
    return changed


def _repair_title_root(sent: SpacySpan) -> bool:
    """ "Coach Kim stands/acl:relcl in front of the mirror": the title read as a noun the root and the rest a
    relative clause with the name its subject -> the verb the root, the title part of the name."""
    title = sent.root
    if (
        title.i != sent.start
        or not title.text[:1].isupper()
        or title.lower_.rstrip(".") not in lexicon.TITLES
    ):
        return False
    if title.i + 1 >= sent.end or not sent.doc[title.i + 1].text[:1].isupper():
        return False
    name = sent.doc[title.i + 1]
    verb = next(
        (c for c in title.children if c.dep_ == "acl:relcl" and c.pos_ == "VERB" and name.head.i == c.i), None
    )
    if verb is None or name.dep_ != "nsubj":
        return False
    rest = [c for c in title.children if c.i not in (name.i, verb.i)]
    verb.head, verb.dep_ = verb, "ROOT"
    title.head, title.dep_ = name, "compound"
    for c in rest:  # the full stop and anything else the title held: the sentence's
        c.head = verb
    return True


_NAMING_WORDS = frozenset({"named", "called"})


def _person_noun(tok: Token) -> bool:
    """A common noun for a person ("waitress", "grandson", "students"), not a name nor a title of one."""
    return (
        tok.pos_ == "NOUN"
        and not tok.text[:1].isupper()
        and (tok.lemma_.lower() in lexicon.PERSON_NOUNS or tok.lower_ in lexicon.PERSON_NOUNS)
    )


def _names_at(sent: SpacySpan, i: int) -> list[Token]:
    """The names from token i on: "Rosa", "Aiko and Pedro", "Ana, Ben and Cy" (empty when token i is none)."""
    doc, names = sent.doc, []
    while i < sent.end and is_title(doc[i]):
        i += 1  # "his boss Mrs. Lane": the name's token (the title stays part of the name)
    while i < sent.end and doc[i].text[:1].isupper() and doc[i].is_alpha and _is_person(doc[i]):
        names.append(doc[i])
        if i + 2 < sent.end and doc[i + 1].text in ("and", ",") and doc[i + 2].text[:1].isupper():
            i += 2
        elif i + 3 < sent.end and doc[i + 1].text == "," and doc[i + 2].text == "and":
            i += 3
        else:
            break
    return names


def _described_names(sent: SpacySpan) -> tuple[Token, list[Token], int] | None:
    """(person noun, the names it describes, index after them) of "A waitress named Rosa", "His grandson
    Eli", "Two students, Aiko and Pedro," and "Rosa, the waitress,"; None when the sentence has none."""
    doc = sent.doc
    for tok in sent:
        if not _person_noun(tok) or tok.i + 1 >= sent.end:
            continue
        nxt = doc[tok.i + 1]
        if nxt.lower_ in _NAMING_WORDS:  # "a waitress named Rosa"
            names = _names_at(sent, tok.i + 2)
            if names:
                return tok, names, names[-1].i + 1
        elif nxt.text == ",":  # "two students, Aiko and Pedro, come in"
            names = _names_at(sent, tok.i + 2)
            end = names[-1].i + 1 if names else 0
            if names and end < sent.end and doc[end].text == ",":
                return tok, names, end + 1
        elif names := _names_at(sent, tok.i + 1):  # "his grandson Eli"
            return tok, names, names[-1].i + 1
        start = tok.i - 1  # "Rosa, the waitress, walks": the noun between commas after the name
        while start > sent.start and doc[start].pos_ in ("DET", "ADJ", "PRON"):
            start -= 1
        if (
            start - 1 >= sent.start
            and doc[start].text == ","
            and nxt.text == ","
            and _is_person(doc[start - 1])
            and doc[start - 1].text[:1].isupper()
        ):
            return tok, [doc[start - 1]], tok.i + 2
    return None


def _repair_described_name(sent: SpacySpan) -> bool:
    """ "A waitress named Rosa walks/xcomp to the table", "His grandson/nsubj Eli/nsubj runs in", "Two
    students/nsubj, Aiko/conj and Pedro, come in": a person noun with the names that say who it is -> the
    names are the subject of the verb after them, the noun only describes the first (appos), so one
    character acts (Rosa), not two (a waitress and Rosa)."""
    found = _described_names(sent)
    if found is None:
        return False
    noun, names, after = found
    if noun.dep_ == "appos" and noun.head in names:
        return False  # an earlier repair read it so already ("Vincent, the barber, sweeps/NOUN")
    doc = sent.doc
    verb = next((t for t in doc[after : sent.end] if t.pos_ == "VERB"), None)
    if verb is None:
        return False
    first = names[0]
    if first.head.i == first.i or first.dep_ == "ROOT":
        return False  # the name is the root already: nothing to hang it under
    if verb.head.i != verb.i and any(a.i == noun.i for a in verb.ancestors):
        verb.head, verb.dep_ = verb, "ROOT"  # "walks/xcomp" under "named" under "waitress/ROOT"
    for t in sent:
        if t.head.i == noun.i and t.i != noun.i and t.i > names[-1].i:
            t.head = verb  # the full stop and what else the noun held after the names
    if noun.dep_ == "ROOT" or noun.head.i == noun.i or noun.i < noun.head.i < after:
        first.head, first.dep_ = verb, "nsubj"  # "A waitress/ROOT named Rosa walks": Rosa walks
    else:
        first.head, first.dep_ = noun.head, noun.dep_  # "Sophie and her trainer/conj Marcus": Marcus/conj
    for other in names[1:]:
        other.head, other.dep_ = first, "conj"
    noun.head, noun.dep_ = first, "appos"
    for t in doc[noun.i + 1 : first.i]:
        if t.lower_ in _NAMING_WORDS:
            t.head, t.dep_, t.pos_, t.tag_ = noun, "amod", "ADJ", "JJ"  # "named": no call on the phone
    return True


def repair_character_sentence(sent: SpacySpan) -> bool:
    """Repair the tree of one character sentence in place; True when something changed."""
    return (
        _repair_title_root(sent)
        | _repair_determined_adverb(sent)
        | _repair_subject_relative_clause(sent)
        | _repair_progressive(sent)
        | _repair_state(sent)
        | _repair_participle_argument(sent)
        | _repair_adverb_subject(sent)
        | _repair_adverb_name(sent)
        | _repair_name_as_verb(sent)
        | _repair_verbless(sent)
        | _repair_conjoined_verb(sent)
        | _repair_verb_as_subject(sent)
        | _repair_clause_as_subject(sent)
        | _repair_pronoun_relative_clause(sent)
        | _repair_noun_conjunct_verb(sent)
        | _repair_verb_conjunct_noun(sent)
        | _repair_described_name(sent)  # last: on the verb the repairs above may have made one
    )


_POSTURE_VERBS = frozenset("hang stand sit lie lean rest".split())


def repair_scene_sentence(sent: SpacySpan) -> bool:
    """ "... and the oven/compound glows/NNS": a scene verb the tagger read as a plural noun, its thing
    hung under it as a compound -> the verb, with the thing as its subject (then the oven is an object)."""
    changed = False
    for tok in sent:
        verb = tok.lower_[:-1]
        if tok.tag_ != "NNS" or not tok.lower_.endswith("s") or verb not in lexicon.SCENE_VERBS:
            continue
        if verb in lexicon.RELATION_VERBS or verb in _POSTURE_VERBS:
            continue  # "hangs above", "stands near": the scene reader's own relations
        things = [c for c in tok.children if c.dep_ == "compound" and c.i < tok.i and c.pos_ == "NOUN"]
        if not things or exact_category([things[-1].lower_]) is None:
            continue
        tok.pos_, tok.tag_, tok.lemma_ = "VERB", "VBZ", tok.lower_[:-1]
        things[-1].dep_ = "nsubj"
        changed = True
    for tok in sent:  # "A basket/compound stands/VERB beside/nmod the bench": the thing is the subject
        if tok.pos_ != "VERB" or any(c.dep_ in ("nsubj", "nsubj:pass") for c in tok.children):
            continue
        things = [c for c in tok.lefts if c.dep_ == "compound" and c.pos_ == "NOUN"]
        if not things or exact_category([things[-1].lower_]) is None:
            continue
        things[-1].dep_ = "nsubj"
        for c in tok.rights:
            if c.dep_ == "nmod" and any(g.dep_ == "case" for g in c.children):
                c.dep_ = "obl"
        changed = True
    return changed
