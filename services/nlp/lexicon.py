"""Words -> canonical names: object categories, attributes, rooms (from ``wana.assets.vocabulary``) and
actions (from the action catalogue, ``wana.domain.actions``), plus the NLP stage's own word lists
(people, relation words, manners, social labels).

Every lookup is cached; the action library loads on first use. Over 400 lines because most of it
is word lists and override tables, kept in one place so that one file says what a word means.
"""

from __future__ import annotations

import functools
import re

from services.nlp import verbs
from wana.assets import vocabulary

# --- objects ---------------------------------------------------------------------------------------

PERSON_NOUNS = frozenset(
    "man woman boy girl person guy lady gentleman child kid baby teacher student pupil doctor nurse chef cook "
    "worker carpenter boxer singer dancer musician pianist guitarist drummer artist painter player waiter "
    "waitress officer policeman driver friend mother father mom dad brother sister son daughter grandma "
    "grandpa wife husband boss manager colleague customer visitor guest stranger athlete coach people men "
    "women children kids girls boys someone somebody everyone everybody hero heroine knight wizard witch "
    "king queen prince princess soldier guard detective villain thief farmer sailor pirate priest monk "
    "servant maid butler clerk receptionist librarian scientist professor janitor cleaner mayor judge "
    "lawyer shopkeeper baker grandmother grandfather granny uncle aunt parent parents teenager "
    "traveller traveler stranger giant dwarf elf merchant innkeeper bartender actor actress audience "
    "crowd duke duchess lord lady servant messenger twin twins captain intern apprentice patient barber "
    "dentist hairdresser cashier passenger conductor tourist neighbour neighbor toddler grandson "
    "granddaughter niece nephew fiance fiancee bride groom host hostess chief commander sheriff "
    "teammates player players spectator spectators performer drummer bassist vocalist "
    "reporter journalist photographer mechanic plumber electrician gardener housekeeper nanny "
    "caretaker porter bellboy concierge owner landlord landlady tenant referee umpire "
    "trainer instructor tutor partner roommate classmate coworker boyfriend girlfriend cousin "
    "assistant secretary employee nurse surgeon pharmacist technician engineer programmer designer "
    # the cast of quest text and fantasy
    "rogue archer mage sorcerer sorceress warrior paladin ranger hunter blacksmith healer bandit "
    "adventurer goblin troll ogre dragon fairy ghost robot monster pilot ".split()
)
# the cast of children's stories: an animal that acts is a character (shown as a figure); "it" may
# name one ("The bunny hops. It picks up a carrot")
ANIMAL_NOUNS = frozenset(
    "bear bunny rabbit pig piglet wolf fox frog toad owl duck duckling goose hen cat kitten "
    "dog puppy lion tiger monkey elephant squirrel hedgehog tortoise turtle horse pony donkey cow "
    "calf sheep lamb goat deer fawn bird chick chicken rooster badger beaver otter raccoon".split()
)
PERSON_NOUNS = PERSON_NOUNS | ANIMAL_NOUNS
# Animals whose word also names a catalog thing (the computer mouse): a character only as the
# subject of an action verb ("The little mouse creeps to the table"), a thing everywhere else.
THING_ANIMALS = frozenset({"mouse"})
NON_OBJECT_NOUNS = (
    frozenset(
        "room floor wall ceiling corner middle center centre side left right front back top bottom end time "
        "second seconds minute minutes moment hour hours day night way place area space home house building "
        "street garden yard outside inside ground music song morning evening afternoon noon midnight dawn "
        "dusk sunrise sunset twilight while week weekend month year today tomorrow yesterday meantime "
        "instant daytime nighttime".split()
    )
    | frozenset(
        # places a story is set in that are no room type and no furniture: never an unknown object
        "attic loft basement cellar greenhouse ward carriage compartment cabin bakery park beach forest "
        "field meadow hill river lake sea shore street road alley path lane corridor stairs staircase "
        "stairway steps landing lift lifts platform station village town city castle tower cottage "
        "hut barn stable shop store market square courtyard balcony terrace porch patio roof rooftop sky "
        "threshold row aisle centre tavern inn pub saloon dungeon cave".split()
    )
    | frozenset(
        # what is said, felt, done or made of, not a thing to put in the room
        "word words groan sigh smile grin frown laugh laughter tears breath care work job task speech toast "
        "joke jokes story apology thanks greeting handshake hug kiss nod glance look silence noise sound "
        "song tune match game race fight lesson class meeting party break rest dream idea thought question "
        "answer reply goodbye farewell hello news dust dirt soil mud sand flour dough water air smoke steam darkness shadow "
        "everything something nothing anything thing things piece pieces bit bits band crowd team family "
        "way time surface surfaces clipping clippings crumb crumbs ping pong tennis chess cards badminton "
        "tag puzzle homework notes".split()
    )
    | frozenset(
        # what a character wears: on the body, not in the room
        "shoe shoes boot boots sock socks slipper slippers coat jacket hat cap scarf dress suit tie uniform "
        "sleeve sleeves apron spectacles".split()
    )
)
# Words a character says as the object of a verb ("says goodbye", "waves hello", "bids farewell"):
# what is said, never a thing or place the act is aimed at.
SAID_WORDS = frozenset("goodbye bye farewell hello hi hey goodnight sorry thanks yes no cheers".split())
# What one casts or throws that is no thing in hand ("casts a spell at the troll", "shoots a glance at
# Ada"): the act is aimed at the one after "at", who is its target.
AIMED_ACTS = frozenset("spell curse hex charm jinx glance look smile wink kiss stare glare insult".split())
WORN_NOUNS = frozenset(
    "shoe boot sock slipper coat jacket hat cap scarf dress suit tie uniform apron spectacles glasses "
    "gloves glove sweater jumper cardigan helmet mask ring necklace robe cloak".split()
)
# What things do in a scene sentence ("a lamp glows"), which the tagger may read as plural nouns.
SCENE_VERBS = frozenset(
    "glow hum buzz flicker shine gleam sparkle hang stand sit lie lean rest wait crowd line fill run "
    "stretch dust cover smell tick creak rattle loom tower overlook face hover dangle sway".split()
)
# Parts of a thing: "slams the lid" acts on the thing last named (the washing machine).
PART_NOUNS = frozenset("lid handle knob cover edge hinge".split())
COUNT_WORDS = {
    "one": 1,
    "two": 2,
    "three": 3,
    "four": 4,
    "five": 5,
    "six": 6,
    "seven": 7,
    "eight": 8,
    "nine": 9,
    "ten": 10,
    "eleven": 11,
    "twelve": 12,
    "a couple of": 2,
    "couple": 2,
    "pair": 2,
    "both": 2,
    "several": 3,
    "some": 3,
    "many": 3,
    "few": 3,
    "multiple": 3,
    "lots": 3,
}
PLURAL_DEFAULT_COUNT = 3  # "there are books on the shelf": an unnamed number of several


