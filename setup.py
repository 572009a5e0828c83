"""Build hook only (the project is declared in pyproject.toml): ship assets/ and models/ in the wheel.

The committed assets and trained models live at the repository root, beside the packages, so that
the rebuild scripts and the docs can name them plainly. A wheel copies them into
``wana/_packaged/`` where ``wana.domain.paths`` finds them with ``importlib.resources``; a checkout
or an editable install reads them in place. About 17 MB uncompressed (the spaCy pipeline is 13 MB).
"""

from __future__ import annotations

import shutil
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

ROOT = Path(__file__).resolve().parent
PACKAGED = ("assets", "models")  # folders copied to wana/_packaged/<name>
SKIPPED = shutil.ignore_patterns("__pycache__", "*.pyc", "imported")  # imported: a user's own clips


class BuildPyWithAssets(build_py):
    """build_py that also copies the packaged asset folders into the built ``wana`` package."""

    def run(self) -> None:
        super().run()
        if getattr(self, "editable_mode", False):
            return  # an editable install reads the checkout's folders in place
        for name in PACKAGED:
            src = ROOT / name
            if src.is_dir():
                shutil.copytree(
                    src,
                    Path(self.build_lib) / "wana" / "_packaged" / name,
                    dirs_exist_ok=True,
                    ignore=SKIPPED,
                )


setup(cmdclass={"build_py": BuildPyWithAssets})
