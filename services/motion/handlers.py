"""Pure request -> reply handlers of the motion service (no zmq)."""

from __future__ import annotations

import math

import numpy as np

from proto.common import reply_header
from proto.motion import (
    PairReply,
    PairRequest,
    SegmentEndState,
    SynthesizeReply,
    SynthesizeRequest,
)
from proto.scene import Scene
from services.motion.arm_clearance import clear_piece
from services.motion.planning import plan_actions
from services.motion.routing import joined_route, scene_route
from services.motion.synthesis import SegmentState, assemble, holding_after, synthesise_segment
from wana.bus.service import Contract, InvalidInput
from wana.fidelity.bodies import skeleton_offsets


def handle_synthesize(req: SynthesizeRequest) -> SynthesizeReply:
    """Plan the character's actions in the scene and synthesise segments from_segment on."""
    if not all(np.isfinite(req.start)):
        raise InvalidInput("start must be finite (x, z, yaw)")
    for name, d in req.distances.items():
        if not (math.isfinite(d) and 0.3 <= d <= 5.0):
            raise InvalidInput(f"distances[{name!r}] must be between 0.3 and 5 metres, got {d}")
    for name, xz in req.others.items():
        if not all(np.isfinite(xz)):
            raise InvalidInput(f"others[{name!r}] must be finite (x, z)")
    if not all(np.isfinite(xz).all() for xz in req.occupied):
        raise InvalidInput("occupied must be finite (x, z) pairs")
    if not all(np.isfinite(xz).all() for xz in req.bodies):
        raise InvalidInput("bodies must be finite (x, z) pairs")
    routes = list(req.routes)
    route_diags: list[str] = []

    def route_fn(
        scene: Scene, a: tuple[float, float], b: tuple[float, float], ignore: frozenset[str] = frozenset()
    ) -> np.ndarray:
        """Precomputed routes first, else A* around the furniture (a straight line where there is none)."""
        if routes:
            r = np.asarray(routes.pop(0), float).reshape(-1, 2)
            if len(r) >= 2 and np.isfinite(r).all():
                return joined_route(scene, a, r, ignore, req.bodies)  # a walk from a seat starts beside it
        wps, why = scene_route(scene, a, b, ignore, bodies=req.bodies)
        if why:
            route_diags.append(why)
        return wps

    posture = req.start_state.posture if req.start_state is not None else "stand"
    plan = plan_actions(
        req.character,
        req.scene,
        req.start,
        route_fn,
        posture=posture,
        holding=req.start_state.holding if req.start_state is not None else "",
        others={k: (float(v[0]), float(v[1])) for k, v in req.others.items()},
        distances=dict(req.distances),
        seats=dict(req.seats),
        spots={k: (float(v[0]), float(v[1])) for k, v in req.spots.items()},
        occupied=[(float(x), float(z)) for x, z in req.occupied],
        bodies=[(float(x), float(z)) for x, z in req.bodies],
    )
    if req.from_segment < 0 or req.from_segment > len(plan.segments):
        raise InvalidInput(f"from_segment {req.from_segment} outside 0..{len(plan.segments)}")
    st = req.start_state
    state = (
        plan.start_state()
        if st is None
        else SegmentState(st.x, st.z, st.yaw, st.posture, st.phase, st.hips_dy).rounded()
    )
    pieces, ends = [], []
    offsets = skeleton_offsets(req.character.name)  # the skeleton the renderer and the checks play
    for k in range(req.from_segment, len(plan.segments)):
        piece, state = synthesise_segment(plan, k, state)
        pieces.append(clear_piece(piece, req.scene, offsets))
        ends.append(
            SegmentEndState(
                x=state.x,
                z=state.z,
                yaw=state.yaw,
                posture=state.posture,
                phase=state.phase,
                hips_dy=state.hips_dy,
                holding=holding_after(plan.segments[k]),
            )
        )
    motion = assemble(req.character.name, pieces, state)
    return SynthesizeReply(
        header=reply_header(req),
        motion=motion,
        end_states=ends,
        diagnostics=list(plan.diagnostics) + route_diags,
    )


def handle_pair(req: PairRequest) -> PairReply:
    """Fit the cast's motions to each other: walkers give way, then paired actions touch (both bodies)."""
    from services.motion.giveway import give_way
    from services.motion.handover import hand_over
    from services.motion.pairs import solve_pairs

    lengths = {int(m.root_position.shape[0]) for m in req.motions.values()}
    if len(lengths) > 1:
        raise InvalidInput(f"the motions must share one time line (lengths {sorted(lengths)})")
    motions = dict(req.motions)
    notes: list[str] = []
    if req.give_way:
        motions, waits = give_way(motions, req.scene)
        notes += waits
    motions, contacts, pair_notes = solve_pairs(motions, req.pairs)
    motions, handed = hand_over(motions, req.pairs)  # "gives the cup to Anna": from hand to hand
    pair_notes += handed
    return PairReply(
        header=reply_header(req), motions=motions, contacts=contacts, diagnostics=notes + pair_notes
    )


CONTRACT: Contract = {SynthesizeRequest: handle_synthesize, PairRequest: handle_pair}
