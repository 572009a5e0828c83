"""BVH read and write (plain or .gz), any hierarchy, any rotation channel order.

`read_bvh` keeps every channel exactly as written so that a read -> write -> read round trip
reproduces each channel (to the 1e-6 printed precision); `BvhClip.local_rotations()` and
`BvhClip.global_positions()` give quaternions and FK positions in the file's own units.
`write_bvh` writes the canonical skeleton (wana.domain.skeleton) from root positions and quaternions.
"""

from __future__ import annotations

import gzip
import io
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from wana.domain import quat
from wana.domain.skeleton import JOINT_NAMES, N_JOINTS, PARENTS, REST_OFFSETS


class BvhError(ValueError):
    """A BVH file that cannot be parsed; the message names the line."""


@dataclass
class BvhClip:
    """A parsed BVH file.

    Attributes:
        joint_names: (J,) names in file order (End Sites excluded).
        parents: (J,) parent index, -1 for roots.
        offsets: (J, 3) OFFSET of each joint, file units.
        channels: per joint, its channel names in file order (e.g. ["Zrotation", "Yrotation", "Xrotation"]).
        end_sites: joint index -> End Site offset (3,).
        frame_time: seconds per frame.
        motion: (T, C) every channel value as written.
    """

    joint_names: list[str]
    parents: np.ndarray
    offsets: np.ndarray
    channels: list[list[str]]
    end_sites: dict[int, np.ndarray]
    frame_time: float
    motion: np.ndarray

    @property
    def fps(self) -> float:
        return 1.0 / self.frame_time

    @property
    def n_frames(self) -> int:
        return int(self.motion.shape[0])

    def channel_slices(self) -> list[slice]:
        out, c = [], 0
        for ch in self.channels:
            out.append(slice(c, c + len(ch)))
            c += len(ch)
        return out

    def index(self, name: str) -> int:
        return self.joint_names.index(name)

    def local_rotations(self) -> np.ndarray:
        """(T, J, 4) local quaternions (x, y, z, w) from the rotation channels (identity where none)."""
        t = self.n_frames
        out = quat.identity((t, len(self.joint_names)))
        for j, (ch, sl) in enumerate(zip(self.channels, self.channel_slices(), strict=True)):
            rot = [(c[0].upper(), k) for k, c in enumerate(ch) if c.lower().endswith("rotation")]
            if not rot:
                continue
            order = "".join(a for a, _ in rot)
            angles = self.motion[:, sl][:, [k for _, k in rot]]
            out[:, j] = quat.from_euler(order, angles)
        return out

    def local_translations(self) -> np.ndarray:
        """(T, J, 3) each joint's translation from its parent: OFFSET, or OFFSET + position channels."""
        t = self.n_frames
        out = np.repeat(self.offsets[None].astype(np.float64), t, axis=0)
        for j, (ch, sl) in enumerate(zip(self.channels, self.channel_slices(), strict=True)):
            vals = self.motion[:, sl]
            for k, c in enumerate(ch):
                if c.lower().endswith("position"):
                    out[:, j, "xyz".index(c[0].lower())] += vals[:, k]
        return out

    def global_transforms(self) -> tuple[np.ndarray, np.ndarray]:
        """FK in file units: positions (T, J, 3) and global rotations (T, J, 4)."""
        rot = self.local_rotations()
        trans = self.local_translations()
        t, nj = rot.shape[:2]
        gpos = np.zeros((t, nj, 3))
        grot = np.zeros((t, nj, 4))
        for j in range(nj):
            p = self.parents[j]
            if p < 0:
                grot[:, j] = rot[:, j]
                gpos[:, j] = trans[:, j]
            else:
                grot[:, j] = quat.mul(grot[:, p], rot[:, j])
                gpos[:, j] = gpos[:, p] + quat.rotate(grot[:, p], trans[:, j])
        return gpos, grot

    def global_positions(self) -> np.ndarray:
        """(T, J, 3) joint positions in file units."""
        return self.global_transforms()[0]


def _open_text(path: str | Path) -> str:
    path = Path(path)
    if path.suffix == ".gz":
        with gzip.open(path, "rt") as fh:
            return fh.read()
    return path.read_text()


