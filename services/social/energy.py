"""The energy of a social story: unary label terms, pairwise potentials φ_me, φ_re, φ_rm and temporal ψ.

State (one flat list of floats, see ``Layout``):
    e[c, s]  (3,)  emotion of character c at character sentence s: VAD change from neutral, in [-1, 1]
    r[p]     (2,)  relation of pair p = (a, b): dominance of a over b, intimacy; in [-1, 1]
    d[p]           standing distance of pair p, metres
    logdelay[q]    ln seconds from the end of A's act to the start of B's response q
    dact[j]        distance of act j aimed at another character, metres
    m[i]           proposed reaction of slot i, an index into the response candidates

Terms (weights in ``Weights``; M is an act's VAD, K_D, K_I couple relation and affect):
    label      W_label ||e[c,s] - VAD(label)||²                         emotion words ("Tom is angry")
    φ_me       W_actor ||e[X,s] - M||² + W_target ||e[Y,s] - R(M)||²   motion <-> emotion of actor and target;
               R(M) = (0.8 V, 0.8 A, 0.5 V - 0.3 D): the target mirrors valence and arousal and loses
               control under a negative act
    φ_re       W_re (e[X,s].D - K_D dom_XY)² + W_re_v (e[X,s].V - K_I int)², both sides, when X and Y interact
    φ_rm       W_rm ((M.D - K_D dom_XY)² + (M.V - K_I int)²) + W_contact max(0, 0.4 - int)² for contact clips;
               for a proposed reaction only the dominance part (a reaction's valence follows the act, via e)
    reaction   W_response ||e[B,s] - M_reaction||²: the proposed clip fits B's emotion at that sentence
    relation   W_rel ||r[p] - r0||² (strong when the text names the relation, weak for the default)
    ψ          W_smooth ||e[c,s] - e[c,s-1]||² + W_decay ||e[c,s]||²   smooth faces that relax to neutral
    delay      W_delay ((logdelay - ln μ) / 0.35)², ln μ = ln 0.6 - 0.6 A_B + 0.5 dom_BA + 0.25 max(0, -V_B):
               aroused responders answer sooner, dominant ones later, unhappy ones hesitate
    distance   W_dist (d[p] - d*(r))², d* = clip(1.2 - 0.6 int + 0.4 |dom|, 0.45, 3) (Hall's proxemic zones);
               acts: contact clips at 0.55 - 0.15 int, others at d[p] exp(-0.25 D_X - 0.1 V_X)
               (confident or warm actors step closer, fearful ones keep away)
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

from services.social.lexicon import ActionEntry, contact_action, response_candidates
from services.social.relations import DEFAULT_RELATION, RELATIONS
from services.social.story import Story

Factor = Callable[..., float]  # f(x: list[float]) -> float; closures bind their indices as defaults


@dataclass(frozen=True)
class Weights:
    label: float = 4.0
    actor: float = 1.2
    target: float = 2.0
    re: float = 0.6
    re_v: float = 0.3
    rm: float = 0.5
    contact: float = 2.0
    rel_given: float = 8.0
    rel_default: float = 0.5
    smooth: float = 2.0
    decay: float = 0.15
    response: float = 1.5
    delay: float = 0.5
    dist: float = 4.0
    dist_act: float = 4.0
    k_d: float = 0.5
    k_i: float = 0.4


@dataclass
class Block:
    """Indices proposed together, with the proposal kind and bounds."""

    kind: str  # "emotion" | "relation" | "distance" | "delay" | "act_distance" | "response"
    indices: tuple[int, ...]
    sigma: float = 0.0
    lo: float = 0.0
    hi: float = 0.0
    choices: int = 0  # categorical size for "response"
    factors: list[int] = field(default_factory=list)


@dataclass
class Model:
    story: Story
    x0: list[float]
    blocks: list[Block]
    factors: list[Factor]
    e_index: dict[tuple[str, int], int]
    pair_index: dict[tuple[str, str], tuple[int, float]]  # (a, b) -> (pair number, +1 | -1 for dominance)
    r0: list[int]  # pair p -> index of r[p]
    dpair: list[int]
    delay_index: list[int]  # response q -> index
    act_distance: list[tuple[int, int]]  # (act number in story.acts, index)
    slots: list[tuple[int, int]]  # (response number, index of m)
    candidates: list[ActionEntry]

    def energy(self, x: list[float]) -> float:
        return sum(f(x) for f in self.factors)


def _sq3(x: list[float], i: int, t: tuple[float, float, float]) -> float:
    return (x[i] - t[0]) ** 2 + (x[i + 1] - t[1]) ** 2 + (x[i + 2] - t[2]) ** 2


def target_feeling(m: tuple[float, float, float]) -> tuple[float, float, float]:
    """R(M): how an act with VAD M makes its target feel."""
    return 0.8 * m[0], 0.8 * m[1], 0.5 * m[0] - 0.3 * m[2]


def pair_distance_goal(dom: float, intimacy: float) -> float:
    """d*(r): the proxemic distance of a relation, metres."""
    return min(3.0, max(0.45, 1.2 - 0.6 * intimacy + 0.4 * abs(dom)))


def build_model(story: Story, w: Weights | None = None) -> Model:
    """Lay out the state, its initial value, the factors and the proposal blocks of a story."""
    w = w or Weights()
    x: list[float] = []
    blocks: list[Block] = []
    S = len(story.steps)
    e_index: dict[tuple[str, int], int] = {}
    for c in story.characters:
        for s in range(story.first_step.get(c, S), S):
            e_index[(c, s)] = len(x)
            blocks.append(Block("emotion", (len(x), len(x) + 1, len(x) + 2), 0.2, -1.0, 1.0))
            x += [0.0, 0.0, 0.0]
    pairs = story.pairs()
    pair_index: dict[tuple[str, str], tuple[int, float]] = {}
    r0: list[int] = []
    dpair: list[int] = []
    priors: list[tuple[tuple[float, float], float]] = []
    for p, (ca, cb) in enumerate(pairs):
        pair_index[(ca, cb)], pair_index[(cb, ca)] = (p, 1.0), (p, -1.0)
        if (ca, cb) in story.relations:
            rel, weight = story.relations[(ca, cb)][1], w.rel_given
        elif (cb, ca) in story.relations:
            d, i = story.relations[(cb, ca)][1]
            rel, weight = (-d, i), w.rel_given
        else:
            rel, weight = RELATIONS[DEFAULT_RELATION], w.rel_default
        priors.append((rel, weight))
        r0.append(len(x))
        blocks.append(Block("relation", (len(x), len(x) + 1), 0.12, -1.0, 1.0))
        x += [rel[0], rel[1]]
    for _ in pairs:
        dpair.append(len(x))
        blocks.append(Block("distance", (len(x),), 0.1, 0.3, 4.0))
        x.append(1.2)
    delay_index = []
    for _ in story.responses:
        delay_index.append(len(x))
        blocks.append(Block("delay", (len(x),), 0.2, math.log(0.1), math.log(3.0)))
        x.append(math.log(1.0))
    act_distance = []
    for n, a in enumerate(story.acts):
        if a.target:
            act_distance.append((n, len(x)))
            blocks.append(Block("act_distance", (len(x),), 0.1, 0.3, 4.0))
            x.append(1.2)
    candidates = response_candidates()
    cand_vad = [c.vad for c in candidates]
    start = min(range(len(candidates)), key=lambda i: sum(v * v for v in cand_vad[i]))  # the most neutral
    slots = []
    for q, r in enumerate(story.responses):
        if r.answer is None and candidates:
            slots.append((q, len(x)))
            blocks.append(Block("response", (len(x),), choices=len(candidates)))
            x.append(float(start))

    factors: list[Factor] = []
    var_factors: dict[int, list[int]] = {}

    def add(f: Factor, *indices: int) -> None:
        for i in indices:
            var_factors.setdefault(i, []).append(len(factors))
        factors.append(f)

    def rel_of(a: str, b: str) -> tuple[int, float]:
        p, sign = pair_index[(a, b)]
        return r0[p], sign

    # label terms
    for c, s, vad in story.emotion_labels:
        if (c, s) in e_index:
            i = e_index[(c, s)]
            add(lambda x, i=i, t=vad: w.label * _sq3(x, i, t), i)
    # ψ: smoothness and decay
    for (c, s), i in e_index.items():
        add(lambda x, i=i: w.decay * (x[i] ** 2 + x[i + 1] ** 2 + x[i + 2] ** 2), i)
        j = e_index.get((c, s - 1))
        if j is not None:
            add(lambda x, i=i, j=j: w.smooth * _sq3(x, i, (x[j], x[j + 1], x[j + 2])), i, j)
    # relation priors and pair distances
    for p, (rel, weight) in enumerate(priors):
        ri, di = r0[p], dpair[p]
        add(lambda x, ri=ri, t=rel, k=weight: k * ((x[ri] - t[0]) ** 2 + (x[ri + 1] - t[1]) ** 2), ri)
        add(lambda x, ri=ri, di=di: w.dist * (x[di] - pair_distance_goal(x[ri], x[ri + 1])) ** 2, ri, di)
    # φ_me, φ_rm per act; φ_re once per interacting pair and step
    interacting: set[tuple[int, int]] = set()
    for a in story.acts:
        ea = e_index[(a.actor, a.step)]
        if a.vad is not None:
            add(lambda x, i=ea, t=a.vad: w.actor * _sq3(x, i, t), ea)
        if not a.target:
            continue
        et = e_index[(a.target, a.step)]
        ri, sign = rel_of(a.actor, a.target)
        if a.vad is not None:
            felt = target_feeling(a.vad)
            add(lambda x, i=et, t=felt: w.target * _sq3(x, i, t), et)
            contact = contact_action(a.action)
            add(
                lambda x, ri=ri, sg=sign, m=a.vad, ct=contact: (
                    w.rm * ((m[2] - w.k_d * sg * x[ri]) ** 2 + (m[0] - w.k_i * x[ri + 1]) ** 2)
                    + (w.contact * max(0.0, 0.4 - x[ri + 1]) ** 2 if ct else 0.0)
                ),
                ri,
            )
        if (ri, a.step) not in interacting:
            interacting.add((ri, a.step))
            ex, ey = (ea, et) if sign > 0 else (et, ea)  # ex: the pair's first character
            add(
                lambda x, ri=ri, ex=ex, ey=ey: (
                    w.re * ((x[ex + 2] - w.k_d * x[ri]) ** 2 + (x[ey + 2] + w.k_d * x[ri]) ** 2)
                    + w.re_v * ((x[ex] - w.k_i * x[ri + 1]) ** 2 + (x[ey] - w.k_i * x[ri + 1]) ** 2)
                ),
                ri,
                ex,
                ey,
            )
    # act distances
    for n, di in act_distance:
        a = story.acts[n]
        p, _ = pair_index[(a.actor, a.target)]
        ri, dp, ea = r0[p], dpair[p], e_index[(a.actor, a.step)]
        if contact_action(a.action):
            add(lambda x, di=di, ri=ri: w.dist_act * (x[di] - (0.55 - 0.15 * x[ri + 1])) ** 2, di, ri)
        else:
            add(
                lambda x, di=di, dp=dp, ea=ea: (
                    w.dist_act * (x[di] - x[dp] * math.exp(-0.25 * x[ea + 2] - 0.1 * x[ea])) ** 2
                ),
                di,
                dp,
                ea,
            )
    # response delays
    for q, r in enumerate(story.responses):
        li = delay_index[q]
        eb = e_index[(r.responder, r.act.step)]
        ri, sign = rel_of(r.responder, r.act.actor)
        add(
            lambda x, li=li, eb=eb, ri=ri, sg=sign: (
                w.delay
                * (
                    (x[li] - (math.log(0.6) - 0.6 * x[eb + 1] + 0.5 * sg * x[ri] + 0.25 * max(0.0, -x[eb])))
                    / 0.35
                )
                ** 2
            ),
            li,
            eb,
            ri,
        )
    # proposed reactions: φ_me with the responder's face, φ_rm with the relation
    contact_flags = [c.contact for c in candidates]
    for q, mi in slots:
        r = story.responses[q]
        eb = e_index[(r.responder, r.act.step)]
        ri, sign = rel_of(r.responder, r.act.actor)

        def reaction(x: list[float], mi: int = mi, eb: int = eb, ri: int = ri, sg: float = sign) -> float:
            m = cand_vad[int(x[mi])]
            e = w.response * _sq3(x, eb, m) + w.rm * (m[2] - w.k_d * sg * x[ri]) ** 2
            if contact_flags[int(x[mi])]:
                e += w.contact * max(0.0, 0.4 - x[ri + 1]) ** 2
            return e

        add(reaction, mi, eb, ri)
    for blk in blocks:
        blk.factors = sorted({f for i in blk.indices for f in var_factors.get(i, [])})
    return Model(
        story,
        x,
        blocks,
        factors,
        e_index,
        pair_index,
        r0,
        dpair,
        delay_index,
        act_distance,
        slots,
        candidates,
    )
