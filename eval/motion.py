"""Evaluate motion synthesis: foot sliding, path following, contact distance, jerk.

Usage:
    .venv/bin/python eval/motion.py [--quick] [--json PATH] [--seed 7]

Scenarios: generated scenes (a chair, a desk, a bed, a button on a wall...) with characters walking,
sitting, typing, standing, waving, lying down, pushing buttons, plus free locomotion along random
waypoints (>= 30 in the full run), and held-out CMU clips from ../shared/data (their captured root
path replayed through the controller; skipped when the data is absent).
JSON keys: foot_slide_cm, path_error_cm, contact_cm (on each character's own skeleton, as drawn), jerk, spine_bend_p95_deg (trunk from upright while a
standing hand reaches a target), prop_grip_error_cm (worst held frame: a prop's grip point to its hand),
actions, scenarios, cmu_clips, ...
Liveliness (issue 23): frozen_share (share of on-stage frames in which no joint turns more than 0.1 degree
in the world since the frame before), measured on the composed motion of whole stories run through the
orchestrator (examples/office.txt; the full run adds the Fountain examples) and on the scenarios with
the idle layer; clips: per library clip, jerk (mean joint jerk, m/s^3), energy (mean joint angular
speed, deg/s) and frozen_share of the clip alone; longest_frozen_s: the longest run of frozen on-stage
frames of any character of those stories, seconds (per character in longest_frozen_s_by_character); clips_highest_jerk / clips_lowest_energy list 20
each for review; clips_held_straight_arm: clips with an arm straight, raised and still for 0.5 s or more.
Targets: foot_slide_cm <= 1.0 (cm per frame while a foot is in contact), contact_cm <= 3.0,
spine_bend_p95_deg <= 30, prop_grip_error_cm <= 1, frozen_share <= 0.05, longest_frozen_s <= 0.5.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from proto.scene import PlacedObject, Room, Scene  # noqa: E402
from proto.ssg import ActionNode, CharacterNode  # noqa: E402
from services.motion.ik import global_transforms  # noqa: E402
from services.motion.pairs import offsets_of  # noqa: E402
from services.motion.planning import plan_actions  # noqa: E402
from services.motion.synthesis import synthesise  # noqa: E402
from wana.arrays import from_wire  # noqa: E402
from wana.domain.actions import load_library  # noqa: E402
from wana.domain.skeleton import JOINT_INDEX  # noqa: E402

SCRIPTS = [
    [("walk", "", "chair"), ("sit", "chair", ""), ("type", "desk", ""), ("stand", "", "")],
    [
        ("walk", "", "desk"),
        ("drink", "cup", ""),
        ("wave", "", ""),
        ("sit", "chair", ""),
        ("write", "desk", ""),
    ],
    [("run", "", "bed"), ("lie_down", "bed", ""), ("sleep", "bed", ""), ("stand", "", "")],
    [
        ("push_button", "elevator_button", ""),
        ("turn_left", "", ""),
        ("walk", "", "chair"),
        ("sit", "chair", ""),
    ],
    [("walk", "", "desk"), ("clap", "", ""), ("think", "", ""), ("bow", "", ""), ("wipe_table", "desk", "")],
]


def make_scene(rng: np.random.Generator) -> Scene:
    yaw = float(rng.uniform(-np.pi, np.pi))
    c, s = np.cos(yaw), np.sin(yaw)
    desk = np.array([rng.uniform(-1, 1), 0.0, rng.uniform(-1, 1)])
    chair = desk + np.array([s, 0.0, c]) * 0.75
    return Scene(
        room=Room(room_type="office", width=8, depth=8, height=3),
        objects=[
            PlacedObject(id="desk", category="desk", position=tuple(desk), yaw=yaw),
            PlacedObject(id="chair", category="office_chair", position=tuple(chair), yaw=yaw + np.pi),
            PlacedObject(
                id="bed",
                category="bed",
                position=(rng.uniform(-3, -2), 0.0, rng.uniform(2, 3)),
                yaw=float(rng.uniform(-1, 1)),
            ),
            PlacedObject(
                id="cup",
                category="cup",
                position=(float(desk[0] + 0.3 * c), 0.76, float(desk[2] - 0.3 * s)),
                yaw=yaw,
                support="desk",
            ),
            PlacedObject(
                id="elevator_button",
                category="elevator_button",
                position=(3.0, 1.1, rng.uniform(-1, 1)),
                yaw=-np.pi / 2,
            ),
        ],
    )


def foot_slide(pos: np.ndarray, contacts: np.ndarray) -> list[float]:
    """Per-frame horizontal foot displacement in cm while the foot is in contact on both frames."""
    out = []
    for k, name in enumerate(("LeftFoot", "RightFoot")):
        f = pos[:, JOINT_INDEX[name]][:, [0, 2]]
        both = (contacts[1:, k] > 0) & (contacts[:-1, k] > 0)
        out.extend((np.linalg.norm(np.diff(f, axis=0), axis=1)[both] * 100).tolist())
    return out


def path_error(root: np.ndarray, waypoints: np.ndarray) -> float:
    """Mean distance (cm) from the root's ground track to the planned polyline, plus nothing else."""
    p = root[:, [0, 2]]
    best = np.full(len(p), np.inf)
    for a, b in zip(waypoints[:-1], waypoints[1:], strict=True):
        d = b - a
        u = np.clip(((p - a) @ d) / max(d @ d, 1e-12), 0, 1)
        best = np.minimum(best, np.linalg.norm(p - (a + u[:, None] * d), axis=1))
    if len(waypoints) == 1:
        best = np.linalg.norm(p - waypoints[0], axis=1)
    return float(best.mean() * 100)


