"""One BVH per character: the canonical skeleton with that character's bone lengths, metres, 30 fps.

Written with the domain library's BVH writer (``wana.domain.bvh``), so our importer reads it back
exactly; the channel layout (root XYZ position + ZYX rotations, ZYX rotations elsewhere) is the
common one that Blender, MotionBuilder and PyPI parsers such as ``bvh`` read.
"""

from __future__ import annotations

import re
import warnings
from pathlib import Path

from proto.motion_data import Motion
from services.render.cast_gltf import CastCharacter
from services.render.skinning import Rig
from wana.domain.bvh import canonical_clip, format_bvh


def safe_filename(name: str) -> str:
    """A file-system-safe stem for a character name ("Mary Ann" -> "Mary_Ann")."""
    stem = re.sub(r"[^A-Za-z0-9_.-]+", "_", name).strip("._")
    return stem or "character"


def motion_bvh(motion: Motion, cast: CastCharacter | None = None) -> str:
    """The BVH text of one character's motion (its own bone lengths as OFFSETs); with ``cast``, the user's
    rig's own joint names, hierarchy and bones, the motion retargeted onto it (services.render.cast_skin)."""
    if cast is not None:
        from services.render.cast_skin import cast_clip

        return format_bvh(cast_clip(cast, motion))
    rig = Rig.from_motion(motion)
    with warnings.catch_warnings():  # Euler angles at gimbal lock are still exact rotations
        warnings.simplefilter("ignore", UserWarning)
        clip = canonical_clip(
            rig.root, rig.rotations, fps=float(motion.fps or 30), offsets=rig.character.offsets.astype(float)
        )
    return format_bvh(clip)


def write_character_bvh(out_dir: str | Path, motion: Motion) -> Path:
    """Write ``<out_dir>/<character>.bvh`` and return its path."""
    path = Path(out_dir) / f"{safe_filename(motion.character)}.bvh"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(motion_bvh(motion))
    return path
