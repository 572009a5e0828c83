"""`wana motion ...`: add BVH clips to the action library (no retraining) and list it.

wana motion import FILE.bvh --tags greet,happy [--name NAME] [--synonyms "say hi,hail"] [--looping]
wana motion list [--tag TAG]
"""

from __future__ import annotations

import argparse
import json
import re
import sys
from pathlib import Path

import numpy as np
from tqdm import tqdm

from wana.domain import quat
from wana.domain.actions import EULER_ORDER, IMPORTED_DIR, clip_from_dict, load_library, reload_library
from wana.domain.skeleton import JOINT_NAMES
from wana.domain.units import FPS


def clip_dict_from_bvh(
    path: Path,
    name: str,
    tags: list[str],
    synonyms: list[str],
    looping: bool = False,
    joint_map: str | None = None,
    key_step: int = 2,
) -> dict:
    """Read, retarget and convert a BVH file into the library's keyframe JSON (a key every key_step frames)."""
    from services.motion.retarget import KNOWN_MAPS, retarget_clip
    from wana.domain.bvh import canonical_motion, read_bvh

    clip = read_bvh(path)
    if clip.joint_names == list(JOINT_NAMES):
        root, rot = canonical_motion(clip)
        if abs(clip.fps - 30) > 1e-3:
            from services.motion.retarget import resample

            root, rot = resample(root, rot, clip.fps, 30.0)
    else:
        root, rot = retarget_clip(clip, KNOWN_MAPS.get(joint_map) if joint_map else None)
    if len(rot) < 2:
        raise ValueError(f"{path}: needs at least two frames")
    heading0 = float(quat.yaw_of(rot[0, 0]))
    inv0 = quat.yaw(np.array(-heading0))
    offs = quat.rotate(inv0, root - root[0] * np.array([1.0, 0.0, 1.0]))
    offs[:, 1] -= 0.95  # library root offsets are relative to the standing hips height
    local = rot.copy()
    local[:, 0] = quat.mul(inv0, rot[:, 0])
    frames = list(range(0, len(rot), key_step))
    if frames[-1] != len(rot) - 1:
        frames.append(len(rot) - 1)
    keys = []
    for f in tqdm(frames, desc=f"import {path.name}", disable=len(frames) < 200):
        e = quat.to_euler(EULER_ORDER, local[f])
        keys.append(
            {
                "t": round(f / FPS, 4),
                "ease": "linear",
                "pose": {n: [round(float(v), 3) for v in e[j]] for j, n in enumerate(JOINT_NAMES)},
                "root": [round(float(v), 4) for v in offs[f]],
            }
        )
    return {
        "name": name,
        "tags": tags,
        "synonyms": synonyms,
        "duration_s": round((len(rot) - 1) / FPS, 4),
        "looping": looping,
        "body_parts": ["full_body"],
        "contact_joints": [],
        "interaction": None,
        "euler": EULER_ORDER,
        "source": "imported",
        "keys": keys,
    }


def _split(s: str) -> list[str]:
    return [x.strip() for x in s.split(",") if x.strip()]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="wana motion", description="Manage the action library.")
    sub = parser.add_subparsers(dest="command", required=True)
    imp = sub.add_parser("import", help="add a BVH clip to the library (retargeted; no retraining)")
    imp.add_argument("file", type=Path, help="a .bvh or .bvh.gz file")
    imp.add_argument("--tags", default="", help="comma-separated tags, e.g. greet,happy")
    imp.add_argument("--name", default="", help="action name (default: the file name)")
    imp.add_argument("--synonyms", default="", help="comma-separated phrases the NLP may map to it")
    imp.add_argument("--looping", action="store_true", help="the clip loops")
    imp.add_argument(
        "--map",
        choices=["cc_base", "cmu", "mixamo"],
        default=None,
        help="source joint names (default: guessed)",
    )
    imp.add_argument(
        "--out", type=Path, default=IMPORTED_DIR, help=f"folder for the clip (default {IMPORTED_DIR})"
    )
    imp.add_argument("--force", action="store_true", help="replace an existing clip of that name")
    lst = sub.add_parser("list", help="print the library")
    lst.add_argument("--tag", default="")
    args = parser.parse_args(argv)
    if args.command == "list":
        for name, c in sorted(load_library().items()):
            if not args.tag or args.tag in c.tags:
                print(f"{name:28s} {c.duration_s:5.2f}s {'loop' if c.looping else '    '} {','.join(c.tags)}")
        return 0
    if not args.file.is_file():
        print(f"error: no such file {args.file}", file=sys.stderr)
        return 2
    stem = args.file.name.split(".")[0]
    name = args.name or re.sub(r"[^a-z0-9_]+", "_", stem.lower()).strip("_")
    if name in load_library() and not args.force:
        print(f"error: an action named {name!r} exists; pass --name or --force", file=sys.stderr)
        return 2
    try:
        d = clip_dict_from_bvh(
            args.file, name, _split(args.tags), _split(args.synonyms), args.looping, args.map
        )
        clip_from_dict(d)  # validate before writing
    except ValueError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    args.out.mkdir(parents=True, exist_ok=True)
    out = args.out / f"{name}.json"
    out.write_text(json.dumps(d, separators=(",", ":")) + "\n")
    reload_library()
    print(f"added {name!r} ({d['duration_s']:.2f}s, {len(d['keys'])} keys) -> {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
