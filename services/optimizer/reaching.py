"""Layouts that bring a missed contact within reach, for the verifier to re-synthesise.

Eq. 2 measures each contact point against the mean position of its joint over the action. When the
motion misses a contact (the approach to a piano bench blocked in the input layout, so the
character sits down beside it; a laptop beyond arm's reach), the annealing cannot see a move fix
it: its anchored surrogate carries the motion with the anchor, so the anchor's own miss stays
whatever the anchor does, and it re-plans no approach. These candidates make the move a person
would: the missed contact's object (its support, for an object resting on another, so that what
rests on it follows) slides along the floor-plane vector from the contact point to the mean
position of its joint over the action, by multiples of the annealing's largest move (3σ of the
truncated normal) up to the whole miss. The annealing's rules hold: the object stays in the room,
makes no new overlap, and neither wall-mounted objects nor objects outside an explicit
``Interaction.movable`` move; an object on another slides on it first (a laptop toward the edge of
its desk), then its support carries it, each as far as the rules allow. When the hips slid off a
seat toward work out of reach, the work comes to the seat first. The motion service then re-synthesises each candidate
(``verify.optimise_and_verify``), and only a verified contact is kept.
"""

from __future__ import annotations

import numpy as np

from proto.motion_data import Motion
from proto.optimizer import CostReport, Interaction
from proto.scene import Scene
from services.optimizer.annealing import LayoutModel
from services.optimizer.body import motion_joint_positions
from services.optimizer.costs import LayoutBatch, SceneGeometry, contact_points_world, joint_index
from services.optimizer.scoring import action_frames

STEPS = (1, 2, 4, 8)  # moves tried, in units of the annealing's largest move (3σ), then the whole miss
SEAT_MISS_MULTIPLES = (1, 2, 3, 4)  # work brought to a seat, in units of the hips' slide off it


def _wall_mounted(category: str) -> bool:
    """Windows, paintings and shelves hung on a wall stay where the wall is."""
    try:
        from wana.assets.vocabulary import CATEGORIES
    except ImportError:  # no asset vocabulary: nothing is known to hang on a wall
        return False
    info = CATEGORIES.get(category)
    return info is not None and info.mount == "wall"


def contact_misses(
    scene: Scene, interaction: Interaction, motion: Motion, report: CostReport, geom: SceneGeometry
) -> list[tuple[str, np.ndarray, float]]:
    """The contacts of ``report`` the motion misses, as floor-plane moves of their objects.

    Args:
        scene: the layout ``report`` scored.
        interaction: the interaction (its action's frames are those eq. 2 averages over).
        motion: the motion in ``scene``.
        report: its exact costs (contact pairs and distances).
        geom: the scene's geometry.

    Returns:
        Per missed pair, largest miss first: the object id, the (2,) x, z unit vector from the contact
        point to its joint's mean position, and the x, z length of that vector in metres.
    """
    pairs = list(report.contact_pairs)
    if not pairs:
        return []
    positions = motion_joint_positions(motion)  # (T, J, 3)
    a0, a1 = action_frames(motion, interaction, len(positions))
    joint_mean = positions[a0:a1][:, joint_index([p.joint for p in pairs])].mean(axis=0)  # (P, 3)
    idx = np.array([geom.contact_index(p.object_id, p.point, p.joint) for p in pairs], dtype=np.int64)
    points = contact_points_world(geom, LayoutBatch.from_scenes([scene]), idx)[0]  # (P, 3)
    misses = []
    for p, dist, point, joint in zip(pairs, report.contact_distances, points, joint_mean, strict=True):
        v = (joint - point)[[0, 2]]
        length = float(np.linalg.norm(v))
        if length > 1e-3:
            misses.append((float(dist), p.object_id, v / length, length))
    misses.sort(key=lambda m: -m[0])
    return [(oid, u, length) for _, oid, u, length in misses]