def jerk(pos: np.ndarray) -> float:
    """Mean joint jerk magnitude, m/s^3."""
    if len(pos) < 4:
        return 0.0
    return float(np.linalg.norm(np.diff(pos, n=3, axis=0) * 30**3, axis=-1).mean())


FROZEN_DEG = 0.1  # degrees a joint must turn between two frames for the frame to count as moving


def joint_turn_deg(global_rot: np.ndarray) -> np.ndarray:
    """(T-1, J) degrees each joint's world orientation turns between consecutive frames."""
    dot = np.clip(np.abs(np.sum(global_rot[1:] * global_rot[:-1], axis=-1)), 0.0, 1.0)
    return np.degrees(2 * np.arccos(dot))


def frozen_share(global_rot: np.ndarray, present: np.ndarray | None = None) -> float:
    """Share of frames (on stage, both this and the previous one) in which no joint turns > FROZEN_DEG."""
    if len(global_rot) < 2:
        return 0.0
    frozen = joint_turn_deg(global_rot).max(axis=1) <= FROZEN_DEG
    on = np.ones(len(frozen), bool) if present is None else (present[1:] > 0) & (present[:-1] > 0)
    return float(frozen[on].mean()) if on.any() else 0.0


def longest_frozen_s(global_rot: np.ndarray, present: np.ndarray | None = None, fps: int = 30) -> float:
    """Seconds of the longest run of frozen on-stage frames (issue 23: never a frozen pose > 0.5 s)."""
    if len(global_rot) < 2:
        return 0.0
    frozen = joint_turn_deg(global_rot).max(axis=1) <= FROZEN_DEG
    if present is not None:
        frozen &= (present[1:] > 0) & (present[:-1] > 0)
    edges = np.diff(np.r_[0, frozen.astype(np.int8), 0])
    runs = np.flatnonzero(edges == -1) - np.flatnonzero(edges == 1)
    return float(runs.max()) / fps if len(runs) else 0.0


