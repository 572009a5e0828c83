"""Messages of the social service: faces, response timing, interpersonal distance and proposed reactions.

Model: Zhao et al., "Triangular Character Animation Sampling" (relation r = (dominance, intimacy), emotion e
as a VAD change, motion m scored by its verb's VAD, MH sampling of an energy of pairwise and temporal
potentials). Seconds, metres; VAD values in [-1, 1]; face weights in [0, 1] in ``expression_names`` order.
"""

from __future__ import annotations

import msgspec

from proto.common import Header, NDArray, Request, Status
from proto.motion_data import Segment
from proto.ssg import SentenceGraph


class ExpressionKey(msgspec.Struct, frozen=True, kw_only=True):
    """A face keyframe, timed relative to the first frame of one character's action.

    The anchor is ``anchor_character``'s action number ``action_index`` (its k-th ActionNode in document
    order, as ``Segment.action_index``); a character's own actions anchor to itself, reactions to what
    another character does anchor to that character's action.
    """

    anchor_character: str
    action_index: int
    at_s: float  # seconds after the anchor action's first frame
    weights: list[float]  # face blendshape weights in [0, 1], SocialPlan.expression_names order
    vad: tuple[float, float, float]  # the emotion (valence, arousal, dominance) the face shows
    reaction: bool = False  # True: the face reacts to another character's action


class StepEmotion(msgspec.Struct, frozen=True, kw_only=True):
    """A character's sampled emotion at one sentence of the story."""

    step: int  # index among the story's character sentences
    sentence_id: str
    vad: tuple[float, float, float]


class CharacterSocial(msgspec.Struct, frozen=True, kw_only=True):
    """One character's face plan."""

    name: str
    rest_weights: list[float]  # face before the first key (the mood when the character first appears)
    keys: list[ExpressionKey] = []  # sorted by anchor time as far as the planner knows it
    emotions: list[StepEmotion] = []


class PairSocial(msgspec.Struct, frozen=True, kw_only=True):
    """The relation and standing distance of one character towards another (both directions are listed)."""

    character: str
    other: str
    relation: str  # label the text gave ("boss" means character is other's boss), or "default"
    dominance: float  # sampled, [-1, 1]: > 0 character dominates other
    intimacy: float  # sampled, [-1, 1]
    distance_m: float  # metres between the two when they face each other


class ActionDistance(msgspec.Struct, frozen=True, kw_only=True):
    """Distance for one action aimed at another character (contact clips: arm's length)."""

    character: str
    action_index: int
    other: str
    distance_m: float  # metres, root to root


class ResponseTiming(msgspec.Struct, frozen=True, kw_only=True):
    """When B reacts to A's action aimed at B."""

    actor: str  # A
    action_index: int  # A's action
    responder: str  # B
    response_index: int  # B's action that answers (-1: none in the text, see SocialPlan.proposals)
    delay_s: float  # seconds from the end of A's action to the start of B's response


class ProposedResponse(msgspec.Struct, frozen=True, kw_only=True):
    """A reaction the text leaves open, chosen among library clips by VAD fit. Only a proposal."""

    character: str  # who reacts (B)
    after: str  # A
    after_action_index: int  # A's action it answers
    action: str  # action-library clip name
    vad: tuple[float, float, float]  # the clip's VAD
    delay_s: float  # seconds after the end of A's action
    fit: float  # energy of the choice (lower fits better)
    proposed: bool = True  # always True: the text did not say it


class SocialPlan(msgspec.Struct, frozen=True, kw_only=True, tag="social_plan"):
    """The social model's answer for one document."""

    expression_names: list[str]
    characters: list[CharacterSocial] = []
    pairs: list[PairSocial] = []
    responses: list[ResponseTiming] = []
    proposals: list[ProposedResponse] = []
    action_distances: list[ActionDistance] = []
    energy_initial: float = 0.0
    energy_final: float = 0.0
    steps: int = 0  # Metropolis-Hastings steps run
    accepted: int = 0  # proposals accepted
    seed: int = 0
    notes: list[str] = []  # words the model could not score, relation labels it did not know


class SocialPlanRequest(Request["SocialPlanReply"], frozen=True, kw_only=True, tag="social_plan_request"):
    """Plan faces, timing, distances and open reactions of the characters of a document."""

    header: Header
    graphs: list[SentenceGraph]  # the document's sentence graphs in order (names resolved)
    seed: int = 0
    steps: int = 0  # Metropolis-Hastings steps; 0 = automatic (scaled to the story, bounded)


class SocialPlanReply(msgspec.Struct, frozen=True, kw_only=True, tag="social_plan_reply"):
    header: Header
    status: Status = "ok"
    plan: SocialPlan


class ExpressionTrackRequest(
    Request["ExpressionTrackReply"], frozen=True, kw_only=True, tag="expression_track_request"
):
    """Fill Motion.expression of one character from a plan and the motion's segments."""

    header: Header
    plan: SocialPlan
    character: str
    segments: list[Segment]
    frames: int = 0  # T; 0 = the segments' last end_frame
    fps: int = 30
    others: dict[str, list[Segment]] = {}  # other characters' segments, to place reaction keys


class ExpressionTrackReply(msgspec.Struct, frozen=True, kw_only=True, tag="expression_track_reply"):
    header: Header
    status: Status = "ok"
    expression: NDArray  # (T, E) float32 face blendshape weights in [0, 1]
