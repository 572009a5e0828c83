"""Contact pairs: which contact points an interaction measures, and how the body may touch them.

Used by the scorer (services.optimizer.scoring): the default pairs of an interaction's targets, the
bones that rest on a contact's object by design, and the arm reach within which the motion
service's IK meets a hand contact.
"""

from __future__ import annotations

import numpy as np

from proto.optimizer import ContactPair, Interaction
from services.optimizer.body import BodySpheres
from services.optimizer.costs import SceneGeometry
from wana.domain.skeleton import JOINT_INDEX, JOINT_NAMES, PARENTS, REST_OFFSETS

IK_ROOTS = ("LeftArm", "RightArm")  # the motion service's two-bone IK brings hands to their contacts


def ik_chain(joint: str) -> tuple[int, float] | None:
    """(index of the arm root, reach in metres) for a joint an arm IK can place, else None.

    The reach is the two IK bones (upper arm and forearm) only: the hand keeps its pose, so a point
    is only sure to be met when the wrist can get there.
    """
    j = JOINT_INDEX[joint]
    bones: list[float] = []
    while j >= 0:
        if JOINT_NAMES[j] in IK_ROOTS:
            return j, float(sum(bones[-2:]))
        bones.append(float(np.linalg.norm(REST_OFFSETS[j])))
        j = int(PARENTS[j])
    return None


def contact_bones(
    spheres: BodySpheres,
    pairs: list[ContactPair],
    ids: tuple[str, ...],
    supports: dict[str, str] | None = None,
) -> np.ndarray:
    """(S, O) true where a sphere's bone touches a contact joint of a pair on that object.

    A bone touches joint j when one of its ends is j, j's parent or one of j's children: hips on a
    seat bring the pelvis and thighs onto it, a hand on keys its fingers and wrist. A hand's bones
    may also rest on what its object stands on (``supports``: object id -> support id): typing on a
    laptop, the wrists and forearms lie on the desk.
    """
    out = np.zeros((len(spheres.radius), len(ids)), dtype=bool)
    supports = supports or {}
    for p in pairs:
        j = JOINT_INDEX[p.joint]
        near = {j, int(PARENTS[j])} | {int(c) for c in np.flatnonzero(PARENTS == j)}
        touches = np.isin(spheres.a, list(near)) | np.isin(spheres.b, list(near))
        out[touches, ids.index(p.object_id)] = True
        below, seen = supports.get(p.object_id, ""), {p.object_id}
        while p.joint != "Hips" and below in ids and below not in seen:
            out[touches, ids.index(below)] = True
            seen.add(below)
            below = supports.get(below, "")
    return out


def default_contacts(geom: SceneGeometry, interaction: Interaction) -> list[ContactPair]:
    """Contact pairs of the targets when the interaction names none.

    For each target: its contact points named after the action (all joints of it); failing that, the
    ones whose name starts with the action ("sit" -> "sit_0" of a sofa, first only); failing that none
    (the target is still exempt from collisions while the action holds).
    """
    pairs: list[ContactPair] = []
    for t in interaction.targets:
        idx = geom.object_contacts(t)
        named = [c for c in idx if geom.contact_names[c] == interaction.action]
        if not named:
            prefixed = sorted(
                {geom.contact_names[c] for c in idx if geom.contact_names[c].startswith(interaction.action)}
            )
            named = [c for c in idx if prefixed and geom.contact_names[c] == prefixed[0]]
        pairs += [
            ContactPair(object_id=t, point=geom.contact_names[c], joint=geom.contact_joints[c]) for c in named
        ]
    return pairs
