"""Simulated annealing of the layout around one interaction (paper Algorithm 2, plus batching).

State: for each movable object, an x, z offset and a horizontal and a vertical scale factor
(vertical positions stay fixed; the vertical scale changes the height). Objects resting on a moved
object follow it: their position in its frame is kept, so a laptop rides on a desk that moves and
rises with a desk that is scaled up. Each step draws ``proposals`` perturbations of the current
state from a truncated normal (σ = 0.02, cut at ±3σ), re-synthesises the motion for each through
``motion_fn``, scores them as one batch, takes the cheapest and accepts it by Metropolis-Hastings
at temperature T = 1 − 0.002·step. The best layout seen is returned, also when the wall-clock
budget runs out; asked to, the search stops early once its cost is 0 (no later layout could beat
it). Deterministic for a given seed.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from proto.motion_data import Motion
from proto.optimizer import CostReport, Interaction, OptimiseSettings
from proto.scene import Scene
from services.optimizer.costs import LayoutBatch, SceneGeometry
from services.optimizer.layout_model import LayoutModel, support_order  # noqa: F401 - re-exported
from services.optimizer.scoring import InteractionScorer
from services.optimizer.shifted import ShiftedScorer

MotionFn = Callable[[Scene], Motion]
SCALE_RANGE = (0.8, 1.25)  # scale factors stay plausible: ±20 % of the object's own size
NEAR_MOTION_M = 0.5  # objects this close to the walked path may move by default
# A new best layout must lower C by more than this. Once the collisions are gone, C is flat up to the
# float noise of C_T (1e-8); taking every such "gain" returned whatever layout the random walk had
# drifted to by the last step (a chair 35 cm further from its desk for nothing).
MIN_GAIN = 1e-4


@dataclass
class OptimisationResult:
    """What optimise_interaction returns.

    Attributes:
        scene: the best layout found.
        motion: the motion re-synthesised in it.
        cost_curve: search cost of the current layout after each step; [0] is the input layout. The
            search tests fewer frames, at cell level, so its values run above the exact ``before`` /
            ``after`` costs; its shape is what it shows.
        before: costs of the input layout and motion.
        after: costs of the returned layout and motion.
        best_curve: lowest search cost so far after each step.
        steps_run: annealing steps run (fewer than asked when the budget ran out or, with
            ``stop_at_zero``, the search cost reached 0).
        elapsed_ms: wall-clock time of the whole optimisation.
        movable: ids of the objects the annealing moved (their supported objects followed).
        candidates: the layouts that were, in turn, the best so far (ties within MIN_GAIN included),
            latest first; at most 12, spread over the search.
    """

    scene: Scene
    motion: Motion
    cost_curve: list[float]
    before: CostReport
    after: CostReport
    best_curve: list[float] = field(default_factory=list)
    steps_run: int = 0
    elapsed_ms: float = 0.0
    movable: list[str] = field(default_factory=list)
    candidates: list[Scene] = field(default_factory=list)


def truncated_normal(
    rng: np.random.Generator, sigma: float, shape: tuple[int, ...], cut: float = 3.0
) -> np.ndarray:
    """Normal samples with std ``sigma`` redrawn until inside ±cut·sigma."""
    x = rng.normal(0.0, sigma, size=shape)
    bad = np.abs(x) > cut * sigma
    while bad.any():
        x[bad] = rng.normal(0.0, sigma, size=int(bad.sum()))
        bad = np.abs(x) > cut * sigma
    return x


def default_movable(
    scene: Scene,
    interaction: Interaction,
    scorer: InteractionScorer,
    motion: Motion,
    hit_objects: np.ndarray | None = None,
) -> list[str]:
    """Targets, their supports, and floor objects the body hits (``hit_objects`` (O,) bool) or passes
    within NEAR_MOTION_M of."""
    from services.optimizer.body import motion_joint_positions

    if interaction.movable:
        return list(interaction.movable)
    by_id = {o.id: o for o in scene.objects}
    chosen: list[str] = []

    def add(i: str) -> None:
        if i in by_id and i not in chosen:
            chosen.append(i)

    from wana.assets.vocabulary import CATEGORIES

    def on_wall(i: str) -> bool:  # windows, paintings, shelves on walls stay where the wall is
        info = CATEGORIES.get(by_id[i].category) if i in by_id else None
        return info is not None and info.mount == "wall"

    for t in interaction.targets:
        add(t)
        if by_id.get(t) is not None and by_id[t].support:
            add(by_id[t].support)
    for p in scorer.pairs:
        add(p.object_id)
    chosen[:] = [i for i in chosen if not on_wall(i)]
    root = motion_joint_positions(motion)[:, 0, [0, 2]]  # (T, 2)
    layout = LayoutBatch.from_scenes([scene])
    for i, o in enumerate(scene.objects):
        if o.support or o.id in chosen:
            continue
        d = np.linalg.norm(root - layout.position[0, i, [0, 2]], axis=1).min()
        mine = scorer.geom.box_owner == i
        corners = np.abs(scorer.geom.box_centre[mine][:, [0, 2]]) + scorer.geom.box_half[mine][:, [0, 2]]
        reach = float(np.linalg.norm(corners, axis=1).max() * max(o.scale)) if mine.any() else 0.0
        if (d <= reach + NEAR_MOTION_M or (hit_objects is not None and hit_objects[i])) and not on_wall(o.id):
            add(o.id)
    return chosen


def optimise_interaction(
    scene: Scene,
    motion_fn: MotionFn,
    interaction: Interaction,
    *,
    seed: int = 0,
    steps: int = 100,
    budget_s: float | None = None,
    settings: OptimiseSettings | None = None,
    motion: Motion | None = None,
    contact_tolerance: float = 0.06,
    geometry: SceneGeometry | None = None,
    search_stride: int = 4,
    search_action_frames: int | None = 6,
    coarse_search: bool = True,
    ik_search: bool = False,
    stop_at_zero: bool = False,
) -> OptimisationResult:
    """Jointly improve the layout and the motion of one interaction.

    Args:
        scene: the input layout.
        motion_fn: the motion service's synthesis for this character's actions, scene -> Motion; called
            once per proposal. It may raise (no route, say): that proposal is then rejected. A
            ``motion_fn.from_layouts(LayoutBatch) -> list[Motion]`` attribute, when present, is used
            instead for all proposals of a step at once.
        interaction: the action, its targets and contacts, and optionally the movable objects.
        seed: random seed; the same inputs and seed give the same result.
        steps: at most this many steps (the paper's 100).
        budget_s: wall-clock budget; when it runs out the best layout so far is returned.
        settings: the other parameters (λ_D, λ_T, temperature, cooling, σ, proposals per step);
            its seed, steps and budget are overridden by the arguments above.
        motion: the motion in ``scene`` if already synthesised (saves one motion_fn call).
        contact_tolerance: penetration (metres) into a target tolerated while the action holds.
        geometry: the scene's object geometry; read from the asset catalog when None.
        search_stride: walking frames tested during the search: every n-th (reports test all).
        search_action_frames: poses tested per non-walking segment during the search (None = all).
        coarse_search: rank proposals with the cell-level collision test (reports are always exact).
        ik_search: rank hand contacts by arm reach (see InteractionScorer's ik_reach), for a motion_fn
            that does not re-solve the IK per proposal (the anchored surrogate).
        stop_at_zero: stop once the best search cost is 0 (below MIN_GAIN): the best layout cannot
            change after that, only the ties kept in ``candidates`` would; for callers that do not
            verify the candidates.

    Returns:
        The best layout, its motion, the cost curve, and the costs before and after.
    """
    t_start = time.perf_counter()
    st = settings or OptimiseSettings()
    rng = np.random.default_rng(seed)
    # The search tests fewer frames (walking at 7.5 Hz, at most 6 poses per action) at cell level;
    # the reports test every frame exactly.
    scorer = InteractionScorer(
        scene,
        interaction,
        lambda_d=st.lambda_d,
        lambda_t=st.lambda_t,
        contact_tolerance=contact_tolerance,
        geometry=geometry,
        frame_stride=search_stride,
        action_frames_max=search_action_frames,
        coarse=coarse_search,
        ik_reach=ik_search,
    )
    reporter = InteractionScorer(
        scene,
        interaction,
        lambda_d=st.lambda_d,
        lambda_t=st.lambda_t,
        contact_tolerance=contact_tolerance,
        geometry=scorer.geom,
        frame_stride=1,
    )
    m0 = motion if motion is not None else motion_fn(scene)
    base = LayoutBatch.from_scenes([scene])
    s0 = scorer.score(base, [m0])
    hit_objects = np.zeros(len(scene.objects), dtype=bool)
    hit_objects[np.unique(scorer.geom.box_owner[s0.box_hit[0]])] = True
    model = LayoutModel(scene, default_movable(scene, interaction, scorer, m0, hit_objects))
    before = reporter.score(base, [m0]).report(0, reporter.pairs)
    state, cost = model.identity(), float(s0.cost[0])
    best: tuple[float, np.ndarray, Motion | None, int] = (cost, state, m0, 0)
    curve, best_curve = [cost], [cost]
    history: list[np.ndarray] = []
    tie = cost  # lowest cost seen: below the best by less than MIN_GAIN
    k_ = max(1, int(st.proposals))
    steps_run = 0
    # A motion_fn whose motions are its base motion translated per frame (the anchored surrogate)
    # is scored as shifts of that base: no Motion is built per proposal.
    shifts_fn = getattr(motion_fn, "shifts", None)
    fast = (
        ShiftedScorer(scorer, m0, base)
        if shifts_fn is not None and getattr(motion_fn, "base_motion", None) is m0
        else None
    )
    if len(model.movable):
        for step in range(max(0, int(steps))):
            if budget_s is not None and time.perf_counter() - t_start >= budget_s:
                break
            temp = max(st.temperature - st.cooling * step, 1e-6)
            delta = truncated_normal(rng, st.sigma, (k_, len(model.movable), 4))
            cand = state[None] + delta
            cand[..., 2:] = np.clip(state[None, :, 2:] * (1.0 + delta[..., 2:]), *SCALE_RANGE)
            layouts = model.layouts(cand)
            motions: list[Motion | None] = []
            ok = np.ones(k_, dtype=bool)
            batch = getattr(motion_fn, "from_layouts", None)
            if fast is not None and shifts_fn is not None:
                motions = [None] * k_  # made for the best layout only, at the end
            elif batch is not None:  # a motion_fn that follows layouts directly (the anchored surrogate)
                motions = batch(layouts)
            else:
                for k in range(k_):
                    try:
                        motions.append(motion_fn(model.scene_at(layouts, k)))
                    except Exception:  # noqa: BLE001 - a proposal the motion cannot follow is rejected
                        motions.append(m0)
                        ok[k] = False
            sc = (
                fast.score(layouts, shifts_fn(layouts))
                if fast is not None and shifts_fn is not None
                else scorer.score(layouts, motions)  # type: ignore[arg-type]
            )
            costs = np.where(ok & model.allowed(layouts), sc.cost, np.inf)
            k = int(np.argmin(costs))
            u = rng.random()
            steps_run = step + 1
            if np.isfinite(costs[k]) and (costs[k] <= cost or u < math.exp(-(costs[k] - cost) / temp)):
                state, cost = cand[k], float(costs[k])
                if cost < best[0] - MIN_GAIN:  # a tie is no gain: keep the layout found first
                    best = (cost, state.copy(), motions[k], steps_run)
                    history.append(state.copy())
                    tie = cost
                elif cost < tie:  # still a candidate for the verifier (it sees what the search cannot)
                    history.append(state.copy())
                    tie = cost
            curve.append(cost)
            best_curve.append(best[0])
            if stop_at_zero and best[0] < MIN_GAIN:
                break  # C is 0 up to float noise: no later layout can be a new best (see MIN_GAIN)
    best_layout = model.layouts(best[1][None])
    if best[2] is None:
        best = (best[0], best[1], motion_fn.from_layouts(best_layout)[0], best[3])  # type: ignore[attr-defined]
    best_motion: Motion = best[2] if best[2] is not None else m0
    after = reporter.score(best_layout, [best_motion]).report(0, reporter.pairs) if best[3] else before
    if after.cost > before.cost:  # the search's (coarser) cost misled it: keep the input
        best, after, best_motion = (best[0], model.identity(), m0, 0), before, m0
        best_layout = model.layouts(best[1][None])
    return OptimisationResult(
        scene=model.scene_at(best_layout, 0) if best[3] else scene,
        motion=best_motion,
        cost_curve=curve,
        before=before,
        after=after,
        best_curve=best_curve,
        steps_run=steps_run,
        elapsed_ms=(time.perf_counter() - t_start) * 1000.0,
        movable=list(model.movable),
        candidates=[model.scene_at(model.layouts(h[None]), 0) for h in _spread(history[::-1], 12)],
    )


def _spread(items: list, n: int) -> list:
    """At most n items, evenly spread from the first to the last."""
    if len(items) <= n:
        return list(items)
    idx = sorted({round(i * (len(items) - 1) / (n - 1)) for i in range(n)})
    return [items[i] for i in idx]
