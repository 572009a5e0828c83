"""Metropolis-Hastings over a social ``Model``: emotion, relation and motion (timing, distance, reaction)
proposals, an annealed temperature, a fixed seed, a bounded number of steps; the lowest-energy state wins.

Each proposal changes one block and re-scores only the factors that touch it, which keeps a two-character
scene of ten actions at a few milliseconds. Continuous proposals are Gaussian random walks reflected at the
bounds (symmetric, so the acceptance ratio is exp(-ΔE / T)), their widths shrinking as √T; reaction proposals draw a candidate uniformly.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

from services.social.energy import Model

MIN_STEPS = 300
MAX_STEPS = 6000
STEPS_PER_BLOCK = 40
T_START = 0.1
T_END = 0.002
SIGMA_FLOOR = 0.15  # proposal widths shrink with the temperature, down to this share


@dataclass(frozen=True)
class SampleResult:
    x: list[float]  # the lowest-energy state seen
    energy_initial: float
    energy_final: float
    steps: int
    accepted: int


def auto_steps(model: Model) -> int:
    """Steps for a model: STEPS_PER_BLOCK per block, within [MIN_STEPS, MAX_STEPS]."""
    return max(MIN_STEPS, min(MAX_STEPS, STEPS_PER_BLOCK * len(model.blocks)))


def _reflect(v: float, lo: float, hi: float) -> float:
    span = hi - lo
    if span <= 0:
        return lo
    v = (v - lo) % (2 * span)
    return lo + (v if v <= span else 2 * span - v)


def sample(model: Model, *, seed: int = 0, steps: int = 0) -> SampleResult:
    """Run the chain from ``model.x0``.

    Args:
        model: the story's energy model.
        seed: seed of the chain's random numbers (same seed, same result).
        steps: number of proposals; 0 = ``auto_steps(model)``.
    """
    rng = random.Random(seed)
    x = list(model.x0)
    factors = model.factors
    energy = model.energy(x)
    initial = energy
    best, best_x = energy, list(x)
    blocks = [b for b in model.blocks if b.factors]
    n = steps or auto_steps(model)
    if not blocks:
        return SampleResult(best_x, initial, energy, 0, 0)
    accepted = 0
    cool = (T_END / T_START) ** (1.0 / max(1, n - 1))
    temperature = T_START
    scale = 1.0
    for _ in range(n):
        b = blocks[rng.randrange(len(blocks))]
        old_vals = [x[i] for i in b.indices]
        old_e = 0.0
        for f in b.factors:
            old_e += factors[f](x)
        if b.kind == "response":
            x[b.indices[0]] = float(rng.randrange(b.choices))
        else:
            sigma = b.sigma * scale
            for i in b.indices:
                x[i] = _reflect(x[i] + rng.gauss(0.0, sigma), b.lo, b.hi)
        new_e = 0.0
        for f in b.factors:
            new_e += factors[f](x)
        delta = new_e - old_e
        if delta <= 0.0 or rng.random() < pow(2.718281828459045, -delta / temperature):
            energy += delta
            accepted += 1
            if energy < best - 1e-12:
                best, best_x = energy, list(x)
        else:
            for i, v in zip(b.indices, old_vals, strict=True):
                x[i] = v
        temperature *= cool
        scale = max(SIGMA_FLOOR, math.sqrt(temperature / T_START))
    return SampleResult(best_x, initial, model.energy(best_x), n, accepted)
