"""Author the action library: turn the compact specs into assets/actions/<name>.json keyframe files.

Usage:
    python -m tools.authoring.author_actions [--out assets/actions]

The specs live in action_specs_*.py as Python (so poses can be built from aimed limbs); what ships
and what the runtime reads is the JSON the script writes (Euler degrees, order ZYX, 0.1 degree).
"""

from __future__ import annotations

import argparse
import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from wana.domain import quat
from wana.domain.actions import ACTIONS_DIR, EULER_ORDER, neutral_rotations
from wana.domain.posing import Pose, neutral
from wana.domain.skeleton import JOINT_INDEX


@dataclass
class Spec:
    """One action as authored: metadata plus keys (time, pose, easing, root offset, root yaw)."""

    name: str
    tags: list[str]
    synonyms: list[str]
    keys: list[tuple]  # (t, pose, ease, root, root_yaw) with trailing items optional
    looping: bool = False
    body_parts: list[str] = field(default_factory=lambda: ["upper_body"])
    interaction: dict | None = None

    @property
    def duration_s(self) -> float:
        return float(self.keys[-1][0])


HOLD_OVERSHOOT = 1.06  # a held pose arrives this far past its mark (upper body) and settles through the hold


def overshoot(pose: Pose, amount: float = HOLD_OVERSHOOT) -> Pose:
    """The pose carried a little past itself from neutral, joint by joint (upper body only: feet stay put)."""
    n = neutral()
    out = dict(pose)
    for name, q in pose.items():
        if name == "Hips" or "Leg" in name or "Foot" in name or "Toe" in name:
            continue
        base = n.get(name, quat.identity())
        out[name] = quat.slerp(base, np.asarray(q, dtype=np.float64), amount)
    return out


def hold(pose: Pose, dur: float = 2.0, ramp: float = 0.4, root=(0.0, 0.0, 0.0)) -> list[tuple]:
    """Neutral -> pose (ramp s) -> a moving hold -> neutral at dur.

    The pose arrives a little past its mark and settles back through the hold (follow-through; a hold
    that never stops moving reads as alive, a dead one as a mannequin).
    """
    n = neutral()
    return [
        (0.0, n, "linear"),
        (ramp, overshoot(pose), "in_out", root),
        (dur - ramp, pose, "in_out", root),
        (dur, n, "in_out"),
    ]


def cycle(
    a: Pose,
    b: Pose,
    period: float = 0.6,
    reps: int = 3,
    ramp: float = 0.4,
    root_a=(0.0, 0.0, 0.0),
    root_b=None,
    settle: bool = True,
) -> list[tuple]:
    """Neutral -> a, then a/b alternations (reps times), then back to neutral."""
    n = neutral()
    root_b = root_a if root_b is None else root_b
    keys: list[tuple] = [(0.0, n, "linear"), (ramp, a, "in_out", root_a)]
    t = ramp
    for _ in range(reps):
        keys.append((t + period / 2, b, "in_out", root_b))
        keys.append((t + period, a, "in_out", root_a))
        t += period
    if settle:
        keys.append((t + ramp, n, "in_out"))
    return keys


def loop(a: Pose, b: Pose, period: float = 1.0, root_a=(0.0, 0.0, 0.0), root_b=None) -> list[tuple]:
    """A looping a -> b -> a cycle (first key equals last)."""
    root_b = root_a if root_b is None else root_b
    return [(0.0, a, "linear", root_a), (period / 2, b, "in_out", root_b), (period, a, "in_out", root_a)]


def seq(*steps: tuple) -> list[tuple]:
    """Keys from (dt, pose, ease[, root[, yaw]]) steps; times accumulate."""
    t = 0.0
    keys = []
    for step in steps:
        t += step[0]
        keys.append((round(t, 4), *step[1:]))
    return keys


def _key_json(key: tuple) -> dict:
    t, pose, *rest = key
    ease = rest[0] if rest else "in_out"
    root = rest[1] if len(rest) > 1 else (0.0, 0.0, 0.0)
    yaw = rest[2] if len(rest) > 2 else 0.0
    base = neutral_rotations()
    full = {name: base[JOINT_INDEX[name]] for name in ("LeftArm", "LeftForeArm", "RightArm", "RightForeArm")}
    full.update(pose)
    out_pose = {}
    for name, q in full.items():
        e = quat.to_euler(EULER_ORDER, np.asarray(q))
        if np.max(np.abs(e)) < 0.05:
            continue
        out_pose[name] = [round(float(x), 1) for x in e]
    d: dict = {"t": round(float(t), 4), "ease": ease if t > 0 else "linear", "pose": out_pose}
    if any(abs(x) > 1e-6 for x in root):
        d["root"] = [round(float(x), 4) for x in root]
    if abs(yaw) > 1e-6:
        d["root_yaw"] = round(float(yaw), 2)
    return d


def spec_to_dict(spec: Spec) -> dict:
    contacts = list(spec.interaction["contacts"]) if spec.interaction else []
    d = {
        "name": spec.name,
        "tags": spec.tags,
        "synonyms": spec.synonyms,
        "duration_s": round(spec.duration_s, 4),
        "looping": spec.looping,
        "body_parts": spec.body_parts,
        "contact_joints": contacts,
        "interaction": spec.interaction,
        "euler": EULER_ORDER,
        "keys": [_key_json(k) for k in spec.keys],
    }
    return d


def all_specs() -> list[Spec]:
    from tools.authoring import (
        action_specs_body,
        action_specs_gestures,
        action_specs_objects,
        action_specs_social,
    )

    specs = (
        action_specs_objects.specs()
        + action_specs_social.specs()
        + action_specs_gestures.specs()
        + action_specs_body.specs()
    )
    names = [s.name for s in specs]
    dupes = {n for n in names if names.count(n) > 1}
    if dupes:
        raise ValueError(f"duplicate action names: {sorted(dupes)}")
    return specs


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m tools.authoring.author_actions",
        description="Write the authored action clips as JSON keyframe files.",
    )
    parser.add_argument(
        "--out", type=Path, default=ACTIONS_DIR, help="output folder (default assets/actions)"
    )
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    specs = all_specs()
    for spec in specs:
        (args.out / f"{spec.name}.json").write_text(
            json.dumps(spec_to_dict(spec), separators=(",", ":")) + "\n"
        )
    print(f"wrote {len(specs)} clips to {args.out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
