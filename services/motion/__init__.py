"""The motion service: neural locomotion, template actions, blending and IK.

CONTRACT: SynthesizeRequest -> SynthesizeReply | ErrorReply.

Python API: services.motion.library (action_names, load_library), services.motion.planning.plan_actions,
services.motion.synthesis (synthesise_segment, synthesise), services.motion.bvh (read_bvh, write_bvh),
services.motion.routing (scene_route, plan_scene_route, free_spot: the optimizer's A* on cached grids).
"""