def clip_review(limit: int = 20) -> dict:
    """Per library clip: jerk, motion energy and frozen share of the clip alone (neutral root, 30 fps)."""
    from tools.authoring.clip_sheets import held_straight_arms
    from wana.domain.actions import get_clip
    from wana.domain.skeleton import REST_OFFSETS, forward_kinematics

    rows = {}
    held: dict[str, list] = {}
    for name in sorted(load_library()):
        clip = get_clip(name)
        rot, offs, _ = clip.sample(30, max(clip.duration_s, 3.0) if clip.looping else clip.duration_s)
        root = offs + np.array([0.0, REST_OFFSETS[0, 1], 0.0])
        pos, grot = forward_kinematics(rot, root)
        turn = joint_turn_deg(grot) if len(rot) > 1 else np.zeros((1, rot.shape[1]))
        rows[name] = {
            "jerk": round(jerk(pos), 2),
            "energy_deg_s": round(float(turn.mean() * 30), 2),
            "frozen_share": round(frozen_share(grot), 3),
            "seconds": round(len(rot) / 30, 2),
        }
        if flags := held_straight_arms(pos):
            held[name] = flags
    by_jerk = sorted(rows, key=lambda n: -rows[n]["jerk"])[:limit]
    by_energy = sorted(rows, key=lambda n: rows[n]["energy_deg_s"])[:limit]
    return {
        "clips": rows,
        "clips_highest_jerk": [[n, rows[n]["jerk"]] for n in by_jerk],
        "clips_lowest_energy": [[n, rows[n]["energy_deg_s"]] for n in by_energy],
        "clip_frozen_share": round(float(np.mean([r["frozen_share"] for r in rows.values()])), 4),
        # (side, start s, seconds) where an arm is straight, raised and still for 0.5 s or more (issue 23:
        # none in the library; the same test as the review sheets of tools/authoring/clip_sheets.py)
        "clips_held_straight_arm": held,
    }


STAGED_STORIES = ("office.txt", "office_morning.fountain", "kitchen_night.fountain")


def staged_frozen(quick: bool) -> dict:
    """frozen_share of every character on stage in whole stories run through the orchestrator in-process."""
    import tempfile

    from services.orchestrator.backend import InProcessBackend
    from services.orchestrator.session import Orchestrator
    from wana.domain.skeleton import forward_kinematics
    from wana.screenplay import looks_like_fountain, to_story

    examples = Path(__file__).resolve().parents[1] / "examples"
    out: dict = {}
    longest: dict = {}
    frozen, total = 0.0, 0
    for story in STAGED_STORIES[:1] if quick else STAGED_STORIES:
        text = (examples / story).read_text()
        if looks_like_fountain(text, story):  # as `wana animate` reads it: cues and dialogue -> sentences
            text = to_story(text)
        with tempfile.TemporaryDirectory(prefix="wana-eval-motion-") as tmp:
            orch = Orchestrator(Path(tmp) / "sessions.db", InProcessBackend(), seed=0)
            try:
                result = orch.create(text, doc_id=story).compute()
            finally:
                orch.close()
        for name, m in result.motions.items():
            rot = from_wire(m.rotations).astype(np.float64)
            _, grot = forward_kinematics(rot, from_wire(m.root_position).astype(np.float64))
            present = from_wire(m.present) if m.present is not None else np.ones(len(rot), np.uint8)
            share = frozen_share(grot, present)
            n = int(((present[1:] > 0) & (present[:-1] > 0)).sum())
            out[f"{story}:{name}"] = round(share, 4)
            longest[f"{story}:{name}"] = round(longest_frozen_s(grot, present), 3)
            frozen += share * n
            total += n
    return {
        "frozen_share": round(frozen / max(total, 1), 4),
        "frozen_share_by_character": out,
        "longest_frozen_s": max(longest.values(), default=0.0),
        "longest_frozen_s_by_character": longest,
    }


