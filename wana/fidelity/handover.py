"""Handing an object over: "Tom gives the cup to Eve" is shown when the cup passes from Tom's hand to Eve's.

The clip that plays ("present") is a gesture with no object, so the check reads the object's prop tracks
(Motion.props): the giver carries it during the action, and the recipient's grip on it starts as the
giver's ends, with the object where the giver let go of it (no jump between hands).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from functools import partial

import numpy as np

from proto.fidelity import Check
from proto.motion_data import PropTrack
from wana.arrays import from_wire
from wana.fidelity.acts import Act
from wana.fidelity.bodies import Body
from wana.fidelity.words import frame_list
from wana.fidelity.world import World, display

# Handing an object over: the clip ("present") is a gesture with no object, so the check looks at the object.
HANDOVER_VERBS = (
    "give",
    "hand",
    "pass",
    "offer",
    "hand over",
    "pass over",
    "give back",
    "hand out",
    "pass on",
    "bring",  # "brings the cup to Sam" (services.nlp.actions: a hand-over when it is brought to someone)
    "deliver",
)
HANDOFF_FRAMES = 15  # the receiver's grip starts within this of the giver's letting go (0.5 s)
HANDOFF_M = 0.15  # ... with the object this close to where the giver let go of it (no jump between hands)


def is_handover(act: Act, characters: set[str]) -> bool:
    """ "Tom gives the cup to Eve", "offers her a mint": a give verb, a recipient and an object to give (a
    give verb with no object is a gesture: "gives Ben a thumbs up")."""
    verb = act.node.verb.lower()
    if not any(verb == v or verb.startswith(v + " ") for v in HANDOVER_VERBS):
        return False
    to = any(r and r in characters and r != act.character for r in (act.node.target, act.node.destination))
    return to and bool(_handed_object(act, characters))


def _handed_object(act: Act, characters: set[str]) -> str:
    """The object word a handover names: in the action node, else the one object its sentence names."""
    for ref in (act.node.target, act.node.instrument, act.node.destination):
        if ref and ref not in characters:
            return ref
    return act.objects[0] if len(act.objects) == 1 else ""


def handover(
    act: Act, world: World, bodies: Mapping[str, Body], props: Mapping[str, Sequence[PropTrack]]
) -> Check:
    """The object passes from the giver's hand to the recipient's: the giver carries it during the action,
    and the recipient's grip on it starts as the giver's ends, with the object where the giver let go."""
    who = act.character
    to = next(r for r in (act.node.target, act.node.destination) if r and r in bodies and r != who)
    base = partial(Check, name="contact", character=who)
    word = _handed_object(act, set(bodies))
    found = {o.id for o in world.find(word)}
    what = display(word)
    if not found:
        return base(ok=False, essential=True, reason=f"there is no {what} in the room for {who} to give {to}")
    seg = act.clip
    assert seg is not None
    lo, hi = act.start, seg.end_frame + HANDOFF_FRAMES
    given = [
        t for t in props.get(who, ()) if t.object_id in found and t.start_frame < hi and t.end_frame > lo
    ]
    if not given:
        return base(
            ok=False,
            reason=f"the {what} is never in {who}'s hand: {who} gestures at {to} with an empty hand",
            frames=frame_list(range(seg.start_frame, seg.end_frame)),
        )
    gave = max(given, key=lambda t: t.end_frame)
    taken = [
        t
        for t in props.get(to, ())
        if t.object_id == gave.object_id and abs(t.start_frame - gave.end_frame) <= HANDOFF_FRAMES
    ]
    if not taken:
        return base(
            ok=False,
            reason=f"{who} holds the {what} but {to} never takes it",
            frames=[min(gave.end_frame, seg.end_frame) - 1],
        )
    let_go = from_wire(gave.position)[-1]
    caught = from_wire(taken[0].position)[0]
    jump = float(np.linalg.norm(let_go - caught))
    if jump > HANDOFF_M:
        return base(
            ok=False,
            reason=f"the {what} jumps {jump:.2f} m from {who}'s hand to {to}'s (their hands never meet)",
            frames=[gave.end_frame - 1, taken[0].start_frame],
        )
    return base(
        ok=True, reason=f"the {what} passes from {who}'s hand to {to}'s at frame {taken[0].start_frame}"
    )


__all__ = ["HANDOFF_FRAMES", "HANDOFF_M", "handover", "is_handover"]
