"""Every sentence's checks, from its parse and the computed animation; verdicts that join in other checks.

    checks = story_checks([(s.id, s.kind) ...], graphs, scene, motions, unavailable)
    verdicts(checks, extra=camera_checks)      # sentence id -> SentenceVerdict

FK runs once per character and every per-frame test once per motion; each sentence takes its own frames
out of those passes (the editor calls this after every edit).
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence

import numpy as np

from proto.fidelity import Check, SentenceVerdict, verdict_of
from proto.motion_data import Motion
from proto.scene import Scene
from proto.ssg import SentenceGraph
from wana.arrays import from_wire
from wana.domain.body_limits import HANDS_MAX_MS, HIPS_MAX_MS, STRIKES
from wana.domain.skeleton import JOINT_NAMES
from wana.fidelity import action_checks as ac
from wana.fidelity import body_checks as bc
from wana.fidelity import contact_checks as cc
from wana.fidelity.acts import Act, activity, owned_frames, stays_until, story_acts, to_blame
from wana.fidelity.bodies import Body, body_of
from wana.fidelity.clips import clip_needs
from wana.fidelity.places import placement
from wana.fidelity.scene_checks import object_checks, relation_checks
from wana.fidelity.words import frame_list, third_person
from wana.fidelity.world import World, display

# Parser diagnostics that mean something the sentence asked for was dropped -> (check name, essential).
DROPPED = {
    "W101": ("object_exists", False),
    "W102": ("performed", True),
    "W103": ("performed", True),
    "W104": ("command_visible", True),
    "W105": ("performed", True),
    "W107": ("relation_holds", False),
    "W108": ("performed", False),
    "W109": ("performed", True),
    "E110": ("performed", True),
    "E112": ("performed", True),
}
ARMS = np.array(
    [n.removeprefix("Left").removeprefix("Right") in ("Hand", "HandMiddle1", "ForeArm") for n in JOINT_NAMES]
)
HANDS = np.array(
    [n.removeprefix("Left").removeprefix("Right") in ("Hand", "HandMiddle1") for n in JOINT_NAMES]
)
HANDOFF_S = 0.5  # seconds a hand stays on a prop's grip before it takes it and after it lets go of it
STAGE_NEEDS = {  # stage -> the sentence kinds that cannot be shown without it
    "parse": ("scene", "action", "command", "empty"),
    "scene": ("scene", "action"),
    "motion": ("action",),
}


def story_checks(
    sentences: Sequence[tuple[str, str]],
    graphs: Mapping[str, SentenceGraph],
    scene: Scene | None,
    motions: Mapping[str, Motion],
    unavailable: Mapping[str, str] | None = None,
) -> dict[str, list[Check]]:
    """Per-sentence checks of what the animation shows.

    Args:
        sentences: (sentence id, kind) in document order.
        graphs: sentence id -> resolved SentenceGraph (what the sentence asks).
        scene: the composed (optimised) scene, None when none was composed.
        motions: character -> assembled Motion (segments carry sentence_id and action_index).
        unavailable: stage -> why it did not run (each sentence that needed it gets a failing check).

    Returns:
        sentence id -> its checks (every sentence id of `sentences` is a key).
    """
    unavailable = dict(unavailable or {})
    out: dict[str, list[Check]] = {sid: [] for sid, _ in sentences}
    world = World(scene) if scene is not None else None
    bodies = {name: body_of(m) for name, m in motions.items() if m.root_position.shape[0] > 0}
    acts = story_acts(sentences, graphs, motions)

    for sid, kind in sentences:
        graph = graphs.get(sid)
        kind = graph.kind if graph is not None else kind
        out[sid].extend(_dropped(graph, kind, unavailable, world))
        if graph is not None and kind == "scene" and world is not None:
            out[sid].extend(object_checks(graph, world))
            out[sid].extend(relation_checks(graph, world))
    if world is not None:
        _action_checks(out, acts, world, bodies, motions)
    for sid, _ in sentences:
        graph = graphs.get(sid)
        if graph is not None and graph.kind == "action":
            out[sid].extend(_wrong_character(graph, set(motions)))
            out[sid].extend(_nothing_to_show(graph, out[sid]))
    for sid, checks in out.items():  # a dropped verb said once, by the check that names the character
        if any(c.name == "performed" and c.character and not c.ok for c in checks):
            out[sid] = [c for c in checks if not (c.name == "performed" and not c.character and not c.ok)]
    return out


# Words that let a sentence's actor go unnamed ("He sits", "They talk", "Everyone waves").
STAND_INS = frozenset(
    "he she they him her them his hers their we us i you it everyone everybody all both together each "
    "someone somebody".split()
)


SENTENCE_WORDS = frozenset("the a an then now later suddenly finally meanwhile after before".split())


def _wrong_character(graph: SentenceGraph, known: set[str]) -> list[Check]:
    """The sentence names who acts, and the animation has someone else do it ("Forrest walks in." played by
    Jenny): the checks of the character the parse chose would judge the wrong person's motion.

    An actor is named when a word of its name or the words the parse says the sentence used for it appear in
    the text; a sentence with a pronoun or a group word ("He", "They", "everyone") names nobody for certain.
    """
    text = graph.text.lower().replace("’", "'")
    words = set(re.findall(r"[a-z']+", text))
    if words & STAND_INS:
        return []
    named = {n for n in known if n and re.search(rf"\b{re.escape(n.lower())}\b", text)}
    out = []
    for c in graph.characters:
        said = set(re.findall(r"[a-z']+", f"{c.name} {c.mention}".lower())) - {"mr", "mrs", "ms", "dr", "the"}
        if not c.actions or said & words:
            continue
        names = named or {
            w for w in re.findall(r"\b[A-Z][a-z]+\b", graph.text) if w.lower() not in SENTENCE_WORDS
        }
        who = " and ".join(sorted(names)) if names else "someone else"
        verb = c.actions[0].verb or c.actions[0].action
        out.append(
            Check(
                name="performed",
                character=c.name,
                ok=False,
                essential=True,
                reason=f"the sentence is about {who}, but {c.name} is the one who {third_person(verb)}",
            )
        )
    return out


def _nothing_to_show(graph: SentenceGraph, checks: list[Check]) -> list[Check]:
    """An action sentence with no action, relation or command and no check: nothing of it is shown, and it
    must not pass as if it were ("Forrest holds Jenny's hand." parsed to nothing)."""
    if checks or graph.social or graph.commands or any(c.actions for c in graph.characters):
        return []
    if re.search(r"\b(is|are|was|were)\s+(a|an|the|my|his|her|their|very|\w+'s)\b", graph.text.lower()):
        return []  # a description ("Old Pete is a carpenter."): it asks for nothing to be seen
    return [
        Check(
            name="performed",
            ok=False,
            essential=True,
            reason="no action of this sentence was understood: the animation shows nothing for it",
        )
    ]


def _dropped(
    graph: SentenceGraph | None, kind: str, unavailable: Mapping[str, str], world: World | None
) -> list[Check]:
    """Failing checks for what the sentence asked and the pipeline dropped (nothing passes silently)."""
    checks = []
    first_name = (
        "object_exists" if kind == "scene" else "command_visible" if kind == "command" else "performed"
    )
    for stage, why in unavailable.items():
        if kind in STAGE_NEEDS.get(stage, ()) or (stage == "social" and graph is not None and graph.social):
            checks.append(
                Check(
                    name=first_name, ok=False, essential=True, reason=f"the {stage} stage did not run: {why}"
                )
            )
    if graph is None:
        return checks
    if world is None and kind in ("scene", "action") and "scene" not in unavailable:
        checks.append(Check(name=first_name, ok=False, essential=True, reason="no room was composed"))
    for d in graph.diagnostics:
        code = d.code.split()[0]
        if code == "W101" and kind != "scene":
            continue  # an action's object word ("wipes the sweat", "tells a story"): contact judges its target
        if code in DROPPED:
            name, essential = DROPPED[code]
            checks.append(Check(name=name, ok=False, essential=essential, reason=f"not shown: {d.message}"))
    return checks


def _action_checks(
    out: dict[str, list[Check]],
    acts: list[Act],
    world: World,
    bodies: Mapping[str, Body],
    motions: Mapping[str, Motion],
) -> None:
    exempt: dict[str, dict[str, np.ndarray]] = {name: {} for name in bodies}
    resting: dict[str, dict[str, np.ndarray]] = {name: {} for name in bodies}  # hands on a named surface
    touching: dict[tuple[str, str], np.ndarray] = {}  # (a, b) -> frames they touch on purpose
    seen: set[str] = set()
    begins: dict[str, int] = {}  # sentence id -> the first frame any of its actions plays
    for act in acts:
        if act.start >= 0:
            begins[act.sentence_id] = min(begins.get(act.sentence_id, act.start), act.start)
    props = {name: list(m.props) for name, m in motions.items()}
    frames = max((b.frames for b in bodies.values()), default=0)
    world.follow([t for m in motions.values() for t in m.props], frames)
    for name, tracks in props.items():  # what one carries is in one's hands, no body inside furniture
        if name not in bodies:
            continue
        for t in tracks:
            if t.object_id in world.poses:
                mask = exempt[name].setdefault(
                    t.object_id, np.zeros((bodies[name].frames, len(bodies[name].radii)), bool)
                )
                mask[max(0, t.start_frame) : max(0, t.end_frame)] = True
                # the hand closing on it before the prop leaves its place and letting go after it is set
                # down is on its grip, no hand inside it (solo-workshop-19 s7: the hand 7 cm in the saw
                # just set on the workbench, the frames show the hand on the saw)
                near = int(round(HANDOFF_S * motions[name].fps))
                hands = HANDS[bodies[name].point_joint][None, :]
                mask[max(0, t.start_frame - near) : max(0, t.start_frame)] |= hands
                mask[max(0, t.end_frame) : max(0, t.end_frame + near)] |= hands
    floor, floors, last = 0, {}, ""
    for act in acts:  # the floor of a sentence: when the action sentence before it began
        if act.sentence_id != last and last:
            floor = begins.get(last, floor)
        floors[act.sentence_id], last = floor, act.sentence_id
    for act in acts:
        body = bodies.get(act.character)
        motion = motions.get(act.character)
        checks = out.setdefault(act.sentence_id, [])
        checks.append(ac.performed(act, body is not None, floors[act.sentence_id]))
        if body is None or motion is None:
            continue
        first = act.character not in seen
        seen.add(act.character)
        until = stays_until(act, motion)
        touching_until = stays_until(act, motion, through_standing_up=True)
        contact, used = cc.contact(act, body, world, bodies, props)
        if contact is not None:
            checks.append(contact)
        where = placement(act, body, world)
        if where is not None:
            checks.append(where)
        if act.clip is not None:
            hold = np.zeros(body.frames, bool)
            hold[act.start : touching_until] = True  # backing up to a seat touches it too
            for oid, whole in used.items():
                points = np.ones(len(body.radii), bool) if whole else ARMS[body.point_joint]
                mask = exempt[act.character].setdefault(oid, np.zeros((body.frames, len(body.radii)), bool))
                mask |= hold[:, None] & points[None, :]
            named = {o.id for oid in act.objects for o in world.copies(oid)} - set(used)
            for oid in sorted(
                named
            ):  # the surface the sentence names ("sits at the table"): hands rest on it
                mask = resting[act.character].setdefault(oid, np.zeros((body.frames, len(body.radii)), bool))
                mask[act.start : touching_until] |= HANDS[body.point_joint][None, :]  # walking up to it too
            clip = clip_needs(act.node.action)
            if clip is not None and clip.object == "person":
                other = cc.other_character(act, bodies)
                if other:
                    on = np.zeros(body.frames, bool)
                    on[act.clip.start_frame : act.clip.end_frame] = True
                    lo, hi = sorted((act.character, other))
                    touching[(lo, hi)] = touching.get((lo, hi), np.zeros(body.frames, bool)) | on
        on_stage = presence(motion, body.frames)
        for check in (
            ac.supported(act, body, world, until),
            ac.entrance(act, body, world, first, on_stage),
        ):
            if check is not None:
                checks.append(check)
    _body_checks(out, acts, world, bodies, motions, exempt, touching, resting)


def presence(motion: Motion, frames: int) -> np.ndarray:
    """(frames,) bool: the character is on stage (Motion.present; always when the motion has none)."""
    if motion.present is None:
        return np.ones(frames, bool)
    present = from_wire(motion.present).astype(bool).reshape(-1)
    out = np.ones(frames, bool)
    n = min(frames, len(present))
    out[:n] = present[:n]
    if n and n < frames:
        out[n:] = present[n - 1]
    return out


def _body_checks(
    out: dict[str, list[Check]],
    acts: list[Act],
    world: World,
    bodies: Mapping[str, Body],
    motions: Mapping[str, Motion],
    exempt: dict[str, dict[str, np.ndarray]],
    touching: dict[tuple[str, str], np.ndarray],
    resting: dict[str, dict[str, np.ndarray]],
) -> None:
    """penetration, overlap and continuity per (sentence, acting character), from one pass per motion."""
    names = sorted(bodies)
    on_stage = {name: presence(motions[name], bodies[name].frames) for name in names}
    apart: dict[str, list[bc.FrameFailures]] = {name: [] for name in names}
    doing = {name: activity(motions[name], bodies[name].frames) for name in names}
    for i, a in enumerate(names):
        for b in names[i + 1 :]:
            n = min(bodies[a].frames, bodies[b].frames)
            off = ~(on_stage[a][:n] & on_stage[b][:n])  # someone off stage: nobody to collide with
            allowed = touching.get((a, b))
            allowed = off if allowed is None else (allowed[:n] | off)
            fa, fb = bc.overlap(bodies[a], bodies[b], allowed)
            # One fault, one culprit: the frames go to the sentence of whoever caused them, not to both.
            blame_a, blame_b = to_blame(doing[a], doing[b], n)
            for start, end in bc.runs(fa.failing[:n] | fb.failing[:n]):  # one run, one cause: its start's
                blame_a[start:end], blame_b[start:end] = blame_a[start], blame_b[start]
            apart[a].append(_only(fa, blame_a))
            apart[b].append(_only(fb, blame_b))
    for name in names:
        body, motion = bodies[name], motions[name]
        mine = [a for a in acts if a.character == name]
        owned = owned_frames(mine, motion)
        inside = bc.penetration(body, world, exempt.get(name, {}), resting.get(name, {}))
        boundaries = sorted({s.start_frame for s in motion.segments if s.start_frame > 0})
        strikes = np.zeros(body.frames, bool)
        for seg in motion.segments:
            if seg.action in STRIKES:
                strikes[max(seg.start_frame, 0) : seg.end_frame] = True
        fast, popped = bc.speeds(body, motion.fps, strikes), bc.pops(body, boundaries)
        # Off stage nothing is seen: no furniture to be inside, and the hidden move to the door is no jump.
        here = on_stage[name]
        seen = here.copy()
        seen[1:] &= here[:-1]
        inside.failing[:] &= here
        fast.failing[:] &= seen
        popped.failing[:] &= seen
        owner = np.full(body.frames, "", object)  # the sentence each frame of this character belongs to
        for sid, frames in owned.items():
            owner[frames.start : min(frames.stop, body.frames)] = sid
        # A fault that lasts is the doing of the sentence it began in (a chest sunk into the table when
        # sitting down stays the sit's, not the fault of each later "looks down" played in that pose).
        inside_cause = _caused_by(inside, owner)
        merged = _merged(apart[name]) if apart[name] else None
        overlap_cause = _caused_by(merged, owner) if merged is not None else None
        for sid, frames in owned.items():
            f = np.arange(frames.start, min(frames.stop, body.frames))
            checks = out.setdefault(sid, [])
            checks.append(_penetration_check(name, inside, np.nonzero(inside_cause == sid)[0]))
            if merged is not None and overlap_cause is not None:
                checks.append(_overlap_check(name, merged, np.nonzero(overlap_cause == sid)[0]))
            checks.append(_continuity_check(name, fast, popped, f))


def _caused_by(fail: bc.FrameFailures, owner: np.ndarray) -> np.ndarray:
    """(T,) per failing frame the sentence its run began in ("" where fine or before any sentence)."""
    cause = np.full(len(fail.failing), "", object)
    for start, end in bc.runs(fail.failing, fail.what):
        cause[start:end] = owner[start]
    return cause


def _merged(fails: list[bc.FrameFailures]) -> bc.FrameFailures:
    """The worst of several failures per frame (one character against each of the others)."""
    merged = bc.FrameFailures.none(len(fails[0].failing))
    for x in fails:
        worse = x.failing & (x.amount > merged.amount)
        merged.failing[worse] = True
        merged.amount[worse] = x.amount[worse]
        merged.what[worse] = x.what[worse]
        merged.joint[worse] = x.joint[worse]
    return merged


def _only(fail: bc.FrameFailures, blamed: np.ndarray) -> bc.FrameFailures:
    """The failures on the frames this side is blamed for (the rest are the other side's doing)."""
    keep = np.zeros(len(fail.failing), bool)
    keep[: len(blamed)] = blamed
    drop = ~keep
    failing = fail.failing & keep
    amount, what, joint = fail.amount.copy(), fail.what.copy(), fail.joint.copy()
    amount[drop], what[drop], joint[drop] = 0.0, "", -1
    return bc.FrameFailures(failing, amount, what, joint)


def _joint_word(j: int) -> str:
    name = JOINT_NAMES[j] if 0 <= j < len(JOINT_NAMES) else "body"
    side = "left " if name.startswith("Left") else "right " if name.startswith("Right") else ""
    part = name.removeprefix("Left").removeprefix("Right")
    words = {
        "HandMiddle1": "fingers",
        "UpLeg": "thigh",
        "Leg": "shin",
        "ForeArm": "forearm",
        "Arm": "upper arm",
        "ToeBase": "toes",
        "Spine": "belly",
        "Spine1": "chest",
        "Spine2": "chest",
    }
    return side + words.get(part, part.lower())


def _frames_words(n: int) -> str:
    return "1 frame" if n == 1 else f"{n} frames"


def _verb(j: int, singular: str) -> str:
    """ "is"/"moves" for a part, "are"/"move" for the parts named in the plural (fingers, toes)."""
    if not _joint_word(j).endswith("s"):
        return singular
    return "are" if singular == "is" else singular.removesuffix("s")


def _worst(fail: bc.FrameFailures, f: np.ndarray) -> tuple[np.ndarray, int]:
    bad = f[fail.failing[f]]
    worst = int(bad[np.argmax(fail.amount[bad])]) if len(bad) else -1
    return bad, worst


def _penetration_check(name: str, fail: bc.FrameFailures, f: np.ndarray) -> Check:
    bad, w = _worst(fail, f)
    if w < 0:
        return Check(
            name="penetration", character=name, ok=True, reason=f"no part of {name} goes into furniture"
        )
    return Check(
        name="penetration",
        character=name,
        ok=False,
        reason=f"{name}'s {_joint_word(int(fail.joint[w]))} {_verb(int(fail.joint[w]), 'is')} {fail.amount[w] * 100:.0f} cm inside the "
        f"{display(str(fail.what[w]))} ({_frames_words(len(bad))}, worst at frame {w})",
        frames=frame_list(bad),
    )


def _overlap_check(name: str, merged: bc.FrameFailures, f: np.ndarray) -> Check:
    bad, w = _worst(merged, f)
    if w < 0:
        return Check(
            name="overlap", character=name, ok=True, reason=f"{name}'s body stays clear of the others"
        )
    return Check(
        name="overlap",
        character=name,
        ok=False,
        reason=f"{name}'s {_joint_word(int(merged.joint[w]))} {_verb(int(merged.joint[w]), 'is')} {merged.amount[w] * 100:.0f} cm inside "
        f"{merged.what[w]}'s body ({_frames_words(len(bad))}, worst at frame {w})",
        frames=frame_list(bad),
    )


def _continuity_check(name: str, fast: bc.FrameFailures, popped: bc.FrameFailures, f: np.ndarray) -> Check:
    bad_fast, wf = _worst(fast, f)
    bad_pop, wp = _worst(popped, f)
    if wf < 0 and wp < 0:
        return Check(name="continuity", character=name, ok=True, reason=f"{name} moves smoothly")
    reasons = []
    if wf >= 0:
        limit = HIPS_MAX_MS if JOINT_NAMES[int(fast.joint[wf])] == "Hips" else HANDS_MAX_MS
        reasons.append(
            f"{name}'s {_joint_word(int(fast.joint[wf]))} {_verb(int(fast.joint[wf]), 'moves')} {fast.amount[wf]:.1f} m/s at frame {wf} "
            f"(at most {limit:.0f} m/s)"
        )
    if wp >= 0:
        reasons.append(
            f"{name}'s pose jumps at frame {wp}: the {_joint_word(int(popped.joint[wp]))} {_verb(int(popped.joint[wp]), 'moves')} "
            f"{popped.amount[wp]:.2f} m in one frame"
        )
    frames = sorted(set(bad_fast.tolist()) | set(bad_pop.tolist()))
    return Check(
        name="continuity", character=name, ok=False, reason="; ".join(reasons), frames=frame_list(frames)
    )


def verdicts(
    checks_by_sentence: Mapping[str, list[Check]], extra: Mapping[str, list[Check]] | None = None
) -> dict[str, SentenceVerdict]:
    """Sentence id -> verdict over its own checks and any others (the render service's camera checks)."""
    extra = extra or {}
    out = {}
    for sid in list(checks_by_sentence) + [s for s in extra if s not in checks_by_sentence]:
        checks = list(checks_by_sentence.get(sid, [])) + list(extra.get(sid, []))
        out[sid] = SentenceVerdict(sentence_id=sid, verdict=verdict_of(checks), checks=checks)
    return out


__all__ = ["story_checks", "verdicts"]