def run_scenario(character: CharacterNode, scene: Scene, start) -> dict:
    plan = plan_actions(character, scene, start)
    motion, pieces, _ = synthesise(plan)
    root = from_wire(motion.root_position).astype(np.float64)
    rot = from_wire(motion.rotations).astype(np.float64)
    contacts = from_wire(motion.foot_contact)
    pos, grot = global_transforms(rot, root)
    # contacts where the character is drawn: on its own skeleton (wana.assets.characters), as the renderer
    # and the story checks pose it, not the reference skeleton the clips are authored on
    drawn, _ = global_transforms(rot, root, offsets_of(character.name))
    slides = foot_slide(pos, contacts)
    paths, contact = [], []
    f0 = 0
    for p in pieces:
        n = len(p.root)
        if p.segment.kind == "locomotion" and len(p.segment.waypoints) >= 2:
            start_xz = np.array([[p.root[0, 0], p.root[0, 2]]])
            wps = np.concatenate([start_xz, np.asarray(p.segment.waypoints)])
            paths.append(path_error(p.root, wps))
        for joint, (frames, target) in p.contact_frames.items():
            if len(frames):
                contact.extend(
                    (np.linalg.norm(drawn[f0 + frames, JOINT_INDEX[joint]] - target, axis=1) * 100).tolist()
                )
        f0 += n
    return {
        "slides": slides,
        "paths": paths,
        "contact": contact,
        "jerk": jerk(pos),
        "frames": len(root),
        "spine": spine_bends(pos, pieces),
        "grip": grip_errors(pos, motion),
        "frozen": frozen_share(grot),
        "frozen_idle": _frozen_with_idle(motion),
    }


def _frozen_with_idle(motion) -> float:  # noqa: ANN001 - proto Motion
    """frozen_share of a scenario's motion with the idle layer the orchestrator applies (wana.domain.idle)."""
    from wana.domain.idle import enliven_motion

    m = enliven_motion(motion)
    _, grot = global_transforms(
        from_wire(m.rotations).astype(np.float64), from_wire(m.root_position).astype(np.float64)
    )
    return frozen_share(grot)


def spine_bends(pos: np.ndarray, pieces: list) -> list[float]:
    """Degrees between the trunk (hips -> neck) and upright on every frame a standing hand reaches a target."""
    out, f0 = [], 0
    up = pos[:, JOINT_INDEX["Neck"]] - pos[:, JOINT_INDEX["Hips"]]
    angle = np.degrees(np.arccos(np.clip(up[:, 1] / np.linalg.norm(up, axis=1), -1, 1)))
    for p in pieces:
        reach = [fr for j, (fr, _) in p.contact_frames.items() if "Hand" in j and len(fr)]
        if reach and "Hips" not in p.contact_frames and p.segment.action not in ("sit", "lie_down"):
            frames = np.unique(np.concatenate(reach))
            out.extend(angle[f0 + frames].tolist())
        f0 += len(p.root)
    return out


def grip_errors(pos: np.ndarray, motion) -> list[float]:  # noqa: ANN001 - proto Motion
    """Per held frame, cm between a prop's grip point (world) and the joint holding it."""
    from wana.domain import quat

    out = []
    for t in motion.props:
        origin = from_wire(t.position).astype(np.float64)
        grip = origin + quat.rotate(
            from_wire(t.rotation).astype(np.float64), np.broadcast_to(t.grip, origin.shape)
        )
        hand = pos[t.start_frame : t.end_frame, JOINT_INDEX[t.joint]]
        out.extend((np.linalg.norm(grip - hand, axis=1) * 100).tolist())
    return out


def scenarios(n: int, seed: int):
    rng = np.random.default_rng(seed)
    for i in range(n):
        scene = make_scene(rng)
        start = (float(rng.uniform(-3, 3)), float(rng.uniform(-3, -2)), float(rng.uniform(-np.pi, np.pi)))
        if i % 3 == 2:  # free locomotion along random waypoints
            acts = [
                ActionNode(
                    verb="walk", action=rng.choice(["walk", "run", "walk_slowly", "jog"]), destination=d
                )
                for d in rng.choice(["desk", "bed", "chair", "elevator_button"], 3)
            ]
        else:
            script = SCRIPTS[i % len(SCRIPTS)]
            acts = [ActionNode(verb=a, action=a, target=t, destination=d) for a, t, d in script]
        yield f"scenario_{i:02d}", CharacterNode(name=f"c{i}", actions=acts), scene, start


