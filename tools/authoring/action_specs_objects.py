"""Authored actions that use an object: postures on furniture, devices, instruments, tools, chores.

Interaction kinds (what the target object must offer, matched by contact joint in the catalog):
seat, bed, keyboard, instrument, handheld, surface, button, door, container, tool, bag, floor_item.
"""

from __future__ import annotations

from tools.authoring.author_actions import Spec, cycle, hold, loop, seq
from wana.domain.posing import arm, arms, head, hips, legs, merge, neutral, spine

N = neutral()
SIT_ROOT = (0.0, -0.42, -0.22)
SIT_LEGS = legs((0.0, -0.12, 1.0), (0.0, -1.0, 0.08))
SIT = merge(N, SIT_LEGS, spine(4))
LIE_ROOT = (0.0, -0.45, -0.6)
LIE = merge(hips(-90), arms((0.15, -1.0, 0.0), (0.1, -1.0, 0.0)), head(10))
KNEEL = merge(N, legs((0.0, -0.6, 0.8), (0.0, -0.3, -1.0)))
SQUAT = merge(N, legs((0.15, -0.5, 1.0), (0.05, -1.0, -0.35), 0.0), spine(25))
BOTH_MIDDLE = ["LeftHandMiddle1", "RightHandMiddle1"]


def I(obj: str, contacts: list[str], window: tuple[float, float]) -> dict:  # noqa: E743 - short spec helper
    return {"object": obj, "contacts": contacts, "window": list(window)}


def _typing(fore_x: float = -0.1) -> tuple[dict, dict]:
    a = merge(
        SIT,
        spine(8),
        head(20),
        arm("L", (0.15, -1.0, 0.35), (fore_x, -0.1, 1.0), (0, 0, -10)),
        arm("R", (0.15, -1.0, 0.35), (fore_x, -0.02, 1.0), (0, 0, -10)),
    )
    b = merge(
        SIT,
        spine(8),
        head(20),
        arm("L", (0.15, -1.0, 0.35), (fore_x, -0.02, 1.0), (0, 0, -10)),
        arm("R", (0.15, -1.0, 0.35), (fore_x, -0.1, 1.0), (0, 0, -10)),
    )
    return a, b


def _right(upper, fore, hand=(0, 0, 0), base=None) -> dict:
    return merge(N if base is None else base, arm("R", upper, fore, hand))


def _both(upper, fore, hand=(0, 0, 0), base=None) -> dict:
    return merge(N if base is None else base, arms(upper, fore, hand))


