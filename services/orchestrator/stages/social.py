"""The social stage: the `social` plan node, and one `face:<name>` node per character (social service)."""

from __future__ import annotations

from collections.abc import Sequence

import msgspec
import numpy as np

from proto.motion_data import Motion, Segment
from proto.social import ExpressionTrackReply, ExpressionTrackRequest, SocialPlan, SocialPlanRequest
from proto.ssg import SentenceGraph
from services.orchestrator.stages import StageContext, content_of
from services.orchestrator.views import social_part
from wana.arrays import from_wire, to_wire
from wana.domain.idle import seed_of, with_blinks


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
        face = with_blinks(face, plan.expression_names, seed_of(entry.name))  # the eyes blink now and then
        out[entry.name] = msgspec.structs.replace(motion, expression=to_wire(face))
    return out