@functools.lru_cache(maxsize=65536)
def category_of(phrase: str) -> str | None:
    """Catalog category of a word or phrase ("couch" -> "sofa", "notebook computer" -> "laptop")."""
    phrase = phrase.strip().lower()
    if not phrase or phrase in PERSON_NOUNS or phrase in NON_OBJECT_NOUNS:
        return None
    if phrase in vocabulary.CATEGORIES:
        return phrase
    return vocabulary.lookup(phrase)


def attribute_of(word: str) -> tuple[str, str] | None:
    """(knob, value) of an attribute word ("wooden" -> ("material", "wooden"), "big" -> ("size", "large"))."""
    return vocabulary.normalize_attribute(word.lower())


@functools.lru_cache(maxsize=65536)
def room_of(phrase: str) -> str | None:
    """Room type of a phrase ("working shop" -> "workshop"), or None."""
    phrase = phrase.strip().lower()
    if not phrase or phrase in ("room", "house", "home", "place"):
        return None
    return vocabulary.lookup_room(phrase)


def category_words(category: str) -> list[str]:
    """Words that name a category: its name parts, last word and one-word synonyms."""
    info = vocabulary.CATEGORIES.get(category)
    words = [category, category.split("_")[-1]]
    if info is not None:
        words += [s.replace(" ", "_") for s in info.synonyms]
    return list(dict.fromkeys(words))


