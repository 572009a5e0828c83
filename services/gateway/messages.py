"""JSON messages the gateway pushes to the editor, built from the orchestrator's results.

The animation message is compact: arrays travel as base64 of little-endian float32 bytes, so a client
decodes them with one `new Float32Array(...)`. Every character and object carries a content hash; the live
WebSocket (services.gateway.delta) sends an entry the client already holds as a short `unchanged` stub.
The layout is documented in services/gateway/README.md.
"""

from __future__ import annotations

import base64
import json
from collections.abc import Mapping
from typing import Any
from urllib.parse import quote

import msgspec
import numpy as np

from proto.fidelity import Check, SentenceVerdict
from proto.motion_data import Motion
from proto.scene import PlacedObject
from services.orchestrator.document import Document
from services.orchestrator.pipeline import PipelineResult
from services.orchestrator.queries import content_hash
from wana.arrays import from_wire, to_wire
from wana.domain import skeleton
from wana.domain.units import FPS
from wana.fidelity import story_checks, verdicts

FIDELITY_CODE = "W401"  # proto.common.ERROR_CODES: the animation does not show this


def b64_f32(array: np.ndarray) -> str:
    """Base64 of the array as C-order little-endian float32 bytes."""
    return base64.b64encode(np.ascontiguousarray(array, dtype="<f4").tobytes()).decode("ascii")


def mesh_url(obj: PlacedObject) -> str:
    """The URL of one object variant's GLB; equal for equal (category, attributes, seed)."""
    query = f"seed={obj.seed}"
    if obj.attributes:
        attrs = json.dumps(dict(sorted(obj.attributes.items())), separators=(",", ":"))
        query += f"&attributes={quote(attrs, safe='')}"
    return f"/api/meshes/{quote(obj.category, safe='')}.glb?{query}"


def sentence_list(result: PipelineResult | None, doc: Document) -> list[dict[str, Any]]:
    """Sentences with offsets and kinds; before the parser answers, kinds are 'unknown'."""
    if result is not None and result.sentences and result.version == doc.version:
        return [{"id": s.id, "start": s.start, "end": s.end, "kind": s.kind} for s in result.sentences]
    return [{"id": s.id, "start": s.start, "end": s.end, "kind": "unknown"} for s in doc.sentences]


def story_verdicts(
    result: PipelineResult, extra_checks: Mapping[str, list[Check]] | None = None
) -> dict[str, SentenceVerdict]:
    """Sentence id -> verdict of the story checks (wana.fidelity) on this result, with any extra checks.

    A result the pipeline was not asked to animate (no scene and nothing unavailable: the parse alone) has
    nothing to judge yet and gets no verdicts.
    """
    if result.scene is None and not result.unavailable:
        return {}
    checks = story_checks(
        [(s.id, s.kind) for s in result.sentences],
        result.graphs,
        result.scene,
        result.motions,
        result.unavailable,
    )
    return verdicts(checks, extra_checks)


def check_entry(check: Check) -> dict[str, Any]:
    return {
        "name": check.name,
        "ok": check.ok,
        "reason": check.reason,
        "frames": list(check.frames),
        "character": check.character,
    }


def pipeline_entries(result: PipelineResult) -> dict[str, list[dict[str, Any]]]:
    """Sentence id -> the pipeline's diagnostics of it (document offsets): cheap, sent with the animation."""
    out: dict[str, list[dict[str, Any]]] = {}
    for sid, items in result.diagnostics.items():
        for d in items:
            out.setdefault(sid, []).append(
                {
                    "sentence_id": sid,
                    "code": d.code,
                    "message": d.message,
                    "severity": d.severity,
                    "start": d.span.start,
                    "end": d.span.end,
                }
            )
    return out