def specs() -> list[Spec]:
    s: list[Spec] = []
    add = s.append
    # --- postures -------------------------------------------------------------------------------
    half_sit = merge(N, legs((0.0, -0.6, 0.8), (0.0, -1.0, 0.2)), spine(25))
    add(
        Spec(
            "sit",
            ["posture", "furniture"],
            ["sit down", "take a seat", "be seated", "sit on"],
            seq(
                (0.0, N, "linear"),
                (0.6, half_sit, "in_out", (0, -0.22, -0.12)),
                (0.6, SIT, "out", SIT_ROOT),
                (0.8, SIT, "linear", SIT_ROOT),
            ),
            body_parts=["full_body"],
            interaction=I("seat", ["Hips"], (1.2, 2.0)),
        )
    )
    add(
        Spec(
            "stand",
            ["posture"],
            ["stand up", "get up", "rise", "stand still"],
            seq(
                (0.0, SIT, "linear", SIT_ROOT),
                (0.6, half_sit, "in_out", (0, -0.22, -0.12)),
                (0.6, N, "out"),
                (0.6, N, "linear"),
            ),
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "sit_on_floor",
            ["posture"],
            ["sit on the ground", "sit cross-legged"],
            seq(
                (0.0, N, "linear"),
                (0.7, SQUAT, "in_out", (0, -0.4, -0.1)),
                (
                    0.7,
                    merge(N, legs((0.5, -0.1, 1.0), (-0.6, -0.1, 0.8)), spine(10)),
                    "out",
                    (0, -0.82, -0.25),
                ),
                (
                    0.8,
                    merge(N, legs((0.5, -0.1, 1.0), (-0.6, -0.1, 0.8)), spine(10)),
                    "linear",
                    (0, -0.82, -0.25),
                ),
            ),
            body_parts=["full_body"],
            interaction=None,
        )
    )
    add(
        Spec(
            "lie_down",
            ["posture", "furniture", "rest"],
            ["lie", "lay down", "lie on", "go to bed", "sleep"],
            seq(
                (0.0, N, "linear"),
                (0.7, SIT, "in_out", SIT_ROOT),
                (0.9, LIE, "in_out", LIE_ROOT),
                (1.0, LIE, "linear", LIE_ROOT),
            ),
            body_parts=["full_body"],
            interaction=I("bed", ["Hips"], (1.6, 2.6)),
        )
    )
    add(
        Spec(
            "kneel",
            ["posture"],
            ["kneel down", "get on one's knees"],
            hold(KNEEL, 2.6, 0.7, (0, -0.38, 0.0)),
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "squat",
            ["posture", "exercise"],
            ["crouch", "squat down", "duck"],
            hold(SQUAT, 2.2, 0.6, (0, -0.38, -0.15)),
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "lean_on_wall",
            ["posture", "rest"],
            ["lean", "lean against"],
            hold(
                merge(N, hips(0, 0, 6), spine(-4, 0, -6), arm("L", (0.5, -0.8, -0.3), (-0.6, -0.2, -0.3))),
                3.0,
                0.7,
                (0.1, -0.02, -0.05),
            ),
            body_parts=["full_body"],
            interaction=I("surface", ["LeftHand"], (0.7, 2.3)),
        )
    )
    add(
        Spec(
            "sleep",
            ["rest", "furniture"],
            ["nap", "doze", "fall asleep"],
            loop(
                LIE,
                merge(LIE, spine(-6), head(6), arms((0.18, -1.0, 0.05), (0.12, -1.0, 0.05))),
                4.0,
                LIE_ROOT,
            ),
            looping=True,
            body_parts=["full_body"],
            interaction=I("bed", ["Hips"], (0.0, 4.0)),
        )
    )
    # --- computer and devices --------------------------------------------------------------------
    ta, tb = _typing()
    add(
        Spec(
            "type",
            ["computer", "work", "seated"],
            ["type on", "use the laptop", "use the computer", "work on the laptop", "typewrite", "key in"],
            loop(ta, tb, 0.4),
            looping=True,
            interaction=I("keyboard", BOTH_MIDDLE, (0.0, 0.4)),
        )
    )
    mouse = merge(SIT, spine(6), head(18), arm("R", (0.3, -0.9, 0.35), (0.1, -0.1, 1.0), (0, 0, -10)))
    add(
        Spec(
            "use_mouse",
            ["computer", "work", "seated"],
            ["click", "move the mouse", "browse"],
            loop(mouse, merge(mouse, arm("R", (0.35, -0.9, 0.3), (0.2, -0.1, 1.0), (0, 0, -10))), 1.2),
            looping=True,
            interaction=I("keyboard", ["RightHandMiddle1"], (0.0, 1.2)),
        )
    )
    phone_ear = _right((0.35, -0.7, 0.35), (-0.35, 1.0, 0.05), (0, 0, 30))
    add(
        Spec(
            "call_with_phone",
            ["phone", "talk", "device"],
            ["call", "phone", "make a call", "talk on the phone", "ring", "dial"],
            seq(
                (0.0, N, "linear"),
                (0.6, phone_ear, "in_out"),
                (0.9, merge(phone_ear, head(0, 0, -8)), "in_out"),
                (0.9, merge(phone_ear, head(5, 10, -4)), "in_out"),
                (0.9, phone_ear, "in_out"),
                (0.6, N, "in_out"),
            ),
            interaction=I("handheld", ["RightHand"], (0.6, 3.3)),
        )
    )
    text = merge(_both((0.15, -1.0, 0.2), (-0.25, 0.3, 1.0), (-20, 0, 0)), head(30))
    add(
        Spec(
            "text_on_phone",
            ["phone", "device"],
            ["text", "message", "check the phone", "look at the phone", "use the phone"],
            cycle(text, merge(text, arm("R", (0.15, -1.0, 0.2), (-0.3, 0.35, 1.0), (-30, 0, 0))), 0.5, 4),
            interaction=I("handheld", ["RightHand"], (0.4, 2.4)),
        )
    )
    photo = merge(_both((0.35, -0.5, 0.5), (-0.45, 0.6, 0.6), (0, 0, 0)), head(-5))
    add(
        Spec(
            "take_photo",
            ["camera", "device"],
            ["photograph", "take a picture", "snap"],
            hold(photo, 2.4, 0.6),
            interaction=I("handheld", ["RightHand"], (0.6, 1.8)),
        )
    )
    remote = _right((0.15, -0.7, 0.7), (0.0, 0.1, 1.0), (-10, 0, 0))
    add(
        Spec(
            "watch_tv",
            ["tv", "leisure"],
            ["watch", "watch television", "use the remote"],
            hold(merge(remote, head(-3)), 3.0, 0.6),
        )
    )
    # --- drinking, eating, kitchen ----------------------------------------------------------------
    cup_low = _right((0.2, -0.9, 0.4), (-0.2, 0.2, 1.0))
    # The elbow comes up in front and the forearm folds back, so that the wrist (where the cup is held)
    # ends 15 cm from the head's centre, at the lips; the sip holds for most of the window.
    cup_mouth = merge(_right((-0.25, 0.05, 0.97), (-0.24, 0.49, -0.84), (0, 0, 20)), head(-15))
    add(
        Spec(
            "drink",
            ["eat", "kitchen", "handheld"],
            ["sip", "drink from", "have a drink", "drink water", "drink soda", "drink coffee", "drink tea"],
            seq(
                (0.0, N, "linear"),
                (0.5, cup_low, "in_out"),
                (0.5, cup_mouth, "in_out"),
                (1.4, cup_mouth, "linear"),
                (0.5, cup_low, "in_out"),
                (0.4, N, "in_out"),
            ),
            interaction=I("handheld", ["RightHand"], (0.5, 2.9)),
        )
    )
    spoon_low = merge(_right((0.2, -0.9, 0.4), (-0.1, 0.0, 1.0)), head(20))
    spoon_up = merge(_right((0.3, -0.6, 0.5), (-0.5, 0.8, 0.3)), head(5))
    add(
        Spec(
            "eat",
            ["eat", "kitchen"],
            ["have a meal", "have lunch", "have dinner", "dine", "have breakfast"],
            cycle(spoon_low, spoon_up, 1.0, 3),
            interaction=I("surface", ["RightHandMiddle1"], (0.4, 3.4)),
        )
    )
    stir = merge(
        N,
        arm("R", (0.2, -0.8, 0.6), (-0.1, -0.2, 1.0)),
        arm("L", (0.2, -0.8, 0.5), (-0.4, -0.1, 1.0)),
        head(25),
    )
    add(
        Spec(
            "cook",
            ["kitchen", "work"],
            ["stir", "fry", "make food", "prepare food"],
            cycle(stir, merge(stir, arm("R", (0.1, -0.8, 0.6), (-0.4, -0.2, 1.0))), 0.8, 4),
            interaction=I("surface", ["RightHandMiddle1"], (0.4, 3.6)),
        )
    )
    chop_up = merge(
        N,
        arm("R", (0.25, -0.6, 0.6), (-0.1, 0.3, 1.0)),
        arm("L", (0.15, -0.8, 0.5), (-0.5, -0.2, 1.0)),
        head(30),
        spine(10),
    )
    chop_dn = merge(chop_up, arm("R", (0.25, -0.8, 0.55), (-0.1, -0.4, 1.0)))
    add(
        Spec(
            "chop",
            ["kitchen", "tool"],
            ["cut", "slice", "dice"],
            cycle(chop_up, chop_dn, 0.4, 6),
            interaction=I("surface", ["RightHandMiddle1"], (0.4, 2.8)),
        )
    )
    wash = merge(N, arms((0.2, -0.8, 0.5), (-0.3, -0.3, 1.0)), spine(15), head(25))
    add(
        Spec(
            "wash_dishes",
            ["kitchen", "chore"],
            ["do the dishes", "wash up", "rinse"],
            cycle(wash, merge(N, arms((0.3, -0.8, 0.45), (-0.1, -0.4, 1.0)), spine(15), head(25)), 0.8, 4),
            interaction=I("surface", BOTH_MIDDLE, (0.4, 3.6)),
        )
    )
    pour = _right((0.35, -0.4, 0.7), (0.1, 0.1, 1.0), (0, 0, 0))
    add(
        Spec(
            "pour",
            ["kitchen", "handheld"],
            ["pour water", "fill"],
            seq(
                (0.0, N, "linear"),
                (0.5, pour, "in_out"),
                (0.6, merge(pour, arm("R", (0.35, -0.4, 0.7), (0.1, 0.1, 1.0), (0, 0, -70))), "in_out"),
                (0.8, merge(pour, arm("R", (0.35, -0.4, 0.7), (0.1, 0.1, 1.0), (0, 0, -70))), "linear"),
                (0.5, pour, "in_out"),
                (0.5, N, "in_out"),
            ),
            interaction=I("handheld", ["RightHand"], (0.5, 2.4)),
        )
    )
    add(
        Spec(
            "open_fridge",
            ["kitchen", "door"],
            ["open the refrigerator", "open the fridge"],
            seq(
                (0.0, N, "linear"),
                (0.5, _right((0.3, -0.3, 0.9), (0.0, 0.0, 1.0)), "in_out"),
                (0.8, merge(_right((0.7, -0.3, 0.6), (0.6, 0.0, 0.5)), spine(0, -15)), "in_out"),
                (0.6, N, "in_out"),
            ),
            interaction=I("door", ["RightHand"], (0.5, 1.3)),
        )
    )
    # --- music ---------------------------------------------------------------------------------------
    pa, pb = _typing(0.05)
    add(
        Spec(
            "play_piano",
            ["music", "instrument", "seated"],
            ["play the piano", "play keyboard", "play music"],
            loop(
                merge(pa, arm("L", (0.35, -0.9, 0.4), (0.1, -0.1, 1.0))),
                merge(pb, arm("R", (0.35, -0.9, 0.4), (0.1, -0.1, 1.0))),
                0.8,
            ),
            looping=True,
            interaction=I("instrument", BOTH_MIDDLE, (0.0, 0.8)),
        )
    )
    guitar = merge(
        N,
        arm("L", (0.5, -0.5, 0.6), (0.7, 0.3, 0.6), (0, 0, 20)),
        arm("R", (0.3, -0.8, 0.4), (-0.8, 0.1, 0.5)),
        head(20, -10),
    )
    add(
        Spec(
            "play_guitar",
            ["music", "instrument"],
            ["strum", "play the guitar"],
            loop(guitar, merge(guitar, arm("R", (0.3, -0.8, 0.4), (-0.8, -0.3, 0.5))), 0.5),
            looping=True,
            interaction=I("handheld", ["LeftHand", "RightHand"], (0.0, 0.5)),
        )
    )
    drums_a = merge(
        SIT,
        arm("L", (0.3, -0.8, 0.5), (0.1, 0.4, 1.0)),
        arm("R", (0.3, -0.8, 0.5), (0.1, -0.2, 1.0)),
        head(10),
    )
    drums_b = merge(
        SIT,
        arm("L", (0.3, -0.8, 0.5), (0.1, -0.2, 1.0)),
        arm("R", (0.3, -0.8, 0.5), (0.1, 0.4, 1.0)),
        head(10),
    )
    add(
        Spec(
            "play_drums",
            ["music", "instrument", "seated"],
            ["drum", "play the drums"],
            loop(drums_a, drums_b, 0.5),
            looping=True,
            interaction=I("instrument", BOTH_MIDDLE, (0.0, 0.5)),
        )
    )
    violin = merge(
        N,
        arm("L", (0.5, 0.0, 0.9), (-0.2, 0.2, 1.0), (0, 0, 40)),
        arm("R", (0.6, -0.4, 0.5), (-1.0, 0.1, 0.2)),
        head(10, 20, 15),
    )
    add(
        Spec(
            "play_violin",
            ["music", "instrument"],
            ["fiddle", "play the violin"],
            loop(violin, merge(violin, arm("R", (0.7, -0.3, 0.3), (0.2, 0.1, 1.0))), 1.2),
            looping=True,
            interaction=I("handheld", ["LeftHand"], (0.0, 1.2)),
        )
    )
    flute = merge(
        N,
        arm("L", (0.3, -0.5, 0.6), (-0.7, 0.2, 0.6)),
        arm("R", (0.5, -0.4, 0.5), (0.5, 0.4, 0.7)),
        head(0, -10),
    )
    add(
        Spec(
            "play_flute",
            ["music", "instrument"],
            ["play the flute", "blow the flute"],
            loop(flute, merge(flute, spine(-4, 6)), 2.0),
            looping=True,
            interaction=I("handheld", ["LeftHand"], (0.0, 2.0)),
        )
    )
    mic = merge(_right((0.25, -0.6, 0.6), (-0.4, 0.8, 0.5), (0, 0, 20)), head(-8))
    add(
        Spec(
            "sing_with_microphone",
            ["music", "talk", "handheld"],
            ["sing", "sing into the microphone", "perform a song", "karaoke", "hum"],
            cycle(
                mic,
                merge(mic, arm("L", (0.6, -0.1, 0.6), (0.7, 0.3, 0.5)), spine(-5, 8), head(-15, 8)),
                1.2,
                3,
            ),
            interaction=I("handheld", ["RightHand"], (0.4, 4.0)),
        )
    )
    phones = merge(_both((0.6, 0.2, 0.05), (-0.4, 0.9, 0.0), (0, 0, 30)), head(5))
    add(
        Spec(
            "listen_with_headphones",
            ["music", "device", "rest"],
            ["listen to music", "put on headphones", "listen"],
            loop(phones, merge(phones, head(-5, 0, 6)), 1.0),
            looping=True,
            interaction=I("handheld", ["LeftHand", "RightHand"], (0.0, 1.0)),
        )
    )
    conduct_a = _both((0.6, 0.2, 0.5), (0.3, 0.6, 0.6))
    add(
        Spec(
            "conduct",
            ["music"],
            ["conduct an orchestra", "wave a baton"],
            loop(conduct_a, _both((0.5, -0.3, 0.6), (0.2, -0.1, 1.0)), 0.8),
            looping=True,
        )
    )
    # --- reading, writing, teaching --------------------------------------------------------------------
    book = merge(_both((0.1, -1.0, 0.3), (-0.35, 0.4, 1.0), (-25, 0, 0)), head(30))
    add(
        Spec(
            "read",
            ["read", "book", "handheld"],
            ["read a book", "study", "browse the book", "look through"],
            seq(
                (0.0, N, "linear"),
                (0.6, book, "in_out"),
                (1.6, merge(book, head(30, 6)), "linear"),
                (0.4, merge(book, arm("R", (0.2, -0.9, 0.35), (-0.6, 0.5, 0.8), (-25, 0, 0))), "in_out"),
                (0.4, book, "in_out"),
                (1.4, merge(book, head(30, 4)), "linear"),
                (0.6, N, "in_out"),
            ),
            interaction=I("handheld", ["LeftHand", "RightHand"], (0.6, 4.4)),
        )
    )
    paper = _both((0.2, -0.7, 0.5), (-0.1, 0.6, 0.9), (-10, 0, 0))
    add(
        Spec(
            "read_newspaper",
            ["read", "handheld"],
            ["read the newspaper", "read the paper", "read a letter"],
            hold(merge(paper, head(15)), 3.5, 0.6),
            interaction=I("handheld", ["LeftHand", "RightHand"], (0.6, 2.9)),
        )
    )
    board_a = merge(N, arm("R", (0.3, 0.3, 0.9), (0.1, 0.5, 1.0), (0, 0, -20)), head(-10))
    board_b = merge(N, arm("R", (0.6, 0.2, 0.8), (0.5, 0.4, 0.8), (0, 0, -20)), head(-10, -15))
    add(
        Spec(
            "write_on_blackboard",
            ["teach", "write", "surface"],
            ["write on the board", "write on the whiteboard", "draw on the board", "teach", "chalk"],
            cycle(board_a, board_b, 0.9, 4),
            interaction=I("surface", ["RightHandMiddle1"], (0.4, 4.0)),
        )
    )
    write = merge(
        SIT,
        spine(12),
        head(30),
        arm("R", (0.25, -0.9, 0.4), (-0.2, -0.1, 1.0), (0, 0, -20)),
        arm("L", (0.2, -0.9, 0.4), (-0.5, -0.1, 1.0)),
    )
    add(
        Spec(
            "write",
            ["write", "seated", "work"],
            ["write a letter", "take notes", "sign", "note down", "jot"],
            loop(write, merge(write, arm("R", (0.3, -0.9, 0.4), (0.0, -0.1, 1.0), (0, 0, -20))), 1.0),
            looping=True,
            interaction=I("surface", ["RightHandMiddle1"], (0.0, 1.0)),
        )
    )
    add(
        Spec(
            "draw",
            ["art", "write"],
            ["sketch", "doodle"],
            loop(write, merge(write, arm("R", (0.2, -0.9, 0.45), (-0.3, -0.1, 1.0), (0, 0, -35))), 1.6),
            looping=True,
            interaction=I("surface", ["RightHandMiddle1"], (0.0, 1.6)),
        )
    )
    paint_a = merge(N, arm("R", (0.4, -0.2, 0.9), (0.2, 0.4, 1.0)), head(-5))
    add(
        Spec(
            "paint",
            ["art", "surface"],
            ["paint a picture", "paint the wall", "brush"],
            cycle(paint_a, merge(N, arm("R", (0.4, -0.5, 0.8), (0.2, -0.3, 1.0)), head(5)), 1.0, 3),
            interaction=I("surface", ["RightHandMiddle1"], (0.4, 3.4)),
        )
    )
    present = merge(N, arm("R", (0.8, 0.1, 0.5), (0.8, 0.3, 0.6), (0, 0, 0)), head(0, -25))
    add(
        Spec(
            "present",
            ["teach", "talk", "work"],
            ["give a presentation", "lecture", "explain the slides", "show"],
            cycle(present, merge(N, arm("R", (0.6, -0.3, 0.6), (0.1, 0.3, 1.0)), head(0, 5)), 1.5, 2),
        )
    )
    # --- tools, sport equipment, chores ---------------------------------------------------------------
    bag_guard = merge(
        N, arms((0.3, -0.7, 0.4), (-0.3, 0.8, 0.5), (0, 0, 0)), legs((0.1, -1.0, 0.15), (0.05, -1.0, 0.0))
    )
    punch_r = merge(bag_guard, arm("R", (0.1, -0.1, 1.0), (0.0, 0.0, 1.0)), spine(5, 20))
    punch_l = merge(bag_guard, arm("L", (0.1, -0.1, 1.0), (0.0, 0.0, 1.0)), spine(5, -20))
    add(
        Spec(
            "punch_bag",
            ["sport", "fight", "exercise"],
            ["hit the punching bag", "box", "punch the bag", "train boxing"],
            seq(
                (0.0, N, "linear"),
                (0.4, bag_guard, "in_out"),
                (0.2, punch_r, "out"),
                (0.25, bag_guard, "in_out"),
                (0.2, punch_l, "out"),
                (0.25, bag_guard, "in_out"),
                (0.2, punch_r, "out"),
                (0.3, bag_guard, "in_out"),
                (0.4, N, "in_out"),
            ),
            interaction=I("bag", ["RightHand"], (0.6, 0.6)),
        )
    )
    saw_a = merge(
        N,
        spine(25),
        head(20),
        arm("R", (0.3, -0.6, 0.5), (0.0, -0.4, 1.0)),
        arm("L", (0.6, -0.8, 0.5), (-0.1, -0.9, 0.4)),
        legs((0.05, -1.0, 0.2), (0.0, -1.0, 0.0)),
    )
    saw_b = merge(saw_a, arm("R", (0.25, -0.9, -0.2), (0.0, -0.8, 0.6)))
    add(
        Spec(
            "saw",
            ["tool", "work", "workshop"],
            ["saw wood", "cut wood", "use the saw"],
            cycle(saw_a, saw_b, 0.7, 5),
            interaction=I("tool", ["RightHand"], (0.4, 3.9)),
        )
    )
    ham_up = merge(
        N,
        spine(15),
        head(25),
        arm("R", (0.3, -0.2, 0.6), (-0.1, 0.9, 0.1)),
        arm("L", (0.2, -0.8, 0.5), (-0.3, -0.4, 1.0)),
    )
    ham_dn = merge(ham_up, arm("R", (0.3, -0.7, 0.6), (-0.1, -0.4, 1.0)))
    add(
        Spec(
            "hammer",
            ["tool", "work", "workshop"],
            ["hammer a nail", "pound", "nail", "hit with a hammer"],
            cycle(ham_up, ham_dn, 0.55, 5),
            interaction=I("tool", ["RightHand"], (0.4, 3.2)),
        )
    )
    drill = merge(
        N, arm("R", (0.2, -0.3, 0.9), (0.0, 0.0, 1.0)), arm("L", (0.1, -0.4, 0.9), (-0.4, 0.0, 1.0)), head(5)
    )
    add(
        Spec(
            "drill",
            ["tool", "work", "workshop"],
            ["use the drill", "bore"],
            loop(drill, merge(drill, spine(6, 3), arm("R", (0.2, -0.15, 0.9), (0.0, 0.12, 1.0))), 0.3),
            looping=True,
            interaction=I("tool", ["RightHand"], (0.0, 0.3)),
        )
    )
    screw = merge(
        N,
        spine(15),
        head(25),
        arm("R", (0.3, -0.7, 0.5), (-0.1, -0.3, 1.0)),
        arm("L", (0.2, -0.8, 0.5), (-0.3, -0.4, 1.0)),
    )
    add(
        Spec(
            "screw",
            ["tool", "workshop"],
            ["use the screwdriver", "tighten", "fix", "repair"],
            cycle(
                screw,
                merge(
                    N,
                    spine(15),
                    head(25),
                    arm("R", (0.3, -0.7, 0.5), (-0.1, -0.3, 1.0), (0, 0, 80)),
                    arm("L", (0.2, -0.8, 0.5), (-0.3, -0.4, 1.0)),
                ),
                0.6,
                5,
            ),
            interaction=I("tool", ["RightHand"], (0.4, 3.4)),
        )
    )
    sweep_a = merge(
        N,
        spine(15),
        arm("R", (0.3, -0.9, 0.3), (0.1, -0.9, 0.6)),
        arm("L", (0.3, -0.5, 0.6), (-0.3, -0.5, 0.8)),
        head(20),
    )
    sweep_b = merge(
        N,
        spine(15, -15),
        arm("R", (0.5, -0.9, -0.1), (0.3, -0.9, 0.1)),
        arm("L", (0.1, -0.6, 0.6), (-0.6, -0.6, 0.5)),
        head(20, 10),
    )
    add(
        Spec(
            "sweep",
            ["chore", "tool", "clean"],
            ["sweep the floor", "broom", "clean the floor"],
            cycle(sweep_a, sweep_b, 1.0, 3),
            interaction=I("tool", ["RightHand", "LeftHand"], (0.4, 3.4)),
        )
    )
    add(
        Spec(
            "mop",
            ["chore", "tool", "clean"],
            ["mop the floor"],
            cycle(sweep_a, merge(sweep_b, spine(20, 15)), 1.2, 3),
            interaction=I("tool", ["RightHand", "LeftHand"], (0.4, 4.0)),
        )
    )
    add(
        Spec(
            "vacuum",
            ["chore", "tool", "clean"],
            ["hoover", "vacuum the floor"],
            cycle(
                merge(N, arm("R", (0.2, -0.9, 0.5), (0.0, -0.7, 0.9))),
                merge(N, arm("R", (0.2, -0.4, 0.9), (0.0, -0.5, 1.0)), spine(15)),
                1.2,
                3,
            ),
            interaction=I("tool", ["RightHand"], (0.4, 4.0)),
        )
    )
    wipe_a = merge(N, spine(30), head(20), arm("R", (0.2, -0.7, 0.7), (0.4, -0.5, 0.9)))
    wipe_b = merge(N, spine(30), head(20), arm("R", (0.0, -0.7, 0.7), (-0.5, -0.5, 0.9)))
    add(
        Spec(
            "wipe_table",
            ["chore", "clean", "surface"],
            ["wipe", "clean the table", "polish", "dust"],
            cycle(wipe_a, wipe_b, 0.8, 4),
            interaction=I("surface", ["RightHandMiddle1"], (0.4, 3.6)),
        )
    )
    add(
        Spec(
            "wipe_window",
            ["chore", "clean", "surface"],
            ["clean the window", "wash the window"],
            cycle(
                merge(N, arm("R", (0.4, 0.2, 0.9), (0.4, 0.4, 0.8))),
                merge(N, arm("R", (0.1, 0.2, 0.9), (-0.4, 0.4, 0.8))),
                0.8,
                4,
            ),
            interaction=I("surface", ["RightHandMiddle1"], (0.4, 3.6)),
        )
    )
    iron = merge(N, spine(20), head(30), arm("R", (0.2, -0.8, 0.5), (0.0, -0.3, 1.0)))
    add(
        Spec(
            "iron",
            ["chore", "clean"],
            ["iron clothes", "press the shirt"],
            cycle(iron, merge(N, spine(25), head(30), arm("R", (0.2, -0.6, 0.8), (0.0, -0.4, 1.0))), 1.0, 3),
            interaction=I("surface", ["RightHandMiddle1"], (0.4, 3.4)),
        )
    )
    fold = merge(N, spine(20), head(30), arms((0.2, -0.8, 0.5), (-0.2, -0.2, 1.0)))
    add(
        Spec(
            "fold_clothes",
            ["chore"],
            ["fold the laundry", "fold"],
            cycle(fold, merge(N, spine(20), head(30), arms((0.2, -0.8, 0.5), (-0.6, 0.3, 0.7))), 1.0, 3),
            interaction=I("surface", BOTH_MIDDLE, (0.4, 3.4)),
        )
    )
    water = merge(N, arm("R", (0.4, -0.6, 0.6), (0.3, -0.2, 1.0), (0, 0, -40)), head(25))
    add(
        Spec(
            "water_plants",
            ["chore", "garden", "handheld"],
            ["water the plants", "water the flowers", "garden"],
            cycle(water, merge(water, arm("R", (0.5, -0.5, 0.6), (0.3, -0.5, 1.0), (0, 0, -50))), 1.2, 2),
            interaction=I("handheld", ["RightHand"], (0.4, 2.8)),
        )
    )
    brush_t = merge(_right((0.3, -0.6, 0.4), (-0.6, 0.75, 0.3)), head(-5))
    add(
        Spec(
            "brush_teeth",
            ["hygiene", "bathroom"],
            ["clean teeth"],
            cycle(brush_t, merge(_right((0.3, -0.6, 0.4), (-0.75, 0.6, 0.3))), 0.3, 8),
        )
    )
    comb = merge(_right((0.6, 0.4, 0.1), (-0.3, 0.9, 0.0)), head(-5))
    add(
        Spec(
            "comb_hair",
            ["hygiene", "bathroom"],
            ["brush hair", "comb"],
            cycle(comb, merge(_right((0.6, 0.4, -0.2), (-0.3, 0.8, -0.4))), 0.8, 4),
        )
    )
    add(
        Spec(
            "wash_hands",
            ["hygiene", "bathroom"],
            ["rinse hands"],
            cycle(
                merge(wash, spine(10)),
                merge(N, arms((0.2, -0.8, 0.5), (-0.6, -0.3, 0.8)), spine(10), head(25)),
                0.5,
                5,
            ),
            interaction=I("surface", BOTH_MIDDLE, (0.4, 2.9)),
        )
    )
    # --- buttons, doors, picking things up ---------------------------------------------------------------
    press = _right((0.2, -0.1, 1.0), (0.0, 0.0, 1.0), (0, 0, 0))
    add(
        Spec(
            "push_button",
            ["device", "button"],
            ["press the button", "press", "hit the button", "ring the bell", "call the elevator"],
            seq(
                (0.0, N, "linear"),
                (0.5, _right((0.2, -0.3, 0.9), (0.0, 0.0, 1.0)), "in_out"),
                (0.25, press, "out"),
                (0.35, press, "linear"),
                (0.5, N, "in_out"),
            ),
            interaction=I("button", ["RightHandMiddle1"], (0.75, 1.1)),
        )
    )
    add(
        Spec(
            "press_switch",
            ["device", "button"],
            ["switch on", "switch off", "turn on the light", "turn off the light", "flip the switch"],
            seq(
                (0.0, N, "linear"),
                (0.5, _right((0.3, 0.0, 0.9), (0.0, 0.2, 1.0)), "in_out"),
                (0.2, _right((0.3, -0.1, 0.9), (0.0, 0.1, 1.0)), "out"),
                (0.5, N, "in_out"),
            ),
            interaction=I("button", ["RightHandMiddle1"], (0.5, 0.7)),
        )
    )
    knob = _right((0.2, -0.5, 0.9), (0.0, 0.0, 1.0))
    add(
        Spec(
            "open_door",
            ["door"],
            ["open", "open the door", "unlock"],
            seq(
                (0.0, N, "linear"),
                (0.5, knob, "in_out"),
                (0.3, _right((0.2, -0.5, 0.9), (0.0, 0.0, 1.0), (0, 0, -45)), "in_out"),
                (0.7, merge(_right((0.2, -0.6, 0.6), (0.1, -0.2, 0.6), (0, 0, -45)), spine(-5)), "in_out"),
                (0.5, N, "in_out"),
            ),
            interaction=I("door", ["RightHand"], (0.5, 0.8)),
        )
    )
    add(
        Spec(
            "close_door",
            ["door"],
            ["close", "shut", "shut the door", "lock"],
            seq(
                (0.0, N, "linear"),
                (0.5, _right((0.3, -0.4, 0.6), (0.2, -0.1, 0.8)), "in_out"),
                (0.7, merge(_right((0.2, -0.3, 0.95), (0.0, 0.0, 1.0)), spine(8)), "in_out"),
                (0.5, N, "in_out"),
            ),
            interaction=I("door", ["RightHand"], (0.5, 1.2)),
        )
    )
    knock_a = _right((0.4, -0.4, 0.7), (-0.1, 0.6, 0.8), (0, 0, 0))
    add(
        Spec(
            "knock",
            ["door"],
            ["knock on the door", "rap"],
            cycle(knock_a, _right((0.3, -0.3, 0.9), (0.0, 0.3, 1.0)), 0.3, 3),
            interaction=I("door", ["RightHandMiddle1"], (0.55, 0.6)),
        )
    )
    add(
        Spec(
            "open_drawer",
            ["furniture", "container"],
            ["pull out the drawer", "open the cabinet"],
            seq(
                (0.0, N, "linear"),
                (0.6, merge(_right((0.15, -0.8, 0.5), (0.0, -0.3, 1.0)), spine(20)), "in_out"),
                (0.6, merge(_right((0.15, -0.95, 0.1), (0.0, -0.9, 0.4)), spine(15)), "in_out"),
                (0.5, N, "in_out"),
            ),
            interaction=I("container", ["RightHand"], (0.6, 0.8)),
        )
    )
    bend_pick = merge(
        N,
        spine(60),
        head(10),
        arm("R", (0.1, -1.0, 0.4), (0.0, -1.0, 0.3)),
        legs((0.0, -0.9, 0.4), (0.0, -1.0, -0.2)),
    )
    add(
        Spec(
            "pick_up",
            ["object", "handheld"],
            ["pick up", "take", "grab", "lift", "get", "collect", "fetch"],
            seq(
                (0.0, N, "linear"),
                (0.7, bend_pick, "in_out", (0, -0.12, -0.08)),
                (0.3, bend_pick, "linear", (0, -0.12, -0.08)),
                (0.7, _right((0.2, -0.9, 0.3), (-0.1, -0.2, 1.0)), "in_out"),
                (0.4, _right((0.2, -0.9, 0.3), (-0.1, -0.2, 1.0)), "linear"),
            ),
            body_parts=["full_body"],
            interaction=I("floor_item", ["RightHandMiddle1"], (0.7, 1.0)),
        )
    )
    add(
        Spec(
            "put_down",
            ["object", "handheld"],
            ["put", "place", "set down", "drop", "leave"],
            seq(
                (0.0, _right((0.2, -0.9, 0.3), (-0.1, -0.2, 1.0)), "linear"),
                (0.7, bend_pick, "in_out", (0, -0.12, -0.08)),
                (0.3, bend_pick, "linear", (0, -0.12, -0.08)),
                (0.7, N, "in_out"),
            ),
            body_parts=["full_body"],
            interaction=I("floor_item", ["RightHandMiddle1"], (0.7, 1.0)),
        )
    )
    carry = _both((0.15, -0.9, 0.35), (-0.35, 0.0, 1.0), (0, 0, 0))
    add(
        Spec(
            "carry",
            ["object", "handheld"],
            ["hold", "carry a box", "bring", "deliver"],
            loop(carry, merge(_both((0.15, -0.9, 0.4), (-0.35, 0.15, 1.0)), spine(-6)), 1.0),
            looping=True,
            interaction=I("handheld", ["LeftHand", "RightHand"], (0.0, 1.0)),
        )
    )
    push = merge(_both((0.2, -0.2, 1.0), (0.0, 0.0, 1.0)), spine(20))
    add(
        Spec(
            "push",
            ["object", "force"],
            ["push the cart", "shove", "press against"],
            seq(
                (0.0, N, "linear"),
                (0.5, merge(_both((0.2, -0.4, 0.9), (-0.1, 0.3, 1.0)), spine(15)), "in_out"),
                (0.6, push, "in_out", (0, 0, 0.15)),
                (0.4, push, "linear", (0, 0, 0.15)),
                (0.5, N, "in_out"),
            ),
            interaction=I("surface", ["LeftHand", "RightHand"], (0.5, 1.5)),
        )
    )
    pull = merge(_both((0.2, -0.4, 0.6), (0.0, -0.1, 0.5)), spine(-10))
    add(
        Spec(
            "pull",
            ["object", "force"],
            ["drag", "tug", "haul"],
            seq(
                (0.0, N, "linear"),
                (0.5, merge(_both((0.2, -0.2, 1.0), (0.0, 0.0, 1.0)), spine(15)), "in_out"),
                (0.6, pull, "in_out", (0, 0, -0.15)),
                (0.4, pull, "linear", (0, 0, -0.15)),
                (0.5, N, "in_out"),
            ),
            interaction=I("surface", ["LeftHand", "RightHand"], (0.5, 1.5)),
        )
    )
    throw_back = merge(_right((0.7, 0.5, -0.4), (0.2, 0.9, -0.2)), spine(-5, -20))
    throw_fwd = merge(_right((0.2, 0.1, 1.0), (0.0, -0.1, 1.0)), spine(15, 15))
    add(
        Spec(
            "throw",
            ["object", "sport"],
            ["toss", "throw the ball", "fling", "pitch"],
            seq(
                (0.0, N, "linear"),
                (0.6, throw_back, "in_out"),
                (0.25, throw_fwd, "in"),
                (0.3, throw_fwd, "out"),
                (0.5, N, "in_out"),
            ),
        )
    )
    catch = _both((0.2, -0.1, 1.0), (0.0, 0.3, 1.0), (0, 0, 60))
    add(
        Spec(
            "catch",
            ["object", "sport"],
            ["receive", "catch the ball"],
            seq(
                (0.0, N, "linear"),
                (0.4, catch, "out"),
                (0.3, merge(_both((0.2, -0.5, 0.8), (-0.2, 0.3, 1.0)), spine(-5)), "in_out"),
                (0.6, _both((0.2, -0.5, 0.8), (-0.2, 0.3, 1.0)), "linear"),
                (0.5, N, "in_out"),
            ),
        )
    )
    lift = merge(_both((0.15, -0.6, 0.5), (-0.2, 0.6, 0.6)), spine(-5))
    add(
        Spec(
            "lift_weights",
            ["sport", "exercise"],
            ["lift weights", "curl dumbbells", "work out"],
            cycle(merge(N, arms((0.15, -1.0, 0.1), (0.1, -1.0, 0.2))), lift, 1.2, 4),
            interaction=I("handheld", ["LeftHand", "RightHand"], (0.0, 5.2)),
        )
    )
    add(
        Spec(
            "dribble",
            ["sport", "ball"],
            ["bounce the ball", "play basketball"],
            cycle(
                merge(
                    N,
                    arm("R", (0.3, -0.8, 0.4), (0.1, -0.2, 1.0)),
                    spine(15),
                    legs((0.1, -1.0, 0.2), (0.05, -1.0, -0.1)),
                ),
                merge(
                    N,
                    arm("R", (0.3, -0.9, 0.3), (0.1, -0.9, 0.5)),
                    spine(15),
                    legs((0.1, -1.0, 0.2), (0.05, -1.0, -0.1)),
                ),
                0.5,
                6,
                root_a=(0, -0.06, 0),
            ),
            body_parts=["full_body"],
        )
    )
    shoot = merge(_both((0.25, 0.6, 0.8), (-0.1, 1.0, 0.4), (-30, 0, 0)), head(-15))
    add(
        Spec(
            "shoot_basket",
            ["sport", "ball"],
            ["shoot the ball", "shoot a basket"],
            seq(
                (0.0, N, "linear"),
                (
                    0.5,
                    merge(_both((0.2, -0.5, 0.8), (-0.3, 0.8, 0.5)), legs((0, -0.8, 0.6), (0, -1, -0.5))),
                    "in_out",
                    (0, -0.15, 0),
                ),
                (0.3, shoot, "out", (0, 0.1, 0)),
                (0.3, shoot, "linear"),
                (0.5, N, "in_out"),
            ),
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "use_tablet",
            ["device"],
            ["use the tablet", "swipe"],
            cycle(
                merge(text, arm("R", (0.2, -0.8, 0.4), (0.0, 0.3, 1.0))),
                merge(text, arm("R", (0.3, -0.8, 0.4), (0.3, 0.3, 1.0))),
                0.8,
                3,
            ),
            interaction=I("handheld", ["LeftHand"], (0.4, 2.8)),
        )
    )
    add(
        Spec(
            "eat_snack",
            ["eat", "handheld"],
            ["snack", "bite", "eat an apple"],
            cycle(cup_low, merge(cup_mouth, head(-5)), 1.2, 3),
            interaction=I("handheld", ["RightHand"], (0.4, 4.0)),
        )
    )
    add(
        Spec(
            "smoke",
            ["handheld"],
            ["have a cigarette", "puff"],
            cycle(_right((0.2, -0.9, 0.2), (-0.1, -0.1, 1.0)), merge(cup_mouth, head(-5)), 2.0, 2),
            interaction=I("handheld", ["RightHand"], (0.4, 4.4)),
        )
    )
    return s