def hypernyms(category: str) -> list[str]:
    return vocabulary.hypernyms(category) if category in vocabulary.CATEGORIES else []


# --- relations ---------------------------------------------------------------------------------------

# One-word prepositions -> SSG relation.
RELATION_PREPS = {
    "on": "on",
    "upon": "on",
    "onto": "on",
    "atop": "on",
    "over": "above",
    "above": "above",
    "near": "near",
    "by": "near",
    "at": "near",
    "close": "near",
    "beside": "next_to",
    "besides": "next_to",
    "alongside": "next_to",
    "along": "next_to",
    "against": "next_to",
    "behind": "behind",
    "under": "under",
    "underneath": "under",
    "beneath": "under",
    "below": "under",
    "in": "in",
    "inside": "in",
    "within": "in",
    "into": "in",
    "around": "around",
    "surrounding": "around",
    "opposite": "facing",
    "facing": "facing",
    "toward": "facing",
    "towards": "facing",
}
# Relational nouns in "in front of", "on top of", "to the left of", "at the back of" -> relation.
RELATION_NOUNS = {
    "front": "in_front_of",
    "top": "on",
    "left": "left_of",
    "right": "right_of",
    "back": "behind",
    "rear": "behind",
    "side": "next_to",
    "middle": "in",
    "center": "in",
    "centre": "in",
    "bottom": "under",
    "corner": "in",
    "underside": "under",
}
# Ends of a thing an action goes to: "sits at the head of the table" is at the table (a chair at its end).
# Only for action sentences: a scene sentence's "on the end of the workbench" keeps its layout.
END_NOUNS = frozenset({"head", "end"})
RELATION_VERBS = {
    "face": "facing",
    "surround": "around",
    "overlook": "facing",
    "cover": "on",
    "hang": "on",
    "border": "next_to",
    "flank": "next_to",
    "support": "under",
    "hold": "under",
}

# --- characters and actions ---------------------------------------------------------------------------

PRONOUNS = {
    "he": "he",
    "him": "he",
    "she": "she",
    "her": "she",
    "they": "they",
    "them": "they",
    "i": "i",
    "me": "i",
    "you": "you",
    "we": "they",
    "us": "they",
    "everyone": "all",
    "everybody": "all",
}
OBJECT_PRONOUNS = frozenset({"it", "this", "that", "them"})
# A group named as one ("The band bows", "the whole team cheers"): everyone on stage, as "everyone" is.
COLLECTIVE_NOUNS = frozenset("band team group class family crew choir orchestra troupe cast".split())
FEMALE_NAMES = frozenset(
    "eve mary alice anna lucy kate emma lily sara sarah nina julia jane emily olivia sophia mia amy laura "
    "linda susan lisa maria anne ann helen grace chloe zoe ella ava rose ruth clara lena ada eva ivy iris "
    "nora maya leah hannah sophie amelia isla freya priya aisha fatima mei yuki elena marta ines wendy "
    "alice dorothy gretel goldilocks cinderella belle jasmine elsa anna wanda may".split()
)
MALE_NAMES = frozenset(
    "tom john bob peter sam david jack mike ben paul james michael mark luke adam alex max leo tim chris dan "
    "daniel joe george harry henry nick oscar ryan steve will bill fred frank ken carl eric jim finn "
    "hugo theo noah liam ethan owen kai omar raj ivan jamal jose luis carlos pedro hans hansel jack "
    "aladdin peter arthur merlin robin rick walter hank".split()
)
FEMALE_NOUNS = frozenset(
    "woman girl lady mother mom sister daughter grandma granny wife waitress aunt auntie ms mrs miss "
    "madam madame queen princess nana witch heroine grandmother maid".split()
)
MALE_NOUNS = frozenset(
    "man boy guy gentleman father dad brother son grandpa husband policeman uncle mr mister sir king "
    "prince lord knight wizard grandfather butler".split()
)
# Words written before a name that make one character with it ("Dr. Jones", "Uncle Bob", "Ms Lee").
TITLES = frozenset(
    "mr mrs ms miss mx dr doctor prof professor uncle aunt auntie grandma granny grandpa grandad nana "
    "sir madam madame lady lord captain capt officer detective det inspector sergeant sgt coach nurse "
    "mister master king queen prince princess father brother sister mother saint st judge mayor "
    "agent general colonel major lieutenant lt chef little old young big officer constable "
    "private corporal reverend rev pastor sheriff deputy governor senator president".split()
)
# A word's category when a verb says which thing it is: the bag a boxer punches is the punching bag.
VERB_SENSES: dict[tuple[str, str], str] = {
    ("handbag", verb): "boxing_bag" for verb in ("punch", "hit", "kick", "jab", "strike", "box", "pound")
}

