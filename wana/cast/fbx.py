"""FBX characters through Blender: its FBX importer and glTF exporter in a subprocess (``bpy_to_glb.py``),
so that the rest of ``wana.cast`` reads one format. Blender is optional (the 'blender' extra); without it the
message says how to get it or to export a GLB from the user's tool instead."""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from wana.cast.glb_rig import CastError

SCRIPT = Path(__file__).with_name("bpy_to_glb.py")
TIMEOUT_S = 300
MISSING = (
    "an FBX character needs Blender as a Python module (bpy): run `make setup` (the 'blender' extra), "
    "`pip install bpy==5.0.1`, or set WANA_BLENDER_PYTHON to a Python that has bpy; or export the character "
    "as GLB from your tool"
)


def fbx_to_glb(path: str | Path) -> bytes:
    """The GLB bytes Blender writes for an FBX character.

    Raises:
        CastError: no Blender here, or Blender could not convert the file.
    """
    python = os.environ.get("WANA_BLENDER_PYTHON", "")
    if python and not Path(python).is_file():
        raise CastError(f"WANA_BLENDER_PYTHON={python} is not a file; {MISSING}")
    if not python:
        if importlib.util.find_spec("bpy") is None:  # looks it up without loading Blender
            raise CastError(MISSING)
        python = sys.executable
    with tempfile.TemporaryDirectory(prefix="wana-cast-") as tmp:
        dst = Path(tmp) / "character.glb"
        run = subprocess.run(
            [python, str(SCRIPT), str(Path(path).resolve()), str(dst)],
            capture_output=True,
            text=True,
            timeout=TIMEOUT_S,
            env={**os.environ, "PYTHONNOUSERSITE": "1"},
        )
        if run.returncode != 0 or not dst.is_file():
            tail = "\n".join((run.stdout + run.stderr).strip().splitlines()[-6:])
            raise CastError(f"Blender could not convert {path} to GLB ({run.returncode}): {tail}")
        return dst.read_bytes()
