"""The social stage: the `social` plan node, one `face:<name>` node per character (social service), and the
`cast` node that fits the characters' motions to each other once they share a time line (motion service:
walkers give way, two-person actions touch on both bodies).

"""

from __future__ import annotations

from collections.abc import Sequence

import msgspec
import numpy as np

from proto.motion import PairedAction, PairReply, PairRequest
from proto.motion_data import Motion, Segment
from proto.social import ExpressionTrackReply, ExpressionTrackRequest, SocialPlan, SocialPlanRequest
from proto.ssg import CharacterNode, SentenceGraph
from services.orchestrator.stages import StageContext, content_of
from services.orchestrator.views import social_part
from wana.arrays import from_wire, to_wire
from wana.domain.actions import get_clip


def social_plan(ctx: StageContext, graphs: Sequence[SentenceGraph]) -> SocialPlan:
    """The story's social plan (faces, response timing, distances): the `social` node."""
    request = SocialPlanRequest(header=ctx.header(), graphs=list(graphs), seed=ctx.seed)
    return ctx.engine.query("social", social_part(graphs), lambda: ctx.backend.call(request).plan)


def frame_count(motion: Motion) -> int:
    return int(motion.root_position.shape[0])


def fit_frames(track: np.ndarray, frames: int) -> np.ndarray:
    """(T, E) -> (frames, E): the last row held, or the end cut."""
    if len(track) >= frames:
        return track[:frames]
    return np.concatenate([track, np.repeat(track[-1:], frames - len(track), axis=0)])


def faces(ctx: StageContext, plan: SocialPlan, motions: dict[str, Motion]) -> dict[str, Motion]:
    """Each planned character's motion with its face track (Motion.expression) from the plan.

    A face depends on the character's part of the plan and on when its own actions and the actions it
    reacts to happen; holds and the story's length do not matter (the face holds after its last key), so
    the track is computed to a length of its own and held or cut to the motion's.
    """
    out = dict(motions)
    if not plan.characters:
        return out
    acting: dict[str, list[Segment]] = {
        name: [seg for seg in motion.segments if seg.action_index >= 0] for name, motion in motions.items()
    }
    for entry in plan.characters:
        motion = motions.get(entry.name)
        if motion is None:
            continue
        anchors = sorted({k.anchor_character for k in entry.keys} - {entry.name})
        others = {n: acting[n] for n in anchors if n in acting}
        ends = [seg.end_frame for segs in (acting[entry.name], *others.values()) for seg in segs]
        lag = max([k.at_s for k in entry.keys], default=0.0)
        frames = max(ends, default=0) + int(lag * motion.fps) + 2
        request = ExpressionTrackRequest(
            header=ctx.header(),
            plan=plan,
            character=entry.name,
            segments=acting[entry.name],
            frames=frames,
            fps=motion.fps,
            others=others,
        )

        def track(request: ExpressionTrackRequest = request) -> ExpressionTrackReply:
            return content_of(ctx.backend.call(request))

        reply = ctx.engine.query(
            f"face:{entry.name}",
            [plan.expression_names, entry, acting[entry.name], others, frames],
            track,
        )
        face = fit_frames(from_wire(reply.expression), frame_count(motion))
        out[entry.name] = msgspec.structs.replace(motion, expression=to_wire(face))
    return out


def paired_actions(
    characters: dict[str, tuple[CharacterNode, list[str]]], plan: SocialPlan | None
) -> list[PairedAction]:
    """The story's two-person actions (clips whose interaction object is a person: hug, handshake, ...), in
    the characters' order, each with its partner when the text names one and the partner's answer delay
    (the social model's response delay to that action, when it has one)."""
    delays = {
        (r.actor, r.action_index, r.responder): r.delay_s
        for r in (plan.responses if plan is not None else [])
    }
    out: list[PairedAction] = []
    for name, (node, _) in characters.items():
        for k, action in enumerate(node.actions):
            try:
                clip = get_clip(action.action) if action.action else None
            except KeyError:
                continue
            if clip is None or clip.interaction is None or clip.interaction.object != "person":
                continue
            partner = next(
                (r for r in (action.target, action.destination) if r in characters and r != name), ""
            )
            delay = delays.get((name, k, partner), 0.0) if partner else 0.0
            out.append(
                PairedAction(actor=name, action_index=k, action=clip.name, partner=partner, delay_s=delay)
            )
    return out


def fit_cast(ctx: StageContext, motions: dict[str, Motion], pairs: list[PairedAction]) -> PairReply | None:
    """The `cast` node: the motions with walkers giving way and paired contacts solved (None: one character)."""
    if len(motions) < 2 or len({frame_count(m) for m in motions.values()}) != 1:
        return None
    request = PairRequest(header=ctx.header(), motions=motions, pairs=pairs)

    def run() -> PairReply:
        return content_of(ctx.backend.call(request))

    return ctx.engine.query("cast", [motions, pairs], run)