def parse_bvh(text: str) -> BvhClip:
    """Parse BVH text; raises BvhError for malformed input."""
    lines = text.splitlines()
    names: list[str] = []
    parents: list[int] = []
    offsets: list[list[float]] = []
    channels: list[list[str]] = []
    end_sites: dict[int, np.ndarray] = {}
    stack: list[int] = []
    pending_end = False
    i = 0
    if not lines or lines[0].strip() != "HIERARCHY":
        raise BvhError("line 1: expected HIERARCHY")
    i = 1
    try:
        while i < len(lines):
            tok = lines[i].split()
            i += 1
            if not tok:
                continue
            head = tok[0]
            if head in ("ROOT", "JOINT"):
                if len(tok) < 2:
                    raise BvhError(f"line {i}: {head} without a name")
                names.append(tok[1])
                parents.append(stack[-1] if stack and head == "JOINT" else -1)
                offsets.append([0.0, 0.0, 0.0])
                channels.append([])
                pending_end = False
            elif head == "End":
                pending_end = True
            elif head == "{":
                stack.append(-2 if pending_end else len(names) - 1)
            elif head == "}":
                if not stack:
                    raise BvhError(f"line {i}: unbalanced '}}'")
                stack.pop()
                pending_end = False
            elif head == "OFFSET":
                vals = [float(x) for x in tok[1:4]]
                if pending_end:
                    owner = next(s for s in reversed(stack[:-1]) if s >= 0)
                    end_sites[owner] = np.array(vals)
                else:
                    offsets[-1] = vals
            elif head == "CHANNELS":
                n = int(tok[1])
                if len(tok) != n + 2:
                    raise BvhError(f"line {i}: CHANNELS says {n} but lists {len(tok) - 2}")
                channels[-1] = tok[2:]
            elif head == "MOTION":
                break
            else:
                raise BvhError(f"line {i}: unexpected token {head!r}")
        if stack:
            raise BvhError("hierarchy braces do not balance")
        frames = int(lines[i].split(":")[1])
        frame_time = float(lines[i + 1].split(":")[1])
        i += 2
    except (IndexError, ValueError) as exc:
        if isinstance(exc, BvhError):
            raise
        raise BvhError(f"line {i}: {exc}") from exc
    n_channels = sum(len(c) for c in channels)
    body = "\n".join(ln for ln in lines[i:] if ln.strip())
    motion = np.loadtxt(io.StringIO(body), dtype=np.float64, ndmin=2) if body else np.zeros((0, n_channels))
    if motion.shape[0] != frames:
        raise BvhError(f"Frames: says {frames} but {motion.shape[0]} motion lines follow")
    if frames and motion.shape[1] != n_channels:
        raise BvhError(
            f"motion lines have {motion.shape[1]} values, the hierarchy declares {n_channels} channels"
        )
    if not names:
        raise BvhError("no joints in HIERARCHY")
    return BvhClip(
        joint_names=names,
        parents=np.array(parents, dtype=np.int64),
        offsets=np.array(offsets),
        channels=channels,
        end_sites=end_sites,
        frame_time=frame_time,
        motion=motion.reshape(frames, n_channels),
    )


def read_bvh(path: str | Path) -> BvhClip:
    """Read a .bvh or .bvh.gz file."""
    return parse_bvh(_open_text(path))


def format_bvh(clip: BvhClip) -> str:
    """The BVH text of a clip (6 decimals, so a round trip keeps every channel to 1e-6)."""
    out = ["HIERARCHY"]
    children: dict[int, list[int]] = {j: [] for j in range(len(clip.joint_names))}
    for j, p in enumerate(clip.parents):
        if p >= 0:
            children[int(p)].append(j)

    def emit(j: int, depth: int) -> None:
        pad = "  " * depth
        kind = "ROOT" if clip.parents[j] < 0 else "JOINT"
        out.append(f"{pad}{kind} {clip.joint_names[j]}")
        out.append(f"{pad}{{")
        o = clip.offsets[j]
        out.append(f"{pad}  OFFSET {o[0]:.6f} {o[1]:.6f} {o[2]:.6f}")
        if clip.channels[j]:
            out.append(f"{pad}  CHANNELS {len(clip.channels[j])} {' '.join(clip.channels[j])}")
        for c in children[j]:
            emit(c, depth + 1)
        if not children[j]:
            e = clip.end_sites.get(j, np.zeros(3))
            out.extend(
                [
                    f"{pad}  End Site",
                    f"{pad}  {{",
                    f"{pad}    OFFSET {e[0]:.6f} {e[1]:.6f} {e[2]:.6f}",
                    f"{pad}  }}",
                ]
            )
        out.append(f"{pad}}}")

    for r in [j for j, p in enumerate(clip.parents) if p < 0]:
        emit(r, 0)
    out += ["MOTION", f"Frames: {clip.n_frames}", f"Frame Time: {clip.frame_time:.8f}"]
    out.extend(" ".join(f"{v:.6f}" for v in row) for row in clip.motion)
    return "\n".join(out) + "\n"


