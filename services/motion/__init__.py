"""The motion service: neural locomotion, template actions, blending and IK.

CONTRACT: SynthesizeRequest -> SynthesizeReply | ErrorReply; PairRequest -> PairReply | ErrorReply.

Python API: wana.domain.actions (action_names, load_library), services.motion.planning.plan_actions,
services.motion.synthesis (synthesise_segment, synthesise), wana.domain.bvh (read_bvh, write_bvh),
services.motion.routing (scene_route, plan_scene_route, free_spot: wana.domain.routes' A* on cached grids,
round the characters standing in the way), services.motion.pairs (solve_pairs: two-person actions on both
bodies), services.motion.giveway (give_way: walkers wait for each other, a space-time reservation).
Skeleton, quaternions, BVH and the action catalogue are the domain library's (wana.domain); the clips
are authored by tools/authoring (python -m tools.authoring.author_actions).
"""
