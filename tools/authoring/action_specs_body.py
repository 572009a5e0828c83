"""Authored whole-body actions: looking, turning, stepping, idling, exercise, fighting, dancing.

Clips tagged "locomotion" (walk, run, ...) are in-place gait cycles kept for previews and as the
fallback when the locomotion network is unavailable; synthesis drives travel with the controller.
"""

from __future__ import annotations

from tools.authoring.author_actions import Spec, cycle, hold, loop, seq
from wana.domain.posing import arm, arms, head, hips, leg, legs, merge, neutral, spine

N = neutral()
STEP_L = merge(N, leg("L", (0.0, -1.0, 0.45), (0.0, -1.0, -0.35)))
STEP_R = merge(N, leg("R", (0.0, -1.0, 0.45), (0.0, -1.0, -0.35)))


def _gait(
    stride: float,
    lift: float,
    arm_swing: float,
    lean: float,
    period: float,
    name: str,
    tags,
    syn,
    side: float = 0.0,
    back: bool = False,
) -> Spec:
    """In-place gait cycle: contact L, passing, contact R, passing."""
    f = -1.0 if back else 1.0
    a = merge(
        N,
        spine(lean),
        leg("L", (side, -1.0, f * stride), (side, -1.0, f * stride * 0.5)),
        leg("R", (-side, -1.0, -f * stride), (-side, -1.0, -f * stride - lift * 0.5)),
        arm("L", (0.12, -1.0, -arm_swing), (0.08, -1.0, -arm_swing + 0.2)),
        arm("R", (0.12, -1.0, arm_swing), (0.08, -1.0, arm_swing + 0.3)),
    )
    b = merge(
        N,
        spine(lean),
        leg("R", (-side, -1.0, f * stride), (-side, -1.0, f * stride * 0.5)),
        leg("L", (side, -1.0, -f * stride), (side, -1.0, -f * stride - lift * 0.5)),
        arm("R", (0.12, -1.0, -arm_swing), (0.08, -1.0, -arm_swing + 0.2)),
        arm("L", (0.12, -1.0, arm_swing), (0.08, -1.0, arm_swing + 0.3)),
    )
    pa = merge(
        a, leg("R", (0.0, -1.0, lift), (0.0, -1.0, -lift)), leg("L", (0.0, -1.0, 0.0), (0.0, -1.0, 0.0))
    )
    pb = merge(
        b, leg("L", (0.0, -1.0, lift), (0.0, -1.0, -lift)), leg("R", (0.0, -1.0, 0.0), (0.0, -1.0, 0.0))
    )
    q = period / 4
    drop = (0.0, -0.03 * (1 + stride), 0.0)
    keys = [
        (0.0, a, "linear", drop),
        (q, pa, "in_out"),
        (2 * q, b, "in_out", drop),
        (3 * q, pb, "in_out"),
        (4 * q, a, "in_out", drop),
    ]
    return Spec(name, ["locomotion", *tags], syn, keys, looping=True, body_parts=["full_body"])


def _turn(deg: float, name: str, syn) -> Spec:
    keys = seq(
        (0.0, N, "linear"),
        (0.3, STEP_L, "in_out", (0, 0, 0), deg * 0.25),
        (0.3, N, "in_out", (0, 0, 0), deg * 0.5),
        (0.3, STEP_R, "in_out", (0, 0, 0), deg * 0.75),
        (0.3, N, "in_out", (0, 0, 0), deg),
    )
    tags = ["turn", "locomotion_in_place"]
    return Spec(name, tags, syn, keys, body_parts=["full_body"])


def _step(direction: tuple[float, float], name: str, syn) -> Spec:
    dx, dz = direction
    lead = leg("L", (0.3 * dx, -1.0, 0.3 * dz + 0.1), (0.3 * dx, -1.0, 0.0))
    keys = seq(
        (0.0, N, "linear"),
        (0.4, merge(N, lead), "in_out", (dx * 0.2, -0.02, dz * 0.2)),
        (0.4, N, "in_out", (dx * 0.4, 0, dz * 0.4)),
    )
    return Spec(name, ["step", "locomotion_in_place"], syn, keys, body_parts=["full_body"])


