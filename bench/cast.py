#!/usr/bin/env python
"""Feet on the floor for `--cast` rigs: the foot height error at planted frames of a walk, per rig.

The three rigs of the tests (tests/unit/cast_rigs.py: Mixamo names in centimetres; Unreal names, A-pose,
long legs, short torso, twist and finger joints; unknown names with a map, short legs) walk the demo walk
of the built-in Eve; at every frame a canonical foot is planted (its horizontal speed under 0.6 m/s) the
rig's ankle height over its soles is compared with the built-in ankle's height over its soles, and the
planted foot's horizontal speed with the built-in one's (the path over the floor is kept, not the stride,
so legs of another length slide).

    .venv/bin/python bench/cast.py --quick --json out/bench_cast.json

Target (issue 21, item 4): within 2 cm.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from proto.render import CastMember  # noqa: E402
from services.render.cast_gltf import cast_pose, load_cast  # noqa: E402
from services.render.demo import walk_motion  # noqa: E402
from services.render.skinning import Rig  # noqa: E402
from tests.unit.cast_rigs import CUSTOM, MIXAMO, UNREAL, rig_glb, rig_joints  # noqa: E402
from wana.domain.skeleton import JOINT_INDEX  # noqa: E402

FEET = ("LeftFoot", "RightFoot")


def measure(frames: int) -> dict[str, dict[str, float]]:
    walk = walk_motion("Eve", (-2.0, 1.0), (1.0, -1.0), frames)
    eve = Rig.from_motion(walk)
    canon = eve.joint_positions
    ch = eve.character
    canon_ankle = ch.rest_joint_positions()[JOINT_INDEX["LeftFoot"], 1] - ch.vertices[:, 1].min()
    feet = canon[:, [JOINT_INDEX[f] for f in FEET]]
    speed = np.linalg.norm(np.diff(feet[..., [0, 2]], axis=0), axis=-1) * walk.fps
    planted = [(int(f) + 1, int(k)) for f, k in zip(*np.nonzero(speed < 0.6), strict=True)]
    rigs = {
        "mixamo_cm": (rig_glb(rig_joints(MIXAMO), centimetres=True), {}),
        "unreal_apose_long_legs_extras": (
            rig_glb(rig_joints(UNREAL, legs=1.15, torso=0.85, extras=True), a_pose=True),
            {},
        ),
        "unknown_names_map_short_legs": (rig_glb(rig_joints(CUSTOM, legs=0.8, arms=1.1)), CUSTOM),
    }
    out = {}
    for name, (data, joint_map) in rigs.items():
        cast = load_cast([CastMember(name="Eve", glb=data, joint_map=joint_map)])["Eve"]
        pose = cast_pose(cast, walk)
        ankle = cast.rig.rest_world()[cast.joints["LeftFoot"], 1, 3] - cast.rig.floor()
        err = [
            abs(
                (pose.world[f, cast.joints[FEET[k]], 1] - ankle)
                - (canon[f, JOINT_INDEX[FEET[k]], 1] - canon_ankle)
            )
            for f, k in planted
        ]
        user_feet = pose.world[:, [cast.joints[f] for f in FEET]]
        user_speed = np.linalg.norm(np.diff(user_feet[..., [0, 2]], axis=0), axis=-1) * walk.fps
        slide = [float(user_speed[f - 1, k] - speed[f - 1, k]) for f, k in planted]
        out[name] = {
            "planted_foot_frames": len(err),
            "extra_slide_m_s": round(max(slide), 3),  # planted foot's speed over the canonical one's
            "max_cm": round(float(max(err)) * 100, 3),
            "mean_cm": round(float(np.mean(err)) * 100, 3),
        }
    return out


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--quick", action="store_true", help="a 60-frame walk (default 240)")
    p.add_argument("--json", help="write the numbers here")
    args = p.parse_args()
    result = measure(60 if args.quick else 240)
    for name, r in result.items():
        print(
            f"{name:32s} planted {r['planted_foot_frames']:4d}  max {r['max_cm']:.2f} cm  "
            f"mean {r['mean_cm']:.2f} cm  extra slide {r['extra_slide_m_s']:.2f} m/s"
        )
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps(result, indent=2))
    return 0 if all(r["max_cm"] <= 2.0 for r in result.values()) else 1


if __name__ == "__main__":
    raise SystemExit(main())
