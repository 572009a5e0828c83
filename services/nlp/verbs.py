"""Verbs people write -> the library action that shows them, or why none can.

The motion library's own synonyms (``assets/actions/*.json``) cover the words its clips were named
for; this table adds the verbs storytellers, screenwriters and quest writers use for the same
movements (household, office, school, kitchen, sport, music, social, emotion, gesture, posture,
locomotion), phrasal verbs keyed "verb particle" ("pull out", "hand over"), and the verbs no clip
can show (thinking, owning, remembering), which get the W113 diagnostic instead of W102.
"""

from __future__ import annotations


def _table(rows: str) -> dict[str, str]:
    """ "action: verb, verb phrase, ..." lines -> {verb: action}."""
    out: dict[str, str] = {}
    joined = rows.strip().replace("\n    ", " ")  # indented lines continue the one above
    for line in joined.splitlines():
        action, _, words = line.partition(":")
        for word in words.split(","):
            word = word.strip()
            if word:
                out.setdefault(word, action.strip())
    return out


VERB_ACTIONS: dict[str, str] = _table(
    """
walk: squeeze in, squeeze through, squeeze past, weave, disappear, vanish, make one's way, stroll out, head down, wander down, burst through, burst in, amble, stroll, pace, wander, roam, head, proceed, advance, return, leave, exit, enter, cross, go, slip out, slip away, slip in, slip past, nip out,
    come, arrive, depart, follow, lead, stride, strut, trek, hike, patrol, travel, move, walk over,
    walk in, walk out, walk away, walk up, come in, come back, come over, go back, go out, go in,
    go over, get in, get out, head back, head out, make way, step in, step out, move over, accompany,
    escort, pass, circle, visit, reach, meander, promenade, saunter off, come closer, go away, turn up
run: dash, sprint, race, hurry, rush, bolt, flee, charge, scurry, scamper, gallop, run off, run away,
    run out, run in, run over, run back, chase, hasten, zoom, dart, escape
jog: trot, lope, jog along
walk_slowly: shuffle, plod, trudge, dawdle, stroll slowly, crawl along, mosey, drag oneself
tiptoe: sneak, creep, slink, prowl, tiptoe in, sneak in, sneak out, steal away
limp: hobble, shamble, lurch
march: parade, stomp off, storm, storm off, storm out, stalk
skip: frolic, prance, caper, bounce along, play, play a game, play games, play tag, play hide and seek, play together, romp
crawl: slither, crawl in, crawl out, crawl under, wriggle
step_back: back away, retreat, recoil, withdraw, step away, move back, shrink back, back up
step_forward: step up, step closer, move forward, move closer, approach, come forward, lean forward
step_left: step aside, move aside, make room
stumble: stagger, trip, totter, wobble, falter, reel, slip
jump: hop, leap, bounce, spring, vault, jump up, jump down, hop up, leap up, bound, pounce, jump out, jump out from behind, leap out, pop out, spring out
jump_forward: jump over, leap over, hurdle, jump across, leap forward
climb: clamber, scramble, ascend, climb up, climb down, climb over, climb in, mount, descend
fall_down: fall, collapse, tumble, faint, topple, drop down, fall over, keel over, pass out, slump
turn_around: turn, turn back, turn round, spin round, whirl, wheel round, about-face, look back
spin: twirl, pivot, rotate, whirl around, pirouette around
sit: flop, flop onto, slump onto, slump on, slump into, slump down, slump back, sit back down, lower oneself, seat, sink into, plonk, plop, sink down, sit down, be seated, take a seat, settle, settle down, perch, plop down, flop down, squat down on,
    relax, rest, lounge, sit back, sit up, slouch, recline
sit_on_floor: sit cross-legged
stand: awake, awaken, jolt awake, start awake, snap awake, jerk awake, jolt up, stand up, get up, rise, arise, straighten up, jump to one's feet, spring up, stand still,
    wake up, get to one's feet
lie_down: curl up, snuggle up, cuddle up, lie, lay down, lie back, stretch out, sprawl, recline on, go to bed, sleep, nap, snooze,
    doze, doze off, drift off, fall asleep, slumber, rest on
kneel: kneel down, get down, genuflect, drop to one's knees
squat: dive, dodge, crouch, stoop down, hunker down, duck, bend down, huddle
hide: cower, take cover, duck behind, hide behind, lurk, conceal oneself, hide under, hide in, duck down behind, crouch behind
lean_on_wall: lean, lean against, lean back, lean on, rest against, prop oneself
idle: wait around, stand around, linger, loiter, pause, stay, remain, freeze, hesitate, stop, halt,, say nothing, do nothing, keep quiet, fall silent, keep still, hang around, hang about
    pose, watch on, stand by
wait: await, wait for, hold on, hang on, stay put
stretch: limber up, warm up, loosen up, unwind
yoga: meditate, balance, breathe deeply
tai_chi: do tai chi
push_up: do push-ups, do pushups
squat_exercise: do squats, exercise, train, work out
jumping_jacks: do jumping jacks
lift_weights: lift weights, pump iron, bench press, lift the dumbbells, lift dumbbells, curl, do curls, lift the barbell, press weights
shadow_box: spar, box, shadowbox
punch: hit, strike, smack, whack, jab, thump, sock, bash, wallop, beat, batter, pummel, attack
punch_left: hook
kick: boot, kick at, kick out, stamp on, punt
throw: toss, fling, hurl, pitch, lob, chuck, cast, throw away, throw out, toss away
catch: receive, grab the ball, intercept, catch hold
dribble: bounce the ball, play basketball
shoot_basket: shoot, dunk, score, shoot hoops
block: defend, guard, parry, fend off, shield, protect
pick_up: fumble, fumble for, reach for, pick, take, grab, seize, snatch, collect, gather, fetch, retrieve, lift, raise, hold up,
    pick out, take out, get out, take down, take away, get, obtain, scoop, scoop up,
    grasp, clutch, lift up, unpack, pluck, grip, find, pocket
pull: pull out
put_down: stuff, shove in, lower, put, place, set, lay, drop, deposit, leave, set down, lay down, put away, put back, put in,
    pack, stow, store, hang, hang up, plant, position, arrange, stack, pile, load, unload
carry: hold, bring, take along, haul, lug, deliver, transport, carry in, carry out, bring in, keep
pull: drag, tug, yank, heave, draw, pull back, pull up, tow, pull over
push: shove, press against, nudge, push open, push back, roll, slide, shift, move aside
push_person: push away, shove away, shove aside, knock over
present: give, hand, pass, offer, hand over, pass over, give back, hand out, pass on, show, display,
    demonstrate, reveal, hold out, present, serve, share, lend, return something, donate, pay
introduce: introduce oneself
talk: give a speech, make a speech, speechify, say, tell, speak, reply, answer, respond, ask, explain, discuss, chat, converse, mention, state,
    announce, declare, add, continue, remark, comment, suggest, insist, admit, confess, promise, warn,
    report, describe, inform, joke, chatter, babble, ramble, gossip, lecture, preach, recite, narrate, hang out,
    read aloud, propose, demand, order, command, call, exclaim, interrupt, repeat, speak up, talk back,
    chime in, negotiate, bargain, plead with, persuade, convince, complain, grumble, mutter, mumble,
    stammer, stutter, lie to, question, query, inquire, enquire, wonder aloud
whisper: murmur, mutter softly, breathe, confide, hiss
shout: yell, scream, shriek, cry out, call out, holler, roar, bellow, howl, exclaim loudly, screech, swear, cuss, curse loudly
quarrel: bicker, squabble, row, fight, wrangle, clash, feud
argue: debate, dispute, contradict, protest, object, disagree with, challenge
criticize: scold, reprimand, rebuke, lecture at, blame, reproach, chide, berate, nag, tell off, accuse
threaten: menace, intimidate, bully, glare, glower, shake one's fist
apologize: apologise, say sorry, beg forgiveness, excuse oneself, repent
comfort: console, reassure, soothe, calm, calm down, pat, stroke, support, encourage, cheer up, pet
hug: embrace, cuddle, hold close, squeeze, snuggle, clasp
kiss_cheek: kiss, peck, smooch
blow_kiss: blow a kiss
shake_hands: shake, handshake, congratulate, welcome, meet
hold_hands: take by the hand, lead by the hand, take hands, hold hand
high_five: high-five, highfive, slap hands
wave: greet, hail, salute with hand, wave hello, wave goodbye, say goodbye, say hello, bid farewell,
    wave back, signal to
wave_hands: flag down, signal, gesture wildly, flail
beckon: call in, usher, wave in, summon, call over, motion, gesture, invite, wave over
point: indicate, point out, gesture at, aim, direct, signpost
point_up: raise a hand, raise one's hand, put up a hand
bow: thank, curtsy, curtsey, bow down, take a bow, kowtow
greet_bow: nod hello, bow to greet, blow out, blow out the candles, blow on, blow, blow the candles, blow the candle
salute: salute smartly, give a salute
nod: agree, accept, approve, nod along, confirm, acknowledge, consent, say yes
shake_head: refuse, decline, deny, disagree, reject, say no, disapprove, forbid
shrug: shrug off, not know, dismiss
thumbs_up: like, endorse, okay
clap: applaud, cheer on, give applause, clap along
celebrate: cheer, rejoice, triumph, win, party, whoop, exult, jump for joy, hurrah, win, dance with joy, punch the air with joy, throw one's arms up, leap for joy
fist_pump: punch the air, pump a fist, pump, fist pump, fist-pump, fistpump, pump one's fist, fist bump the air
laugh: smile, grin, giggle, chuckle, chortle, beam, smirk, snicker, guffaw, cackle, titter, laugh at,
    crack up, burst out laughing
cry: weep, sob, wail, bawl, whimper, mourn, grieve, sniffle, tear up, break down, burst into tears
cover_face: bury one's face, blush, hide one's face, cringe, despair
facepalm: sigh, groan
scratch_head: wonder, puzzle, ponder aloud, be puzzled, frown, scowl
think: ponder, consider, contemplate, reflect, daydream, muse, brood, meditate on, plan, imagine,, play chess, play cards, play a board game, solve a puzzle, do a puzzle, do homework
    dream, worry, hesitate over, deliberate, concentrate, focus, recall, wonder about
cross_arms: fold arms, sulk, pout, huff, fume
hands_on_hips: stand akimbo, put hands on hips
tap_foot: tap, tap one's foot, fidget
stomp: stamp, stamp one's feet, throw a tantrum
shiver: shudder, tremble, quiver, shake with cold, freeze up
yawn: get tired, tire, stretch sleepily
sneeze: achoo
cough: clear one's throat, choke, splutter, wheeze, gasp, pant
wipe_sweat: mop the brow, wipe one's brow, sweat
fan_self: fan, cool off, cool down
rub_hands: warm one's hands, rub one's hands, dry, dry off, dry one's hands, towel off, pat dry
surrender: give up, raise hands, put hands up, yield, give in
pray: beg, plead, implore, worship
get_hit: flinch, wince, stagger back, be hit, get hurt, fall back
look_at: look, watch, see, observe, notice, stare, gaze, glance, peer, peek, peep, view, study,
    examine, inspect, check, regard, eye, admire, spot, watch over, keep an eye on, look over,
    look into, look for, search for, seek, follow with eyes, face
look_around: search, explore, scan, survey, look about, glance around, peer around, look round
look_up: look upward, gaze up, glance up
look_down: nod off, look downward, gaze down, glance down, bow one's head, hang one's head
look_left: glance left
look_right: glance right
read: peruse, skim, scan a page, read through, browse, leaf through, flip through, study a book, learn,
    revise, review, proofread, look through
read_newspaper: read the paper
write: scribble, jot, jot down, note, note down, sign, fill in, fill out, copy, take notes, record,, take notes, make notes, take a note, sign the form, sign the paper, fill in the form, write a letter, write notes
    print, doodle on paper, draft, compose, mark, grade, correct, address, label, autograph
write_on_blackboard: teach, chalk, lecture on the board, write on the board
draw: sketch, doodle, trace, illustrate, outline, colour, color, shade, design
paint: brush, decorate, daub
type: key in, keyboard, code, program, email, blog, chat online, work, type up, log in, google, search online,
    compute, calculate
use_mouse: click, scroll, drag and drop, select
use_tablet: swipe, tap the screen, scroll through
text_on_phone: text, message, tweet, post, check messages, scroll the phone
call_with_phone: phone, ring, ring up, dial, call up, telephone, make a call
pick_up_phone_answer: answer the phone, pick up the phone
take_photo: photograph, snap, film, record video, take a selfie
watch_tv: watch television, channel-surf
listen_with_headphones: listen, hear, listen in, overhear, eavesdrop
cook: fry, bake, boil, grill, roast, stir, simmer, saute, prepare, heat, toast, microwave, season,, brew, brew coffee, make a coffee, make some coffee, make espresso, make a cup of coffee, make a sandwich, make toast, make pancakes, bake a cake, fry eggs, make soup, put the kettle on
    mix, whisk, knead, scramble eggs, make breakfast, make dinner, make lunch, make tea, make coffee
chop: snip, shear, slice, dice, cut, carve, mince, peel, grate, trim, cut up, chop up
pour: fill, pour out, serve drinks, spill, refill, empty, top up
eat: dine, feast, consume, devour, chew, gobble, swallow, taste, nibble on, have breakfast,, swallow, take a pill, take pills, take medicine, take a tablet, eat cake, eat a piece of cake, have a snack
    have lunch, have dinner, lunch, breakfast, sup
eat_snack: snack, nibble, munch, bite, lick, crunch, graze
drink: sip, gulp, swig, slurp, sup from, drain, toast with, quench
wash_dishes: wash up, do the dishes, rinse, scrub dishes, dry dishes
wash_hands: wash, rinse hands, scrub, soap, lather, bathe, shower
wipe_table: wipe, dust, polish, clean, tidy, tidy up, clean up, scrub the table, clear the table, mop up
wipe_window: wash the window, clean the glass, squeegee
mop: mop the floor, swab
sweep: brush the floor, sweep up, sweep the floor, sweep out, sweep away
vacuum: hoover, vacuum the carpet
iron: press, press clothes, iron clothes
fold_clothes: fold, fold up, do the laundry, sort laundry, hang laundry, tuck, tuck in, smooth, smooth out, straighten the blanket, make the bed
water_plants: water, garden, weed, sprinkle, plant flowers
open_door: open, unlock, open up, let in, let out, open the door, open the box, unwrap, unwrap the present, tear open
close_door: close, shut, lock, slam, shut the door
open_drawer: open the drawer, rummage, pull out the drawer
open_fridge: open the fridge, raid the fridge
press_switch: switch on, switch off, turn on, turn off, flip, toggle, light, dim, flick, light the candles, light a candle, light up, switch the light on, turn on the light, turn off the light, blow out the lamp
push_button: press the button, push the button, hit the button, buzz, ring the bell
knock: rap, tap on, bang on, pound on, knock on
hammer: nail, pound, bang, hammer in
saw: saw through, cut wood
drill: bore, drill into
screw: fix, repair, mend, assemble, tighten, unscrew, adjust, tinker, build, install, construct
smoke: puff, light a cigarette
brush_teeth: clean one's teeth
comb_hair: comb, brush one's hair, style one's hair, do one's hair
check_watch: check the time, look at the clock
count_fingers: count, enumerate, list, tally
play_piano: play the piano, play keys, compose music
play_guitar: strum, pluck the guitar, play guitar, jam, play the guitar, play the electric guitar, play bass, play the bass, rock out, shred
play_violin: fiddle, play the violin, bow the violin
play_drums: drum, beat the drums, play the drums, play the drum kit, bang the drums, hit the drums, drum along
play_flute: pipe, play the flute, blow the flute
sing_with_microphone: sing, croon, chant, serenade, rap, perform, sing along, whistle, yodel
conduct: wave a baton, direct the orchestra
dance: boogie, groove, waltz, tango, shimmy, sway, jive, twist, rock, dance around, bop, salsa, disco
dance_ballet: pirouette, plie, twirl gracefully
dance_hiphop: breakdance, krump, moonwalk
swing_arms: swing, flap, wave one's arms around, play ping pong, play table tennis, play tennis, play badminton, play squash, swing a racket, serve the ball
touch_toes: bend over, stoop, bow down low, reach down
"""
)