def specs() -> list[Spec]:
    s: list[Spec] = []
    add = s.append
    # --- looking and turning --------------------------------------------------------------------
    add(
        Spec(
            "look_at",
            ["look", "head"],
            ["look", "watch", "stare at", "gaze at", "observe", "glance at", "see", "notice"],
            hold(merge(N, head(-8, 0, 4), spine(-3)), 2.0),
            body_parts=["head"],
        )
    )
    add(
        Spec(
            "look_left",
            ["look", "head"],
            ["look to the left"],
            hold(merge(N, head(0, 60), spine(0, 15)), 2.0),
            body_parts=["head", "spine"],
        )
    )
    add(
        Spec(
            "look_right",
            ["look", "head"],
            ["look to the right"],
            hold(merge(N, head(0, -60), spine(0, -15)), 2.0),
            body_parts=["head", "spine"],
        )
    )
    add(
        Spec(
            "look_up",
            ["look", "head"],
            ["look at the sky", "look at the ceiling", "raise the head"],
            hold(merge(N, head(-40), spine(-8)), 2.0),
            body_parts=["head", "spine"],
        )
    )
    add(
        Spec(
            "look_down",
            ["look", "head"],
            ["look at the floor", "lower the head", "bow the head"],
            hold(merge(N, head(40), spine(8)), 2.0),
            body_parts=["head", "spine"],
        )
    )
    add(_turn(90.0, "turn_left", ["turn to the left", "turn left"]))
    add(_turn(-90.0, "turn_right", ["turn to the right", "turn right"]))
    add(_turn(180.0, "turn_around", ["turn back", "spin around", "face the other way", "about-face"]))
    # --- stepping and gaits ---------------------------------------------------------------------
    add(_step((0.0, 1.0), "step_forward", ["step ahead", "approach"]))
    add(_step((0.0, -1.0), "step_back", ["back off", "retreat", "step backward", "back away"]))
    add(_step((1.0, 0.0), "step_left", ["step aside to the left"]))
    add(_step((-1.0, 0.0), "step_right", ["step aside to the right"]))
    add(
        _gait(
            0.35,
            0.35,
            0.25,
            3,
            1.1,
            "walk",
            ["move"],
            [
                "walk",
                "go",
                "stroll",
                "move",
                "head to",
                "come",
                "enter",
                "leave",
                "walk in",
                "walk to",
                "go to",
                "wander",
            ],
        )
    )
    add(
        _gait(
            0.25,
            0.25,
            0.15,
            2,
            1.4,
            "walk_slowly",
            ["move", "slow"],
            ["amble", "saunter", "trudge", "shuffle"],
        )
    )
    add(
        _gait(
            0.6,
            0.9,
            0.6,
            10,
            0.7,
            "run",
            ["move", "fast"],
            ["run", "sprint", "dash", "race", "rush", "hurry"],
        )
    )
    add(_gait(0.45, 0.6, 0.4, 6, 0.85, "jog", ["move", "exercise"], ["jog", "trot"]))
    add(
        _gait(
            0.3,
            0.3,
            0.15,
            -2,
            1.2,
            "walk_backward",
            ["move"],
            ["walk backwards", "back up", "reverse"],
            back=True,
        )
    )
    add(
        _gait(
            0.05,
            0.3,
            0.05,
            0,
            1.0,
            "sidestep_left",
            ["move", "side"],
            ["shuffle left", "side-step left"],
            side=0.3,
        )
    )
    add(
        _gait(
            0.05,
            0.3,
            0.05,
            0,
            1.0,
            "sidestep_right",
            ["move", "side"],
            ["shuffle right", "side-step right"],
            side=-0.3,
        )
    )
    add(_gait(0.3, 0.8, 0.3, 0, 1.2, "march", ["move", "formal"], ["parade", "stomp along"]))
    add(
        _gait(
            0.2, 0.25, 0.1, 6, 1.2, "tiptoe", ["move", "quiet"], ["sneak", "creep", "tip-toe", "walk quietly"]
        )
    )
    add(_gait(0.3, 0.2, 0.1, 12, 1.5, "limp", ["move", "hurt"], ["hobble"]))
    # --- idling ---------------------------------------------------------------------------------------
    breathe = merge(N, spine(-4), head(-4), arms((0.16, -1.0, 0.02), (0.1, -1.0, 0.2)))
    add(
        Spec(
            "idle",
            ["idle", "wait"],
            ["stand", "stay", "remain", "do nothing", "linger", "be"],
            loop(N, breathe, 3.0),
            looping=True,
        )
    )
    add(
        Spec(
            "wait",
            ["idle", "wait"],
            ["wait for", "await", "hang around", "stand by"],
            loop(
                merge(N, hips(0, 0, 3), spine(0, 0, -3)),
                merge(N, hips(0, 0, -3), spine(0, 0, 3), head(0, 15)),
                4.0,
            ),
            looping=True,
        )
    )
    add(
        Spec(
            "tap_foot",
            ["idle", "impatient"],
            ["be impatient", "tap"],
            cycle(
                merge(N, leg("R", (0, -1, 0.3), (0, -1, 0.3), 20)),
                merge(N, leg("R", (0, -1, 0.3), (0, -1, 0.3), -10)),
                0.4,
                5,
            ),
            body_parts=["lower_body"],
        )
    )
    add(
        Spec(
            "stretch",
            ["exercise", "tired", "idle"],
            ["stretch arms", "limber up", "warm up"],
            seq(
                (0.0, N, "linear"),
                (0.7, merge(N, arms((0.2, 1.0, 0.0), (0.1, 1.0, 0.0)), spine(-8), head(-15))),
                (1.0, merge(N, arms((0.2, 1.0, 0.0), (0.1, 1.0, 0.0)), spine(-10, 0, 12))),
                (1.0, merge(N, arms((0.2, 1.0, 0.0), (0.1, 1.0, 0.0)), spine(-10, 0, -12))),
                (0.7, N),
            ),
        )
    )
    add(
        Spec(
            "yawn",
            ["tired"],
            ["be tired", "be sleepy", "be bored"],
            seq(
                (0.0, N, "linear"),
                (0.6, merge(N, arm("R", (0.2, -0.4, 0.6), (-0.6, 0.8, 0.1)), head(-25), spine(-5))),
                (1.0, merge(N, arm("R", (0.2, -0.4, 0.6), (-0.6, 0.8, 0.1)), head(-25), spine(-5)), "linear"),
                (0.6, N),
            ),
        )
    )
    add(
        Spec(
            "shiver",
            ["cold", "scared", "emotion"],
            ["tremble", "be cold", "freeze", "shake"],
            cycle(
                merge(N, arms((0.2, -0.9, 0.4), (-1.0, 0.3, 0.2)), spine(8, 3)),
                merge(N, arms((0.2, -0.9, 0.4), (-1.0, 0.35, 0.2)), spine(8, -3)),
                0.15,
                12,
            ),
        )
    )
    add(
        Spec(
            "fan_self",
            ["hot"],
            ["be hot", "cool down", "fan"],
            cycle(
                merge(N, arm("R", (0.3, -0.4, 0.7), (-0.3, 0.8, 0.5), (0, 0, 60))),
                merge(N, arm("R", (0.3, -0.4, 0.7), (-0.3, 0.8, 0.5), (0, 0, 20))),
                0.35,
                6,
            ),
        )
    )
    add(
        Spec(
            "wipe_sweat",
            ["hot", "tired"],
            ["wipe the brow", "mop the brow"],
            seq(
                (0.0, N, "linear"),
                (0.5, merge(N, arm("R", (0.5, 0.2, 0.5), (-0.6, 0.7, 0.2)), head(-10))),
                (0.5, merge(N, arm("R", (0.6, 0.2, 0.5), (-0.2, 0.8, 0.1)), head(-10))),
                (0.5, N),
            ),
        )
    )
    add(
        Spec(
            "sneeze",
            ["ill"],
            ["achoo"],
            seq(
                (0.0, N, "linear"),
                (0.6, merge(N, head(-20), spine(-8), arm("R", (0.2, -0.5, 0.6), (-0.6, 0.8, 0.2)))),
                (0.25, merge(N, head(25), spine(20), arm("R", (0.2, -0.5, 0.6), (-0.6, 0.8, 0.2))), "in"),
                (0.6, N),
            ),
        )
    )
    add(
        Spec(
            "cough",
            ["ill"],
            ["clear the throat"],
            cycle(
                merge(N, spine(10), head(10), arm("R", (0.2, -0.5, 0.6), (-0.6, 0.8, 0.2))),
                merge(N, spine(18), head(18), arm("R", (0.2, -0.5, 0.6), (-0.6, 0.8, 0.2))),
                0.35,
                3,
            ),
        )
    )
    add(
        Spec(
            "rub_hands",
            ["cold", "happy"],
            ["warm hands"],
            cycle(
                merge(N, arms((0.2, -0.8, 0.5), (-0.7, 0.1, 0.7))),
                merge(N, arms((0.2, -0.8, 0.5), (-0.7, 0.2, 0.7), (0, 20, 0))),
                0.3,
                6,
            ),
        )
    )
    # --- exercise --------------------------------------------------------------------------------------
    jump_crouch = merge(
        N, legs((0, -0.7, 0.7), (0, -1.0, -0.4)), spine(20), arms((0.1, -0.8, -0.5), (0.1, -0.9, -0.3))
    )
    jump_air = merge(
        N, legs((0, -1.0, 0.1), (0, -1.0, -0.1), -20), arms((0.3, 0.8, 0.3), (0.2, 1.0, 0.2)), spine(-5)
    )
    add(
        Spec(
            "jump",
            ["exercise", "happy", "sport"],
            ["leap", "hop", "jump up", "bounce"],
            # the arms swing up over the 0.35 s of the push-off (hands at most 8 m/s: continuity's 10 m/s)
            seq(
                (0.0, N, "linear"),
                (0.3, jump_crouch, "in_out", (0, -0.2, 0)),
                (0.35, jump_air, "in_out", (0, 0.35, 0)),
                (0.25, jump_air, "in", (0, 0.15, 0)),
                (0.3, jump_crouch, "in_out", (0, -0.15, 0)),
                (0.3, N, "in_out"),
            ),
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "jump_forward",
            ["exercise", "sport"],
            ["long jump", "jump over"],
            seq(
                (0.0, N, "linear"),
                (0.3, jump_crouch, "in_out", (0, -0.2, 0)),
                (0.4, jump_air, "in_out", (0, 0.3, 0.5)),
                (0.4, jump_crouch, "in_out", (0, -0.15, 1.0)),
                (0.3, N, "in_out", (0, 0, 1.0)),
            ),
            body_parts=["full_body"],
        )
    )
    jj_open = merge(N, legs((0.35, -1.0, 0.0), (0.35, -1.0, 0.0)), arms((0.6, 0.8, 0.0), (0.4, 1.0, 0.0)))
    add(
        Spec(
            "jumping_jacks",
            ["exercise"],
            ["do jumping jacks", "star jumps"],
            cycle(merge(N, arms((0.1, -1.0, 0.0), (0.05, -1.0, 0.0))), jj_open, 0.8, 5, root_b=(0, 0.04, 0)),
            body_parts=["full_body"],
        )
    )
    plank = merge(
        hips(70), arms((0.15, -0.3, 1.0), (0.1, -0.2, 1.0)), head(-25), legs((0, -1, 0.0), (0, -1, 0.0), -60)
    )
    add(
        Spec(
            "push_up",
            ["exercise"],
            ["do push-ups", "press up"],
            seq(
                (0.0, N, "linear"),
                (0.8, merge(N, legs((0, -0.5, 0.9), (0, -1, -0.4)), spine(40)), "in_out", (0, -0.5, 0)),
                (0.6, plank, "in_out", (0, -0.62, -0.3)),
                (0.6, merge(plank, arms((0.4, 0.1, 0.9), (0.2, -0.8, 0.5))), "in_out", (0, -0.78, -0.3)),
                (0.6, plank, "in_out", (0, -0.62, -0.3)),
                (0.6, merge(plank, arms((0.4, 0.1, 0.9), (0.2, -0.8, 0.5))), "in_out", (0, -0.78, -0.3)),
                (0.6, plank, "in_out", (0, -0.62, -0.3)),
            ),
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "touch_toes",
            ["exercise", "stretch"],
            ["bend over", "bend down", "stoop"],
            hold(
                merge(N, spine(80), hips(20), head(10), arms((0.1, -1.0, 0.3), (0.0, -1.0, 0.2))),
                2.6,
                0.8,
                (0, -0.05, -0.1),
            ),
        )
    )
    add(
        Spec(
            "squat_exercise",
            ["exercise"],
            ["do squats", "knee bends"],
            cycle(
                N,
                merge(
                    N,
                    legs((0.1, -0.4, 1.0), (0.05, -1.0, -0.4)),
                    spine(30),
                    arms((0.1, -0.2, 1.0), (0.0, -0.1, 1.0)),
                ),
                1.4,
                4,
                root_b=(0, -0.4, -0.15),
            ),
            body_parts=["full_body"],
        )
    )
    tree = merge(N, leg("R", (-0.6, -0.6, 0.3), (0.7, -0.7, 0.0)), arms((0.05, 1.0, 0.1), (-0.2, 1.0, 0.0)))
    add(
        Spec(
            "yoga",
            ["exercise", "calm"],
            ["do yoga", "balance", "stand on one leg", "meditate"],
            hold(tree, 3.0, 0.8),
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "tai_chi",
            ["exercise", "calm"],
            ["do tai chi"],
            cycle(
                merge(N, arms((0.3, -0.3, 0.8), (0.1, 0.2, 1.0)), legs((0.15, -1, 0.1), (0.1, -1, -0.1))),
                merge(
                    N,
                    arms((0.6, -0.1, 0.6), (0.6, 0.3, 0.7)),
                    spine(0, 20),
                    legs((0.15, -0.9, 0.3), (0.1, -1, -0.3)),
                ),
                2.0,
                2,
                root_b=(0, -0.08, 0),
            ),
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "swing_arms",
            ["exercise"],
            ["circle the arms", "loosen up"],
            cycle(
                merge(N, arms((0.1, -0.2, 1.0), (0.0, 0.0, 1.0))),
                merge(N, arms((0.2, 1.0, 0.1), (0.1, 1.0, -0.1))),
                0.8,
                3,
            ),
        )
    )
    # --- fighting ----------------------------------------------------------------------------------------
    guard = merge(N, arms((0.3, -0.7, 0.4), (-0.3, 0.8, 0.5)), legs((0.1, -1.0, 0.15), (0.05, -1.0, 0.0)))
    add(
        Spec(
            "punch",
            ["fight", "angry"],
            ["hit", "strike", "jab", "smack"],
            seq(
                (0.0, N, "linear"),
                (0.35, guard),
                (0.18, merge(guard, arm("R", (0.1, 0.0, 1.0), (0.0, 0.0, 1.0)), spine(0, 25)), "out"),
                (0.35, guard),
                (0.4, N),
            ),
        )
    )
    add(
        Spec(
            "punch_left",
            ["fight", "angry"],
            ["left jab"],
            seq(
                (0.0, N, "linear"),
                (0.35, guard),
                (0.18, merge(guard, arm("L", (0.1, 0.0, 1.0), (0.0, 0.0, 1.0)), spine(0, -25)), "out"),
                (0.35, guard),
                (0.4, N),
            ),
        )
    )
    add(
        Spec(
            "shadow_box",
            ["fight", "exercise", "sport"],
            ["spar", "shadowbox"],
            cycle(
                merge(guard, arm("R", (0.1, 0.0, 1.0), (0.0, 0.0, 1.0)), spine(0, 20)),
                merge(guard, arm("L", (0.1, 0.0, 1.0), (0.0, 0.0, 1.0)), spine(0, -20)),
                0.6,
                4,
            ),
        )
    )
    kick = merge(
        N,
        leg("R", (0.0, -0.1, 1.0), (0.0, -0.2, 1.0), -30),
        spine(-15),
        arms((0.5, -0.5, 0.2), (0.3, 0.3, 0.6)),
    )
    add(
        Spec(
            "kick",
            ["fight", "sport"],
            ["boot", "kick the ball", "kick at"],
            seq(
                (0.0, N, "linear"),
                (0.4, merge(N, leg("R", (0.0, -0.8, -0.5), (0.0, -0.5, -1.0))), "in_out"),
                (0.2, kick, "out"),
                (0.5, N),
            ),
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "kick_left",
            ["fight", "sport"],
            ["left kick"],
            seq(
                (0.0, N, "linear"),
                (0.4, merge(N, leg("L", (0.0, -0.8, -0.5), (0.0, -0.5, -1.0))), "in_out"),
                (0.2, merge(N, leg("L", (0.0, -0.1, 1.0), (0.0, -0.2, 1.0), -30), spine(-15)), "out"),
                (0.5, N),
            ),
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "block",
            ["fight", "scared"],
            ["defend", "guard", "shield oneself", "protect"],
            hold(
                merge(
                    N,
                    arms((0.4, 0.0, 0.8), (-0.5, 0.8, 0.3)),
                    spine(10),
                    head(15),
                    legs((0.1, -1.0, -0.2), (0.05, -1.0, -0.3)),
                ),
                1.6,
                0.25,
            ),
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "fall_down",
            ["fall", "hurt"],
            ["fall", "collapse", "faint", "trip", "drop down"],
            seq(
                (0.0, N, "linear"),
                (
                    0.4,
                    merge(
                        N,
                        legs((0, -0.7, 0.6), (0, -1.0, -0.5)),
                        spine(20),
                        arms((0.6, 0.2, 0.5), (0.5, 0.4, 0.5)),
                    ),
                    "in",
                    (0, -0.3, 0),
                ),
                (
                    0.5,
                    merge(hips(-80), arms((0.7, -0.2, 0.2), (0.8, 0.0, 0.2)), head(10)),
                    "in",
                    (0, -0.82, -0.6),
                ),
                (1.0, merge(hips(-85), arms((0.7, -0.2, 0.2), (0.8, 0.0, 0.2))), "linear", (0, -0.84, -0.6)),
            ),
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "stumble",
            ["fall", "hurt"],
            ["stagger", "lose balance", "trip over"],
            seq(
                (0.0, N, "linear"),
                (
                    0.3,
                    merge(
                        N,
                        spine(25),
                        arms((0.7, 0.3, 0.5), (0.5, 0.6, 0.5)),
                        leg("R", (0, -0.9, 0.6), (0, -1, 0.2)),
                    ),
                    "in",
                    (0, -0.06, 0.2),
                ),
                (0.4, merge(N, spine(-10), arms((0.7, 0.0, 0.0), (0.8, 0.2, 0.0))), "out", (0, 0, 0.45)),
                (0.5, N, "in_out", (0, 0, 0.5)),
            ),
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "get_hit",
            ["fight", "hurt"],
            ["be hit", "flinch", "recoil"],
            seq(
                (0.0, N, "linear"),
                (
                    0.15,
                    merge(N, spine(-15), head(-20), arms((0.4, -0.5, 0.3), (0.2, 0.1, 0.6))),
                    "out",
                    (0, 0, -0.15),
                ),
                (0.7, N, "in_out", (0, 0, -0.2)),
            ),
            body_parts=["full_body"],
        )
    )
    # --- dancing and play ---------------------------------------------------------------------------------
    d1 = merge(
        N,
        hips(0, 15, 5),
        spine(0, -20, -5),
        arms((0.5, -0.2, 0.5), (0.2, 0.7, 0.6)),
        legs((0.1, -1, 0.1), (0.05, -1, -0.1)),
    )
    d2 = merge(
        N,
        hips(0, -15, -5),
        spine(0, 20, 5),
        arms((0.5, 0.3, 0.4), (0.4, 0.8, 0.2)),
        legs((0.1, -0.95, 0.2), (0.05, -1, -0.25)),
    )
    add(
        Spec(
            "dance",
            ["dance", "happy", "music"],
            ["dance", "boogie", "groove", "party", "move to the music"],
            loop(d1, d2, 1.0, (0, -0.04, 0), (0, -0.08, 0)),
            looping=True,
            body_parts=["full_body"],
        )
    )
    b1 = merge(
        N, arms((0.6, 0.6, 0.3), (-0.3, 0.9, 0.2)), leg("R", (-0.2, -1.0, -0.1), (0.1, -1.0, -0.1), -40)
    )
    b2 = merge(
        N,
        arms((0.9, 0.0, 0.2), (0.9, 0.1, 0.3)),
        leg("R", (0.0, -0.6, -0.8), (0.0, -0.4, -0.9), -30),
        spine(20),
    )
    add(
        Spec(
            "dance_ballet",
            ["dance", "music", "calm"],
            ["do ballet", "pirouette", "twirl"],
            cycle(b1, b2, 1.6, 3),
            body_parts=["full_body"],
        )
    )
    h1 = merge(
        N, arms((0.5, -0.1, 0.6), (-0.6, 0.1, 0.8)), legs((0.2, -0.9, 0.3), (0.1, -1, -0.3)), spine(15)
    )
    h2 = merge(
        N, arms((0.8, -0.4, -0.1), (0.5, -0.5, 0.5)), legs((0.2, -1, 0.0), (0.1, -1, 0.0)), spine(0, 0, 10)
    )
    add(
        Spec(
            "dance_hiphop",
            ["dance", "music"],
            ["breakdance", "hip-hop"],
            loop(h1, h2, 0.8, (0, -0.1, 0), (0, 0, 0)),
            looping=True,
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "spin",
            ["dance", "happy"],
            ["twirl around", "rotate", "pirouette around"],
            seq(
                (0.0, N, "linear"),
                (0.4, merge(N, arms((0.9, 0.1, 0.0), (1.0, 0.1, 0.0))), "in_out", (0, 0, 0), 120),
                (0.4, merge(N, arms((0.9, 0.1, 0.0), (1.0, 0.1, 0.0))), "linear", (0, 0, 0), 240),
                (0.4, N, "in_out", (0, 0, 0), 360),
            ),
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "skip",
            ["happy", "move"],
            ["skip along", "frolic"],
            cycle(
                merge(STEP_L, arms((0.2, -0.5, 0.7), (0.1, 0.2, 0.9))),
                merge(STEP_R, arms((0.2, -0.5, 0.7), (0.1, 0.2, 0.9))),
                0.7,
                3,
                root_a=(0, 0.05, 0),
                root_b=(0, 0.08, 0),
            ),
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "stomp",
            ["angry"],
            ["stamp the feet", "throw a tantrum"],
            cycle(
                merge(N, leg("R", (0, -0.7, 0.6), (0, -1, -0.2)), arms((0.3, -0.9, 0.0), (0.3, -0.9, 0.0))),
                merge(N, spine(10)),
                0.5,
                3,
            ),
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "climb",
            ["move", "sport"],
            ["climb up", "climb the ladder", "scale"],
            loop(
                merge(
                    N,
                    leg("L", (0, -0.4, 0.9), (0, -1, 0)),
                    arm("R", (0.3, 1.0, 0.3), (0.1, 1.0, 0.2)),
                    arm("L", (0.3, 0.3, 0.8), (0.1, 0.5, 0.8)),
                ),
                merge(
                    N,
                    leg("R", (0, -0.4, 0.9), (0, -1, 0)),
                    arm("L", (0.3, 1.0, 0.3), (0.1, 1.0, 0.2)),
                    arm("R", (0.3, 0.3, 0.8), (0.1, 0.5, 0.8)),
                ),
                1.2,
            ),
            looping=True,
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "crawl",
            ["move"],
            ["crawl on all fours", "creep on the floor"],
            loop(
                merge(
                    hips(-75),
                    arms((0.15, -0.2, 1.0), (0.1, -0.2, 1.0)),
                    legs((0, -0.2, 1.0), (0, -1, 0.0)),
                    head(-30),
                ),
                merge(
                    hips(-75),
                    arms((0.15, -0.4, 0.9), (0.1, -0.2, 1.0)),
                    legs((0, -0.3, 1.0), (0, -1, 0.1)),
                    head(-30),
                ),
                1.0,
                (0, -0.55, 0),
                (0, -0.55, 0),
            ),
            looping=True,
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "hide",
            ["scared", "play"],
            ["duck down", "take cover", "cower"],
            hold(
                merge(
                    N,
                    legs((0.15, -0.5, 1.0), (0.05, -1.0, -0.35)),
                    spine(35),
                    head(20),
                    arms((0.3, 0.1, 0.7), (-0.6, 0.8, 0.2)),
                ),
                2.4,
                0.5,
                (0, -0.4, -0.15),
            ),
            body_parts=["full_body"],
        )
    )
    add(
        Spec(
            "pick_up_phone_answer",
            ["phone", "talk"],
            ["answer the phone", "pick up the phone"],
            seq(
                (0.0, N, "linear"),
                (0.5, merge(N, arm("R", (0.2, -0.8, 0.5), (0.0, -0.4, 1.0)), head(20))),
                (0.6, merge(N, arm("R", (0.35, -0.7, 0.35), (-0.35, 1.0, 0.05), (0, 0, 30)))),
                (
                    1.5,
                    merge(N, arm("R", (0.35, -0.7, 0.35), (-0.35, 1.0, 0.05), (0, 0, 30)), head(0, 10)),
                    "linear",
                ),
            ),
            interaction={"object": "handheld", "contacts": ["RightHand"], "window": [0.5, 2.6]},
        )
    )
    return s