MANNER_STOP = frozenset(
    "then now first finally again also still just later soon already next there here away back home in out "
    "up down around off over together too even only not never always once twice very so really thereby "
    "afterwards meanwhile instead almost".split()
)
DIRECTION_ADVERBS = {
    "left": "left",
    "right": "right",
    "around": "around",
    "back": "back",
    "backward": "backward",
    "backwards": "backward",
    "forward": "forward",
    "forwards": "forward",
    "up": "up",
    "down": "down",
}
LOCOMOTION_ACTIONS = frozenset(
    {
        "walk",
        "run",
        "jog",
        "walk_slowly",
        "walk_backward",
        "march",
        "limp",
        "tiptoe",
        "skip",
        "crawl",
        "step_forward",
        "step_back",
        "stumble",
        "sidestep_left",
        "sidestep_right",
    }
)
DESTINATION_PREPS = frozenset(
    {
        "to",
        "toward",
        "towards",
        "into",
        "through",
        "across",
        "along",
        "onto",
        "past",
        "up",
        "down",
        "over",
        "in",
    }
)
INSTRUMENT_PREPS = frozenset({"with", "using", "via"})
ASPECT_VERBS = frozenset(
    {
        "start",
        "begin",
        "continue",
        "help",  # "Cheryl helps him pick it up": she picks it up
        "keep",
        "try",
        "go",
        "stop",
        "finish",
        "want",
        "decide",
        "like",
        "love",
        "seem",
        "need",
        "attempt",
        "come",
        "burst",
    }
)
# Verbs whose meaning is social between two characters: action + SocialNode(kind="emotion").
SOCIAL_VERBS = frozenset(
    "apologize apologise thank hug kiss greet comfort console insult praise blame scold forgive congratulate "
    "argue quarrel shout yell scream smile laugh threaten criticize criticise fight punch push hit slap "
    "tease mock ignore admire love hate help invite welcome cheer beg reprimand rebuke embrace cuddle "
    "bicker reassure salute high-five highfive whisper chat".split()
)
# Verbs that two or more subjects do to each other when no one else is named ("Tom and Mary hug",
# "They quarrel"); clips that touch a person or are social talk count too (see is_reciprocal).
RECIPROCAL_VERBS = frozenset(
    "hug embrace cuddle kiss greet meet fight quarrel argue bicker chat talk high-five highfive".split()
)
# Nouns an event verb like "give" or "have" turns into an action: "gives Mary a hug", "have a quarrel".
LIGHT_VERBS = frozenset("give have make take do share".split())
# Body parts as objects of a gesture ("shakes hands with", "waves his hands at"): part of the action's
# name, never its target or an unknown object.
BODY_PARTS = frozenset(
    "hand hands arm arms head fist fists finger fingers thumb thumbs shoulder shoulders hair teeth face "
    "foot feet leg legs cheek cheeks eye eyes forehead brow knee knees lip lips mouth nose ear ears neck "
    "belly stomach chin wrist wrists elbow elbows toe toes eyebrows".split()
)
REFLEXIVE_PRONOUNS = frozenset(
    "himself herself themselves itself myself yourself ourselves yourselves oneself".split()
)
RECIPROCAL_PHRASES = frozenset({"each other", "one another"})
EMOTION_WORDS = frozenset(
    "angry happy sad nervous excited tired scared afraid calm surprised bored anxious annoyed upset proud "
    "jealous confused disappointed furious glad worried lonely relaxed shy embarrassed ashamed hopeful "
    "frightened cheerful grumpy sleepy curious disgusted amused delighted miserable depressed content".split()
)
SOCIAL_RELATION_WORDS = frozenset(
    "friend friends colleague colleagues enemy enemies sibling siblings stranger strangers partner partners "
    "neighbor neighbors neighbour neighbours rival rivals couple lovers lover boss teacher student sister "
    "brother mother father wife husband son daughter coach manager assistant employee employer classmate "
    "classmates teammate teammates roommate roommates cousin cousins parent parents child children "
    "boyfriend girlfriend fiance fiancee family relatives acquaintances acquaintance".split()
)
# Participles that state a relation between their subjects -> the social model's relation label.
RELATION_STATES = {
    "married": "couple",
    "engaged": "couple",
    "dating": "couple",
    "related": "relatives",
}

