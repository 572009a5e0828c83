"""Messages of the optimizer service: joint layout and motion optimisation, walking routes.

Paper: Zhang et al., Write-An-Animation (PG 2021), §4.3, Algorithm 2. Metres, world frame, Y up.
"""

from __future__ import annotations

from typing import Literal

import msgspec

from proto.common import Header, Request, Status
from proto.motion_data import Motion
from proto.scene import Scene
from proto.ssg import CharacterNode

# How the motion follows each proposed layout (see services/optimizer/resynthesis.py):
#   "anchored": the given motion moves with its anchor object (fast; needs only `motion`);
#   "hybrid": anneal with "anchored", then re-synthesise the best layout once through the motion
#             service and keep it only if it is better (needs `character`);
#   "motion_service": re-synthesise through the motion service for every proposal (slow; set a budget).
Resynthesis = Literal["anchored", "hybrid", "motion_service"]


class ContactPair(msgspec.Struct, frozen=True, kw_only=True):
    """An object's contact point and the joint the action brings to it."""

    object_id: str  # PlacedObject.id
    point: str  # interaction name of the object's catalog contact point, e.g. "sit", "write"
    joint: str = ""  # canonical joint, e.g. "Hips"; "" = the contact point's main joint


class Interaction(msgspec.Struct, frozen=True, kw_only=True):
    """One character action on objects, the unit the optimiser works on."""

    character: str
    action: str  # action-library name of the segment whose contacts count, e.g. "sit"
    targets: list[str] = []  # object ids the action uses; touching them while it holds is tolerated
    contacts: list[ContactPair] = []  # explicit pairs; empty = each target's contact points named `action`
    movable: list[str] = []  # ids the annealing may move; empty = the targets and the objects near the motion
    segment_index: int = -1  # Motion.segments index of the action; -1 = the last segment named `action`


class OptimiseSettings(msgspec.Struct, frozen=True, kw_only=True):
    """Algorithm 2's settings; the defaults are the paper's (batch, budget and seed are ours)."""

    lambda_d: float = 1.0  # weight of the collision cost C_D
    lambda_t: float = 10.0  # weight of the contact cost C_T (per metre)
    steps: int = 100  # at most this many annealing steps
    temperature: float = 1.0  # starting temperature
    cooling: float = 0.002  # temperature decrease per step
    sigma: float = 0.02  # std of the truncated-normal perturbation (metres for x, z; relative for scale)
    proposals: int = 4  # proposals per step, scored as one batch
    seed: int = 0
    budget_s: float = 0.0  # wall-clock budget in seconds; 0 = none (the best layout so far is returned)


class CostReport(msgspec.Struct, frozen=True, kw_only=True):
    """The costs of one layout with its motion."""

    cost: float  # C = λ_D·C_D + λ_T·C_T
    collision_cost: float  # C_D, eq. 1, in [0, 1]
    contact_cost: float  # C_T, eq. 2, metres
    collided_boxes: int  # collision boxes the body hits at any frame
    locomotion_collided_boxes: int  # of those, boxes hit while walking
    contact_distances: list[float] = []  # metres, one per contact pair
    contact_pairs: list[ContactPair] = []  # in the order of contact_distances


class OptimiseRequest(Request["OptimiseReply"], frozen=True, kw_only=True, tag="optimise_request"):
    """Optimise the layout around one interaction; the motion is re-synthesised for every proposal."""

    header: Header
    scene: Scene
    interaction: Interaction
    motion: Motion  # the character's motion in `scene`, as the motion service made it
    settings: OptimiseSettings = OptimiseSettings()
    resynthesis: Resynthesis = "anchored"
    character: CharacterNode | None = None  # the character's actions, for "hybrid" / "motion_service"
    start: tuple[float, float, float] = (0.0, 0.0, 0.0)  # x, z metres and yaw radians where it starts


class OptimiseReply(msgspec.Struct, frozen=True, kw_only=True, tag="optimise_reply"):
    header: Header
    status: Status = "ok"
    scene: Scene  # the optimised layout
    before: CostReport
    after: CostReport
    cost_curve: list[float] = []  # cost of the current layout after each step (index 0 = before)
    best_curve: list[float] = []  # best cost so far after each step
    steps_run: int = 0
    elapsed_ms: float = 0.0
    resynthesis: str = (
        ""  # how the motion that verified the layout was made: "anchored", "motion_service" or "input"
    )
    movable: list[str] = []  # ids of the objects the annealing moved (objects they support followed)


class CostRequest(Request["CostReply"], frozen=True, kw_only=True, tag="cost_request"):
    """Evaluate C_D and C_T of a scene and motion without optimising."""

    header: Header
    scene: Scene
    interaction: Interaction
    motion: Motion
    lambda_d: float = 1.0
    lambda_t: float = 10.0


class CostReply(msgspec.Struct, frozen=True, kw_only=True, tag="cost_reply"):
    header: Header
    status: Status = "ok"
    report: CostReport


OptimizerRequest = OptimiseRequest | CostRequest
