"""The optimizer service: joint scene-layout and motion optimisation (paper §4.3, Algorithm 2).

CONTRACT:
    OptimiseRequest -> OptimiseReply | ErrorReply   simulated annealing of the layout around one interaction
    CostRequest     -> CostReply | ErrorReply       C_D (eq. 1), C_T (eq. 2) and C of a scene and motion

Python API (in-process, no bus):
    wana.domain.routes.plan_route(scene, start_xz, goal_xz, *, radius=0.25, cell=0.05, ignore=frozenset(), step_in=1.0)
        -> (N, 2) waypoints; raises NoRouteError. The motion service's ``route_fn``.
    annealing.optimise_interaction(scene, motion_fn, interaction, *, seed=0, steps=100, budget_s=None, ...)
        -> OptimisationResult(scene, motion, cost_curve, before, after, best_curve, steps_run, ...)
    verify.optimise_and_verify(scene, interaction, motion, *, character=None, start=(0, 0, 0), settings=None)
        -> VerifiedResult: anneal with the anchored surrogate, re-synthesise the winners, keep a verified one.
    resynthesis.motion_service_fn(character, start) / anchored_motion_fn(scene, motion, interaction)
        -> motion_fn: Scene -> Motion.
    scoring.InteractionScorer(scene, interaction, ...).score_scenes(scenes, motions) -> Scores (C, C_D, C_T, hits).

Routes (grid, A*, smoothing) and object geometry (catalog boxes as oriented boxes) are the domain
library's (wana.domain.routes, wana.domain.object_geometry). The motion re-synthesis comes in through
motion_port, installed by the composition root (wana.compose); the optimizer imports no motion code.

Modules: motion_port (the injected motion synthesis), body (FK, bone
spheres), costs (eq. 1, eq. 2, batched layouts), collisions (voxel-grid collider), contacts (contact
pairs), scoring (K proposals as one batch), shifted (the annealing's fast path: K proposals of the
anchored surrogate as shifts of one motion, all objects in one broad phase), annealing (Algorithm 2),
resynthesis, clearing (obstacles pushed off a blocked walk, for re-planning), reaching (a missed
contact's object moved toward its joint), layout_model (annealing states as layouts; room, overlap
and support rules), seating (a seated draft's seat joins its interaction and the verifier), verify,
handlers, worker.
"""