# Verb lemma (+ object word) -> action name, for phrasings the motion library's synonyms do not carry.
ACTION_OVERRIDES: dict[tuple[str, str], str] = {
    ("chat", "phone"): "call_with_phone",
    ("talk", "phone"): "call_with_phone",
    ("speak", "phone"): "call_with_phone",
    ("answer", "phone"): "pick_up_phone_answer",
    ("use", "phone"): "text_on_phone",
    ("check", "phone"): "text_on_phone",
    ("look", "phone"): "text_on_phone",
    ("use", "laptop"): "type",
    ("use", "computer"): "type",
    ("work", "laptop"): "type",
    ("work", "computer"): "type",
    ("use", "keyboard"): "type",
    ("use", "tablet"): "use_tablet",
    ("use", "mouse"): "use_mouse",
    ("watch", "television"): "watch_tv",
    ("sing", "microphone"): "sing_with_microphone",
    ("hit", "boxing_bag"): "punch_bag",
    ("punch", "boxing_bag"): "punch_bag",
    ("kick", "boxing_bag"): "kick",
    ("box", "boxing_bag"): "punch_bag",
    ("lift", "dumbbell"): "lift_weights",
    ("lift", "barbell"): "lift_weights",
    ("lift", "kettlebell"): "lift_weights",
    ("open", "refrigerator"): "open_fridge",
    ("open", "door"): "open_door",
    ("close", "door"): "close_door",
    ("open", "drawer"): "open_drawer",
    ("open", "chest"): "open_drawer",
    ("open", "cabinet"): "open_drawer",
    ("open", "kitchen_cabinet"): "open_drawer",
    ("open", "wardrobe"): "open_drawer",
    ("open", "dresser"): "open_drawer",
    ("open", "box"): "open_drawer",
    ("open", "locker"): "open_drawer",
    ("open", "filing_cabinet"): "open_drawer",
    ("close", "window"): "close_door",
    ("open", "window"): "open_door",
    ("pull", "chair"): "pull",
    ("write", "blackboard"): "write_on_blackboard",
    ("write", "whiteboard"): "write_on_blackboard",
    ("draw", "whiteboard"): "write_on_blackboard",
    ("read", "newspaper"): "read_newspaper",
    ("open", "newspaper"): "read_newspaper",  # opened to be read, not a door
    ("open", "book"): "read",
    ("open", "magazine"): "read",
    ("clean", "window"): "wipe_window",
    ("wipe", "window"): "wipe_window",
    ("clean", "table"): "wipe_table",
    ("clean", "floor"): "mop",
    ("water", "plant"): "water_plants",
    ("listen", "headphones"): "listen_with_headphones",
    ("listen", "music"): "listen_with_headphones",
    ("listen", "song"): "listen_with_headphones",
    ("listen", "earphones"): "listen_with_headphones",
    ("listen", "podcast"): "listen_with_headphones",
    ("listen", "headphone"): "listen_with_headphones",
    ("take", "photo_frame"): "take_photo",
    ("take", "picture"): "take_photo",
    ("take", "photo"): "take_photo",
    ("play", "drum_kit"): "play_drums",
    ("play", "flute"): "play_flute",
    ("play", "grand_piano"): "play_piano",
    ("play", "synthesizer"): "play_piano",
    ("play", "electric_guitar"): "play_guitar",
    ("play", "bass_guitar"): "play_guitar",
    ("play", "violin"): "play_violin",
    ("play", "cello"): "play_violin",
    ("play", "ball"): "kick",
    ("play", "phone"): "text_on_phone",
    ("burst", "tear"): "cry",
    ("burst", "tears"): "cry",
    ("burst", "laughter"): "laugh",
    ("play", "tablet"): "use_tablet",
    ("play", "game_console"): "use_tablet",
    ("play", "computer"): "type",
    ("play", "guitar"): "play_guitar",
    ("play", "piano"): "play_piano",
    ("play", "microphone"): "sing_with_microphone",
    ("blow", "candle"): "greet_bow",
    ("blow", "cake"): "greet_bow",
    ("light", "candle"): "press_switch",
    ("cut", "cake"): "chop",
    ("eat", "cake"): "eat",
    ("make", "coffee_maker"): "cook",
    ("use", "coffee_maker"): "cook",
    ("take", "pill_bottle"): "eat",
    ("swallow", "pill_bottle"): "eat",
    ("dry", "dish"): "wash_dishes",
    ("dry", "plate"): "wash_dishes",
    ("sweep", "floor"): "sweep",
    ("sweep", "broom"): "sweep",
    ("sign", "paper"): "write",
    ("throw", "ball"): "throw",
    ("shoot", "ball"): "shoot_basket",
    ("push", "person"): "push_person",
    ("shake", "hands"): "shake_hands",
    ("hold", "hands"): "hold_hands",
    ("ride", "exercise_bike"): "jog",
    ("run", "treadmill"): "jog",
    ("use", "treadmill"): "jog",
    ("press", "button"): "push_button",
    ("press", "switch"): "press_switch",
    ("turn", "lamp"): "press_switch",
    ("sit", "floor"): "sit_on_floor",
    ("sit", "ground"): "sit_on_floor",
    ("lie", "bed"): "lie_down",
    ("lie", "sofa"): "lie_down",
    ("wash", "hands"): "wash_hands",
    ("brush", "teeth"): "brush_teeth",
    ("comb", "hair"): "comb_hair",
    ("kiss", "cheek"): "kiss_cheek",
}
# Verbs whose thing decides the clip ("plays the piano", "plays ping pong"): with a thing no entry
# knows, no clip; alone ("the kids play") the verb's own row.
# "blows the whistle": what is blown says what is done (out the candles, a kiss, the flute); a thing
# no phrase names has no clip, and the bare verb's lean (blowing out candles) is not it.
OBJECT_NAMES_THE_ACTION = frozenset({"play", "blow"})
# Verb lemma alone -> action name where the library's synonym table points elsewhere.
VERB_OVERRIDES: dict[str, str] = {
    "listen": "look_at",
    "hum": "",  # a sound, not a movement (the library's "hum" holds a microphone)  # listening to someone is attending to them; "to music" is the headphones clip
    "stand": "stand",
    "sleep": "sleep",
    "be": "",
    "lie": "lie_down",
    "kiss": "kiss_cheek",
    "smile": "laugh",
    "hold": "carry",
    "go": "walk",
    "head": "walk",
    "approach": "walk",
    "return": "walk",
    "leave": "walk",
    "wander": "walk",
    "step": "step_forward",
    "hurry": "run",
    "rush": "run",
    "sprint": "run",
    "type": "type",
    "sit": "sit",
    "greet": "wave",
    "thank": "bow",  # the library has no "thank" clip: a small bow of thanks
    "congratulate": "shake_hands",  # and none for congratulating: a handshake
    "console": "comfort",
    "highfive": "high_five",
    "reassure": "comfort",
    "turn": "turn_around",
    "chat": "talk",
    "speak": "talk",
    "relax": "sit",
    "rest": "sit",
    "work": "type",
    "study": "read",
    "use": "",
    "do": "",
    "have": "",
    "get": "",
    "make": "",
    "take": "pick_up",
    "watch": "look_at",
}


