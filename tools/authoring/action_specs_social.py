"""Authored social actions (aimed at another character or at nobody); the gestures keyed as curves
(wave, point, nod, shrug, laugh...) are in action_specs_gestures.py."""

from __future__ import annotations

from tools.authoring.author_actions import Spec, cycle, hold, loop, seq
from wana.domain.posing import arm, arms, head, legs, merge, neutral, spine

N = neutral()


def _r(upper, fore, hand=(0, 0, 0), *extra) -> dict:
    return merge(N, arm("R", upper, fore, hand), *extra)


def _l(upper, fore, hand=(0, 0, 0), *extra) -> dict:
    return merge(N, arm("L", upper, fore, hand), *extra)


def _b(upper, fore, hand=(0, 0, 0), *extra) -> dict:
    return merge(N, arms(upper, fore, hand), *extra)


def P(contacts: list[str], window: tuple[float, float]) -> dict:
    """A social interaction: the contacts meet the partner character."""
    return {"object": "person", "contacts": contacts, "window": list(window)}


def specs() -> list[Spec]:
    s: list[Spec] = []
    add = s.append
    five = _r((0.4, 0.7, 0.5), (0.1, 1.0, 0.3))
    add(
        Spec(
            "high_five",
            ["social", "happy", "greet"],
            ["give a high five", "high five", "slap hands"],
            seq(
                (0.0, N, "linear"),
                (0.5, _r((0.5, 0.2, 0.3), (0.2, 1.0, -0.2))),
                (0.25, five, "in"),
                (0.35, five, "linear"),
                (0.5, N, "in_out"),
            ),
            interaction=P(["RightHandMiddle1"], (0.75, 1.1)),
        )
    )
    shake = _r((0.05, -0.7, 0.7), (-0.05, -0.1, 1.0), (0, 0, -80))
    add(
        Spec(
            "shake_hands",
            ["social", "greet", "formal"],
            ["shake hands with", "handshake", "shake someone's hand", "meet"],
            seq(
                (0.0, N, "linear"),
                (0.6, shake, "in_out"),
                (0.25, _r((0.05, -0.65, 0.7), (-0.05, 0.05, 1.0), (0, 0, -80))),
                (0.25, shake),
                (0.25, _r((0.05, -0.65, 0.7), (-0.05, 0.05, 1.0), (0, 0, -80))),
                (0.25, shake),
                (0.6, N, "in_out"),
            ),
            interaction=P(["RightHand"], (0.6, 1.6)),
        )
    )
    hug = merge(N, arms((0.5, -0.1, 0.85), (-0.9, 0.0, 0.3)), spine(5), head(5, 20))
    add(
        Spec(
            "hug",
            ["social", "affection", "happy"],
            ["embrace", "hold", "cuddle", "give a hug"],
            seq(
                (0.0, N, "linear"),
                (0.7, merge(N, arms((0.6, 0.0, 0.8), (0.3, 0.1, 1.0))), "in_out"),
                (0.5, hug, "in_out"),
                (1.2, merge(hug, spine(5, 0, 4)), "in_out"),
                (0.7, N, "in_out"),
            ),
            interaction=P(["LeftHand", "RightHand"], (1.2, 2.4)),
        )
    )
    bow = merge(N, spine(45), head(15), arms((0.05, -1.0, 0.1), (0.0, -1.0, 0.1)))
    add(
        Spec(
            "bow",
            ["social", "formal", "respect"],
            ["bow to", "take a bow", "bow down"],
            seq(
                (0.0, N, "linear"),
                (0.7, bow, "in_out", (0, 0, -0.05)),
                (0.6, bow, "linear", (0, 0, -0.05)),
                (0.7, N, "in_out"),
            ),
            body_parts=["upper_body", "spine"],
        )
    )
    sorry = merge(N, spine(20), head(25), arms((0.1, -1.0, 0.25), (-0.3, -0.6, 0.7)))
    add(
        Spec(
            "apologize",
            ["social", "sad", "talk"],
            ["say sorry", "apologise", "beg pardon", "excuse oneself", "regret"],
            seq(
                (0.0, N, "linear"),
                (0.6, sorry, "in_out"),
                (0.8, merge(sorry, head(35, 0, 5)), "in_out"),
                (
                    0.8,
                    merge(sorry, _b((0.3, -0.6, 0.6), (0.3, 0.2, 1.0), (0, 0, 60)), spine(20), head(20)),
                    "in_out",
                ),
                (0.8, sorry, "in_out"),
                (0.6, N, "in_out"),
            ),
        )
    )
    scold = merge(
        N,
        arm("R", (0.3, -0.1, 0.95), (0.0, 0.2, 1.0)),
        arm("L", (0.6, -0.8, -0.2), (-0.7, -0.3, 0.2)),
        spine(-5),
        head(-5),
    )
    add(
        Spec(
            "criticize",
            ["social", "angry", "talk"],
            ["criticise", "scold", "blame", "reprimand", "lecture", "rebuke", "tell off"],
            cycle(scold, merge(scold, arm("R", (0.3, -0.2, 0.95), (0.0, -0.2, 1.0))), 0.5, 5),
        )
    )
    q_a = merge(N, arms((0.5, -0.3, 0.7), (0.3, 0.4, 0.9), (0, 0, 60)), spine(5, 10), head(-5, -10))
    q_b = merge(N, arms((0.6, -0.6, 0.4), (0.8, 0.1, 0.5), (0, 0, 60)), spine(-5, -10), head(5, 10))
    add(
        Spec(
            "quarrel",
            ["social", "angry", "talk"],
            ["argue", "fight with", "dispute", "bicker", "yell at", "shout at"],
            cycle(q_a, q_b, 0.8, 4),
        )
    )
    clap_a = merge(_b((0.25, -0.5, 0.8), (-0.55, 0.25, 0.8), (0, 0, 0)), head(-3))
    clap_b = merge(_b((0.3, -0.5, 0.8), (-0.1, 0.25, 1.0), (0, 0, 0)), head(-3))
    add(
        Spec(
            "clap",
            ["social", "happy", "gesture"],
            ["applaud", "clap hands", "give a hand", "cheer"],
            cycle(clap_b, clap_a, 0.4, 6),
        )
    )
    salute = _r((0.8, 0.1, 0.5), (-0.6, 0.7, 0.0), (0, 0, -20))
    add(
        Spec(
            "salute",
            ["gesture", "formal", "respect"],
            ["give a salute"],
            hold(merge(salute, head(-3)), 2.0, 0.4),
        )
    )
    cheer = _b((0.4, 1.0, 0.1), (0.05, 1.0, 0.25))  # elbows soft: a cheer, not a held straight arm
    add(
        Spec(
            "celebrate",
            ["happy", "gesture"],
            ["cheer", "rejoice", "win", "hooray", "be happy"],
            cycle(
                cheer,
                merge(_b((0.6, 0.8, 0.1), (0.4, 1.0, 0.0)), legs((0, -1, 0.1), (0, -1, -0.1))),
                0.5,
                4,
                root_b=(0, 0.06, 0),
            ),
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "thumbs_up",
            ["gesture", "happy", "agree"],
            ["give a thumbs up", "approve", "like"],
            hold(_r((0.2, -0.5, 0.8), (-0.1, 0.6, 0.8), (0, 0, 80)), 2.0),
        )
    )
    beckon = _r((0.3, -0.5, 0.8), (0.1, 0.4, 1.0), (0, 0, 80))
    add(
        Spec(
            "beckon",
            ["gesture", "social"],
            ["call over", "invite", "come here", "summon"],
            cycle(beckon, _r((0.3, -0.5, 0.8), (0.0, 0.8, 0.4), (0, 0, 80)), 0.5, 3),
        )
    )
    add(
        Spec(
            "facepalm",
            ["gesture", "sad", "frustrated"],
            ["slap forehead"],
            hold(merge(_r((0.2, -0.5, 0.6), (-0.5, 0.8, 0.3), (0, 0, -30)), head(20)), 2.0),
        )
    )
    cry = merge(_b((0.2, -0.6, 0.7), (-0.5, 0.8, 0.2)), head(30), spine(15))
    add(
        Spec(
            "cry",
            ["sad", "emotion"],
            ["weep", "sob", "be sad", "mourn"],
            cycle(cry, merge(cry, spine(20), head(35)), 0.8, 4),
        )
    )
    add(
        Spec(
            "cover_face",
            ["sad", "scared", "emotion"],
            ["hide the face", "be ashamed", "be embarrassed"],
            hold(merge(_b((0.2, -0.5, 0.6), (-0.55, 0.8, 0.2)), head(25), spine(10)), 2.4),
        )
    )
    add(
        Spec(
            "blow_kiss",
            ["affection", "gesture"],
            ["kiss", "send a kiss"],
            seq(
                (0.0, N, "linear"),
                (0.5, _r((0.3, -0.5, 0.6), (-0.6, 0.8, 0.2))),
                (0.4, _r((0.6, 0.2, 0.8), (0.3, 0.3, 1.0))),
                (0.5, N, "in_out"),
            ),
        )
    )
    add(
        Spec(
            "fist_pump",
            ["happy", "gesture"],
            ["pump the fist", "yes!"],
            cycle(_r((0.4, -0.6, 0.4), (0.1, 1.0, 0.2)), _r((0.5, 0.9, 0.1), (0.2, 1.0, 0.0)), 0.4, 3),
        )
    )
    pat = _r((0.3, 0.0, 0.95), (-0.3, -0.1, 1.0))
    add(
        Spec(
            "comfort",
            ["social", "affection", "sad"],
            ["console", "pat on the shoulder", "reassure", "soothe"],
            cycle(pat, _r((0.3, 0.05, 0.95), (-0.3, 0.1, 1.0)), 0.6, 3),
            interaction=P(["RightHand"], (0.4, 2.2)),
        )
    )
    add(
        Spec(
            "push_person",
            ["social", "angry", "fight"],
            ["shove someone", "push away"],
            seq(
                (0.0, N, "linear"),
                (0.4, _b((0.3, -0.5, 0.7), (-0.2, 0.4, 0.9), (0, 0, 0))),
                (0.2, merge(_b((0.2, 0.0, 1.0), (0.0, 0.1, 1.0)), spine(15)), "out", (0, 0, 0.12)),
                (0.5, N, "in_out"),
            ),
            interaction=P(["LeftHand", "RightHand"], (0.6, 0.7)),
        )
    )
    talk = merge(_b((0.2, -0.8, 0.5), (-0.1, 0.1, 1.0), (0, 0, 60)), head(0, 5))
    add(
        Spec(
            "talk",
            ["talk", "social"],
            ["say", "speak", "chat", "tell", "converse", "discuss", "explain", "ask"],
            cycle(talk, merge(_b((0.3, -0.8, 0.5), (0.3, 0.2, 1.0), (0, 0, 60)), head(5, -5)), 1.0, 3),
        )
    )
    add(
        Spec(
            "whisper",
            ["talk", "social"],
            ["murmur", "tell a secret"],
            hold(
                merge(
                    _r((0.2, -0.5, 0.7), (-0.6, 0.8, 0.3), (0, 0, -30)), spine(15, 0, -10), head(10, 0, -10)
                ),
                2.4,
            ),
        )
    )
    shout = merge(_b((0.3, -0.5, 0.6), (-0.5, 0.8, 0.3), (0, 0, 30)), head(-15), spine(-5))
    add(Spec("shout", ["talk", "angry"], ["yell", "scream", "call out", "cry out"], hold(shout, 2.0)))
    add(
        Spec(
            "greet_bow",
            ["greet", "formal"],
            ["nod hello"],
            seq((0.0, N, "linear"), (0.4, merge(N, spine(15), head(15))), (0.4, N)),
        )
    )
    add(
        Spec(
            "argue",
            ["social", "angry", "talk"],
            ["debate", "contradict"],
            cycle(
                merge(q_a, arm("L", (0.1, -1.0, 0.1), (0.0, -1.0, 0.2))),
                merge(q_b, arm("L", (0.1, -1.0, 0.1), (0.0, -1.0, 0.2))),
                0.7,
                4,
            ),
        )
    )
    add(
        Spec(
            "threaten",
            ["social", "angry"],
            ["menace", "shake the fist"],
            cycle(_r((0.4, -0.2, 0.8), (0.0, 0.9, 0.4)), _r((0.4, -0.1, 0.8), (0.0, 0.7, 0.6)), 0.4, 4),
        )
    )
    add(
        Spec(
            "kiss_cheek",
            ["affection", "social"],
            ["peck", "kiss on the cheek"],
            hold(merge(N, spine(12, 0, -8), head(10, 0, -15), _r((0.3, -0.3, 0.9), (0.0, 0.1, 1.0))), 1.8),
            interaction=P(["RightHand"], (0.4, 1.4)),
        )
    )
    add(
        Spec(
            "hold_hands",
            ["affection", "social"],
            ["take someone's hand", "walk hand in hand"],
            loop(
                _r((0.4, -0.9, 0.1), (0.3, -0.9, 0.2)),
                merge(_r((0.4, -0.9, 0.2), (0.3, -0.9, 0.35)), head(0, -16)),
                2.0,
            ),
            looping=True,
            interaction=P(["RightHand"], (0.0, 2.0)),
        )
    )
    add(
        Spec(
            "introduce",
            ["social", "talk", "greet"],
            ["present someone", "introduce oneself"],
            seq(
                (0.0, N, "linear"),
                (0.5, _r((0.6, -0.4, 0.6), (0.7, 0.2, 0.6), (0, 0, 60))),
                (1.2, merge(_r((0.6, -0.4, 0.6), (0.7, 0.2, 0.6), (0, 0, 60)), head(0, -20))),
                (0.5, N, "in_out"),
            ),
        )
    )
    add(
        Spec(
            "pray",
            ["emotion", "calm"],
            ["put hands together", "beg", "plead"],
            hold(merge(_b((0.15, -0.7, 0.6), (-0.6, 0.7, 0.4), (0, 0, 0)), head(20)), 2.6),
        )
    )
    add(
        Spec(
            "surrender",
            ["gesture", "scared"],
            ["raise hands", "give up", "hands up"],
            hold(_b((0.9, 0.4, 0.0), (0.05, 1.0, 0.0), (0, 0, 0)), 2.2),
        )
    )
    add(
        Spec(
            "cross_arms",
            ["gesture", "angry", "idle"],
            ["fold arms", "be annoyed", "wait impatiently"],
            hold(merge(_b((0.25, -0.9, 0.35), (-1.0, 0.15, 0.25)), head(-5)), 3.0),
        )
    )
    add(
        Spec(
            "hands_on_hips",
            ["gesture", "angry", "idle"],
            ["put hands on hips", "stand akimbo"],
            hold(_b((0.7, -0.7, -0.2), (-0.6, -0.5, 0.35), (0, 0, 0)), 2.6),
        )
    )
    add(
        Spec(
            "scratch_head",
            ["gesture", "doubt", "think"],
            ["be confused", "wonder", "puzzle"],
            cycle(_r((0.7, 0.5, 0.2), (-0.4, 0.9, -0.2)), _r((0.7, 0.5, 0.1), (-0.5, 0.8, -0.3)), 0.3, 5),
        )
    )
    think = merge(
        _r((0.1, -0.9, 0.4), (-0.45, 0.85, 0.2), (0, 0, -20)),
        _l((0.15, -1.0, 0.3), (-0.9, 0.1, 0.3)),
        head(8, 0, 8),
    )
    add(
        Spec(
            "think",
            ["think", "idle", "head"],
            ["ponder", "consider", "wonder", "reflect", "contemplate", "meditate on"],
            seq(
                (0.0, N, "linear"),
                (0.6, think),
                (1.4, merge(think, head(-5, 10, 8))),
                (1.4, think),
                (0.6, N, "in_out"),
            ),
        )
    )
    add(
        Spec(
            "check_watch",
            ["gesture", "idle", "time"],
            ["look at the watch", "check the time"],
            hold(merge(_l((0.15, -0.8, 0.5), (-0.6, 0.2, 0.8), (0, 0, -70)), head(35, 10)), 2.0),
        )
    )
    add(
        Spec(
            "count_fingers",
            ["gesture", "talk"],
            ["count", "enumerate", "list"],
            cycle(
                merge(_b((0.2, -0.8, 0.5), (-0.3, 0.3, 1.0)), head(15)),
                merge(_b((0.2, -0.8, 0.5), (-0.4, 0.35, 1.0)), head(15)),
                0.6,
                4,
            ),
        )
    )
    add(
        Spec(
            "look_around",
            ["look", "head", "idle"],
            ["look about", "search", "explore", "scan the room"],
            seq(
                (0.0, N, "linear"),
                (0.6, merge(N, head(0, 60), spine(0, 20))),
                (1.0, merge(N, head(0, 60), spine(0, 20)), "linear"),
                (1.0, merge(N, head(0, -60), spine(0, -20))),
                (0.8, merge(N, head(0, -60), spine(0, -20)), "linear"),
                (0.6, N),
            ),
            body_parts=["head", "spine"],
        )
    )
    return s
