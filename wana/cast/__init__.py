"""Bring your own character: a user's rigged humanoid (GLB, VRM, FBX through Blender) mapped onto the
canonical skeleton by joint names, and the canonical motion retargeted onto its own joints and proportions.

Shared by the orchestrator (it reads and checks the files ``--cast`` names before the pipeline runs) and the
render service (it writes the GLB with the user's mesh); the rig travels between them as GLB bytes in
``proto.render.CastMember``.
"""

from wana.cast.glb_rig import CastError, CastRig, read_rig
from wana.cast.names import REQUIRED, map_joints
from wana.cast.retarget import CastPose, retarget

__all__ = ["REQUIRED", "CastError", "CastPose", "CastRig", "map_joints", "read_rig", "retarget"]