@functools.lru_cache(maxsize=1)
def _library() -> tuple[frozenset[str], dict[str, str]]:
    try:
        from wana.domain.clip_headers import clip_headers

        headers = clip_headers()  # names and synonyms only: no keyframes to build at start-up
        synonyms: dict[str, str] = {}
        for h in headers.values():  # as wana.domain.actions.synonym_index orders them
            synonyms.setdefault(h.name.replace("_", " "), h.name)
            for s in h.synonyms:
                synonyms.setdefault(s.lower(), h.name)
        return frozenset(headers), synonyms
    except Exception:  # the motion library is optional for parsing: fall back to the overrides alone
        return frozenset(set(ACTION_OVERRIDES.values()) | set(VERB_OVERRIDES.values()) - {""}), {}


def action_names() -> frozenset[str]:
    return _library()[0]


@functools.lru_cache(maxsize=1)
def _clip_info() -> dict[str, tuple[frozenset[str], str]]:
    """Action name -> (its tags, the object its interaction touches: "person", a category or "")."""
    try:
        from wana.domain.clip_headers import clip_headers

        return {name: (frozenset(h.tags), h.interaction_object) for name, h in clip_headers().items()}
    except Exception:
        return {}


def is_social(verb: str, action: str) -> bool:
    """True when a verb aimed at a character is a social act (carries a SocialNode): a social verb or a
    clip the motion library tags "social" ("hug", "bow", "criticize", "shake_hands"). A plain gesture
    ("waves at", "points at", "claps for") is an action aimed at the character and no SocialNode, as
    the gold set has it; "greets" is both."""
    if verb.lower() in SOCIAL_VERBS:
        return True
    tags, _ = _clip_info().get(action, (frozenset(), ""))
    return "social" in tags and "gesture" not in tags