def cmu_heldout(quick: bool) -> list[dict]:
    """Replay held-out CMU root paths through the controller; report path error and foot sliding."""
    from services.motion.locomotion import locomote
    from services.motion.retarget import retarget_clip
    from services.motion.train_locomotion import HELD_OUT, SHARED
    from wana.domain.bvh import read_bvh

    out = []
    for rel in HELD_OUT[:1] if quick else HELD_OUT:
        path = SHARED / "cmu_mocap_iclone" / rel
        if not path.is_file():
            continue
        root, rot = retarget_clip(read_bvh(path))
        track = root[:, [0, 2]]
        speed = float(np.linalg.norm(np.diff(track, axis=0), axis=1).mean() * 30)
        wps = track[::10]
        heading0 = float(np.arctan2(*(track[10] - track[0])))
        loco = locomote(wps, speed, heading0)
        pos, _ = global_transforms(loco.rotations, loco.root_position)
        from services.motion.locomotion import lock_walk

        locked = lock_walk(loco.rotations, loco.root_position, loco.contacts)
        pos_locked, _ = global_transforms(locked, loco.root_position)
        out.append(
            {
                "clip": rel,
                "speed_m_s": speed,
                "path_error_cm": path_error(loco.root_position, wps),
                "foot_slide_raw_cm": float(np.mean(foot_slide(pos, loco.contacts) or [0])),
                "foot_slide_cm": float(np.mean(foot_slide(pos_locked, loco.contacts) or [0])),
                "source": loco.source,
            }
        )
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--quick", action="store_true", help="10 scenarios and one CMU clip (< 30 s)")
    parser.add_argument("--json", type=Path, default=None, help="write the metrics here")
    parser.add_argument("--seed", type=int, default=7)
    args = parser.parse_args(argv)
    t0 = time.time()
    n = 10 if args.quick else 36
    slides, paths, contact, jerks, frames, spine, grip = [], [], [], [], 0, [], []
    frozen, frozen_idle = [], []
    for _name, ch, scene, start in scenarios(n, args.seed):
        r = run_scenario(ch, scene, start)
        slides += r["slides"]
        paths += r["paths"]
        contact += r["contact"]
        jerks.append(r["jerk"])
        frames += r["frames"]
        spine += r["spine"]
        grip += r["grip"]
        frozen.append(r["frozen"])
        frozen_idle.append(r["frozen_idle"])
    cmu = cmu_heldout(args.quick)
    result = {
        "foot_slide_cm": round(float(np.mean(slides)), 4) if slides else 0.0,
        "path_error_cm": round(float(np.mean(paths)), 4) if paths else 0.0,
        "contact_cm": round(float(np.mean(contact)), 4) if contact else 0.0,
        "contact_p95_cm": round(float(np.percentile(contact, 95)), 4) if contact else 0.0,
        "jerk": round(float(np.mean(jerks)), 3),
        "spine_bend_p95_deg": round(float(np.percentile(spine, 95)), 2) if spine else 0.0,
        "prop_grip_error_cm": round(float(np.max(grip)), 4) if grip else None,
        "prop_held_frames": len(grip),
        "actions": len(load_library()),
        "scenarios": n,
        "frames": frames,
        "cmu_clips": len(cmu),
        "cmu_path_error_cm": round(float(np.mean([c["path_error_cm"] for c in cmu])), 4) if cmu else None,
        "cmu_foot_slide_cm": round(float(np.mean([c["foot_slide_cm"] for c in cmu])), 4) if cmu else None,
        "cmu_foot_slide_raw_cm": round(float(np.mean([c["foot_slide_raw_cm"] for c in cmu])), 4)
        if cmu
        else None,
        "scenario_frozen_share_raw": round(float(np.mean(frozen)), 4),
        "scenario_frozen_share": round(float(np.mean(frozen_idle)), 4),
        **staged_frozen(args.quick),
        **clip_review(),
        "seed": args.seed,
        "seconds": round(time.time() - t0, 2),
    }
    print(f"{'metric':24s} value")
    for k, v in result.items():
        if k != "clips":
            print(f"{k:24s} {v}")
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(result, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