def verdict_entries(
    result: PipelineResult, judged: Mapping[str, SentenceVerdict]
) -> tuple[dict[str, list[dict[str, Any]]], dict[str, dict[str, Any]]]:
    """The story verdicts as W401 warnings on their sentences' spans (sentence id -> entries), and each
    sentence's verdict as the editor reads it (sentence id -> verdict entry)."""
    spans = {s.id: (s.start, s.end) for s in result.sentences}
    warnings: dict[str, list[dict[str, Any]]] = {}
    for sid, verdict in judged.items():
        start, end = spans.get(sid, (0, 0))
        for check in verdict.checks:
            if not check.ok:
                warnings.setdefault(sid, []).append(
                    {
                        "sentence_id": sid,
                        "code": FIDELITY_CODE,
                        "message": f"the animation does not show this: {check.reason}",
                        "severity": "warning",
                        "start": start,
                        "end": end,
                        "check": check.name,
                    }
                )
    entries = {
        sid: {"sentence_id": sid, "verdict": v.verdict, "checks": [check_entry(c) for c in v.checks]}
        for sid, v in judged.items()
    }
    return warnings, entries


def diagnostics_message(
    result: PipelineResult, doc: Document, extra_checks: Mapping[str, list[Check]] | None = None
) -> dict[str, Any]:
    """Per-sentence diagnostics with document offsets, the stages that could not run, and each sentence's
    verdict: every failed story check is also a W401 warning on its sentence's span. (The whole of it: the
    live socket sends the same as deltas, services.gateway.diagdelta.)"""
    warnings, judged = verdict_entries(result, story_verdicts(result, extra_checks))
    diags = [e for items in pipeline_entries(result).values() for e in items]
    diags += [e for items in warnings.values() for e in items]
    diags.sort(key=lambda d: (d["start"], d["end"], d["code"]))
    return {
        "type": "diagnostics",
        "version": result.version,
        "sentences": sentence_list(result, doc),
        "diagnostics": diags,
        "unavailable": dict(result.unavailable),
        "verdicts": list(judged.values()),
    }


def sent_motion(motion: Motion) -> Motion:
    """What the animation message carries of a Motion: no foot contacts or face, no trailing hold.

    The face (`expression`) is not sent to the editor, and social sampling changes it for a character whose
    body motion an edit of someone else left alone. The orchestrator pads every character with a held
    pose to the story's length, so an edit that lengthens one character's story would re-pad the others;
    the editor holds a figure's last pose past its last frame, so the held frames after the first are cut.
    Neither must make the editor fetch a body again.
    """
    motion = msgspec.structs.replace(motion, foot_contact=None, expression=None)
    last = motion.segments[-1] if motion.segments else None
    rotations = from_wire(motion.rotations)
    if last is None or last.action != "hold" or last.end_frame != len(rotations) or last.start_frame < 1:
        return motion
    cut = last.start_frame + 1
    return msgspec.structs.replace(
        motion,
        rotations=to_wire(rotations[:cut]),
        root_position=to_wire(from_wire(motion.root_position)[:cut]),
        present=None if motion.present is None else to_wire(from_wire(motion.present)[:cut]),
        segments=[*motion.segments[:-1], msgspec.structs.replace(last, end_frame=cut)],
    )


def motion_hash(motion: Motion) -> str:
    """Content hash of what the animation message carries of a Motion (see `sent_motion`)."""
    return content_hash(sent_motion(motion))