def is_reciprocal(verb: str, action: str) -> bool:
    """True when plural subjects with no target do the action to each other ("Tom and Mary hug",
    "They quarrel"); gestures of a crowd ("The students clap") are not."""
    if verb.lower() in RECIPROCAL_VERBS:
        return True
    tags, touches = _clip_info().get(action, (frozenset(), ""))
    return touches == "person" or {"social", "talk"} <= tags


def social_label(verb: str, action: str) -> str:
    """Label of the SocialNode of a social act: the verb as written ("scold", "greet") when it is a
    social verb, else the library's name for what was done ("shake_hands" for "shake hands")."""
    verb = verb.lower()
    return verb if verb in SOCIAL_VERBS or not action else action


@functools.lru_cache(maxsize=1)
def verb_words() -> frozenset[str]:
    """Verb lemmas the action vocabulary knows: library names and the first word of each synonym,
    the override tables and the social verbs (the lemmatizer prefers these among its guesses)."""
    names, synonyms = _library()
    words = {n.split("_")[0] for n in names} | {p.split()[0] for p in synonyms if p.split()}
    words |= {v for v, _ in ACTION_OVERRIDES} | set(VERB_OVERRIDES) | SOCIAL_VERBS | RECIPROCAL_VERBS
    words |= set(RELATION_VERBS) | LIGHT_VERBS | ASPECT_VERBS
    words |= {p.split()[0] for p in verbs.VERB_ACTIONS} | set(verbs.NOT_ANIMATABLE)
    return frozenset(w for w in words if w.isalpha() or "-" in w)


def hyphenated_verbs() -> frozenset[str]:
    """Hyphenated action verbs ("high-five") the tokenizer must keep as one word (base forms)."""
    _, synonyms = _library()
    words = SOCIAL_VERBS | RECIPROCAL_VERBS | set(synonyms) | set(verbs.VERB_ACTIONS)
    # and the hyphenated words of phrases ("push-ups" of "do push-ups"), in their singular too
    parts = {p for w in words if " " in w for p in w.split() if "-" in p}
    parts |= {p[:-1] for p in parts if p.endswith("s")}
    return frozenset(w for w in words | parts if "-" in w and " " not in w)


def _tokens(text: str) -> list[str]:
    return [t for t in re.split(r"[^a-z0-9]+", text.lower()) if t]


