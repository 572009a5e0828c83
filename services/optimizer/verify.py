"""Anneal with the fast anchored surrogate, then verify the winner with the motion service.

The surrogate (services.optimizer.resynthesis.anchored_motion_fn) makes the search cheap but cannot
see what only a full re-synthesis changes (a route that opens up, an approach point that becomes
reachable). So the search's last few best layouts are re-synthesised through the motion service
and scored exactly. A candidate qualifies when its walk hits no more boxes than the input's and
either its cost C is lower or its walk hits fewer boxes without losing contact (C_T within 5 cm or
the input's); among those, a walk with fewer hit boxes wins, then the lower C. When none of them
walks collision-free and the input's walk hits boxes, layouts with those obstacles pushed off the walk
(services.optimizer.clearing) are re-synthesised too, the route re-planned by A* in each. When the
input misses a contact (C_T above 5 cm), layouts with the missed contact's object moved toward its
joint (services.optimizer.reaching) are re-synthesised first, and the search's layouts are verified
even when its own exact report (on the surrogate's motion) saw no gain. Without a qualifying
candidate the input comes back; a qualifying one that still misses a contact is reached from once
more. The annealing itself runs only when its layouts would be verified: not when the input hits no
box and every contact is within 1 cm, nor when a reach layout already verified collision-free with its
contacts held. When the body, still (seated), ends up inside furniture the reach brought close (legs in a
desk's drawer pedestal), that furniture slides sideways off it (services.optimizer.legroom). A
draft that starts seated (and no character given) is re-synthesised on its seat first and
verified by re-synthesising the sit and the action there (services.optimizer.seating).
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from dataclasses import dataclass

from proto.motion_data import Motion
from proto.optimizer import CostReport, Interaction, OptimiseSettings
from proto.scene import Scene
from proto.ssg import CharacterNode
from services.optimizer.annealing import OptimisationResult, optimise_interaction
from services.optimizer.clearing import clearing_layouts
from services.optimizer.costs import SceneGeometry
from services.optimizer.legroom import legroom_layouts
from services.optimizer.reaching import reaching_layouts
from services.optimizer.resynthesis import MotionFn, anchored_motion_fn, motion_service_fn
from services.optimizer.scoring import InteractionScorer
from services.optimizer.seating import seat_under, seated_interaction, seated_verifier

CONTACT_OK_M = 0.05  # contact distance (metres) counted as contact
# A reach that holds within this (metres) ends the verification; one that holds only barely may be
# beaten by a longer move, so the next reach is still tried.
REACH_SETTLED_M = CONTACT_OK_M / 2
CONTACT_EXACT_M = 0.01  # an input whose every contact is this close (metres) and that hits nothing is kept


@dataclass
class VerifiedResult:
    """The annealing result plus what the motion service made of its winner.

    Attributes:
        search: the annealing result (its motion is the surrogate's).
        scene: the layout returned (the winner, or the input when the winner did not verify).
        motion: the motion returned.
        after: exact costs of the returned scene and motion.
        made: "motion_service" (verified winner), "input" (winner rejected) or "anchored" (no verifier).
    """

    search: OptimisationResult
    scene: Scene
    motion: Motion
    after: CostReport
    made: str


def optimise_and_verify(
    scene: Scene,
    interaction: Interaction,
    motion: Motion,
    *,
    character: CharacterNode | None = None,
    start: tuple[float, float, float] = (0.0, 0.0, 0.0),
    settings: OptimiseSettings | None = None,
    verifier: MotionFn | None = None,
    geometry: SceneGeometry | None = None,
    candidates: int = 4,
    clearing: int = 6,
    reaching: int = 6,
    legroom: int = 2,
) -> VerifiedResult:
    """Optimise one interaction with the anchored surrogate and verify the result.

    Args:
        scene: input layout.
        interaction: the interaction (its first target anchors the motion).
        motion: the motion in ``scene``.
        character: the character's actions; with ``start`` they make the motion-service verifier.
        start: (x, z, yaw) where the character starts.
        settings: annealing settings (seed, steps, budget included).
        verifier: scene -> Motion used instead of the motion service (tests, other synthesisers).
        geometry: the scene's object geometry (read from the catalog when None).
        candidates: how many of the search's successive best layouts to re-synthesise, spread from the
            best back to the first improvement.
        clearing: when none of those gives a collision-free walk and the input's walk hits boxes, at
            most this many layouts with the obstacles pushed off the walk (services.optimizer.clearing)
            are re-synthesised too.
        reaching: when the input misses a contact (C_T above 5 cm), at most this many layouts with the
            missed contact's object moved toward its joint (services.optimizer.reaching) are
            re-synthesised first, smallest move first.
        legroom: when the returned layout's still body (seated legs) hits furniture, at most this many
            layouts with that furniture slid sideways off it (services.optimizer.legroom) are
            re-synthesised; the first that hits fewer boxes and keeps the contacts is returned.

    Returns:
        The verified result.
    """
    st = settings or OptimiseSettings()
    geom = geometry if geometry is not None else SceneGeometry.from_scene(scene)
    if verifier is None and character is None:
        interaction, motion, verifier = _seated(scene, interaction, motion, geom)
    t_start = time.perf_counter()

    def run_search(stop_at_zero: bool = False) -> OptimisationResult:
        return optimise_interaction(
            scene,
            anchored_motion_fn(scene, motion, interaction, geom),
            interaction,
            seed=st.seed,
            steps=st.steps,
            budget_s=st.budget_s if st.budget_s > 0 else None,
            settings=st,
            motion=motion,
            geometry=geom,
            ik_search=verifier is not None or character is not None,
            stop_at_zero=stop_at_zero,
        )

    if verifier is None and character is not None:
        verifier = motion_service_fn(character, start)
    if verifier is None:  # nothing verifies the search's other candidates: stop once C is 0
        search = run_search(stop_at_zero=True)
        return VerifiedResult(search, search.scene, search.motion, search.after, "anchored")
    reporter = InteractionScorer(
        scene, interaction, lambda_d=st.lambda_d, lambda_t=st.lambda_t, frame_stride=1, geometry=geom
    )
    base = reporter.score_scenes([scene], [motion]).report(0, reporter.pairs)
    if base.collided_boxes == 0 and max(base.contact_distances, default=0.0) <= CONTACT_EXACT_M:
        # Nothing to gain: no box hit, every contact on its point (a layout already optimised).
        return VerifiedResult(_unsearched(scene, motion, base, t_start), scene, motion, base, "input")
    searched: list[OptimisationResult] = []  # the annealing, run when the reach alone does not settle it
    chosen: tuple[tuple[int, float], Scene, Motion, CostReport] | None = None

    def search_picks() -> list[Scene]:
        # The search's best layouts are verified even when its exact report kept the input: that
        # report scores the surrogate's motion, which does not re-solve the arm IK nor re-plan the
        # approach, so a layout that brings a contact within reach looks no better there than the input.
        searched.append(run_search())
        history = searched[0].candidates  # best first
        if not history and base.locomotion_collided_boxes == 0 and base.contact_cost <= CONTACT_OK_M:
            return []
        picks = sorted({round(i * (len(history) - 1) / max(candidates - 1, 1)) for i in range(candidates)})
        return [history[i] for i in picks] if history else []

    tried: list[tuple[int, Scene, Motion]] = []  # verified clearing layouts: walk hits, scene, motion

    def unsolved() -> bool:
        return bool(base.locomotion_collided_boxes) and (chosen is None or chosen[0][0] > 0)

    def solved() -> bool:  # a verified layout whose walk is collision-free and whose contacts hold
        return chosen is not None and chosen[0][0] == 0 and chosen[3].contact_cost <= CONTACT_OK_M

    def queue() -> Iterator[tuple[Scene, str]]:
        if base.contact_cost > CONTACT_OK_M:
            # A contact is missed: the moves that bring its object toward the joint, all of them
            # (the first that holds may hold barely), smallest first.
            yield from (
                (c, "reach")
                for c in reaching_layouts(
                    scene, interaction, motion, base, geom, sigma=st.sigma, tolerance=CONTACT_OK_M
                )[:reaching]
            )
        if solved():
            return  # a reach verified: the search's layouts would not be tried (see the loop below)
        yield from ((c, "search") for c in search_picks())
        if not unsolved():
            return
        # The walk still runs into something: move those obstacles off it and let the motion service
        # re-plan the route (the surrogate cannot see a route open up). A second round clears what
        # the new route of the most promising first-round layout runs into.
        walk_hits = reporter.score_scenes([scene], [motion]).locomotion_box_hit[0]
        yield from (
            (c, "clearing") for c in clearing_layouts(scene, interaction, motion, walk_hits, geom)[:clearing]
        )
        if not unsolved() or not tried:
            return
        _, first, first_motion = min(tried, key=lambda t: t[0])
        walk_hits = reporter.score_scenes([first], [first_motion]).locomotion_box_hit[0]
        again = clearing_layouts(first, interaction, first_motion, walk_hits, geom)
        yield from ((c, "clearing again") for c in again[: max(1, clearing // 2)])

    for cand, kind in queue():
        if solved() and (kind != "reach" or chosen[3].contact_cost <= REACH_SETTLED_M):  # type: ignore[index]
            break  # take it
        real = verifier(cand)
        rep = reporter.score_scenes([cand], [real]).report(0, reporter.pairs)
        if kind == "clearing" and rep.locomotion_collided_boxes:
            tried.append((rep.locomotion_collided_boxes, cand, real))
        fewer_walk_hits = (
            rep.locomotion_collided_boxes < base.locomotion_collided_boxes
            and rep.contact_cost <= max(base.contact_cost, CONTACT_OK_M)
        )
        no_new_walk_hits = rep.locomotion_collided_boxes <= base.locomotion_collided_boxes
        if no_new_walk_hits and (rep.cost < base.cost or fewer_walk_hits):
            key = (rep.locomotion_collided_boxes, rep.cost)
            if chosen is None or key < chosen[0]:
                chosen = (key, cand, real, rep)
    if chosen is not None and max(chosen[3].contact_distances, default=0.0) > CONTACT_OK_M:
        # The best verified layout still misses a contact (the search cleared the walk, the laptop
        # stayed out of reach): reach once more, from it, keeping its walk.
        _, first, first_motion, first_rep = chosen
        again = reaching_layouts(
            first, interaction, first_motion, first_rep, geom, sigma=st.sigma, tolerance=CONTACT_OK_M
        )
        for cand in again[:reaching]:
            real = verifier(cand)
            rep = reporter.score_scenes([cand], [real]).report(0, reporter.pairs)
            key = (rep.locomotion_collided_boxes, rep.cost)
            if key < chosen[0]:
                chosen = (key, cand, real, rep)
                if max(rep.contact_distances, default=0.0) <= CONTACT_OK_M:
                    break  # every contact met: a longer move only moves the furniture further
    # The still body (seated legs) inside furniture the reach brought close: slide it sideways.
    kept = (chosen[1], chosen[2], chosen[3], "motion_service") if chosen else (scene, motion, base, "input")
    if legroom and kept[2].collided_boxes > kept[2].locomotion_collided_boxes:
        for cand in legroom_layouts(kept[0], interaction, kept[1], reporter, limit=legroom):
            real = verifier(cand)
            rep = reporter.score_scenes([cand], [real]).report(0, reporter.pairs)
            if (
                rep.locomotion_collided_boxes <= kept[2].locomotion_collided_boxes
                and rep.collided_boxes < kept[2].collided_boxes
                and rep.contact_cost <= max(kept[2].contact_cost, CONTACT_OK_M)
            ):
                kept = (cand, real, rep, "motion_service")
                break
    search = searched[0] if searched else _unsearched(scene, motion, base, t_start)
    return VerifiedResult(search, kept[0], kept[1], kept[2], kept[3])


def _unsearched(scene: Scene, motion: Motion, base: CostReport, t_start: float) -> OptimisationResult:
    """The result of an annealing that did not need to run (0 steps): the input, its costs."""
    return OptimisationResult(
        scene=scene,
        motion=motion,
        cost_curve=[base.cost],
        before=base,
        after=base,
        best_curve=[base.cost],
        steps_run=0,
        elapsed_ms=(time.perf_counter() - t_start) * 1000.0,
    )


def _seated(
    scene: Scene, interaction: Interaction, motion: Motion, geom: SceneGeometry
) -> tuple[Interaction, Motion, MotionFn | None]:
    """For a draft that starts seated: the interaction with its seat, the sit and the action
    re-synthesised on the seat as it is now, and that re-synthesis as the verifier
    (services.optimizer.seating); otherwise the inputs and no verifier."""
    seat = seat_under(scene, motion, interaction, geom)
    if seat is None:
        return interaction, motion, None
    verifier = seated_verifier(motion, interaction, seat)
    try:
        resynthesised = verifier(scene)
    except Exception:  # noqa: BLE001 - the motion service cannot seat it here: optimise the draft as given
        return interaction, motion, None
    return seated_interaction(interaction, seat, geom), resynthesised, verifier
