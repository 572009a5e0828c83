"""Where the packaged assets and models are, in a checkout and in an installed wheel alike.

Three places, first found wins:

1. ``$WANA_ASSETS`` / ``$WANA_MODELS``: a folder the user points at (their own action clips, a
   retrained locomotion network, a read-only install they cannot write beside).
2. The wheel's package data: ``pip install .`` copies the repository's ``assets/`` and ``models/``
   into ``wana/_packaged/`` (see ``setup.py``), found here with ``importlib.resources``.
3. The source checkout: ``assets/`` and ``models/`` beside the ``wana`` package.

Every module that reads a committed file asks this one; nothing else computes a path from
``__file__``.
"""

from __future__ import annotations

import os
from importlib import resources
from pathlib import Path

ASSETS_ENV = "WANA_ASSETS"
MODELS_ENV = "WANA_MODELS"
PACKAGED = "_packaged"  # folder inside the installed ``wana`` package that holds assets/ and models/


class AssetsNotFound(FileNotFoundError):
    """Neither the override, the wheel's package data nor a checkout holds the folder."""


def _checkout_root() -> Path:
    """The repository root when running from a source checkout (or an editable install)."""
    return Path(str(resources.files("wana"))).resolve().parent


def _locate(kind: str, env: str) -> Path:
    override = os.environ.get(env)
    if override:
        folder = Path(override).expanduser().resolve()
        if not folder.is_dir():
            raise AssetsNotFound(f"${env} is {override!r}, which is no folder")
        return folder
    packaged = Path(str(resources.files("wana"))) / PACKAGED / kind
    if packaged.is_dir():
        return packaged
    checkout = _checkout_root() / kind
    if checkout.is_dir():
        return checkout
    raise AssetsNotFound(
        f"no {kind}/ folder: set ${env}, install the wheel (it ships {kind}/), or run from a checkout"
    )


def assets_dir() -> Path:
    """The folder of packaged assets (actions/, scenedb/, social/, ...)."""
    return _locate("assets", ASSETS_ENV)


def models_dir() -> Path:
    """The folder of trained models (nlp/en_wana, locomotion/)."""
    return _locate("models", MODELS_ENV)


def asset_path(*parts: str) -> Path:
    """A path under ``assets_dir()``, e.g. ``asset_path("social", "vad.tsv")`` (need not exist yet)."""
    return assets_dir().joinpath(*parts)


def model_path(*parts: str) -> Path:
    """A path under ``models_dir()``, e.g. ``model_path("locomotion")`` (need not exist yet)."""
    return models_dir().joinpath(*parts)


def repo_root() -> Path | None:
    """The source checkout's root, or None when running from an installed wheel.

    Only for tools that rebuild committed files or read ``../shared/data`` beside a checkout.
    """
    root = _checkout_root()
    return root if (root / "pyproject.toml").is_file() else None