@functools.lru_cache(maxsize=65536)
def action_for(
    verb: str,
    particle: str = "",
    obj_words: tuple[str, ...] = (),
    prep: str = "",
    direction: str = "",
    person_object: bool = False,
    _retry: bool = True,
) -> str:
    """Action-library name for a verb and what surrounds it, or "" when none fits.

    Args:
        verb: verb lemma ("sit", "chat").
        particle: verb particle ("up" in "pick up").
        obj_words: words naming the object or instrument, most specific first: the category, its
            hypernyms and the word as written ("boxing_bag", "boxing_equipment", "bag").
        prep: the preposition before that object ("on" in "chatting on the phone").
        direction: a direction adverb ("left" in "turns left").
        person_object: the action is aimed at a character ("pushes Tom").
    """
    names, synonyms = _library()
    verb = verb.lower().replace("-", " ")  # "high-five" -> the library's "high five"
    if particle and f"{verb} {particle}" in verbs.NOT_ANIMATABLE:
        return ""  # "takes off his boot": dressing, which no clip shows
    if verb in ("put", "slip", "pull") and prep == "on" and any(o.lower() in WORN_NOUNS for o in obj_words):
        return ""  # "puts on/ADP her coat"
    objs = [o.lower().replace(" ", "_") for o in obj_words if o]
    if person_object:
        objs.append("person")

    def known(name: str) -> str | None:
        return name if name in names else None

    specific: list[str | None] = []
    if direction:
        specific += [known(f"{verb}_{direction}"), synonyms.get(f"{verb} {direction}")]
    if particle:
        specific += [known(f"{verb}_{particle}"), synonyms.get(f"{verb} {particle}")]
    # "raises both hands" is not "raises a hand": the plural body part as written first
    specific += [verbs.BODY_PART_ACTIONS.get((verb, o)) for o in objs if o.endswith("s")]
    for o in objs:
        specific.append(ACTION_OVERRIDES.get((verb, o)))
        specific.append(verbs.BODY_PART_ACTIONS.get((verb, o)))
        specific += [
            known(f"{verb}_{o}"),
            known(f"{verb}_{o}s"),
            known(f"{verb}_{prep}_{o}") if prep else None,
        ]
        phrase_obj = o.replace("_", " ")
        specific += [
            synonyms.get(f"{verb} the {phrase_obj}"),
            synonyms.get(f"{verb} {phrase_obj}"),
            synonyms.get(f"{verb} a {phrase_obj}"),  # "give a hug", "take a bow"
            synonyms.get(f"{verb} {prep} the {phrase_obj}") if prep else None,
        ]
        # storytellers' verb phrases ("make coffee", "play ping pong", "take notes", "dry dishes")
        specific += [
            verbs.VERB_ACTIONS.get(f"{verb} {phrase_obj}"),
            verbs.VERB_ACTIONS.get(f"{verb} the {phrase_obj}"),
            verbs.VERB_ACTIONS.get(f"{verb} a {phrase_obj}"),
        ]
    if prep:
        specific += [known(f"{verb}_{prep}"), synonyms.get(f"{verb} {prep}")]
    if particle:
        specific.append(verbs.VERB_ACTIONS.get(f"{verb} {particle}"))
    if prep:
        specific.append(verbs.VERB_ACTIONS.get(f"{verb} {prep}"))
    for c in specific:
        if c:
            return c
    if _retry and (objs or prep or particle or direction):
        # A synonym verb ("chat" -> talk) tried again with the object ("talk on the phone").
        alias = synonyms.get(verb)
        if alias and "_" not in alias and alias != verb:
            hit = action_for(alias, particle, obj_words, prep, direction, person_object, _retry=False)
            if hit and hit != alias:
                return hit
    if verb in VERB_OVERRIDES:
        return VERB_OVERRIDES[verb]
    if verb in OBJECT_NAMES_THE_ACTION and [o for o in objs if o != "person"]:
        return ""  # "plays with the mirror": no clip plays a mirror, and skipping about is not it
    return known(verb) or synonyms.get(verb) or verbs.VERB_ACTIONS.get(verb, "")


def is_known_verb(verb: str) -> bool:
    """True when a verb lemma maps to some action by itself."""
    return bool(action_for(verb))
