"""Review sheets of the action library: one PNG per clip, stick figures from the front and the side.

Usage:
    python -m tools.authoring.clip_sheets [--out out/clips] [--only wave,point] [--tiles 8]

Each sheet shows the clip at evenly spaced frames (front view above, side view below: the left side
drawn blue, the right red), titled with the clip's length and flags from ``held_straight_arms``
(an arm held straight and raised for half a second or more reads as a mannequin's). The drawing is
deliberately plain (PIL lines, no renderer): it is fast enough to look at all 181 clips after every
authoring change.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw

from wana.domain.actions import ActionClip, get_clip, load_library
from wana.domain.skeleton import JOINT_INDEX, PARENTS, REST_OFFSETS, forward_kinematics
from wana.domain.units import FPS

STRAIGHT_DEG = 12.0  # an elbow bent less than this is straight
RAISED_DEG = 60.0  # an upper arm more than this from the trunk's downward line (degrees) is raised
HELD_S = 0.5  # seconds a straight, raised arm must stay still to count as held
STILL_M_S = 0.15  # metres per second the hand may drift and still count as held
TILE = 150  # pixels per view


def sample(clip: ActionClip) -> tuple[np.ndarray, np.ndarray]:
    """Joint positions (T, J, 3) of a clip played in place, and its rotations (T, J, 4)."""
    rot, offs, _ = clip.sample(FPS, max(clip.duration_s, 3.0) if clip.looping else clip.duration_s)
    root = offs + np.array([0.0, REST_OFFSETS[0, 1], 0.0])
    pos, _ = forward_kinematics(rot, root)
    return pos, rot


def held_straight_arms(pos: np.ndarray) -> list[tuple[str, float, float]]:
    """(side, start s, seconds) of every stretch where an arm is straight, raised and held still."""
    out = []
    least = int(HELD_S * FPS)
    for side in ("Left", "Right"):
        sh, el, wr = (pos[:, JOINT_INDEX[f"{side}{j}"]] for j in ("Arm", "ForeArm", "Hand"))
        upper, fore = el - sh, wr - el
        cos = np.sum(upper * fore, axis=1) / (np.linalg.norm(upper, axis=1) * np.linalg.norm(fore, axis=1))
        bend = np.degrees(np.arccos(np.clip(cos, -1, 1)))
        down = pos[:, JOINT_INDEX["Hips"]] - pos[:, JOINT_INDEX["Neck"]]
        cos_t = np.sum(upper * down, axis=1) / (np.linalg.norm(upper, axis=1) * np.linalg.norm(down, axis=1))
        elev = np.degrees(np.arccos(np.clip(cos_t, -1, 1)))  # 0: along the body, 90: out, 180: overhead
        speed = np.zeros(len(wr))
        speed[1:] = np.linalg.norm(np.diff(wr, axis=0), axis=1) * FPS
        bad = (bend < STRAIGHT_DEG) & (elev > RAISED_DEG) & (speed < STILL_M_S)
        idx = np.flatnonzero(bad)
        if not len(idx):
            continue
        breaks = np.flatnonzero(np.diff(idx) > 1)
        for a, b in zip(np.r_[idx[0], idx[breaks + 1]], np.r_[idx[breaks], idx[-1]], strict=True):
            if b + 1 - a >= least:
                out.append((side, round(a / FPS, 2), round((b + 1 - a) / FPS, 2)))
    return out


def _draw(d: ImageDraw.ImageDraw, pts: np.ndarray, ox: int, oy: int, axis: int) -> None:
    """Stick figure of one frame: pts (J, 3), horizontal axis 0 (front view) or 2 (side view)."""
    s = TILE / 2.2

    def px(p: np.ndarray) -> tuple[float, float]:
        h = p[axis] * (-1 if axis == 0 else 1)  # the front view looks at the character: its left on the right
        return ox + TILE / 2 + h * s, oy + TILE - 8 - p[1] * s

    d.line([(ox, oy + TILE - 8), (ox + TILE, oy + TILE - 8)], fill=(190, 190, 190))
    for j, p in enumerate(PARENTS):
        if p < 0:
            continue
        name = REST_OFFSETS_NAMES[j]
        colour = (
            (40, 90, 220)
            if name.startswith("Left")
            else (220, 60, 50)
            if name.startswith("Right")
            else (40, 40, 40)
        )
        d.line([px(pts[p]), px(pts[j])], fill=colour, width=3)
    hx, hy = px(pts[JOINT_INDEX["Head"]])
    d.ellipse([hx - 7, hy - 12, hx + 7, hy + 2], outline=(40, 40, 40), width=2)


REST_OFFSETS_NAMES = tuple(sorted(JOINT_INDEX, key=JOINT_INDEX.get))  # joint names in skeleton order


def sheet(clip: ActionClip, tiles: int = 8) -> tuple[Image.Image, list[tuple[str, float, float]]]:
    """The review sheet of one clip and its held straight-arm stretches."""
    pos, _ = sample(clip)
    pos = pos - np.array([pos[0, 0, 0], 0.0, pos[0, 0, 2]])
    frames = np.unique(np.linspace(0, len(pos) - 1, tiles).round().astype(int))
    flags = held_straight_arms(pos)
    img = Image.new("RGB", (TILE * len(frames), 2 * TILE + 34), "white")
    d = ImageDraw.Draw(img)
    title = f"{clip.name}  {clip.duration_s:.2f} s{'  looping' if clip.looping else ''}"
    if flags:
        title += "  HELD STRAIGHT ARM " + ", ".join(f"{s} at {a} s for {n} s" for s, a, n in flags)
    d.text((6, 4), title, fill=(200, 0, 0) if flags else (0, 0, 0))
    for i, f in enumerate(frames):
        _draw(d, pos[f], i * TILE, 20, 0)
        _draw(d, pos[f], i * TILE, 20 + TILE, 2)
        d.text((i * TILE + 4, 22), f"{f / FPS:.2f}s", fill=(90, 90, 90))
    return img, flags


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m tools.authoring.clip_sheets", description=__doc__.split("\n")[0]
    )
    parser.add_argument("--out", type=Path, default=Path("out/clips"), help="folder for the sheets")
    parser.add_argument("--only", default="", help="comma-separated clip names (default: all)")
    parser.add_argument("--tiles", type=int, default=8, help="frames per sheet")
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    names = [n for n in args.only.split(",") if n] or sorted(load_library())
    flagged = 0
    for name in names:
        img, flags = sheet(get_clip(name), args.tiles)
        img.save(args.out / f"{name}.png")
        if flags:
            flagged += 1
            print(f"{name}: held straight arm {flags}")
    print(f"wrote {len(names)} sheets to {args.out}; {flagged} with a held straight arm")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
