"""Simulated annealing of the layout around one interaction (paper Algorithm 2, plus batching).

State: for each movable object, an x, z offset and a horizontal and a vertical scale factor
(vertical positions stay fixed; the vertical scale changes the height). Objects resting on a moved
object follow it: their position in its frame is kept, so a laptop rides on a desk that moves and
rises with a desk that is scaled up. Each step draws ``proposals`` perturbations of the current
state from a truncated normal (σ = 0.02, cut at ±3σ), re-synthesises the motion for each through
``motion_fn``, scores them as one batch, takes the cheapest and accepts it by Metropolis-Hastings
at temperature T = 1 − 0.002·step. The best layout seen is returned, also when the wall-clock
budget runs out. Deterministic for a given seed.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import msgspec
import numpy as np

from proto.motion_data import Motion
from proto.optimizer import CostReport, Interaction, OptimiseSettings
from proto.scene import PlacedObject, Scene
from services.optimizer.costs import LayoutBatch, SceneGeometry
from services.optimizer.scoring import InteractionScorer
from services.optimizer.shifted import ShiftedScorer

MotionFn = Callable[[Scene], Motion]
SCALE_RANGE = (0.8, 1.25)  # scale factors stay plausible: ±20 % of the object's own size
NEAR_MOTION_M = 0.5  # objects this close to the walked path may move by default


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
        steps_run: annealing steps run (fewer than asked when the budget ran out).
        elapsed_ms: wall-clock time of the whole optimisation.
        movable: ids of the objects the annealing moved (their supported objects followed).
        candidates: the layouts that were, in turn, the best so far, latest (best) first; at most 12,
            spread over the search.
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


def support_order(scene: Scene) -> list[int]:
    """Object indices with every support before the objects resting on it (cycles are cut)."""
    index = {o.id: i for i, o in enumerate(scene.objects)}
    order: list[int] = []
    state = [0] * len(scene.objects)  # 0 new, 1 visiting, 2 done

    def visit(i: int) -> None:
        if state[i]:
            return
        state[i] = 1
        parent = index.get(scene.objects[i].support)
        if parent is not None and state[parent] == 0:
            visit(parent)
        state[i] = 2
        order.append(i)

    for i in range(len(scene.objects)):
        visit(i)
    return order


class LayoutModel:
    """Maps annealing states (K, M, 4) = (dx, dz, horizontal scale, vertical scale) to layouts."""

    def __init__(self, scene: Scene, movable: list[str]) -> None:
        self.scene = scene
        ids = [o.id for o in scene.objects]
        self.movable = [m for m in movable if m in ids]
        self.movable_idx = np.array([ids.index(m) for m in self.movable], dtype=np.int64)
        self.base = LayoutBatch.from_scenes([scene])
        self.parent = np.array([ids.index(o.support) if o.support in ids else -1 for o in scene.objects])
        self.order = support_order(scene)
        # Each object's world footprint relative to its position, per unit of its own scale, for the room check.
        from wana.assets.catalog import world_bounds

        pos0 = self.base.position[0]

        def bounds(o: PlacedObject) -> np.ndarray:
            try:
                return world_bounds(o)
            except KeyError:  # not in the catalog (geometry given as arrays): treat it as a point
                return np.array([o.position, o.position], dtype=float)

        self.extent = (
            np.stack([bounds(o) for o in scene.objects]) - pos0[:, None, :] if ids else np.zeros((0, 2, 3))
        )
        self.extent = self.extent / self.base.scale[0][:, None, :]
        half_w, half_d = scene.room.width / 2 + 1e-3, scene.room.depth / 2 + 1e-3
        self.room_min = np.array([-half_w, -half_d])
        self.room_max = np.array([half_w, half_d])
        lo = pos0[:, [0, 2]] + self.extent[:, 0][:, [0, 2]] * self.base.scale[0][:, [0, 2]]
        hi = pos0[:, [0, 2]] + self.extent[:, 1][:, [0, 2]] * self.base.scale[0][:, [0, 2]]
        # Objects already poking out (a window set into its wall) may not go further out, nothing more.
        self.slack_lo = np.minimum(lo - self.room_min, 0.0)
        self.slack_hi = np.minimum(self.room_max - hi, 0.0)

    def _bounds(self, layout: LayoutBatch) -> tuple[np.ndarray, np.ndarray]:
        lo = layout.position + self.extent[None, :, 0] * layout.scale
        hi = layout.position + self.extent[None, :, 1] * layout.scale
        return lo, hi

    def no_new_overlaps(self, layout: LayoutBatch) -> np.ndarray:
        """(K,) True where no two objects' bounds intersect that did not already (an object and its support
        may touch)."""
        lo, hi = self._bounds(layout)
        inter = np.all(
            (lo[:, :, None] < hi[:, None, :] - 1e-3) & (lo[:, None, :] < hi[:, :, None] - 1e-3), axis=-1
        )
        if not hasattr(self, "_allowed"):
            blo, bhi = self._bounds(self.base)
            base = np.all(
                (blo[:, :, None] < bhi[:, None, :] - 1e-3) & (blo[:, None, :] < bhi[:, :, None] - 1e-3),
                axis=-1,
            )[0]
            n = len(self.parent)
            allowed = base | np.eye(n, dtype=bool)
            for i, p in enumerate(
                self.parent
            ):  # an object rests on its support, and on its support's support
                while p >= 0:
                    allowed[i, p] = allowed[p, i] = True
                    p = self.parent[p]
            self._allowed = allowed
        return ~np.any(inter & ~self._allowed[None], axis=(1, 2))

    def inside_room(self, layout: LayoutBatch) -> np.ndarray:
        """(K,) True where every object of the layout stays inside the room (x and z)."""
        xz = layout.position[..., [0, 2]]
        scale = layout.scale[..., [0, 2]]
        lo = xz + self.extent[None, :, 0][..., [0, 2]] * scale
        hi = xz + self.extent[None, :, 1][..., [0, 2]] * scale
        ok = (lo - self.room_min >= self.slack_lo - 1e-9) & (self.room_max - hi >= self.slack_hi - 1e-9)
        return np.all(ok, axis=(1, 2))

    def identity(self) -> np.ndarray:
        """(M, 4) the state of the input layout."""
        s = np.zeros((len(self.movable), 4))
        s[:, 2:] = 1.0
        return s

    def layouts(self, states: np.ndarray) -> LayoutBatch:
        """(K, M, 4) states -> K layouts."""
        k_ = states.shape[0]
        p0, yaw, s0 = self.base.position[0], self.base.yaw[0], self.base.scale[0]
        own = np.zeros((k_, len(p0), 4))
        own[..., 2:] = 1.0
        own[:, self.movable_idx] = states
        pos = np.empty((k_, len(p0), 3))
        scale = s0[None] * np.stack([own[..., 2], own[..., 3], own[..., 2]], axis=-1)
        for i in self.order:
            par = self.parent[i]
            shift = np.stack([own[:, i, 0], np.zeros(k_), own[:, i, 1]], axis=-1)
            if par < 0:
                pos[:, i] = p0[i] + shift
                continue
            # Keep the offset from the support fixed in the support's frame, scaled with it.
            c, s = math.cos(yaw[par]), math.sin(yaw[par])
            d = p0[i] - p0[par]
            local = np.array([c * d[0] - s * d[2], d[1], s * d[0] + c * d[2]])
            local = local[None] * (scale[:, par] / s0[par])
            world = np.stack(
                [c * local[:, 0] + s * local[:, 2], local[:, 1], -s * local[:, 0] + c * local[:, 2]], -1
            )
            pos[:, i] = pos[:, par] + world + shift
        return LayoutBatch(position=pos, yaw=np.repeat(yaw[None], k_, axis=0), scale=scale)

    def scene_at(self, layout: LayoutBatch, k: int) -> Scene:
        """The Scene of layout k (only changed objects are rebuilt)."""
        objs = []
        for i, o in enumerate(self.scene.objects):
            p = tuple(float(v) for v in layout.position[k, i])
            s = tuple(float(v) for v in layout.scale[k, i])
            objs.append(
                o
                if (p == tuple(o.position) and s == tuple(o.scale))
                else msgspec.structs.replace(o, position=p, scale=s)
            )
        return msgspec.structs.replace(self.scene, objects=objs)


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
            costs = np.where(
                ok & model.inside_room(layouts) & model.no_new_overlaps(layouts), sc.cost, np.inf
            )
            k = int(np.argmin(costs))
            u = rng.random()
            steps_run = step + 1
            if np.isfinite(costs[k]) and (costs[k] <= cost or u < math.exp(-(costs[k] - cost) / temp)):
                state, cost = cand[k], float(costs[k])
                if cost < best[0]:
                    best = (cost, state.copy(), motions[k], steps_run)
                    history.append(state.copy())
            curve.append(cost)
            best_curve.append(best[0])
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