def write_clip(path: str | Path, clip: BvhClip) -> None:
    """Write a BvhClip (gzip when the name ends in .gz)."""
    text = format_bvh(clip)
    path = Path(path)
    if path.suffix == ".gz":
        with gzip.open(path, "wt") as fh:
            fh.write(text)
    else:
        path.write_text(text)


def canonical_clip(
    root_position: np.ndarray,
    rotations: np.ndarray,
    fps: float = 30.0,
    offsets: np.ndarray | None = None,
    scale: float = 1.0,
) -> BvhClip:
    """A BvhClip of the canonical skeleton (channel order Zrotation Yrotation Xrotation, root absolute)."""
    rotations = np.asarray(rotations, dtype=np.float64)
    root_position = np.asarray(root_position, dtype=np.float64)
    if rotations.ndim != 3 or rotations.shape[1:] != (N_JOINTS, 4):
        raise ValueError(f"rotations must be (T, {N_JOINTS}, 4), got {rotations.shape}")
    if root_position.shape != (rotations.shape[0], 3):
        raise ValueError(f"root_position must be ({rotations.shape[0]}, 3), got {root_position.shape}")
    if fps <= 0:
        raise ValueError("fps must be positive")
    offs = (REST_OFFSETS if offsets is None else np.asarray(offsets, dtype=np.float64)).copy() * scale
    offs[0] = 0.0  # the root position channels are absolute
    euler = quat.to_euler("ZYX", quat.normalize(rotations))  # (T, J, 3) as Z, Y, X
    cols = [root_position * scale]
    cols.extend(euler[:, j] for j in range(N_JOINTS))
    motion = np.concatenate(cols, axis=1)
    channels = [["Xposition", "Yposition", "Zposition", "Zrotation", "Yrotation", "Xrotation"]]
    channels += [["Zrotation", "Yrotation", "Xrotation"] for _ in range(N_JOINTS - 1)]
    ends = {j: np.array([0.0, 0.05, 0.0]) * scale for j in range(N_JOINTS) if j not in set(PARENTS.tolist())}
    return BvhClip(
        joint_names=list(JOINT_NAMES),
        parents=PARENTS.copy(),
        offsets=offs,
        channels=channels,
        end_sites=ends,
        frame_time=1.0 / fps,
        motion=motion,
    )


def write_bvh(
    path: str | Path,
    root_position: np.ndarray,
    rotations: np.ndarray,
    fps: float = 30.0,
    offsets: np.ndarray | None = None,
    scale: float = 1.0,
) -> None:
    """Write canonical-skeleton motion as BVH.

    Args:
        path: output file (.bvh, or .bvh.gz to compress).
        root_position: (T, 3) Hips position in metres, world frame.
        rotations: (T, J, 4) local quaternions (x, y, z, w) in wana.domain.skeleton.JOINT_NAMES order.
        fps: frames per second.
        offsets: (J, 3) rest offsets in metres (default: the reference skeleton).
        scale: unit multiplier for the file (1 = metres, 100 = centimetres).
    """
    write_clip(path, canonical_clip(root_position, rotations, fps, offsets, scale))


def canonical_motion(clip: BvhClip, scale: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """Root positions (T, 3) and rotations (T, J, 4) from a BVH of the canonical skeleton (as written here)."""
    if clip.joint_names != list(JOINT_NAMES):
        raise ValueError("not a canonical-skeleton BVH; use services.motion.retarget.retarget_clip")
    gpos, _ = clip.global_transforms()
    return gpos[:, 0] / scale, clip.local_rotations()
