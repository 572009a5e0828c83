"""Messages of the motion service: plan + synthesise a character's motion, list the action library.

Metres, world frame, Y up, 30 fps, quaternions (x, y, z, w). See services/motion/__init__.py.
"""

from __future__ import annotations

from typing import Literal

import msgspec

from proto.common import Header, Request, Status
from proto.motion_data import Motion
from proto.scene import Scene
from proto.ssg import CharacterNode


class SegmentEndState(msgspec.Struct, frozen=True, kw_only=True):
    """Where a character is after a segment (the input of the next one); compare for early cutoff."""

    x: float = 0.0  # metres, world
    z: float = 0.0  # metres, world
    yaw: float = 0.0  # radians about +Y, 0 faces +Z
    posture: str = "stand"  # stand | sit | lie | sit_floor
    phase: float = 0.0  # gait phase in [0, 1)
    hips_dy: float = 0.0  # metres the hips sit above the posture's rest height (a seat's height); 0 standing
    holding: str = ""  # id of the scene object in the hand ("" when the hands are empty)


class SynthesizeRequest(Request["SynthesizeReply"], frozen=True, kw_only=True, tag="synthesize_request"):
    """Synthesise one character's motion from its ordered actions in a scene."""

    header: Header
    character: CharacterNode
    scene: Scene
    start: tuple[float, float, float] = (
        0.0,
        0.0,
        0.0,
    )  # x, z metres and yaw radians where the character starts
    from_segment: int = 0  # recompute from this segment on (earlier ones are skipped)
    start_state: SegmentEndState | None = None  # end state of segment from_segment-1 (None: from `start`)
    routes: list[
        list[tuple[float, float]]
    ] = []  # optional precomputed waypoints, one list per locomotion segment
    others: dict[
        str, tuple[float, float]
    ] = {}  # other characters' x, z (metres, world) when the first action starts
    distances: dict[
        str, float
    ] = {}  # metres to stop from another character when walking up to them (the social model's); absent = 0.8
    seats: dict[
        int, str
    ] = {}  # action index -> the contact point its seat or bed slot is ("sit_0"); absent = default
    spots: dict[
        int, tuple[float, float]
    ] = {}  # action index -> x, z (metres, world) where it stands at its object
    occupied: list[
        tuple[float, float]
    ] = []  # x, z (metres, world) of other characters seated by then: seat slots there are not free
    bodies: list[
        tuple[float, float]
    ] = []  # x, z (metres, world) of other characters standing in the room by then: walks go round them


class SynthesizeReply(msgspec.Struct, frozen=True, kw_only=True, tag="synthesize_reply"):
    header: Header
    status: Status = "ok"
    motion: Motion  # frames of segments from_segment.. (all of them when from_segment = 0)
    end_states: list[SegmentEndState] = []  # one per synthesised segment
    diagnostics: list[str] = []  # e.g. unknown actions replaced by a wait


class PairedAction(msgspec.Struct, frozen=True, kw_only=True):
    """A two-person action of the story (a hug, a handshake): whose clip it is and who it is done to."""

    actor: str  # the character whose action clip it is
    action_index: int  # index of the actor's ActionNode (Segment.action_index of the clip)
    action: str  # action-library name of the clip ("hug", "shake_hands")
    partner: str = ""  # the character it is done to; "" = the nearest one on stage
    delay_s: float = 0.0  # seconds the partner's answer lags the actor (the social model's response delay)


class PairContact(msgspec.Struct, frozen=True, kw_only=True):
    """The contact one paired action reached."""

    actor: str
    partner: str
    action: str
    start_frame: int  # first contact frame (the clip's interaction window), story frames
    end_frame: int  # exclusive
    gap_m: float  # metres: the largest distance from a contact joint to its shared target over those frames


class PairRequest(Request["PairReply"], frozen=True, kw_only=True, tag="pair_request"):
    """Fit the cast's motions to each other once they share one time line: walkers give way to each other
    (services/motion/giveway.py) and paired actions get both bodies' contacts (services/motion/pairs.py)."""

    header: Header
    motions: dict[str, Motion]  # name -> the character's whole motion, story frames
    pairs: list[PairedAction] = []  # in story order
    give_way: bool = True  # a walker about to walk into another character waits until the way is clear
    scene: Scene | None = None  # the room and furniture: a walker no wait helps may step aside where it fits


class PairReply(msgspec.Struct, frozen=True, kw_only=True, tag="pair_reply"):
    header: Header
    status: Status = "ok"
    motions: dict[str, Motion]  # every motion of the request, the changed ones replaced
    contacts: list[PairContact] = []  # one per solved paired action
    diagnostics: list[str] = []  # e.g. a partner too far away to touch


MotionRequest = SynthesizeRequest
__all__ = [
    "Literal",
    "MotionRequest",
    "PairContact",
    "PairReply",
    "PairRequest",
    "PairedAction",
    "SegmentEndState",
    "SynthesizeReply",
    "SynthesizeRequest",
]