# Verbs that name no visible movement: the sentence is kept, the action gets no clip, and the
# diagnostic says why (W113) rather than calling the word unknown.
NOT_ANIMATABLE: dict[str, str] = _table(
    """
a state of mind: know, believe, remember, forget, understand, realize, realise, recognize, recognise,
    suppose, assume, guess, doubt, suspect, expect, hope, wish, want, need, prefer, mean, intend, decide,
    notice silently, feel, sense, fear, trust, mind, care, regret, deserve, learn silently
owning or being: own, have, possess, belong, contain, include, consist, exist, seem, appear, become,
    remain silent, matter, cost, weigh, equal, lack, resemble
time passing: happen, occur, begin, start, end, finish, last, elapse, pass by, continue on, qualify
a sound: hum, purr, tick, ring out, echo, creak, rattle, curse
dressing: put on, take off, dress, undress, wear, button up, zip up, pull on, slip on
"""
)

# Body-part objects that change a verb's clip ("lifts his arm", "raises both hands").
BODY_PART_ACTIONS: dict[tuple[str, str], str] = {
    ("lift", "arm"): "point_up",
    ("lift", "hand"): "point_up",
    ("raise", "arm"): "point_up",
    ("raise", "hand"): "point_up",
    ("lift", "arms"): "surrender",
    ("lift", "hands"): "surrender",
    ("raise", "arms"): "surrender",
    ("raise", "hands"): "surrender",
    ("put", "hands"): "surrender",
    ("shake", "head"): "shake_head",
    ("nod", "head"): "nod",
    ("bow", "head"): "look_down",
    ("lower", "head"): "look_down",
    ("hang", "head"): "look_down",
    ("snap", "fingers"): "beckon",  # "snaps his fingers at Walter": a hand's call for attention, no photo
    ("snap", "finger"): "beckon",
    ("raise", "head"): "look_up",
    ("lift", "head"): "look_up",
    ("turn", "head"): "look_around",
    ("cross", "arms"): "cross_arms",
    ("fold", "arms"): "cross_arms",
    ("fold", "hands"): "pray",
    ("clap", "hands"): "clap",
    ("rub", "hands"): "rub_hands",
    ("wave", "hands"): "wave_hands",
    ("wave", "arms"): "wave_hands",
    ("swing", "arms"): "swing_arms",
    ("stretch", "arms"): "stretch",
    ("stretch", "legs"): "stretch",
    ("cover", "face"): "cover_face",
    ("bury", "face"): "cover_face",
    ("hide", "face"): "cover_face",
    ("scratch", "head"): "scratch_head",
    ("tap", "foot"): "tap_foot",
    ("tap", "feet"): "tap_foot",
    ("stamp", "feet"): "stomp",
    ("stamp", "foot"): "stomp",
    ("shrug", "shoulders"): "shrug",
    ("wipe", "face"): "wipe_sweat",
    ("wipe", "forehead"): "wipe_sweat",
    ("shake", "fist"): "threaten",
    ("slam", "fist"): "punch",
    ("bang", "fist"): "punch",
    ("pound", "fist"): "punch",
    ("pump", "fist"): "fist_pump",
    ("brush", "teeth"): "brush_teeth",
    ("brush", "hair"): "comb_hair",
    ("comb", "hair"): "comb_hair",
    ("wash", "hands"): "wash_hands",
    ("wash", "face"): "wash_hands",
    ("wipe", "hands"): "rub_hands",
    ("put", "arm"): "comfort",
    ("put", "arms"): "hug",
    ("wrap", "arms"): "hug",
    ("throw", "arms"): "hug",
    ("dry", "hands"): "rub_hands",
    ("dry", "hand"): "rub_hands",
    ("dry", "face"): "wipe_sweat",
    ("dry", "hair"): "comb_hair",
    ("pump", "fists"): "fist_pump",
    ("wipe", "hand"): "rub_hands",
    ("touch", "toes"): "touch_toes",
    ("point", "finger"): "point",
    ("hold", "hands"): "hold_hands",
    ("shake", "hands"): "shake_hands",
    ("shake", "hand"): "shake_hands",
    ("take", "hand"): "hold_hands",
    ("kiss", "cheek"): "kiss_cheek",
    ("open", "eyes"): "look_up",
    ("close", "eyes"): "think",
    ("rub", "eyes"): "yawn",
    ("raise", "eyebrows"): "scratch_head",
}


def verb_action(verb: str, particle: str = "") -> str | None:
    """Action for a verb (and its particle) from this table; "" when it is known not animatable; None
    when the table does not know it."""
    if particle:
        hit = VERB_ACTIONS.get(f"{verb} {particle}")
        if hit:
            return hit
        if f"{verb} {particle}" in NOT_ANIMATABLE:
            return ""  # "puts on her coat": dressing, not putting a thing down
    hit = VERB_ACTIONS.get(verb)
    if hit:
        return hit
    if verb in NOT_ANIMATABLE:
        return ""
    return None


# A verb whose clip differs when it holds a thing: balancing plates is carrying them, not a yoga pose.
WITH_THING: dict[str, str] = {"balance": "carry", "cradle": "carry", "clutch": "carry"}

# Falling asleep with nothing to lie on: the head drops where one sits or stands.
DOZE_VERBS = frozenset({"doze", "nod", "drift", "fall", "nap", "snooze"})


def not_animatable_reason(verb: str) -> str:
    """Why a verb has no clip ("a state of mind"), or "" when it is not one of those verbs."""
    return NOT_ANIMATABLE.get(verb, "")
