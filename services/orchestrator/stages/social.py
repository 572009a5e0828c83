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
from proto.scene import Scene
from proto.social import ExpressionTrackReply, ExpressionTrackRequest, SocialPlan, SocialPlanRequest
from proto.ssg import CharacterNode, SentenceGraph
from services.orchestrator.stages import StageContext, content_of
from services.orchestrator.views import social_part
from wana.arrays import from_wire, to_wire
from wana.domain.actions import get_clip
from wana.domain.idle import seed_of, with_blinks
from wana.domain.routes import Reservations


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


LOCOMOTION = ("walk", "walk_slowly", "walk_backward", "run", "jog", "tiptoe", "march", "limp")


def _walking(motion: Motion) -> np.ndarray:
    """(T,) bool: the frames of the motion's locomotion segments."""
    out = np.zeros(frame_count(motion), bool)
    for seg in motion.segments:
        try:
            walk = seg.action in LOCOMOTION or "locomotion" in get_clip(seg.action).tags
        except KeyError:
            walk = False
        if walk:
            out[seg.start_frame : seg.end_frame] = True
    return out


def walkers_meet(motions: dict[str, Motion]) -> bool:
    """True when some character, while walking, comes within a body of another on stage (the reservation
    table's test, wana.domain.routes.Reservations): only then can giving way change anything."""
    table = Reservations()
    paths: dict[str, np.ndarray] = {}
    for name, motion in motions.items():
        xz = from_wire(motion.root_position)[:, [0, 2]].astype(np.float64)
        if motion.present is not None:
            on = from_wire(motion.present).astype(bool).reshape(-1)[: len(xz)]
            xz[: len(on)][~on] = np.nan
        paths[name] = xz
        table.reserve(name, xz)
    for name, motion in motions.items():
        walking = _walking(motion)
        if not walking.any():
            continue
        mine = paths[name].copy()
        mine[~walking[: len(mine)]] = np.nan
        if table.first_conflict(mine, range(len(mine)), exclude={name}) is not None:
            return True
    return False


def fit_cast(
    ctx: StageContext, motions: dict[str, Motion], pairs: list[PairedAction], scene: Scene | None = None
) -> PairReply | None:
    """The `cast` node: the motions with walkers giving way and paired contacts solved.

    None (and no node at all) when there is nothing to fit: one character, no two-person action and no two
    characters who meet while one walks. So a story whose characters never come near each other recomputes
    as before, and an edit there re-runs no `cast` node. ``scene``: where a walker may step aside.
    """
    if len(motions) < 2 or len({frame_count(m) for m in motions.values()}) != 1:
        return None
    if not pairs and not walkers_meet(motions):
        return None
    request = PairRequest(header=ctx.header(), motions=motions, pairs=pairs, scene=scene)

    def run() -> PairReply:
        return content_of(ctx.backend.call(request))

    return ctx.engine.query("cast", [motions, pairs, scene], run)
