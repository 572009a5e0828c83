"""Actions done seated: which seat the character sits on, and the interaction that includes it.

The orchestrator optimises each interaction of a story in turn, on a draft motion made before the
layout was optimised: "Eve sits on the chair. Eve types on the laptop." gives a draft of typing that
starts seated where the chair *was*. A seated action is the seat's as much as its target's: the
body goes wherever the seat goes, the hands only reach the keys when seat and laptop are close,
and the hips may slide forward on the seat (services.motion.synthesis, SCOOT_MAX), which eq. 2
sees as a miss of the seat's contact. So for such an interaction the optimiser

- finds the seat: the seat contact point (joint Hips, named "sit...") nearest the draft's hips;
- adds it to the interaction: it becomes the first target (the anchor that the surrogate motion
  follows, services.optimizer.resynthesis) and its hips pair joins the contacts, as when the
  interaction is given as "sit + type" (eval/optimizer.py);
- re-synthesises the sit and the action on that seat through the motion service
  (services.motion.seated) for the input layout and for every layout it verifies.
"""

from __future__ import annotations

from dataclasses import dataclass

import msgspec
import numpy as np

from proto.motion_data import Motion
from proto.optimizer import ContactPair, Interaction
from proto.scene import Scene
from proto.ssg import ActionNode
from services.optimizer.contacts import default_contacts
from services.optimizer.costs import LayoutBatch, SceneGeometry, contact_points_world
from services.optimizer.motion_port import installed
from services.optimizer.resynthesis import MotionFn
from services.optimizer.scoring import action_segment, is_locomotion
from wana.arrays import from_wire
from wana.domain.units import FPS

SEATED_HIPS_MAX_M = 0.8  # hips below this height (metres) at the first frame: the character is seated
SEAT_SEARCH_M = 0.8  # a seat point this far (x, z metres) from the draft's hips may be its seat
SEATING_ACTIONS = ("sit", "lie_down", "sleep", "stand")  # actions that change the posture themselves


@dataclass(frozen=True)
class Seat:
    """The seat a seated action is done on."""

    object_id: str
    point: str  # its contact point's name, e.g. "sit", "sit_0"


def seat_under(scene: Scene, motion: Motion, interaction: Interaction, geom: SceneGeometry) -> Seat | None:
    """The seat a motion that starts seated sits on, or None when it starts standing.

    Args:
        scene: the layout (the seat may have moved since the motion was made).
        motion: the draft: its first segment is the action itself (no walk, no sitting down).
        interaction: the interaction (its targets are never the seat).
        geom: the scene's geometry.

    Returns:
        The nearest seat contact point within SEAT_SEARCH_M of the first frame's hips, or None.
    """
    segs = sorted(motion.segments, key=lambda s: s.start_frame)
    if not segs or is_locomotion(segs[0].action) or segs[0].action in SEATING_ACTIONS:
        return None
    if interaction.action in SEATING_ACTIONS:
        return None
    hips = from_wire(motion.root_position)[0].astype(np.float64)
    if hips[1] > SEATED_HIPS_MAX_M:
        return None
    seats = [
        c
        for c in range(len(geom.contact_names))
        if geom.contact_joints[c] == "Hips"
        and geom.contact_names[c].startswith("sit")
        and geom.ids[geom.contact_owner[c]] not in interaction.targets
    ]
    if not seats:
        return None
    points = contact_points_world(geom, LayoutBatch.from_scenes([scene]), np.array(seats))[0]
    dist = np.linalg.norm(points[:, [0, 2]] - hips[[0, 2]], axis=1)
    best = int(np.argmin(dist))
    if dist[best] > SEAT_SEARCH_M:
        return None
    c = seats[best]
    return Seat(object_id=geom.ids[geom.contact_owner[c]], point=geom.contact_names[c])


def seated_interaction(interaction: Interaction, seat: Seat, geom: SceneGeometry) -> Interaction:
    """The interaction with its seat: first target, and its hips pair first among the contacts."""
    pairs = list(interaction.contacts) or default_contacts(geom, interaction)
    return msgspec.structs.replace(
        interaction,
        targets=[seat.object_id, *[t for t in interaction.targets if t != seat.object_id]],
        contacts=[ContactPair(object_id=seat.object_id, point=seat.point, joint="Hips"), *pairs],
        segment_index=-1,
    )


def seated_verifier(motion: Motion, interaction: Interaction, seat: Seat) -> MotionFn:
    """scene -> the motion service's sit on ``seat`` and the interaction's action, as the draft does it.

    The action keeps the draft's length; its target is the interaction's first non-seat target.
    """
    a0, a1 = action_segment(motion, interaction, len(from_wire(motion.root_position)))
    target = next((t for t in interaction.targets if t != seat.object_id), "")
    node = ActionNode(
        verb=interaction.action,
        action=interaction.action,
        target=target,
        duration_s=(a1 - a0) / float(motion.fps or FPS),
    )
    return installed().seated_action(motion.character, seat.object_id, node)