def reaching_layouts(
    scene: Scene,
    interaction: Interaction,
    motion: Motion,
    report: CostReport,
    geom: SceneGeometry,
    *,
    sigma: float = 0.02,
    tolerance: float = 0.05,
    limit: int = 8,
) -> list[Scene]:
    """Candidate layouts with each missed contact's object moved toward the joint that misses it.

    Args:
        scene: the input layout.
        interaction: its contacts and, when given, the objects that may move.
        motion: the motion in ``scene``.
        report: the exact costs of ``scene`` with ``motion``.
        geom: the scene's geometry.
        sigma: the annealing's σ (metres); moves are multiples of 3σ (STEPS), then the whole miss.
        tolerance: contact distance (metres) below which a pair counts as met and nothing moves.
        limit: at most this many layouts.

    Returns:
        Layouts, the largest miss first and, for each, the smallest move first; empty when every
        contact is met or nothing may move.
    """
    if not report.contact_pairs or max(report.contact_distances, default=0.0) <= tolerance:
        return []
    by_id = {o.id: o for o in scene.objects}
    missed = {
        p.object_id
        for p, d in zip(report.contact_pairs, report.contact_distances, strict=True)
        if d > tolerance
    }
    out: list[Scene] = []
    seen: set[tuple[str, float, float]] = set()
    seat_ids = {p.object_id for p in report.contact_pairs if p.joint == "Hips"}
    work = [o for o in dict.fromkeys(p.object_id for p in report.contact_pairs) if o not in seat_ids]
    for oid, unit, length in contact_misses(scene, interaction, motion, report, geom):
        if oid not in missed:
            continue
        step = 3.0 * sigma
        toward = sorted({round(min(k * step, length), 4) for k in STEPS} | {round(length, 4)})
        moves = [(oid, unit, toward)]
        if oid in seat_ids:
            # The hips slid forward off the seat toward work out of reach (services.motion.synthesis,
            # SCOOT_MAX): bring the work to the seat first, which leaves the seat's approach as it is.
            # The slide is capped, so the work may have to come further than the miss.
            closer = sorted({round(k * length, 4) for k in SEAT_MISS_MULTIPLES})
            moves = [(w, -unit, closer) for w in work] + moves
        for target, direction, sizes in moves:
            for mover in _movers(by_id, target, interaction):
                model = LayoutModel(scene, [mover])
                for size in sizes:
                    move = _allowed_move(model, direction, size)  # as far as the rules let it go
                    key = (mover, round(float(direction[0]), 3), round(move, 3))
                    if move < 0.01 or key in seen:
                        continue
                    seen.add(key)
                    state = model.identity()
                    state[0, :2] = direction * move
                    out.append(model.scene_at(model.layouts(state[None]), 0))
                    if len(out) >= limit:
                        return out
    return out


def _allowed_move(model: LayoutModel, direction: np.ndarray, size: float, halvings: int = 6) -> float:
    """The longest move of the model's one object along ``direction`` (x, z unit), at most ``size``
    metres, that keeps the layout allowed (bisection; 0 when none is)."""

    def ok(move: float) -> bool:
        state = model.identity()
        state[0, :2] = direction * move
        return bool(model.allowed(model.layouts(state[None]))[0])

    if ok(size):
        return size
    lo, hi = 0.0, size
    for _ in range(halvings):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if ok(mid) else (lo, mid)
    return lo


def _movers(by_id: dict, oid: str, interaction: Interaction) -> list[str]:
    """The objects that may carry ``oid`` toward a joint: itself (a laptop slides on its desk), then
    what it rests on (the desk, the laptop riding on it); never a wall-mounted object nor one outside
    an explicit ``Interaction.movable``."""
    chain = [oid]
    while by_id[chain[-1]].support in by_id and by_id[chain[-1]].support not in chain:
        chain.append(by_id[chain[-1]].support)
    return [
        m
        for m in chain
        if not _wall_mounted(by_id[m].category) and (not interaction.movable or m in interaction.movable)
    ]
