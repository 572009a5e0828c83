"""Layouts that give a seated body its legroom back, for the verifier to re-synthesise.

Bringing work to a seat (services.optimizer.reaching pulls a desk toward its chair so the hands
reach the laptop) can push the furniture into the seated body: Eve's right leg inside the desk's
drawer pedestal while she types. Eq. 1 counts those boxes, but the candidates that brought the work
close never move it sideways, and moving the seat back undoes the reach. These candidates make the
move a person would: each floor object the body hits while it is not walking (never a target of the
action, never wall-mounted, never outside an explicit ``Interaction.movable``) slides sideways,
along the line through the hips, away from the body, by the smallest of LATERAL_STEPS_M that leaves
the fewest of its boxes hit in the current motion (scored exactly, every frame). What rests on it (the laptop) stays
where it is in the world when its footprint stays on its support, so the hands keep their keys;
otherwise it rides along. The motion service then re-synthesises each candidate
(``verify.optimise_and_verify``) and only a verified clearance is kept.
"""

from __future__ import annotations

import numpy as np

from proto.motion_data import Motion
from proto.optimizer import Interaction
from proto.scene import Scene
from services.optimizer.body import motion_joint_positions
from services.optimizer.costs import LayoutBatch, world_boxes
from services.optimizer.layout_model import LayoutModel
from services.optimizer.reaching import _wall_mounted
from services.optimizer.scoring import InteractionScorer, is_locomotion
from wana.domain.skeleton import JOINT_INDEX

LATERAL_STEPS_M = (0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4)  # sideways moves tried, metres
RANK_STRIDE = 2  # frames tested when ranking the moves: every n-th


def seated_hits(scorer: InteractionScorer, scene: Scene, motion: Motion) -> np.ndarray:
    """(O,) number of boxes of each non-target object the body hits outside its walks."""
    s = scorer.score_scenes([scene], [motion])
    still = s.box_hit[0] & ~s.locomotion_box_hit[0]
    counts = np.bincount(scorer.geom.box_owner[still], minlength=len(scorer.geom.ids))
    counts[scorer.is_target] = 0
    return counts


def legroom_layouts(
    scene: Scene,
    interaction: Interaction,
    motion: Motion,
    scorer: InteractionScorer,
    *,
    limit: int = 2,
) -> list[Scene]:
    """Candidate layouts with each object the still body hits slid sideways off it.

    Args:
        scene: the layout (the verifier's best so far).
        interaction: its targets (never moved here) and, when given, the objects that may move.
        motion: the motion in ``scene`` (re-synthesised there).
        scorer: an exact scorer (frame_stride 1) of the interaction on ``scene``'s objects.
        limit: at most this many layouts.

    Returns:
        Layouts, the object with the most hit boxes first and, for it, the smallest clearing move
        first (one per side at most); empty when the still body hits nothing it may move.
    """
    hits = seated_hits(scorer, scene, motion)
    if not hits.any():
        return []
    geom = scorer.geom
    positions = motion_joint_positions(motion)  # (T, J, 3)
    still = np.ones(len(positions), dtype=bool)
    for seg in motion.segments:
        if is_locomotion(seg.action):
            still[max(0, seg.start_frame) : max(0, seg.end_frame)] = False
    if not still.any():
        return []
    hips_l = positions[still][:, JOINT_INDEX["LeftUpLeg"]].mean(axis=0)
    hips_r = positions[still][:, JOINT_INDEX["RightUpLeg"]].mean(axis=0)
    lateral = (hips_l - hips_r)[[0, 2]]
    if np.linalg.norm(lateral) < 1e-6:
        return []
    lateral = lateral / np.linalg.norm(lateral)  # x, z unit toward the body's left
    centre = ((hips_l + hips_r) / 2)[[0, 2]]
    base = LayoutBatch.from_scenes([scene])
    box_centre = world_boxes(geom, base)[0][0]  # (B, 3)
    # Moves are ranked on every RANK_STRIDE-th frame (the verifier scores its pick on all of them).
    ranker = InteractionScorer(
        scene,
        interaction,
        frame_stride=RANK_STRIDE,
        geometry=geom,
        contact_tolerance=scorer.contact_tolerance,
    )
    out: list[Scene] = []
    for oi in np.argsort(-hits, kind="stable"):
        if hits[oi] == 0 or len(out) >= limit:
            break
        obj = scene.objects[int(oi)]
        if obj.support or _wall_mounted(obj.category):
            continue
        if interaction.movable and obj.id not in interaction.movable:
            continue
        riders = [o.id for o in scene.objects if o.support == obj.id]
        # Away from the body: the side of the hips the object's hit boxes are on goes further out.
        mine = np.flatnonzero(geom.box_owner == oi)
        side = float(np.dot(box_centre[mine][:, [0, 2]].mean(axis=0) - centre, lateral))
        directions = [np.sign(side) * lateral if abs(side) > 1e-3 else lateral]
        for direction in directions:
            move = _clearing_move(scene, ranker, motion, obj.id, riders, direction, int(oi), int(hits[oi]))
            if move is not None:
                out.append(move)
            if len(out) >= limit:
                break
    return out


def _clearing_move(
    scene: Scene,
    scorer: InteractionScorer,
    motion: Motion,
    oid: str,
    riders: list[str],
    direction: np.ndarray,
    oi: int,
    hits_now: int,
) -> Scene | None:
    """The smallest allowed sideways move of ``oid`` that leaves the fewest of its boxes hit by the still
    body (a pedestal clears, the apron across the legs stays), its riders kept in place in the world
    when allowed; None when no step of LATERAL_STEPS_M leaves fewer than ``hits_now``."""
    n = len(LATERAL_STEPS_M)
    steps = np.asarray(LATERAL_STEPS_M)[:, None] * direction[None]  # (N, 2)
    model = LayoutModel(scene, [oid, *riders])
    states = np.repeat(model.identity()[None], 2 * n, axis=0)  # riders fixed in the world, then riding
    states[:, 0, :2] = np.concatenate([steps, steps])
    if riders:
        states[:n, 1:, :2] = -steps[:, None]
    allowed = model.allowed(model.layouts(states))
    # Per step, riders kept in place when allowed, else carried: one layout per step to score.
    pick = np.array([i if allowed[i] else i + n for i in range(n)])
    pick = pick[allowed[pick]]
    if not len(pick):
        return None
    layouts = model.layouts(states[pick])
    s = scorer.score(layouts, [motion] * len(pick))
    still = s.box_hit & ~s.locomotion_box_hit
    left = still[:, scorer.geom.box_owner == oi].sum(axis=1)
    if left.min() >= hits_now:
        return None
    return model.scene_at(layouts, int(np.argmax(left == left.min())))  # the smallest such move
