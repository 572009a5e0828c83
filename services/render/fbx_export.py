"""FBX through Blender's own exporter: our GLB in through Blender's glTF importer, out as FBX.

Game engines and DCC tools import FBX; the only FBX writer that they all agree with is Autodesk's SDK or
Blender's, so the render service hands the GLB (characters, skins, animation, held props, the director's
camera) to Blender and takes its FBX back. Blender runs in a subprocess (``bpy_fbx.py``) so that ``bpy``,
a 370 MB module with its own process state, never loads into a worker. Which Python runs it:
``$WANA_BLENDER_PYTHON`` when set (a separate interpreter that has bpy), else this one if it has bpy.
"""

from __future__ import annotations

import importlib.util
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

SCRIPT = Path(__file__).with_name("bpy_fbx.py")
TIMEOUT_S = 300


def missing_message(what: str) -> str:
    """What to install when ``what`` (an FBX export, a Cycles render) finds no Blender."""
    return (
        f"{what} needs Blender as a Python module (bpy==5.0.1): run `make setup` (it installs the "
        "'blender' extra) or `pip install bpy==5.0.1`, or point WANA_BLENDER_PYTHON at a Python that has bpy"
    )


MISSING = missing_message("an FBX export")


def blender_python(missing: str = MISSING) -> str:
    """The interpreter that runs Blender.

    Raises:
        ModuleNotFoundError: no interpreter with bpy (the message says how to get one).
    """
    chosen = os.environ.get("WANA_BLENDER_PYTHON", "")
    if chosen:
        if not Path(chosen).is_file():
            raise ModuleNotFoundError(f"WANA_BLENDER_PYTHON={chosen} is not a file; {missing}")
        return chosen
    if importlib.util.find_spec("bpy") is None:  # looks the module up without loading it
        raise ModuleNotFoundError(missing)
    return sys.executable


def run_blender(*args: str) -> str:
    """Run ``bpy_fbx.py`` with these arguments; its standard output.

    Raises:
        RuntimeError: Blender failed (its last output lines in the message).
    """
    run = subprocess.run(
        [blender_python(), str(SCRIPT), *args],
        capture_output=True,
        text=True,
        timeout=TIMEOUT_S,
        env={**os.environ, "PYTHONNOUSERSITE": "1"},
    )
    if run.returncode != 0:
        tail = "\n".join((run.stdout + run.stderr).strip().splitlines()[-8:])
        raise RuntimeError(f"Blender failed ({run.returncode}): {tail}")
    return run.stdout


def glb_to_fbx(glb: bytes) -> bytes:
    """The FBX bytes of a GLB (``services.render.gltf_export.scene_glb``), written by Blender."""
    with tempfile.TemporaryDirectory(prefix="wana-fbx-") as tmp:
        src, dst = Path(tmp) / "scene.glb", Path(tmp) / "animation.fbx"
        src.write_bytes(glb)
        run_blender("export", str(src), str(dst))
        if not dst.is_file():
            raise RuntimeError("Blender wrote no FBX")
        return dst.read_bytes()


def probe(path: str | Path, frames: list[int]) -> dict:
    """What Blender's importer reads from an FBX or GLB: joint world positions at the frames, skins, cameras
    (``bpy_fbx.probe``)."""
    out = run_blender("probe", str(path), *(str(f) for f in frames))
    line = next(x for x in out.splitlines() if x.startswith("WANA_PROBE "))
    return json.loads(line[len("WANA_PROBE ") :])
