"""`pip install .` gives a wana that animates from any folder: assets and models ship in the wheel.

Builds the wheel from a copy of the checkout's files (so the worktree gets no build/ folder),
installs it with ``--no-deps`` into a fresh venv that borrows the shared venv's third-party packages
through a ``.pth`` line (no download), then runs ``wana`` from an unrelated folder with no
PYTHONPATH. The installed package, not the checkout, must be what runs and what finds the files.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
STORY = (
    "In the office there is a desk$. A chair is in front of the desk$.\nEve walks to the chair. Eve sits.\n"
)

pytestmark = [pytest.mark.slow, pytest.mark.integration]


def _copy_checkout(dst: Path) -> None:
    files = subprocess.run(
        ["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
        cwd=REPO,
        capture_output=True,
        check=True,
    ).stdout.split(b"\0")
    for name in filter(None, files):
        src = REPO / os.fsdecode(name)
        if src.is_file():
            target = dst / os.fsdecode(name)
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, target)


@pytest.fixture(scope="module")
def installed(tmp_path_factory: pytest.TempPathFactory) -> dict[str, object]:
    tmp = tmp_path_factory.mktemp("wheel")
    src = tmp / "src"
    _copy_checkout(src)
    venv = tmp / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    py = venv / "bin" / "python"
    purelib = Path(
        subprocess.run(
            [str(py), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
            capture_output=True,
            text=True,
            check=True,
        ).stdout.strip()
    )
    # The shared venv's packages (numpy, spaCy, ...) after the fresh venv's own: a plain path line, so
    # the shared venv's editable finder for the checkout is not loaded.
    (purelib / "_shared_venv.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "WANA_ASSETS", "WANA_MODELS")}
    env.update(OMP_NUM_THREADS="1", PIP_NO_INDEX="1", PIP_DISABLE_PIP_VERSION_CHECK="1")
    subprocess.run(
        [str(py), "-m", "pip", "install", "-q", "--no-deps", "--no-build-isolation", str(src)],
        check=True,
        env=env,
        cwd=tmp,
        timeout=600,
    )
    elsewhere = tmp / "elsewhere"
    elsewhere.mkdir()
    shutil.rmtree(src)  # nothing may read the sources once installed
    return {"py": py, "wana": venv / "bin" / "wana", "env": env, "cwd": elsewhere, "purelib": purelib}


def _run(installed: dict[str, object], *args: str, timeout: float = 600) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [str(installed["wana"]), *args],
        cwd=installed["cwd"],
        env=installed["env"],  # type: ignore[arg-type]
        capture_output=True,
        text=True,
        timeout=timeout,
    )


def test_the_installed_package_finds_its_assets_and_models_inside_itself(installed):
    code = (
        "import json, wana; from wana.domain import paths; from wana.domain.actions import load_library;"
        "print(json.dumps([wana.__file__, str(paths.assets_dir()), str(paths.models_dir()),"
        " len(load_library()), paths.repo_root() is None]))"
    )
    out = subprocess.run(
        [str(installed["py"]), "-c", code],
        cwd=installed["cwd"],
        env=installed["env"],  # type: ignore[arg-type]
        capture_output=True,
        text=True,
        check=True,
    )
    module, assets, models, n_clips, no_checkout = json.loads(out.stdout)
    purelib = str(installed["purelib"])
    assert module.startswith(purelib), module
    assert assets.startswith(purelib) and assets.endswith("_packaged/assets"), assets
    assert models.startswith(purelib) and models.endswith("_packaged/models"), models
    assert n_clips > 100 and no_checkout


def test_wana_parse_runs_from_another_folder(installed):
    done = _run(installed, "parse", "Eve sits on the chair.")
    assert done.returncode == 0, done.stderr
    assert "Eve" in done.stdout and "sit" in done.stdout


def test_wana_animate_writes_every_output_from_another_folder(installed):
    story = Path(installed["cwd"]) / "story.txt"  # type: ignore[arg-type]
    story.write_text(STORY)
    done = _run(
        installed,
        "animate",
        "story.txt",
        "-o",
        "out",
        "--in-process",
        "--no-progress",
        "--width",
        "160",
        "--height",
        "120",
    )
    assert done.returncode == 0, done.stderr[-4000:]
    out = Path(installed["cwd"]) / "out"  # type: ignore[arg-type]
    for name in ("animation.mp4", "scene.glb", "Eve.bvh", "report.json"):
        assert (out / name).is_file() and (out / name).stat().st_size > 0, name
    report = json.loads((out / "report.json").read_text())
    assert report  # a real report, written by the installed package
