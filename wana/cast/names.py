"""Which of a user's joints is which canonical joint: by name, for the rigs people have.

Mixamo (``mixamorig:LeftArm``: our own names under a namespace), VRM (the humanoid bone table in the file's
``VRM``/``VRMC_vrm`` extension), Unity's humanoid (``LeftUpperArm``) and Unreal's mannequin (``upperarm_l``);
names are compared without case, namespace or separators. A user map (canonical -> joint name, JSON)
covers any other rig and wins over the tables. Joints no table names (twists, fingers, props) are kept and
follow their parents.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Mapping

from wana.cast.glb_rig import CastError, CastRig
from wana.domain.skeleton import JOINT_NAMES

# without these the motion cannot be shown: the legs carry the feet, the arms the gestures
REQUIRED: tuple[str, ...] = (
    "Hips",
    "Spine",
    "Head",
    "LeftArm",
    "LeftForeArm",
    "LeftHand",
    "RightArm",
    "RightForeArm",
    "RightHand",
    "LeftUpLeg",
    "LeftLeg",
    "LeftFoot",
    "RightUpLeg",
    "RightLeg",
    "RightFoot",
)

# VRM humanoid bones (= Unity's HumanBodyBones in lower camel case) -> canonical
VRM_BONES: dict[str, str] = {
    "hips": "Hips",
    "spine": "Spine",
    "chest": "Spine1",
    "upperChest": "Spine2",
    "neck": "Neck",
    "head": "Head",
    "leftShoulder": "LeftShoulder",
    "leftUpperArm": "LeftArm",
    "leftLowerArm": "LeftForeArm",
    "leftHand": "LeftHand",
    "leftMiddleProximal": "LeftHandMiddle1",
    "rightShoulder": "RightShoulder",
    "rightUpperArm": "RightArm",
    "rightLowerArm": "RightForeArm",
    "rightHand": "RightHand",
    "rightMiddleProximal": "RightHandMiddle1",
    "leftUpperLeg": "LeftUpLeg",
    "leftLowerLeg": "LeftLeg",
    "leftFoot": "LeftFoot",
    "leftToes": "LeftToeBase",
    "rightUpperLeg": "RightUpLeg",
    "rightLowerLeg": "RightLeg",
    "rightFoot": "RightFoot",
    "rightToes": "RightToeBase",
}

_UNREAL: dict[str, str] = {
    "pelvis": "Hips",
    "spine_01": "Spine",
    "spine_02": "Spine1",
    "spine_03": "Spine2",
    "neck_01": "Neck",
    "head": "Head",
    **{
        f"{ue}_{s}": f"{side}{ours}"
        for s, side in (("l", "Left"), ("r", "Right"))
        for ue, ours in (
            ("clavicle", "Shoulder"),
            ("upperarm", "Arm"),
            ("lowerarm", "ForeArm"),
            ("hand", "Hand"),
            ("middle_01", "HandMiddle1"),
            ("thigh", "UpLeg"),
            ("calf", "Leg"),
            ("foot", "Foot"),
            ("ball", "ToeBase"),
        )
    },
}


def _key(name: str) -> str:
    """A name without namespace (``mixamorig:``, ``Armature|``), case or separators."""
    name = re.split(r"[:|]", name)[-1]
    name = re.sub(r"^mixamorig\d*_?", "", name, flags=re.IGNORECASE)
    return re.sub(r"[^0-9a-z]", "", name.lower())


# normalised name -> canonical joint: Mixamo (our own names), Unity/VRM humanoid, Unreal
NAME_TABLE: dict[str, str] = {
    **{_key(n): n for n in JOINT_NAMES},
    **{_key(k): v for k, v in VRM_BONES.items()},
    **{_key(k): v for k, v in _UNREAL.items()},
}


def map_joints(
    rig: CastRig, user_map: Mapping[str, str] | None = None, label: str = "the rig"
) -> dict[str, int]:
    """Canonical joint -> the rig's joint index.

    Args:
        rig: the user's character.
        user_map: canonical joint -> joint name in the rig (a ``--cast-map`` file); wins over the tables.
        label: how messages name the rig.

    Raises:
        CastError: the map names a joint the rig lacks or a canonical joint that does not exist, or the rig
            lacks a required canonical joint (all of them listed).
    """
    index = {n: i for i, n in enumerate(rig.names)}
    out: dict[str, int] = {}
    for bone, j in rig.humanoid.items():  # a VRM says which bone is which itself
        if bone in VRM_BONES:
            out[VRM_BONES[bone]] = j
    for i, name in enumerate(rig.names):
        canonical = NAME_TABLE.get(_key(name))
        if canonical is not None and canonical not in out:
            out[canonical] = i
    for canonical, name in (user_map or {}).items():
        if canonical not in JOINT_NAMES:
            near = difflib.get_close_matches(canonical, JOINT_NAMES, n=1)
            hint = f" (did you mean {near[0]}?)" if near else ""
            raise CastError(f"the joint map names {canonical!r}, not a canonical joint{hint}")
        if name not in index:
            near = difflib.get_close_matches(name, rig.names, n=1)
            hint = f" (did you mean {near[0]!r}?)" if near else ""
            raise CastError(f"the joint map maps {canonical} to {name!r}, which {label} does not have{hint}")
        out[canonical] = index[name]
    missing = [c for c in REQUIRED if c not in out]
    if missing:
        raise CastError(
            f"{label} has no joint for the canonical {', '.join(missing)}; name them in a --cast-map JSON file "
            '(canonical joint -> your joint name, e.g. {"Hips": "pelvis"})'
        )
    return dict(sorted(out.items(), key=lambda kv: JOINT_NAMES.index(kv[0])))