def character_entry(motion: Motion, digest: str | None = None) -> dict[str, Any]:
    """One character of the animation message, with the content hash of what it carries.

    Args:
        motion: the character's whole motion.
        digest: `motion_hash(motion)` when the caller already has it.

    Raises:
        ValueError: rotations (T, J, 4) and root positions (T, 3) disagree.
    """
    motion = sent_motion(motion)
    digest = digest or content_hash(motion)  # = motion_hash of the motion as given
    rotations = from_wire(motion.rotations)  # (T, J, 4)
    root = from_wire(motion.root_position)  # (T, 3)
    if rotations.ndim != 3 or rotations.shape[2] != 4 or root.shape != (rotations.shape[0], 3):
        raise ValueError(
            f"motion of {motion.character}: rotations {rotations.shape} and root {root.shape} disagree"
        )
    names = list(motion.joint_names) or list(skeleton.JOINT_NAMES)
    index = [skeleton.JOINT_INDEX[n] for n in names]
    parents = [names.index(skeleton.JOINT_NAMES[p]) if p >= 0 else -1 for p in skeleton.PARENTS[index]]
    return {
        "name": motion.character,
        "hash": digest,  # equal hash, equal entry: a client may reuse what it has
        "fps": motion.fps,
        "frames": int(rotations.shape[0]),
        "joints": names,
        "parents": parents,
        "offsets": b64_f32(skeleton.REST_OFFSETS[index]),  # (J, 3) metres
        "root_position": b64_f32(root),  # (T, 3) metres, world
        "rotations": b64_f32(rotations),  # (T, J, 4) local quaternions x, y, z, w
        # (T,) 1 while on stage, 0 before its first sentence and after it left; null: always on stage
        "present": None if motion.present is None else b64_f32(from_wire(motion.present).astype(np.float32)),
        "segments": [
            {
                "index": s.index,
                "action": s.action,
                "start_frame": s.start_frame,
                "end_frame": s.end_frame,
                "sentence_id": s.sentence_id,
            }
            for s in motion.segments
        ],
    }


def object_entry(o: PlacedObject) -> dict[str, Any]:
    """One placed object of the animation message, with the content hash of its other fields."""
    entry = {
        "id": o.id,
        "category": o.category,
        "attributes": dict(o.attributes),
        "seed": o.seed,
        "position": list(o.position),
        "yaw": o.yaw,
        "scale": list(o.scale),
        "support": o.support,
        "from_text": o.from_text,
        "mesh_url": mesh_url(o),
    }
    return {**entry, "hash": content_hash(entry)}


def animation_head(
    result: PipelineResult, characters: list[dict[str, Any]], *, compute_ms: float = 0.0
) -> dict[str, Any]:
    """The animation message without its `objects` and `characters` lists.

    Args:
        result: the pipeline's result for one version.
        characters: at least the `fps` and `frames` of each character entry, in message order.
        compute_ms: how long the compute took (reported in `stats`).
    """
    room = None
    if result.scene is not None:
        r = result.scene.room
        room = {"room_type": r.room_type, "width": r.width, "depth": r.depth, "height": r.height}
    commands = [
        {"sentence_id": sid, "kind": c.kind, "value": c.value, "seconds": c.seconds, "target": c.target}
        for sid, c in result.commands
    ]
    return {
        "type": "animation",
        "version": result.version,
        "fps": characters[0]["fps"] if characters else FPS,
        # the story's length: each character's entry may end earlier (its last pose held, see sent_motion)
        "frames": max(
            [c["frames"] for c in characters]
            + [len(from_wire(m.rotations)) for m in result.motions.values()],
            default=0,
        ),
        "room": room,
        "commands": commands,
        "unavailable": dict(result.unavailable),
        "stats": {"ran": list(result.ran), "reused": len(result.reused), "compute_ms": round(compute_ms, 2)},
    }


def animation_message(result: PipelineResult, *, compute_ms: float = 0.0) -> dict[str, Any]:
    """The scene and every character's motion for one version, plus what the pipeline ran (full data)."""
    objects = [object_entry(o) for o in result.scene.objects] if result.scene is not None else []
    characters = [character_entry(m) for _, m in sorted(result.motions.items())]
    return {
        **animation_head(result, characters, compute_ms=compute_ms),
        "objects": objects,
        "characters": characters,
    }


def state_message(doc: Document, *, title: str = "") -> dict[str, Any]:
    """The whole text and version: sent on connect and resume."""
    return {
        "type": "state",
        "doc_id": doc.doc_id,
        "title": title,
        "version": doc.version,
        "text": doc.text,
        "sentences": sentence_list(None, doc),
    }
